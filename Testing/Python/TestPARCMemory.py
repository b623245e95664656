"""GetMemorySize against what a render really adds to the process: the mapper's structures
and what the OpenGL implementation keeps for its passes and its image (measured, since no GL
call tells), without drifting over warm frames, and none of the GL part once the window's
graphics resources are released."""
import os
import sys
import unittest

from parc import vtkPARCVolumeMapper
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
from vtkmodules.vtkRenderingCore import vtkRenderWindow, vtkRenderer, vtkVolume
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
from parctesthelpers import wavelet_property

# GetMemorySize over the resident growth of a new mapper's first frames: the GL part is
# measured, the rest counted; what neither sees (the Python objects, allocator slack) is a
# few percent.
GROWTH_SHARE = (0.8, 1.2)


def resident():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


class TestPARCMemory(unittest.TestCase):
    def setUp(self):
        source = vtkRTAnalyticSource()  # smooth float values about 37..277
        source.SetWholeExtent(-60, 60, -60, 60, -60, 60)
        source.Update()
        self.image = source.GetOutput()
        self.prop = wavelet_property(150)
        self.prop.SetInterpolationTypeToLinear()
        self.renderer = vtkRenderer()
        self.window = vtkRenderWindow()
        self.window.SetOffScreenRendering(1)
        self.window.SetMultiSamples(0)
        self.window.SetSize(300, 300)
        self.window.AddRenderer(self.renderer)
        self.window.Render()  # the GL context, before any mapper

    def show(self, mode):
        mapper = vtkPARCVolumeMapper()
        mapper.SetAccelerationMode(mode)
        mapper.SetInputData(self.image)
        volume = vtkVolume()
        volume.SetMapper(mapper)
        volume.SetProperty(self.prop)
        self.renderer.AddVolume(volume)
        self.renderer.ResetCamera()
        return mapper

    @unittest.skipUnless(sys.platform.startswith("linux"), "reads /proc/self/statm")
    def test_memory_size_follows_the_growth(self):
        before = resident()
        mapper = self.show(vtkPARCVolumeMapper.ACCELERATION_DEPTH_BUFFER)
        for _ in range(3):
            self.window.Render()
        growth = resident() - before
        share = mapper.GetMemorySize() / growth
        print("GetMemorySize / resident growth: %.3f of %d bytes" % (share, growth))
        self.assertGreater(share, GROWTH_SHARE[0], "growth %d" % growth)
        self.assertLess(share, GROWTH_SHARE[1], "growth %d" % growth)

    def test_warm_frames_do_not_drift(self):
        mapper = self.show(vtkPARCVolumeMapper.ACCELERATION_DEPTH_BUFFER)
        self.window.Render()
        first = mapper.GetMemorySize()
        camera = self.renderer.GetActiveCamera()
        for _ in range(30):
            camera.Azimuth(5)
            self.window.Render()
        self.assertEqual(mapper.GetMemorySize(), first, "nothing set up, nothing added")
        mapper.ReleaseGraphicsResources(self.window)
        self.assertLess(mapper.GetMemorySize(), first, "the GL part goes with the resources")

    @unittest.skipUnless(sys.platform.startswith("linux"), "reads /proc/self/statm")
    def test_released_pass_leaves_the_process(self):
        """The colour pass's model, targets and buffers, freed when the mapper no longer draws
        it, leave the process too: the allocator's free pages go back to the system."""
        mapper = self.show(vtkPARCVolumeMapper.ACCELERATION_COLOR_BUFFER)
        for _ in range(2):
            self.window.Render()
        held, before = mapper.GetMemorySize(), resident()
        mapper.SetAccelerationModeToNone()
        for _ in range(2):
            self.window.Render()
        freed, returned = held - mapper.GetMemorySize(), before - resident()
        print("freed %d bytes, resident size %d bytes less" % (freed, returned))
        self.assertGreater(freed, 1 << 20, "the colour pass held its targets and model")
        self.assertGreater(returned, freed // 2, "what was freed left the process")


if __name__ == "__main__":
    unittest.main()
