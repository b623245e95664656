"""A VTK pipeline in Python through `from parc import vtkPARCVolumeMapper`: a procedural
source feeds the mapper, the render draws something, statistics and the float ray-cast image
are reachable, progress events arrive in order, and an abort request stops the cast early."""
import sys
import unittest

from parc import vtkPARCVolumeMapper
from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPiecewiseFunction
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
from vtkmodules.vtkRenderingCore import (vtkColorTransferFunction, vtkRenderWindow,
                                         vtkRenderer, vtkVolume, vtkVolumeProperty)


def make_scene(size=120):
    source = vtkRTAnalyticSource()  # the "wavelet": smooth, values about 37..277
    source.SetWholeExtent(-20, 20, -20, 20, -20, 20)
    mapper = vtkPARCVolumeMapper()
    mapper.SetInputConnection(source.GetOutputPort())
    opacity = vtkPiecewiseFunction()
    opacity.AddPoint(100, 0.0)
    opacity.AddPoint(250, 0.3)
    color = vtkColorTransferFunction()
    color.AddRGBPoint(100, 0.2, 0.3, 1.0)
    color.AddRGBPoint(250, 1.0, 0.8, 0.3)
    prop = vtkVolumeProperty()
    prop.SetScalarOpacity(opacity)
    prop.SetColor(color)
    prop.ShadeOn()
    volume = vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    renderer = vtkRenderer()
    renderer.AddVolume(volume)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(size, size)
    window.AddRenderer(renderer)
    renderer.ResetCamera()
    return mapper, window


class TestPARCPipeline(unittest.TestCase):
    def test_renders_and_reports(self):
        mapper, window = make_scene()
        window.Render()
        self.assertEqual(mapper.GetClassName(), "vtkPARCVolumeMapper")
        self.assertGreater(mapper.GetLastRayCount(), 0)
        self.assertGreaterEqual(mapper.GetLastSampleCount(), mapper.GetLastContributingSampleCount())
        self.assertGreater(mapper.GetLastContributingSampleCount(), 0)
        self.assertGreater(mapper.GetLastGradientCount(), 0, "shading needs gradients")
        self.assertGreater(mapper.GetLastRenderTime(), 0.0)
        image = vtkImageData()
        mapper.GetLastRayCastImage(image)
        self.assertEqual(image.GetDimensions(), (120, 120, 1))
        rgba = image.GetPointData().GetScalars()
        self.assertEqual(rgba.GetNumberOfComponents(), 4)
        alpha = rgba.GetRange(3)
        self.assertGreater(alpha[1], 0.1)
        self.assertLessEqual(alpha[1], 1.0)
        # Auto: depth PARC unless every supercell may contribute (then no pass can help).
        all_pc = mapper.GetLastContributingSupercellCount() == mapper.GetLastSupercellCount()
        self.assertEqual(vtkPARCVolumeMapper.GetAccelerationModeAsString(
            mapper.GetLastAccelerationMode()), "None" if all_pc else "DepthBuffer")
        self.assertGreater(mapper.GetLastSupercellCount(), 0)

    def test_progress_and_abort(self):
        mapper, window = make_scene(size=256)
        fractions = []
        mapper.AddObserver(vtkCommand.ProgressEvent,
                           lambda obj, event: fractions.append(obj.GetProgress()))
        window.Render()
        self.assertGreater(len(fractions), 2)
        self.assertEqual(fractions, sorted(fractions))
        self.assertAlmostEqual(fractions[-1], 1.0)
        full = mapper.GetLastSampleCount()

        def abort(obj, event):
            obj.SetAbortExecute(1)
        mapper.AddObserver(vtkCommand.ProgressEvent, abort)
        window.Render()
        self.assertLess(mapper.GetLastSampleCount(), full)


if __name__ == "__main__":
    result = unittest.main(exit=False).result
    sys.exit(0 if result.wasSuccessful() else 1)
