"""Helpers shared by the Python tests."""
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkRenderingCore import vtkRenderWindow, vtkRenderer, vtkVolume
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the render window's implementation)


def ray_image(mapper):
    """The mapper's last float RGBA ray-cast image, as an (n, 4) numpy array."""
    image = vtkImageData()
    mapper.GetLastRayCastImage(image)
    return vtk_to_numpy(image.GetPointData().GetScalars()).copy()


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
