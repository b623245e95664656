"""ParaView's stock "Volume" representation rendered through PARC by the object-factory
override, with PARC_OVERRIDE_GPU_MAPPER=1 read when the plugin loads (pvbatch, 1 or N ranks).
A representation made before the plugin loaded keeps VTK's GPU mapper; one made after it
renders through PARC: its image differs from the GPU mapper's and is within the plugin
test's tolerance of the "PARC Volume" representation's.

Usage: PARC_OVERRIDE_GPU_MAPPER=1 pvbatch TestPARCPluginOverride.py PLUGIN DATA_DIR OUTPUT_DIR
"""
import os
import sys

from paraview.simple import CreateRenderView, Delete, LoadPlugin, Render, SaveScreenshot
from paraview import servermanager
from vtkmodules.vtkIOImage import vtkPNGReader

from parc_pvtesting import GREY, NEGHIP_OPACITY, read_raw_volume, show_volume

plugin, data, out_dir = sys.argv[1:4]
os.makedirs(out_dir, exist_ok=True)
SIZE = 200
# Mean absolute difference of ParaView's volume mapper and PARC, grey levels of 255, as in
# TestPARCPlugin.py.
MEAN_TOLERANCE = 4.0
failures = []


def check(condition, message):
    print(("ok: " if condition else "FAILED: ") + message)
    if not condition:
        failures.append(message)


def shot(reader, name, representation):
    """The volume in a new view with its representation type; the screenshot's values."""
    view = CreateRenderView()
    view.ViewSize = [SIZE, SIZE]
    view.OrientationAxesVisibility = 0
    display = show_volume(reader, view, GREY, NEGHIP_OPACITY)
    display.SetRepresentationType(representation)
    view.CameraPosition = [150, -90, 120]
    view.CameraFocalPoint = [31.5, 31.5, 31.5]
    view.CameraViewUp = [0, 0, 1]
    Render(view)
    ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()
    path = os.path.join(out_dir, "%s-%d.png" % (name, ranks))
    SaveScreenshot(path, view, ImageResolution=[SIZE, SIZE])
    Delete(view)
    png = vtkPNGReader()
    png.SetFileName(path)
    png.Update()
    scalars = png.GetOutput().GetPointData().GetScalars()
    return [scalars.GetValue(i) for i in range(scalars.GetNumberOfValues())]


def mean_difference(a, b):
    return sum(abs(x - y) for x, y in zip(a, b)) / len(a)


check(os.environ.get("PARC_OVERRIDE_GPU_MAPPER") == "1", "PARC_OVERRIDE_GPU_MAPPER is 1")
reader = read_raw_volume(os.path.join(data, "neghip_64x64x64_uint8.raw"), (64, 64, 64))
gpu = shot(reader, "override-before-plugin", "Volume")  # VTK's GPU mapper
LoadPlugin(plugin, ns=globals())
overridden = shot(reader, "override-volume", "Volume")
parc = shot(reader, "override-parc-volume", "PARC Volume")
check(overridden != gpu, "with the plugin loaded, the stock Volume's pixels change "
      "(mean difference to VTK's GPU mapper %.3f)" % mean_difference(overridden, gpu))
check(mean_difference(overridden, parc) <= MEAN_TOLERANCE,
      "the stock Volume through PARC is within %.1f grey levels of PARC Volume's image "
      "(%.3f)" % (MEAN_TOLERANCE, mean_difference(overridden, parc)))
# Without sys.exit on success, as TestPARCPlugin.py ends (pvbatch and MPI end cleanly then).
if failures:
    sys.exit(1)
