"""Auto chooses the supercell size (AutoSupercellSize): once it has settled on a pass it
tries larger supercells (and smaller ones when larger are slower), keeps the fastest, and
every frame of the search gives the image of unaccelerated casting bit for bit; a size the
user sets is kept."""
import unittest

import numpy as np
from parc import vtkPARCVolumeMapper
from parctesthelpers import offscreen_window, ray_image
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
from vtkmodules.vtkRenderingCore import vtkColorTransferFunction, vtkVolumeProperty

FRAMES = 30  # more than any search takes: 2 frames a scale, one more to set each scale up


def make_scene():
    """An isosurface of a few blobs of the wavelet in a 97^3 volume: depth PARC wins by far,
    so Auto settles on a pass and the search runs."""
    source = vtkRTAnalyticSource()
    source.SetWholeExtent(-48, 48, -48, 48, -48, 48)
    source.SetStandardDeviation(0.25)
    mapper = vtkPARCVolumeMapper()
    mapper.SetInputConnection(source.GetOutputPort())
    mapper.SetBlendModeToIsoSurface()
    prop = vtkVolumeProperty()
    prop.GetIsoSurfaceValues().SetValue(0, 200.0)
    color = vtkColorTransferFunction()
    color.AddRGBPoint(0, 1.0, 0.8, 0.6)
    prop.SetColor(color)
    prop.ShadeOn()
    window = offscreen_window(mapper, prop, 200)
    window.SetMultiSamples(0)
    renderer = window.GetRenderers().GetFirstRenderer()
    renderer.GetActiveCamera().Azimuth(25)
    renderer.GetActiveCamera().Elevation(15)
    renderer.ResetCameraClippingRange()
    return mapper, window


class TestPARCAutoSupercellSize(unittest.TestCase):
    def test_auto_searches_sizes_and_keeps_the_image(self):
        mapper, window = make_scene()
        mapper.SetAccelerationModeToNone()
        window.Render()
        reference = ray_image(mapper)
        self.assertGreater(np.count_nonzero(reference[:, 3]), 100, "the surface shows")

        mapper.SetAccelerationModeToAuto()
        self.assertTrue(mapper.GetAutoSupercellSize())
        sizes, builds = [], []
        for frame in range(FRAMES):
            window.Render()
            sizes.append(tuple(mapper.GetLastSupercellSize()))
            builds.append(mapper.GetModelBuildCount())
            mode = mapper.GetLastAccelerationMode()
            self.assertTrue(np.array_equal(ray_image(mapper), reference),
                            "frame %d, %s, supercells %s" % (
                                frame, mapper.GetAccelerationModeAsString(mode), sizes[-1]))
        self.assertEqual(sizes[0], (4.0, 4.0, 4.0), "the search starts at the mapper's size")
        self.assertIn(mode, (vtkPARCVolumeMapper.ACCELERATION_DEPTH_BUFFER,
                             vtkPARCVolumeMapper.ACCELERATION_COLOR_BUFFER,
                             vtkPARCVolumeMapper.ACCELERATION_BOTH),
                      "Auto settled on a pass")
        self.assertIn((8.0, 8.0, 8.0), sizes, "twice the size was tried")
        tried = sorted(set(s[0] for s in sizes))
        self.assertTrue(set(tried) <= {1.0, 2.0, 4.0, 8.0, 16.0, 32.0}, tried)
        # The search has ended: the last frames keep one size and build nothing.
        self.assertEqual(len(set(sizes[-5:])), 1, sizes)
        self.assertEqual(len(set(builds[-5:])), 1, builds)
        # One classification a size tried (the last one tried again when it is not kept).
        self.assertLessEqual(builds[-1] - builds[0], len(tried) + 1)

    def test_a_size_the_user_sets_is_kept(self):
        mapper, window = make_scene()
        mapper.SetAccelerationModeToAuto()
        mapper.SetSupercellSize(4, 4, 4)
        self.assertFalse(mapper.GetAutoSupercellSize())
        self.assertIn("AutoSupercellSize: 0", str(mapper))
        for _ in range(FRAMES // 2):
            window.Render()
            self.assertEqual(tuple(mapper.GetLastSupercellSize()), (4.0, 4.0, 4.0))


if __name__ == "__main__":
    unittest.main()
