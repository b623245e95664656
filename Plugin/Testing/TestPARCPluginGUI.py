"""The PARC plugin in the ParaView GUI: run as paraview --script=TestPARCPluginGUI.py --exit
with the environment variables PARC_PLUGIN, PARC_DATA_DIR and PARC_RESULT (a file), and
this folder on PYTHONPATH (the GUI runs a script without its __file__). The
GUI's exit status does not tell a script's failure, so the script writes "ok" or what
failed to PARC_RESULT; scripts/paraview.sh reads it.
"""
import os

from paraview.simple import GetActiveViewOrCreate, LoadPlugin, Render
from parc_pvtesting import GREY, NEGHIP_OPACITY, read_raw_volume, show_volume

result = os.environ["PARC_RESULT"]
data = os.path.join(os.environ["PARC_DATA_DIR"], "neghip_64x64x64_uint8.raw")
failures = []
if os.path.exists(data):
    LoadPlugin(os.environ["PARC_PLUGIN"], ns=globals())
    reader = read_raw_volume(data, (64, 64, 64))
    view = GetActiveViewOrCreate("RenderView")
    display = show_volume(reader, view, GREY, NEGHIP_OPACITY)
    display.SetRepresentationType("PARC Volume")
    display.PARCAccelerationMode = "Depth Buffer"
    Render(view)
    display.UpdatePropertyInformation()
    representation = display.GetPropertyValue("Representation")
    samples = display.GetPropertyValue("PARCLastSampleCount")
    mode = display.GetPropertyValue("PARCLastAccelerationMode")
    print("GUI: representation %s, %d samples, acceleration %s" % (representation, samples,
                                                                   mode))
    if representation != "PARC Volume" or not samples > 0 or mode != "DepthBuffer":
        failures.append("the GUI did not render with the PARC mapper (%s, %d samples, %s)"
                        % (representation, samples, mode))
else:
    print("skipped: %s not found" % data)
with open(result, "w") as out:
    out.write("\n".join(failures) if failures else "ok")
