"""Progress on long work: the mapper's ProgressEvent names each set-up step of a render
(GetProgressText) with a progress that only grows, and its casting follows from 0.5 to 1;
a render that sets nothing up reports casting alone, from 0 to 1. The casting fractions
also arrive as VTK's VolumeMapperRenderProgressEvent, from 0 to 1."""
import unittest

from parc import vtkPARCMultiVolume, vtkPARCVolumeMapper
from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
from vtkmodules.vtkRenderingCore import vtkColorTransferFunction, vtkVolume, vtkVolumeProperty

from parctesthelpers import offscreen_window, offscreen_window_showing


def wavelet_property():
    opacity, color = vtkPiecewiseFunction(), vtkColorTransferFunction()
    opacity.AddPoint(150, 0.0)
    opacity.AddPoint(280, 0.3)
    color.AddRGBPoint(0, 1, 1, 1)
    prop = vtkVolumeProperty()
    prop.SetScalarOpacity(opacity)
    prop.SetColor(color)
    prop.SetInterpolationTypeToLinear()
    return prop


class TestPARCProgress(unittest.TestCase):
    def test_set_up_steps_then_casting(self):
        source = vtkRTAnalyticSource()
        source.SetWholeExtent(-40, 40, -40, 40, -40, 40)
        mapper = vtkPARCVolumeMapper()
        mapper.SetInputConnection(source.GetOutputPort())
        mapper.SetAccelerationModeToDepthBuffer()
        window = offscreen_window(mapper, wavelet_property(), 256)
        reports, casting = [], []
        mapper.AddObserver(vtkCommand.ProgressEvent, lambda m, e: reports.append(
            (m.GetProgressText(), m.GetProgress())))
        mapper.AddObserver(vtkCommand.VolumeMapperRenderProgressEvent,
                           lambda m, e: casting.append(m.GetProgress()))

        window.Render()
        steps = [text for text, _ in reports]
        for step in ("reading the scalars", "classifying the cells", "classifying the supercells"):
            self.assertIn(step, steps)
        progress = [p for _, p in reports]
        self.assertEqual(progress, sorted(progress), "the progress only grows")
        cast = [p for text, p in reports if text == "casting rays"]
        self.assertGreater(len(cast), 1, "a 256^2 image is cast in several bands")
        self.assertGreaterEqual(min(cast), 0.5)
        self.assertEqual(cast[-1], 1.0)

        reports.clear()
        window.Render()
        self.assertEqual({text for text, _ in reports}, {"casting rays"}, "nothing set up")
        self.assertLess(reports[0][1], 0.5)
        self.assertEqual(reports[-1][1], 1.0)
        self.assertGreater(len(casting), 0)

    def test_several_volumes_never_go_back(self):
        mapper = vtkPARCVolumeMapper()
        multi = vtkPARCMultiVolume()
        multi.SetMapper(mapper)
        for port, extent in enumerate((20, 30)):
            source = vtkRTAnalyticSource()
            source.SetWholeExtent(-extent, extent, -extent, extent, -extent, extent)
            mapper.SetInputConnection(port, source.GetOutputPort())
            volume = vtkVolume()
            volume.SetProperty(wavelet_property())
            multi.SetVolume(volume, port)
        window = offscreen_window_showing(multi, 128)
        reports = []
        mapper.AddObserver(vtkCommand.ProgressEvent, lambda m, e: reports.append(
            (m.GetProgressText(), m.GetProgress())))
        window.Render()
        self.assertEqual([t for t, _ in reports].count("reading the scalars"), 2)
        # The render's own reports (the pipeline's update of the mapper reports 0 and 1
        # without a text before them).
        progress = [p for t, p in reports if t]
        self.assertEqual(progress, sorted(progress), "the progress only grows")


if __name__ == "__main__":
    unittest.main()
