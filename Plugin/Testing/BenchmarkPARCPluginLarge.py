"""A large volume through the plugin in pvbatch, on 1 rank or several (mpiexec -np N
pvbatch): the "PARC Volume" representation in Auto renders a raw uint8 volume of 1.5-2 GB,
each rank reading and rendering its piece. Not a test: it prints the first frame, the
median and minimum of warm frames as the camera turns, and writes a screenshot that
scripts/paraview.sh compares across rank counts. Each rank's peak memory is printed by
/usr/bin/time around pvbatch.

Usage: pvbatch BenchmarkPARCPluginLarge.py PLUGIN RAW NX NY NZ SCREENSHOT [ROUNDS]
"""
import os
import statistics
import sys
import time

from paraview.simple import CreateRenderView, LoadPlugin, Render, SaveScreenshot
from paraview import servermanager

from parc_pvtesting import read_raw_volume, show_volume

plugin, raw = sys.argv[1:3]
dims = tuple(int(v) for v in sys.argv[3:6])
screenshot = sys.argv[6]
rounds = int(sys.argv[7]) if len(sys.argv) > 7 else 5
LoadPlugin(plugin, ns=globals())
ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()
threads = max(1, (os.cpu_count() or 1) // ranks)
SIZE = 600
STEP_DEGREES = 3.0
# parc-render's "mri" transfer function (scalar range 0-255): skin and tissue translucent.
COLOURS = [0, 0, 0, 0, 38, 0.55, 0.25, 0.15, 89, 0.85, 0.55, 0.45, 153, 0.95, 0.85, 0.75,
           255, 1, 1, 0.95]
OPACITY = [0, 0, 0.5, 0, 38, 0, 0.5, 0, 89, 0.04, 0.5, 0, 153, 0.12, 0.5, 0, 255, 0.5, 0.5, 0]

start = time.perf_counter()
reader = read_raw_volume(raw, dims)
read_seconds = time.perf_counter() - start
view = CreateRenderView()
view.ViewSize = [SIZE, SIZE]
view.OrientationAxesVisibility = 0
display = show_volume(reader, view, COLOURS, OPACITY)
display.SetRepresentationType("PARC Volume")
display.PARCAccelerationMode = "Auto"
display.PARCNumberOfThreads = threads
centre = [0.5 * (d - 1) for d in dims]
view.CameraFocalPoint = centre
view.CameraPosition = [centre[0], centre[1] - 2.5 * dims[1], centre[2]]
view.CameraViewUp = [0, 0, 1]
start = time.perf_counter()
Render(view)
first = time.perf_counter() - start
for _ in range(12):  # Auto's trials and its supercell search
    Render(view)
times = []
for _ in range(rounds):
    view.GetActiveCamera().Azimuth(STEP_DEGREES)
    start = time.perf_counter()
    Render(view)
    times.append(time.perf_counter() - start)
for _ in range(rounds):
    view.GetActiveCamera().Azimuth(-STEP_DEGREES)
Render(view)
SaveScreenshot(screenshot, view, ImageResolution=[SIZE, SIZE])
display.UpdatePropertyInformation()
print("| %d | %d | %.1f | %.2f | %.2f | %.3f | %.3f | %s | %d |" % (
    ranks, threads, os.path.getsize(raw) / 2**20, read_seconds, first, min(times),
    statistics.median(times), display.GetPropertyValue("PARCLastAccelerationMode"),
    display.GetPropertyValue("PARCLastSampleCount")))
