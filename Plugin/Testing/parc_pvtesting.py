"""Helpers shared by the plugin's pvbatch scripts."""
from paraview.simple import ImageReader


def read_raw_volume(path, dimensions, array_name="density"):
    """A reader of a raw unsigned char volume of the given dimensions, updated."""
    reader = ImageReader(FileNames=[path])
    reader.DataScalarType = "unsigned char"
    reader.DataExtent = [0, dimensions[0] - 1, 0, dimensions[1] - 1, 0, dimensions[2] - 1]
    reader.ScalarArrayName = array_name
    reader.UpdatePipeline()
    return reader
