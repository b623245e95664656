"""Helpers shared by the Python tests."""
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPiecewiseFunction
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkRenderingCore import (vtkColorTransferFunction, vtkRenderWindow,
                                         vtkRenderer, vtkVolume, vtkVolumeProperty)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the render window's implementation)


def ray_image(mapper):
    """The mapper's last float RGBA ray-cast image, as an (n, 4) numpy array."""
    image = vtkImageData()
    mapper.GetLastRayCastImage(image)
    return vtk_to_numpy(image.GetPointData().GetScalars()).copy()


def wavelet_property(transparent_below):
    """A volume property for vtkRTAnalyticSource's values (about 37..277): transparent up
    to transparent_below, then opacity rising to 0.3 and colour from blue to orange at 250."""
    opacity = vtkPiecewiseFunction()
    opacity.AddPoint(transparent_below, 0.0)
    opacity.AddPoint(250, 0.3)
    color = vtkColorTransferFunction()
    color.AddRGBPoint(transparent_below, 0.2, 0.3, 1.0)
    color.AddRGBPoint(250, 1.0, 0.8, 0.3)
    prop = vtkVolumeProperty()
    prop.SetScalarOpacity(opacity)
    prop.SetColor(color)
    return prop


def offscreen_window_showing(view_prop, size):
    """An offscreen window of size x size pixels showing view_prop (a volume, a
    multi-volume or an actor), the camera reset to it."""
    renderer = vtkRenderer()
    renderer.AddViewProp(view_prop)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(size, size)
    window.AddRenderer(renderer)
    renderer.ResetCamera()
    return window


def offscreen_window(mapper, prop, size):
    """An offscreen window of size x size pixels showing mapper's input with prop, the
    camera reset to it."""
    volume = vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    return offscreen_window_showing(volume, size)
