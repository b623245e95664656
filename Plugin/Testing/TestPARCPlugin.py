"""The PARC plugin in pvbatch: the "PARC Volume" representation against ParaView's own
"Volume" representation, and the "PARC Polygon Model" filter, on a real volume.

Usage: pvbatch TestPARCPlugin.py PLUGIN DATA_DIR OUTPUT_DIR
Exits non-zero on failure; exits 0 saying "skipped" when the data set is absent.
"""
import os
import sys

from paraview.simple import (CreateRenderView, GetOpacityTransferFunction, ImageReader,
                             LoadPlugin, Render, SaveScreenshot, Show)
from paraview import servermanager
from vtkmodules.vtkIOImage import vtkPNGReader

plugin, data_dir, out_dir = sys.argv[1:4]
data = os.path.join(data_dir, "neghip_64x64x64_uint8.raw")
if not os.path.exists(data):
    print("skipped: %s not found" % data)
    sys.exit(0)
os.makedirs(out_dir, exist_ok=True)
LoadPlugin(plugin, ns=globals())

SIZE = 300
# Mean absolute difference of ParaView's volume mapper and PARC, in grey levels of 255, and
# the largest share of pixels differing by more than 16 levels: the mappers sample and
# shade differently, so their images are close, not equal.
MEAN_TOLERANCE = 4.0
OUTLIER_TOLERANCE = 0.02

reader = ImageReader(FileNames=[data])
reader.DataScalarType = "unsigned char"
reader.DataExtent = [0, 63, 0, 63, 0, 63]
reader.ScalarArrayName = "density"
reader.UpdatePipeline()

view = CreateRenderView()
view.ViewSize = [SIZE, SIZE]
view.OrientationAxesVisibility = 0
view.Background = [0, 0, 0]
try:
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass
display = Show(reader, view)
display.ColorArrayName = ["POINTS", "density"]
opacity = GetOpacityTransferFunction("density")
opacity.Points = [0, 0, 0.5, 0, 40, 0, 0.5, 0, 80, 1, 0.5, 0, 255, 1, 0.5, 0]
display.ScalarOpacityUnitDistance = 1.0
view.CameraPosition = [150, -90, 120]
view.CameraFocalPoint = [31.5, 31.5, 31.5]
view.CameraViewUp = [0, 0, 1]


def shot(name, representation, **settings):
    display.SetRepresentationType(representation)
    for key, value in settings.items():
        setattr(display, key, value)
    Render(view)
    path = os.path.join(out_dir, name + ".png")
    SaveScreenshot(path, view, ImageResolution=[SIZE, SIZE])
    reader_png = vtkPNGReader()
    reader_png.SetFileName(path)
    reader_png.Update()
    scalars = reader_png.GetOutput().GetPointData().GetScalars()
    return [scalars.GetValue(i) for i in range(scalars.GetNumberOfValues())], \
        scalars.GetNumberOfComponents()


failures = []


def check(condition, message):
    print(("ok: " if condition else "FAILED: ") + message)
    if not condition:
        failures.append(message)


reference, components = shot("paraview-volume", "Volume")
parc_auto, _ = shot("parc-volume-auto", "PARC Volume", PARCAccelerationMode="Auto")
parc_none, _ = shot("parc-volume-none", "PARC Volume", PARCAccelerationMode="None")
parc_depth, _ = shot("parc-volume-depth", "PARC Volume", PARCAccelerationMode="Depth Buffer")

check(parc_auto == parc_none and parc_depth == parc_none,
      "PARC Volume gives the same pixels with acceleration None, Depth Buffer and Auto")
lit = sum(1 for i in range(0, len(parc_none), components) if max(parc_none[i:i + 3]) > 16)
check(lit > 0.05 * SIZE * SIZE, "PARC Volume draws the volume (%d lit pixels)" % lit)
differences = [abs(a - b) for a, b in zip(reference, parc_none)]
mean = sum(differences) / len(differences)
outliers = sum(1 for d in differences if d > 16) / len(differences)
check(mean <= MEAN_TOLERANCE,
      "mean difference to ParaView's Volume %.2f <= %.1f grey levels" % (mean, MEAN_TOLERANCE))
check(outliers <= OUTLIER_TOLERANCE,
      "share of values more than 16 levels off %.4f <= %.2f" % (outliers, OUTLIER_TOLERANCE))

# The filter, with the same opacity function.
model = PARCPolygonModel(Input=reader)  # noqa: F821 (defined by LoadPlugin)
model.ScalarOpacityFunction = opacity
model.UpdatePipeline()
polygons = servermanager.Fetch(model)
fields = polygons.GetFieldData()
check(polygons.GetNumberOfCells() > 0, "the polygon model has %d quads" % polygons.GetNumberOfCells())
check(fields.GetArray("Polygons").GetValue(0) == polygons.GetNumberOfCells(),
      "its Polygons count is its number of quads")
bounds = polygons.GetBounds()
check(all(bounds[2 * a] >= 0 and bounds[2 * a + 1] <= 63 for a in range(3)),
      "its quads lie in the volume's box")
# Raising the opacity threshold can only remove contributing supercells.
opacity.Points = [0, 0, 0.5, 0, 120, 0, 0.5, 0, 200, 0.3, 0.5, 0, 255, 0.8, 0.5, 0]
model.UpdatePipeline()
fewer = servermanager.Fetch(model).GetFieldData().GetArray("ContributingSupercells").GetValue(0)
more = fields.GetArray("ContributingSupercells").GetValue(0)
check(0 < fewer < more, "a narrower opacity function leaves fewer contributing supercells "
      "(%d < %d)" % (fewer, more))

sys.exit(1 if failures else 0)
