"""Two overlapping volumes in one image from Python, through vtkMultiVolume's API: an
isosurface on port 0 inside a translucent cloud on port 1 (vtkPARCMultiVolume), each with
its own property and transform. The cloud shows where it lies in front of the surface,
the surface shows through it, and the depth-buffer passes give the unaccelerated bits."""
import unittest

from parc import vtkPARCMultiVolume, vtkPARCVolumeMapper
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkCommonTransforms import vtkTransform
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
from vtkmodules.vtkImagingSources import vtkImageEllipsoidSource
from vtkmodules.vtkRenderingCore import vtkColorTransferFunction, vtkVolume, vtkVolumeProperty
from vtkmodules.vtkRenderingVolume import vtkVolumeMapper

from parctesthelpers import offscreen_window_showing, ray_image


def property_of(opacity_points, rgb, iso=None):
    opacity = vtkPiecewiseFunction()
    for x, y in opacity_points:
        opacity.AddPoint(x, y)
    color = vtkColorTransferFunction()
    color.AddRGBPoint(0, *rgb)
    color.AddRGBPoint(255, *rgb)
    prop = vtkVolumeProperty()
    prop.SetScalarOpacity(opacity)
    prop.SetColor(color)
    if iso is not None:
        prop.GetIsoSurfaceValues().SetValue(0, iso)
    return prop


def make_scene():
    surface = vtkImageEllipsoidSource()  # a solid ball: 255 inside, 0 outside
    surface.SetWholeExtent(0, 40, 0, 40, 0, 40)
    surface.SetCenter(20, 20, 20)
    surface.SetRadius(8, 8, 8)
    surface.SetInValue(255)
    surface.SetOutValue(0)
    cloud = vtkRTAnalyticSource()  # the wavelet, values about 37..277, around the ball
    cloud.SetWholeExtent(-20, 20, -20, 20, -20, 20)

    mapper = vtkPARCVolumeMapper()
    mapper.SetInputConnection(0, surface.GetOutputPort())
    mapper.SetInputConnection(1, cloud.GetOutputPort())
    mapper.SetInputBlendMode(0, vtkVolumeMapper.ISOSURFACE_BLEND)
    mapper.SetInputBlendMode(1, vtkVolumeMapper.COMPOSITE_BLEND)

    ball = vtkVolume()
    ball.SetProperty(property_of([(0, 1.0), (255, 1.0)], (1.0, 0.2, 0.1), iso=128))
    haze = vtkVolume()
    haze.SetProperty(property_of([(100, 0.0), (280, 0.05)], (0.2, 0.4, 1.0)))
    move = vtkTransform()
    move.Translate(20, 20, 20)  # the wavelet's centre onto the ball's
    haze.SetUserTransform(move)
    multi = vtkPARCMultiVolume()
    multi.SetMapper(mapper)
    multi.SetVolume(ball, 0)
    multi.SetVolume(haze, 1)

    return mapper, multi, offscreen_window_showing(multi, 80)


class TestPARCMultiVolume(unittest.TestCase):
    def test_two_volumes_in_one_image(self):
        mapper, multi, window = make_scene()
        bounds = multi.GetBounds()
        self.assertEqual(bounds, (0.0, 40.0, 0.0, 40.0, 0.0, 40.0))
        mapper.SetAccelerationModeToNone()
        window.Render()
        both = ray_image(mapper)
        centre = both.reshape(80, 80, 4)[40, 40]
        self.assertGreater(centre[0], centre[2], "the red ball shows through the blue haze")
        self.assertGreater(centre[2], 0.0, "the haze in front of the ball tints it")
        self.assertEqual(centre[3], 1.0, "the ball is opaque")
        alpha = both[:, 3]
        self.assertGreater(((alpha > 0.0) & (alpha < 0.9)).sum(), 500,
                           "around the ball, the haze alone is translucent")

        mapper.SetAccelerationModeToDepthBuffer()
        window.Render()
        self.assertEqual(mapper.GetLastInputAccelerationMode(1),
                         vtkPARCVolumeMapper.ACCELERATION_DEPTH_BUFFER)
        self.assertTrue((ray_image(mapper) == both).all(), "the passes change no bit")

    def test_blend_mode_per_port(self):
        mapper = vtkPARCVolumeMapper()
        mapper.SetInputBlendMode(1, vtkVolumeMapper.MAXIMUM_INTENSITY_BLEND)
        self.assertEqual(mapper.GetInputBlendMode(1), vtkVolumeMapper.MAXIMUM_INTENSITY_BLEND)
        self.assertEqual(mapper.GetInputBlendMode(2), vtkVolumeMapper.COMPOSITE_BLEND)
        mapper.SetInputBlendMode(0, vtkVolumeMapper.ISOSURFACE_BLEND)
        self.assertEqual(mapper.GetBlendMode(), vtkVolumeMapper.ISOSURFACE_BLEND)


if __name__ == "__main__":
    unittest.main()
