"""Helpers shared by the plugin's pvbatch, pvpython and GUI scripts."""
from paraview.simple import (ColorBy, GetColorTransferFunction, GetOpacityTransferFunction,
                             ImageReader, Show)

# The neghip scene of the tests: grey colours, opaque from 80 up.
GREY = [0, 0, 0, 0, 255, 1, 1, 1]
NEGHIP_OPACITY = [0, 0, 0.5, 0, 40, 0, 0.5, 0, 80, 1, 0.5, 0, 255, 1, 0.5, 0]
# A faint blue cloud of the same volume, for the scenes of two volumes.
CLOUD_COLORS = [0, 0.2, 0.4, 1, 255, 0.2, 0.4, 1]
CLOUD_OPACITY = [0, 0, 0.5, 0, 20, 0, 0.5, 0, 40, 0.03, 0.5, 0, 255, 0.03, 0.5, 0]


def read_raw_volume(path, dimensions, array_name="density"):
    """A reader of a raw unsigned char volume of the given dimensions, updated."""
    reader = ImageReader(FileNames=[path])
    reader.DataScalarType = "unsigned char"
    reader.DataExtent = [0, dimensions[0] - 1, 0, dimensions[1] - 1, 0, dimensions[2] - 1]
    reader.ScalarArrayName = array_name
    reader.UpdatePipeline()
    return reader


def show_volume(reader, view, rgb_points, opacity_points, array_name="density",
                association="POINTS"):
    """reader's display in view, coloured by its array array_name (of points, or of cells)
    with these transfer functions, one opacity unit per world unit. The lookup table and
    opacity function are set on the display explicitly: ColorBy alone leaves it without
    them."""
    display = Show(reader, view)
    ColorBy(display, (association, array_name))
    colors = GetColorTransferFunction(array_name)
    colors.RGBPoints = rgb_points
    opacity = GetOpacityTransferFunction(array_name)
    opacity.Points = opacity_points
    display.LookupTable = colors
    display.ScalarOpacityFunction = opacity
    display.ScalarOpacityUnitDistance = 1.0
    return display
