"""Times of the "PARC Volume" representation beside ParaView's own "Volume" representation
in pvbatch, on 1 rank or several (mpiexec -np N pvbatch), on a real volume. Not a test: it
prints a Markdown table of render times measured side by side in one run, one view per
mapper, frames interleaved (A B C A B C) as the camera turns, minimum and median.

Usage: pvbatch BenchmarkPARCPlugin.py PLUGIN DATA_DIR [ROUNDS]
"""
import os
import platform
import statistics
import sys
import time

from paraview.simple import CreateRenderView, LoadPlugin, Render
from paraview import servermanager

from parc_pvtesting import read_raw_volume, show_volume

plugin, data_dir = sys.argv[1:3]
rounds = int(sys.argv[3]) if len(sys.argv) > 3 else 7
DATA_NAME = "embryo_256x256x256_uint8.raw"
data = os.path.join(data_dir, DATA_NAME)
if not os.path.exists(data):
    print("skipped: %s not found" % data)
    sys.exit(0)
LoadPlugin(plugin, ns=globals())
ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()
cores = os.cpu_count() or 1
threads = max(1, cores // ranks)  # each rank's share of the cores
SIZE = 500
STEP_DEGREES = 5.0

reader = read_raw_volume(data, (256, 256, 256))
SKIN = [0, 0.3, 0.2, 0.1, 90, 0.95, 0.75, 0.55, 255, 1, 1, 1]
OPACITY = [0, 0, 0.5, 0, 60, 0, 0.5, 0, 100, 0.6, 0.5, 0, 255, 1, 0.5, 0]

MAPPERS = [("ParaView Volume", "Volume", {}),
           ("PARC Volume, Auto", "PARC Volume", {"PARCAccelerationMode": "Auto"}),
           ("PARC Volume, None", "PARC Volume", {"PARCAccelerationMode": "None"})]
views = []
for name, representation, settings in MAPPERS:
    view = CreateRenderView()
    view.ViewSize = [SIZE, SIZE]
    view.OrientationAxesVisibility = 0
    display = show_volume(reader, view, SKIN, OPACITY)
    display.Shade = 1
    display.SetRepresentationType(representation)
    for key, value in settings.items():
        setattr(display, key, value)
    if representation == "PARC Volume":
        display.PARCNumberOfThreads = threads
    Render(view)  # first frame: uploads, classification, a camera reset; not timed
    view.CameraPosition = [-250, 600, 450]
    view.CameraFocalPoint = [127.5, 127.5, 127.5]
    view.CameraViewUp = [0, 0, 1]
    views.append((name, view))

times = {name: [] for name, _ in views}
for _ in range(rounds):
    for name, view in views:
        view.GetActiveCamera().Azimuth(STEP_DEGREES)
        start = time.perf_counter()
        Render(view)
        times[name].append(time.perf_counter() - start)

model = "unknown"
try:
    with open("/proc/cpuinfo") as cpuinfo:
        model = next(line.split(":", 1)[1].strip() for line in cpuinfo
                     if line.startswith("model name"))
except (OSError, StopIteration):
    pass
print("\n### %d rank%s\n" % (ranks, "" if ranks == 1 else "s"))
print("- machine: %s, %d cores, %s; %s"
      % (model, cores, platform.platform(),
         servermanager.vtkSMProxyManager.GetParaViewSourceVersion()))
print("- data: %s (composite, shaded, opacity 0 below 60, 0.6 at 100, 1 at 255)" % DATA_NAME)
print("- view %dx%d, camera turned %.0f degrees a frame, %d frames a mapper after one untimed,"
      " interleaved; PARC with %d thread%s a rank" % (SIZE, SIZE, STEP_DEGREES, rounds, threads,
                                                      "" if threads == 1 else "s"))
print()
print("| mapper | min (s) | median (s) | median / ParaView's |")
print("|---|---|---|---|")
reference = statistics.median(times[MAPPERS[0][0]])
for name, _ in views:
    median = statistics.median(times[name])
    print("| %s | %.3f | %.3f | %.2f |" % (name, min(times[name]), median, median / reference))
