"""Helpers shared by the Python tests."""
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.util.numpy_support import vtk_to_numpy


def ray_image(mapper):
    """The mapper's last float RGBA ray-cast image, as an (n, 4) numpy array."""
    image = vtkImageData()
    mapper.GetLastRayCastImage(image)
    return vtk_to_numpy(image.GetPointData().GetScalars()).copy()
