"""The PARC plugin in pvbatch or pvpython, on 1 rank or several (mpiexec -np N pvbatch, or
pvpython connected to mpiexec -np N pvserver): the "PARC Volume" representation against
ParaView's own "Volume" representation, and the "PARC Polygon Model" filter, on a real
volume. With several ranks the reader splits the volume into pieces, each rank renders its
piece with one layer of ghost points, and ParaView composites the pieces.

Usage: pvbatch|pvpython TestPARCPlugin.py PLUGIN DATA_DIR OUTPUT_DIR [--one-rank DIR]
       [--server HOST:PORT]
--one-rank DIR: the OUTPUT_DIR of a 1-rank run, to compare this run's images with.
--server HOST:PORT: connect to a pvserver and load the plugin there too.
Exits non-zero on failure; exits 0 saying "skipped" when the data set is absent.
"""
import argparse
import os
import sys

from paraview.simple import (Connect, CreateRenderView, Hide, LoadPlugin, PointDatatoCellData,
                             Render, SaveScreenshot, Show, Sphere)
from paraview import servermanager

from parc_pvtesting import (CLOUD_COLORS, CLOUD_OPACITY, GREY, NEGHIP_OPACITY,
                            read_raw_volume, show_volume)
from vtkmodules.vtkIOImage import vtkPNGReader

parser = argparse.ArgumentParser()
parser.add_argument("plugin")
parser.add_argument("data_dir")
parser.add_argument("out_dir")
parser.add_argument("--one-rank", dest="one_rank_dir")
parser.add_argument("--server")
arguments = parser.parse_args()
plugin, data_dir, out_dir = arguments.plugin, arguments.data_dir, arguments.out_dir
one_rank_dir = arguments.one_rank_dir
data = os.path.join(data_dir, "neghip_64x64x64_uint8.raw")
if not os.path.exists(data):
    print("skipped: %s not found" % data)
    sys.exit(0)
os.makedirs(out_dir, exist_ok=True)
if arguments.server:
    host, port = arguments.server.rsplit(":", 1)
    Connect(host, int(port))
    LoadPlugin(plugin, remote=False, ns=globals())  # the client's classes
LoadPlugin(plugin, ns=globals())  # the server's (pvbatch: its own)
ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()
print("ranks: %d%s" % (ranks, " (pvserver %s)" % arguments.server if arguments.server else ""))

SIZE = 300
# Mean absolute difference of ParaView's volume mapper and PARC, in grey levels of 255, and
# the largest share of values differing by more than 16 levels: the mappers sample and
# shade differently, so their images are close, not equal.
MEAN_TOLERANCE = 4.0
OUTLIER_TOLERANCE = 0.02
# The same between N ranks and 1 rank: the pieces take the same samples, read their
# neighbours' border points and share one colour table, but ParaView composites the ranks'
# images in 8 bits, and early ray termination stops within a piece. ParaView's own mapper
# must not come closer to its 1-rank image than PARC does.
RANKS_MEAN_TOLERANCE = 0.5
RANKS_OUTLIER_TOLERANCE = 0.001

reader = read_raw_volume(data, (64, 64, 64))

view = CreateRenderView()
view.ViewSize = [SIZE, SIZE]
view.OrientationAxesVisibility = 0
view.Background = [0, 0, 0]
try:
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass
display = show_volume(reader, view, GREY, NEGHIP_OPACITY)
opacity = display.ScalarOpacityFunction
view.CameraPosition = [150, -90, 120]
view.CameraFocalPoint = [31.5, 31.5, 31.5]
view.CameraViewUp = [0, 0, 1]


def read_png(path):
    png = vtkPNGReader()
    png.SetFileName(path)
    png.Update()
    scalars = png.GetOutput().GetPointData().GetScalars()
    return [scalars.GetValue(i) for i in range(scalars.GetNumberOfValues())], \
        scalars.GetNumberOfComponents()


def shot(name, representation, shown=None, **settings):
    """The view's image with a display (default: the density's) in representation and
    settings, written to OUTPUT_DIR/name-RANKS.png: its values and components."""
    shown = display if shown is None else shown
    shown.SetRepresentationType(representation)
    for key, value in settings.items():
        setattr(shown, key, value)
    Render(view)
    path = os.path.join(out_dir, "%s-%d.png" % (name, ranks))
    SaveScreenshot(path, view, ImageResolution=[SIZE, SIZE])
    return read_png(path)


def statistics(shown=None):
    """The PARC statistics of a display's last render (default: the density's), gathered
    from the rendering ranks: counts summed, times of the slowest rank."""
    shown = display if shown is None else shown
    shown.UpdatePropertyInformation()
    return {name: shown.GetPropertyValue("PARCLast" + name)
            for name in ("SampleCount", "RayCount", "ShadowRayCount", "AccelerationMode",
                         "RenderTime")}


def compare(a, b):
    """Mean absolute difference and share of values more than 16 levels apart."""
    differences = [abs(x - y) for x, y in zip(a, b)]
    return sum(differences) / len(differences), \
        sum(1 for d in differences if d > 16) / len(differences)


failures = []


def check(condition, message):
    print(("ok: " if condition else "FAILED: ") + message)
    if not condition:
        failures.append(message)


reference, components = shot("paraview-volume", "Volume", Shade=0)
# The reader's executions on this process from here on (pvbatch: the first rank's; a client
# of pvserver sees none).
reader_runs = [0]
if not arguments.server:
    reader.GetClientSideObject().AddObserver(
        "EndEvent", lambda *_: reader_runs.__setitem__(0, reader_runs[0] + 1))
parc_auto, _ = shot("parc-volume-auto", "PARC Volume", PARCAccelerationMode="Auto")
parc_none, _ = shot("parc-volume-none", "PARC Volume", PARCAccelerationMode="None")
unaccelerated = statistics()
if not arguments.server:
    check(reader_runs[0] == 0, "unshaded point scalars need no border layer: each rank renders "
          "the piece ParaView read to show the volume, not read again (%d reads on %d ranks)"
          % (reader_runs[0], ranks))
parc_depth, _ = shot("parc-volume-depth", "PARC Volume", PARCAccelerationMode="Depth Buffer")
accelerated = statistics()
parc_color, _ = shot("parc-volume-color", "PARC Volume", PARCAccelerationMode="Color Buffer")
parc_walk, _ = shot("parc-volume-walk", "PARC Volume", PARCAccelerationMode="Supercell Walk")
walked = statistics()
# Auto's search of the supercell size over a few frames (two a size), then a fixed size.
check(display.PARCAutoSupercellSize == 1, "Auto chooses the supercell size by default")
display.PARCAccelerationMode = "Auto"
searched = [shot("parc-volume-auto-search", "PARC Volume")[0] for _ in range(6)]
display.PARCAutoSupercellSize = 0
parc_fixed_size, _ = shot("parc-volume-fixed-size", "PARC Volume")

check(parc_auto == parc_none and parc_depth == parc_none and parc_color == parc_none and
      parc_walk == parc_none and all(s == parc_none for s in searched) and
      parc_fixed_size == parc_none,
      "PARC Volume gives the same pixels with acceleration None, Depth Buffer, Color Buffer, "
      "Supercell Walk and Auto, while Auto searches the supercell size and without it")
check(walked["AccelerationMode"] == "SupercellWalk",
      "the Supercell Walk mode reaches the mapper (%s)" % walked["AccelerationMode"])
check(accelerated["AccelerationMode"] == "DepthBuffer" and
      0 < accelerated["SampleCount"] < unaccelerated["SampleCount"],
      "depth-buffer PARC takes fewer samples (%d) than no acceleration (%d)"
      % (accelerated["SampleCount"], unaccelerated["SampleCount"]))
# Each lattice sample of a ray lies in one piece, so the ranks take every sample one rank
# takes, and more: a ray stopped by its opacity in one piece goes on in the pieces behind.
with open(os.path.join(out_dir, "samples-%d.txt" % ranks), "w") as samples_file:
    samples_file.write("%d\n" % unaccelerated["SampleCount"])
if one_rank_dir:
    with open(os.path.join(one_rank_dir, "samples-1.txt")) as samples_file:
        one_rank_samples = int(samples_file.read())
    check(one_rank_samples <= unaccelerated["SampleCount"] < 2 * one_rank_samples,
          "the %d ranks take %d samples without acceleration, at least 1 rank's %d"
          % (ranks, unaccelerated["SampleCount"], one_rank_samples))

# The ranks read their pieces with the border layers the mapper needs as ordinary cells: no
# ghost array the size of a piece is generated, cropped and scanned (tens of seconds for a
# volume of a few hundred MB).
represented = display.GetRepresentedDataInformation()
ghost_arrays = [attributes.GetArrayInformation("vtkGhostType") for attributes in
                (represented.GetPointDataInformation(), represented.GetCellDataInformation())]
check(all(array is None for array in ghost_arrays),
      "the pieces carry no ghost array on %d rank(s)" % ranks)


def lit_pixels(image):
    """The pixels brighter than 16 grey levels in some channel."""
    return sum(1 for i in range(0, len(image), components) if max(image[i:i + 3]) > 16)


lit = lit_pixels(parc_none)
check(lit > 0.05 * SIZE * SIZE, "PARC Volume draws the volume (%d lit pixels)" % lit)


def check_close(own, parc, what):
    mean, outliers = compare(own, parc)
    check(mean <= MEAN_TOLERANCE, "%s: mean difference to ParaView's Volume %.2f <= %.1f grey "
          "levels" % (what, mean, MEAN_TOLERANCE))
    check(outliers <= OUTLIER_TOLERANCE, "%s: share of values more than 16 levels off "
          "ParaView's %.4f <= %.2f" % (what, outliers, OUTLIER_TOLERANCE))


check_close(reference, parc_none, "composite")
# ParaView 5.11's other blend modes reach the mapper through the shared properties.
display.BlendMode = "Isosurface"
display.IsosurfaceValues = [60]
own, _ = shot("paraview-volume-isosurface", "Volume")
parc_iso, _ = shot("parc-volume-isosurface", "PARC Volume", PARCAccelerationMode="None")
parc_iso_auto, _ = shot("parc-volume-isosurface-auto", "PARC Volume", PARCAccelerationMode="Auto")
check(parc_iso_auto == parc_iso and parc_iso != parc_none,
      "isosurface: the same pixels with acceleration None and Auto")
check_close(own, parc_iso, "isosurface")
# Slice: the values on an oblique plane through the volume (ParaView's slice function).
display.BlendMode = "Slice"
for plane in (display.SliceFunction, display.PARCSliceFunction):  # Volume's, PARC Volume's
    plane.Origin = [31.5, 31.5, 35.0]
    plane.Normal = [0.2, 0.3, 1.0]
own_slice, _ = shot("paraview-volume-slice", "Volume")
parc_slice, _ = shot("parc-volume-slice", "PARC Volume", PARCAccelerationMode="None")
parc_slice_auto, _ = shot("parc-volume-slice-auto", "PARC Volume", PARCAccelerationMode="Auto")
lit = lit_pixels(parc_slice)
check(parc_slice_auto == parc_slice and lit > 0.01 * SIZE * SIZE,
      "slice: %d lit pixels, the same with acceleration None and Auto" % lit)
check_close(own_slice, parc_slice, "slice")
display.BlendMode = "Composite"
# Shaded (the two mappers shade differently, so not compared with each other): gradients at
# piece borders read the ghost points.
reader_runs[0] = 0
shaded, _ = shot("parc-volume-shaded", "PARC Volume", Shade=1, PARCAccelerationMode="None")
if not arguments.server:
    check((reader_runs[0] > 0) == (ranks > 1), "shading asks for the border layer: %d reads "
          "of the pieces on %d ranks (none on 1, the whole volume)" % (reader_runs[0], ranks))
shaded_auto, _ = shot("parc-volume-shaded-auto", "PARC Volume", PARCAccelerationMode="Auto")
own_shaded, _ = shot("paraview-volume-shaded", "Volume")
check(shaded_auto == shaded and shaded != parc_none,
      "shaded PARC Volume gives the same pixels with acceleration None and Auto")
if ranks == 1:  # a rank's piece of the 64^3 volume is thinner than a brick: not copied
    bricked, _ = shot("parc-volume-shaded-bricked", "PARC Volume", PARCBrickedCopy=1)
    display.PARCBrickedCopy = 0
    check(bricked == shaded_auto, "PARCBrickedCopy gives the same pixels")
check(statistics()["ShadowRayCount"] == 0, "no shadow ray without PARCShadows")
shadowed, _ = shot("parc-volume-shadows", "PARC Volume", PARCShadows=1,
                   PARCAccelerationMode="None")
shadow_rays = statistics()["ShadowRayCount"]
shadowed_auto, _ = shot("parc-volume-shadows-auto", "PARC Volume", PARCAccelerationMode="Auto")
check(shadow_rays > 0 and shadowed != shaded and shadowed_auto == shadowed,
      "PARCShadows darkens the image (%d shadow rays), with the same pixels with acceleration "
      "None and Auto" % shadow_rays)
display.PARCShadows = 0


def against_one_rank(name, image):
    return compare(read_png(os.path.join(one_rank_dir, name + "-1.png"))[0], image)


def check_like_one_rank(name, image, what):
    """Checks image against the 1-rank run's image of the same name, within the ranks'
    tolerances."""
    mean, outliers = against_one_rank(name, image)
    check(mean <= RANKS_MEAN_TOLERANCE and outliers <= RANKS_OUTLIER_TOLERANCE,
          "%s on %d ranks: mean difference to 1 rank %.3f <= %.1f grey levels, %.5f of "
          "values more than 16 levels off" % (what, ranks, mean, RANKS_MEAN_TOLERANCE, outliers))


if one_rank_dir:
    mean, outliers = against_one_rank("parc-volume-shaded", shaded)
    own_mean, own_outliers = against_one_rank("paraview-volume-shaded", own_shaded)
    check(mean <= RANKS_MEAN_TOLERANCE,
          "mean difference of %d ranks to 1 rank, shaded, %.3f <= %.1f grey levels "
          "(ParaView's Volume: %.3f)" % (ranks, mean, RANKS_MEAN_TOLERANCE, own_mean))
    check(outliers <= RANKS_OUTLIER_TOLERANCE,
          "share of values more than 16 levels off 1 rank's %.5f <= %.3f (ParaView's "
          "Volume: %.5f)" % (outliers, RANKS_OUTLIER_TOLERANCE, own_outliers))
    check(mean <= own_mean and outliers <= own_outliers,
          "PARC's %d-rank image is as close to its 1-rank image as ParaView's Volume's" % ranks)
    # Shadow rays cross the other ranks' pieces, which each rank reads as border layers.
    check_like_one_rank("parc-volume-shadows", shadowed, "shadows")

# Several volumes: an opaque isosurface of the density and a faint cloud of a second copy
# of it (its own array name, so its own transfer functions), both "PARC Volume": the view
# renders them together, every ray meeting both, so the cloud shows in front of the surface
# and not behind it. The copy lies on the same grid, so the ranks split both alike.
display.BlendMode = "Isosurface"
display.IsosurfaceValues = [60]
surface_before = shot("parc-scene-surface-before", "PARC Volume", PARCAccelerationMode="None")[0]
cloud_reader = read_raw_volume(data, (64, 64, 64), "cloud")
cloud = show_volume(cloud_reader, view, CLOUD_COLORS, CLOUD_OPACITY, "cloud")
cloud.SetRepresentationType("PARC Volume")


def scene_shot(name, surface_visible, cloud_visible, mode):
    """The view with the surface and the cloud shown or hidden, both in acceleration mode,
    and the statistics of the surface's last render and the cloud's."""
    display.Visibility = surface_visible
    cloud.Visibility = cloud_visible
    for shown in (display, cloud):
        shown.PARCAccelerationMode = mode
    image = shot(name, "PARC Volume")[0]
    return image, statistics(), statistics(cloud)


together, together_statistics, _ = scene_shot("parc-scene-none", 1, 1, "None")
together_auto, auto_statistics, _ = scene_shot("parc-scene-auto", 1, 1, "Auto")
surface_alone, surface_statistics, _ = scene_shot("parc-scene-surface", 1, 0, "None")
cloud_alone, _, cloud_statistics = scene_shot("parc-scene-cloud", 0, 1, "None")
cloud.Visibility = 0
display.Visibility = 1
check(together_auto == together, "two PARC volumes together: the same pixels with "
      "acceleration None and Auto")
check(together != surface_alone and together != cloud_alone,
      "the image of both differs from each one's alone")
surface_again = shot("parc-scene-surface-again", "PARC Volume")[0]
check(surface_alone == surface_before and surface_again == surface_before,
      "with the cloud hidden, the surface renders alone, as before the cloud was shown")
surface_samples = surface_statistics["SampleCount"]
cloud_samples = cloud_statistics["SampleCount"]
both = together_statistics["SampleCount"]
check(surface_samples <= both < surface_samples + cloud_samples,
      "both volumes are cast in one pass (%d samples), stopping behind the surface: fewer "
      "than the surface's %d and the cloud's %d alone" % (both, surface_samples, cloud_samples))
check(auto_statistics["SampleCount"] < both,
      "Auto takes fewer samples (%d) for the two volumes" % auto_statistics["SampleCount"])
if one_rank_dir:
    check_like_one_rank("parc-scene-none", together, "two volumes")
display.BlendMode = "Composite"

# A translucent sphere beside the volume: the view peels its translucent geometry (for
# volumes too, ParaView's default, with shader code only VTK's GPU mapper has): the PARC
# volume is drawn after the peels, the same in every frame and on every rank count.
sphere = Sphere(Center=[50, 32, 40], Radius=18, ThetaResolution=32, PhiResolution=32)
sphere_display = Show(sphere, view)
sphere_display.Opacity = 0.4
own_translucent = shot("paraview-volume-translucent", "Volume")[0]
translucent = shot("parc-volume-translucent", "PARC Volume", PARCAccelerationMode="Depth Buffer")[0]
translucent_again = shot("parc-volume-translucent-again", "PARC Volume")[0]
check(translucent == translucent_again and translucent != parc_depth,
      "with a translucent sphere: the same image in two frames, the sphere in it")
if one_rank_dir:
    # The ranks composite the sphere's peeled layers too: ParaView's own volume's image
    # moves as much between rank counts.
    mean, outliers = against_one_rank("parc-volume-translucent", translucent)
    own_mean, own_outliers = against_one_rank("paraview-volume-translucent", own_translucent)
    check(mean <= max(RANKS_MEAN_TOLERANCE, own_mean) and
          outliers <= max(RANKS_OUTLIER_TOLERANCE, own_outliers),
          "translucent sphere on %d ranks: mean difference to 1 rank %.3f, %.5f of values "
          "more than 16 levels off (ParaView's Volume: %.3f, %.5f)" % (
              ranks, mean, outliers, own_mean, own_outliers))
Hide(sphere, view)

# Cell scalars (the density averaged to cells): the mapper interpolates between the cells'
# centres, so each rank's piece carries two layers of its neighbours' cells, and the N-rank
# image is the 1-rank one, without acceleration and in Auto alike.
cell_values = PointDatatoCellData(Input=reader)
display.Visibility = 0
cells_display = show_volume(cell_values, view, GREY, NEGHIP_OPACITY, "density", "CELLS")
cells_none = shot("parc-volume-cells-none", "PARC Volume", cells_display,
                  PARCAccelerationMode="None")[0]
cells_auto = shot("parc-volume-cells-auto", "PARC Volume", cells_display,
                  PARCAccelerationMode="Auto")[0]
check(cells_auto == cells_none and cells_none != parc_none and
      lit_pixels(cells_none) > 0.5 * lit_pixels(parc_none),
      "cell scalars: the same pixels with acceleration None and Auto, an image of its own "
      "(%d lit pixels, the point scalars' %d)" % (lit_pixels(cells_none), lit_pixels(parc_none)))
if one_rank_dir:
    check_like_one_rank("parc-volume-cells-none", cells_none, "cell scalars")
Hide(cell_values, view)
display.Visibility = 1

# The filter, with the same opacity function.
model = PARCPolygonModel(Input=reader)  # noqa: F821 (defined by LoadPlugin)
# Named: the property's default is the array coloured last ("cloud"), not one of the input's.
model.Scalars = ["POINTS", "density"]
model.ScalarOpacityFunction = opacity
model.UpdatePipeline()
polygons = servermanager.Fetch(model)
fields = polygons.GetFieldData()
check(polygons.GetNumberOfCells() > 0,
      "the polygon model has %d quads" % polygons.GetNumberOfCells())
if ranks == 1:  # Fetch appends the ranks' models; each rank's field data counts its own
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

# On success the script ends without sys.exit: in pvbatch that frees the view's GL resources
# after its context is gone (an X error, status 1) and, on several ranks, leaves the other
# ranks' MPI unfinalized.
if failures:
    sys.exit(1)
