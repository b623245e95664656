#!/usr/bin/python3
"""Cost as the volume grows (scripts/benchmark.sh; run under Xvfb with the build's Python
packages on PYTHONPATH): the MRI head of mricron-data resized (vtkImageResize, trilinear)
by factors up to 1.5-2 GB, as uint8 and as CT-like int16 (12 v - 1024), rendered unshaded
and shaded by this mapper (Auto) and vtkFixedPointVolumeRayCastMapper (automatic adjustment
off) at half a voxel, in a perspective view. For each volume and shading:

- first frame: each mapper new, in a process of its own and a window whose GL context
  exists, in rounds interleaved (A B A B): minimum and median; and this mapper's set-up
  per voxel (its median first frame less its median warm one);
- warm frames at each image size: both mappers warmed up (this one until Auto has chosen
  its pass and supercell size), then rounds interleaved (A B A B): minimum and median
  (3 rounds, 7 below 128 MiB);
- the same warm frames of this mapper with a copy of the scalars in bricks (BrickedCopy),
  a third mapper in the same rounds (A B C A B C), its casting cost against the head's and
  its GetMemorySize; and once in a process of its own, its first frame (the copy's build
  included) and the resident size its 5 frames add beside its GetMemorySize;
- the frame after a transfer-function edit against a warm frame (this mapper);
- this mapper's casting cost in warm frames (ns per thread: per sample, per sample taken,
  per contributing sample; medians), mode and supercell size; and against the head's own
  size of the same type (x1), whose warm frames, in the same process and window, take
  turns with the volume's at the first image size: the median of the rounds' ratios;
- memory, in the first frame's processes: the resident size 5 frames add (after the
  window's GL context is made) against the volume's bytes, beside GetMemorySize (medians
  over the rounds); and once more in a process whose window has drawn the volume's outline
  first, as a program showing anything else has: the GL implementation's start-up (its
  first compiled program, about 25 MiB on llvmpipe, whichever drawing comes first) is then
  paid before the mapper, and the growth is what the mapper's render adds; beside it, in
  the same way, this mapper without acceleration (no acceleration structure at all) and a
  picture of the window's size shown alone by a vtkImageActor: the floor under any mapper.

Prints markdown; writes CSV data and PNG plots into OUTDIR. The resized volumes are kept in
OUTDIR/volumes while the section runs and removed after.

  benchmark_volume_size.py OUTDIR [--quick] [--only=uint8:3,4;int16:3] [--images=600,1000]
  benchmark_volume_size.py OUTDIR --from=OUTDIR/volume-size.json   (the report of a saved run)
"""
import gc
import json
import os
import shutil
import subprocess
import sys
import time

import numpy as np

HEAD = "/usr/share/mricron/templates/ch2.nii.gz"
HEAD_DIMS = (181, 217, 181)
FACTORS = {"uint8": [1, 2, 3, 4, 6], "int16": [1, 2, 3, 5]}
QUICK_FACTORS = {"uint8": [1, 2], "int16": [1]}
IMAGES, QUICK_IMAGES = [600, 1000], [600]
ROUNDS, QUICK_ROUNDS = 3, 2
# Volumes below this size render in well under a second, where the shared machine's noise
# moves a ratio most: more rounds there (not in a quick run).
SMALL_VOLUME_BYTES, SMALL_VOLUME_ROUNDS = 2**27, 7
# The casting costs of a warm frame (sample_costs), in the tables' order.
SAMPLE_COSTS = ("ns_per_sample", "ns_per_sample_taken", "ns_per_contributing_sample")
WARM_UP_FRAMES = 20  # enough for Auto's trials and its supercell search
MEMORY_FRAMES = 5
# The renders measured after a drawn outline: the mappers (new_mapper) and, as the floor
# under them all, a picture of the window's size alone (show_picture).
OUTLINED = ("fixed", "parc", "none", "picture")
CT_SCALE, CT_OFFSET = 12, -1024  # int16 = 12 * uint8 - 1024: a CT-like range


def volume_dims(factor):
    """The voxels of the head resized by factor, per axis."""
    return [factor * (d - 1) + 1 for d in HEAD_DIMS]


def volume_path(outdir, factor, kind):
    return os.path.join(outdir, "volumes", "head-x%d-%s.npy" % (factor, kind))


def make_volume(outdir, factor, kind):
    """Resizes the head by factor into a .npy of its scalars (x fastest)."""
    from vtkmodules.vtkIOImage import vtkNIFTIImageReader
    from vtkmodules.vtkImagingCore import vtkImageResize
    from vtkmodules.util.numpy_support import vtk_to_numpy
    reader = vtkNIFTIImageReader()
    reader.SetFileName(HEAD)
    resize = vtkImageResize()
    resize.SetInputConnection(reader.GetOutputPort())
    resize.SetResizeMethodToMagnificationFactors()
    resize.SetMagnificationFactors(factor, factor, factor)
    resize.Update()
    values = vtk_to_numpy(resize.GetOutput().GetPointData().GetScalars())
    if kind == "int16":
        values = values.astype(np.int16) * CT_SCALE + CT_OFFSET
    np.save(volume_path(outdir, factor, kind), values.astype(kind))


def load_image(outdir, factor, kind):
    """The resized head as vtkImageData (spacing 1/factor: the head's world size), and its
    scalars (which must outlive the image)."""
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.util.numpy_support import numpy_to_vtk
    values = np.load(volume_path(outdir, factor, kind))
    image = vtkImageData()
    image.SetDimensions(*volume_dims(factor))
    image.SetSpacing(*[1.0 / factor] * 3)
    assert image.GetNumberOfPoints() == values.size
    image.GetPointData().SetScalars(numpy_to_vtk(values, deep=0))
    return image, values


def scene(image, kind, shade, pixels):
    """A window showing the volume (no mapper yet), its property and volume prop."""
    from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
    from vtkmodules.vtkRenderingCore import (vtkColorTransferFunction, vtkRenderWindow,
                                             vtkRenderer, vtkVolume, vtkVolumeProperty)
    import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
    import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: F401
    scale, offset = (CT_SCALE, CT_OFFSET) if kind == "int16" else (1, 0)
    opacity, color = vtkPiecewiseFunction(), vtkColorTransferFunction()
    # parc-render's "mri" preset: skin translucent, bright tissue opaque.
    for v, a, r, g, b in ((0, 0, 0, 0, 0), (38, 0, 0.55, 0.25, 0.15), (89, 0.04, 0.85, 0.55, 0.45),
                          (153, 0.12, 0.95, 0.85, 0.75), (255, 0.5, 1, 1, 0.95)):
        opacity.AddPoint(scale * v + offset, a)
        color.AddRGBPoint(scale * v + offset, r, g, b)
    prop = vtkVolumeProperty()
    prop.SetScalarOpacity(opacity)
    prop.SetColor(color)
    prop.SetInterpolationTypeToLinear()
    prop.SetShade(shade)
    volume = vtkVolume()
    volume.SetProperty(prop)
    renderer = vtkRenderer()
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(pixels, pixels)
    window.AddRenderer(renderer)
    window.Render()  # the GL context, before any mapper
    renderer.AddVolume(volume)
    renderer.ResetCamera(image.GetBounds())
    camera = renderer.GetActiveCamera()
    camera.Elevation(-80)
    camera.Azimuth(30)
    camera.OrthogonalizeViewUp()
    renderer.ResetCameraClippingRange(image.GetBounds())
    return window, volume, opacity


def new_mapper(name, image):
    from vtkmodules.vtkRenderingVolume import vtkFixedPointVolumeRayCastMapper
    from parc import vtkPARCVolumeMapper
    if name in ("parc", "bricked", "none"):
        mapper = vtkPARCVolumeMapper()
        if name == "none":  # no acceleration structure at all: its memory floor
            mapper.SetAccelerationModeToNone()
        else:
            mapper.SetAccelerationModeToAuto()
        mapper.SetBrickedCopy(name == "bricked")
    else:
        mapper = vtkFixedPointVolumeRayCastMapper()
        mapper.SetAutoAdjustSampleDistances(0)
        mapper.SetLockSampleDistanceToInputSpacing(0)
    mapper.SetSampleDistance(0.5 * image.GetSpacing()[0])
    mapper.SetInputData(image)
    return mapper


def timed(window):
    start = time.perf_counter()
    window.Render()
    return time.perf_counter() - start


def supercell_size(mapper):
    """The supercell size of the mapper's last render (builds before AutoSupercellSize:
    its fixed size)."""
    if hasattr(mapper, "GetLastSupercellSize"):
        return tuple(mapper.GetLastSupercellSize())
    return tuple(mapper.GetSupercellSize())


def sample_costs(mapper):
    """The casting time of the mapper's last frame, in ns per thread: per sample; per sample
    taken (the samples less those the map of contributing cells left out, whose share
    changes with the mode and supercell size); per contributing sample."""
    ns = 1e9 * mapper.GetLastCastingTime() * mapper.GetLastNumberOfThreads()
    samples = mapper.GetLastSampleCount()
    return {"ns_per_sample": ns / max(samples, 1),
            "ns_per_sample_taken": ns / max(samples - mapper.GetLastEmptyCellSampleCount(), 1),
            "ns_per_contributing_sample": ns / max(mapper.GetLastContributingSampleCount(), 1)}


def warm_up(window, mapper):
    """Renders this mapper until Auto's mode and supercell size have held for 6 frames."""
    if not mapper.IsA("vtkPARCVolumeMapper"):
        window.Render()
        return
    held, last = 0, None
    for _ in range(WARM_UP_FRAMES):
        window.Render()
        now = (mapper.GetLastAccelerationMode(), supercell_size(mapper))
        held = held + 1 if now == last else 0
        last = now
        if held >= 6:
            break


def min_median(values):
    values = sorted(values)
    return values[0], values[len(values) // 2]


def measure(outdir, factor, kind, images, rounds):
    """Times of one volume (both shadings): a JSON list of rows on stdout."""
    image, values = load_image(outdir, factor, kind)
    # The head at its own size (the same world bounds and view), for casting costs measured
    # in turns with the volume's.
    reference = load_image(outdir, 1, kind) if factor != 1 else None
    rows = []
    for shade in (0, 1):
        window, volume, opacity = scene(image, kind, shade, images[0])
        row = {"factor": factor, "kind": kind, "shade": shade, "voxels": int(values.size),
               "bytes": int(values.nbytes)}
        mappers = {name: new_mapper(name, image) for name in ("parc", "fixed", "bricked")}
        parc, bricked = mappers["parc"], mappers["bricked"]
        for pixels in images:
            window.SetSize(pixels, pixels)
            compared = reference is not None and pixels == images[0]
            if compared:
                mappers["reference"] = new_mapper("parc", reference[0])
            for name in mappers:
                volume.SetMapper(mappers[name])
                warm_up(window, mappers[name])
            times = {"parc": [], "fixed": [], "bricked": []}
            costs = []  # this mapper's casting cost of each warm frame
            against = []  # its ratio to the reference's in the same round
            bricked_against = []  # the same with the bricked copy
            for _ in range(rounds):
                for name in ("parc", "fixed", "bricked"):
                    volume.SetMapper(mappers[name])
                    times[name].append(timed(window))
                    if name == "bricked":
                        bricked_costs = sample_costs(bricked)
                    if name == "parc":
                        costs.append(sample_costs(parc))
                if compared:
                    volume.SetMapper(mappers["reference"])
                    window.Render()
                    own = sample_costs(mappers["reference"])
                    against.append({k: costs[-1][k] / own[k] for k in SAMPLE_COSTS})
                    bricked_against.append(
                        {k: bricked_costs[k] / own[k] for k in SAMPLE_COSTS})
            mappers.pop("reference", None)
            for name, t in times.items():
                row["warm_%s_%d" % (name, pixels)] = min_median(t)
            if pixels == images[0]:
                row["mode"] = parc.GetAccelerationModeAsString(parc.GetLastAccelerationMode())
                row["supercell"] = supercell_size(parc)
                for key in SAMPLE_COSTS:
                    row[key] = min_median([c[key] for c in costs])[1]
                    if against:
                        row["against_head_" + key] = min_median([a[key] for a in against])[1]
                        row["bricked_against_head_" + key] = min_median(
                            [a[key] for a in bricked_against])[1]
                row["bricked_memory_size"] = bricked.GetMemorySize()
        window.SetSize(images[0], images[0])
        volume.SetMapper(parc)
        warm_up(window, parc)
        edits, warm = [], []
        for r in range(rounds):  # an opacity node moved back and forth
            node = [0.0] * 4
            opacity.GetNodeValue(2, node)
            node[1] *= 1.1 if r % 2 == 0 else 1 / 1.1
            opacity.SetNodeValue(2, node)
            edits.append(timed(window))
            warm.append(timed(window))
        row["edit"] = min_median(edits)[1] / min_median(warm)[1]
        rows.append(row)
        del mappers, parc, window, volume
        gc.collect()
    print(json.dumps(rows))


def resident():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def draw_outline(window, image):
    """Shows the volume's outline in window and draws it once."""
    from vtkmodules.vtkFiltersModeling import vtkOutlineFilter
    from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper
    outline = vtkOutlineFilter()
    outline.SetInputData(image)
    mapper = vtkPolyDataMapper()
    mapper.SetInputConnection(outline.GetOutputPort())
    actor = vtkActor()
    actor.SetMapper(mapper)
    window.GetRenderers().GetFirstRenderer().AddActor(actor)
    window.Render()


def show_picture(window, pixels):
    """What any program showing a picture the window's size in it adds (the floor under
    every mapper's memory): the resident size MEMORY_FRAMES frames with a vtkImageActor of
    random RGBA bytes add, the bytes made before (JSON on stdout)."""
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkRenderingCore import vtkImageActor
    from vtkmodules.util.numpy_support import numpy_to_vtk
    picture = vtkImageData()
    picture.SetDimensions(pixels, pixels, 1)
    rgba = np.random.default_rng(1).integers(0, 256, (pixels * pixels, 4), dtype=np.uint8)
    picture.GetPointData().SetScalars(numpy_to_vtk(rgba, deep=1))
    gc.collect()
    before = resident()
    actor = vtkImageActor()
    actor.GetMapper().SetInputData(picture)
    window.GetRenderers().GetFirstRenderer().AddActor(actor)
    for _ in range(MEMORY_FRAMES):
        window.Render()
    print(json.dumps({"growth": resident() - before}))


def first(outdir, factor, kind, name, shade, pixels, outlined=False):
    """A new mapper in a new process: its first frame and the resident size MEMORY_FRAMES
    frames add (JSON on stdout); outlined: after the window has drawn the volume's outline.
    The name "picture" shows a picture of the window's size instead (show_picture)."""
    image, values = load_image(outdir, factor, kind)
    window, volume, _ = scene(image, kind, shade, pixels)
    if outlined:
        draw_outline(window, image)
    if name == "picture":
        show_picture(window, pixels)
        return
    gc.collect()
    before = resident()
    mapper = new_mapper(name, image)
    volume.SetMapper(mapper)
    result = {"first": timed(window)}
    for _ in range(MEMORY_FRAMES - 1):
        window.Render()
    result["growth"] = resident() - before
    if name in ("parc", "bricked"):
        result["memory_size"] = mapper.GetMemorySize()
    print(json.dumps(result))


def child(*args):
    """Runs this script in a new process with args; its last stdout line as JSON."""
    out = subprocess.run([sys.executable, __file__] + [str(a) for a in args], check=True,
                         stdout=subprocess.PIPE, text=True).stdout
    return json.loads(out.strip().splitlines()[-1]) if out.strip() else None


def label(row):
    return "x%d %s (%s MiB)" % (row["factor"], row["kind"], format(row["bytes"] / 2**20, ".0f"))


def time_left(spent, left):
    """The time the volumes left, (bytes, rounds) each, will take, from a line a + b bytes
    fitted to the seconds a round of the volumes measured, (bytes, seconds a round) each in
    spent, took (a volume's rounds share a fixed part, the start of their processes, and a
    part that grows with its bytes); empty before two are measured."""
    if len(spent) < 2:
        return ""
    x = np.array([b for b, _ in spent])
    y = np.array([t for _, t in spent])
    b = max(np.polyfit(x, y, 1)[0], 0.0) if np.ptp(x) > 0 else 0.0
    a = max(float(np.mean(y - b * x)), 0.0)  # the intercept of the line of slope b
    seconds = sum(n * (a + b * size) for size, n in left)
    return "about %.0f min left" % (seconds / 60)


def report(outdir, quick, factors=None, images=None):
    factors = factors or (QUICK_FACTORS if quick else FACTORS)
    images = images or (QUICK_IMAGES if quick else IMAGES)
    rounds = QUICK_ROUNDS if quick else ROUNDS
    os.makedirs(os.path.join(outdir, "volumes"), exist_ok=True)
    rows = []
    volumes = []  # (kind, factor, bytes, rounds) in order
    for kind, kind_factors in factors.items():
        for factor in kind_factors:
            size = float(np.prod(volume_dims(factor))) * np.dtype(kind).itemsize
            small = not quick and size < SMALL_VOLUME_BYTES
            volumes.append((kind, factor, size, SMALL_VOLUME_ROUNDS if small else rounds))
    spent = []  # (bytes, seconds a round) of the volumes measured
    try:
        for index, (kind, factor, size, volume_rounds) in enumerate(volumes):
            left = time_left(spent, [(b, n) for _, _, b, n in volumes[index:]])
            print("[volume size] %d/%d: x%d %s %s" % (index + 1, len(volumes), factor, kind, left),
                  file=sys.stderr, flush=True)
            started = time.time()
            for made in {1, factor}:
                if not os.path.exists(volume_path(outdir, made, kind)):
                    child("--make", outdir, made, kind)
            measured = child("--measure", outdir, factor, kind, ",".join(map(str, images)),
                             volume_rounds)
            for row in measured:
                fresh = {"fixed": [], "parc": []}
                for _ in range(volume_rounds):
                    for name in ("fixed", "parc"):
                        fresh[name].append(child("--first", outdir, factor, kind, name,
                                                 row["shade"], images[0]))
                for name, runs in fresh.items():
                    row["first_" + name] = min_median([run["first"] for run in runs])
                    row["growth_" + name] = min_median([run["growth"] for run in runs])[1]
                    if name == "parc":
                        row["memory_size_" + name] = min_median(
                            [run["memory_size"] for run in runs])[1]
                for name in OUTLINED:
                    row["growth_outlined_" + name] = child(
                        "--first", outdir, factor, kind, name, row["shade"], images[0],
                        "outlined")["growth"]
                # The bricked copy's first frame and memory: one fresh process.
                run = child("--first", outdir, factor, kind, "bricked", row["shade"], images[0])
                for key in ("first", "growth", "memory_size"):
                    row[key + "_bricked"] = run[key]
            rows.extend(measured)
            if factor != 1:  # the head's own size is every volume's reference
                os.remove(volume_path(outdir, factor, kind))
            seconds = time.time() - started
            spent.append((size, seconds / volume_rounds))
            print("(%s: %.0f s)" % (label(measured[0]), seconds), file=sys.stderr, flush=True)
    finally:
        shutil.rmtree(os.path.join(outdir, "volumes"), ignore_errors=True)
    with open(os.path.join(outdir, "volume-size.json"), "w") as f:
        json.dump({"images": images, "rows": rows}, f)
    tables(rows, images)
    plots(outdir, rows, images)


def first_frames(row, name):
    """A mapper's first frame (minimum, median); a saved run of one round has one time."""
    first = row["first_" + name]
    return (first, first) if isinstance(first, (int, float)) else tuple(first)


def tables(rows, images):
    print("| volume | shading | FixedPoint first median (min) (s) | PARC first median (min) (s) "
          "| first: FixedPoint / PARC | PARC set-up (ns per voxel) | " +
          " | ".join("warm %d^2: FixedPoint, PARC median (min) (s) | FixedPoint / PARC" % p
                     for p in images) + " |")
    print("|---|---|---|---|---|---|" + "---|---|" * len(images))
    for r in rows:
        fixed, parc = first_frames(r, "fixed"), first_frames(r, "parc")
        setup = 1e9 * (parc[1] - r["warm_parc_%d" % images[0]][1]) / r["voxels"]
        cells = ["%.3f (%.3f)" % (fixed[1], fixed[0]), "%.3f (%.3f)" % (parc[1], parc[0]),
                 "%.2fx" % (fixed[1] / parc[1]), "%.2f" % setup]
        for p in images:
            f, c = r["warm_fixed_%d" % p], r["warm_parc_%d" % p]
            cells += ["%.3f (%.3f), %.3f (%.3f)" % (f[1], f[0], c[1], c[0]), "%.2fx" % (f[1] / c[1])]
        print("| %s | %s | %s |" % (label(r), "shaded" if r["shade"] else "unshaded", " | ".join(cells)))
    print()
    print("| volume | shading | PARC mode, supercell size | PARC ns per thread: a sample, a "
          "sample taken, a contributing sample | the same against the head's (x1) in turns "
          "(* the smallest volume's, another process) "
          "| edit frame / warm frame | resident growth: FixedPoint, PARC (x volume) "
          "| the same after a drawn outline: FixedPoint, PARC, PARC without acceleration, "
          "a picture of the window's size alone (x volume) "
          "| PARC GetMemorySize (x volume) | GetMemorySize / growth |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    smallest = {}  # the first row of each type and shading (the volumes in growing order)
    for r in rows:
        smallest.setdefault((r["kind"], r["shade"]), r)
    for r in rows:
        v = r["bytes"]
        # Not in runs saved before them: the outlined growth, then acceleration None's.
        outlined = ", ".join("%.2f" % (r["growth_outlined_" + name] / v)
                             for name in OUTLINED
                             if "growth_outlined_" + name in r) or "-"
        keys = [k for k in SAMPLE_COSTS if k in r]  # runs saved before had one cost
        base = smallest[(r["kind"], r["shade"])]
        if "against_head_" + keys[0] in r:
            against = ", ".join("%.2fx" % r["against_head_" + k] for k in keys)
        else:  # the smallest volume itself, and runs saved before the turns
            against = ", ".join("%.2fx" % (r[k] / base[k]) for k in keys) + " *"
        print("| %s | %s | %s, %s | %s | %s | %.2fx | %.2f, %.2f | %s | %.2f | %.2f |" % (
            label(r), "shaded" if r["shade"] else "unshaded", r["mode"],
            "x".join(format(s, "g") for s in r["supercell"]),
            ", ".join("%.1f" % r[k] for k in keys),
            against, r["edit"],
            r["growth_fixed"] / v, r["growth_parc"] / v, outlined, r["memory_size_parc"] / v,
            r["memory_size_parc"] / max(r["growth_parc"], 1)))
    print()
    bricked = [r for r in rows if "bricked_memory_size" in r]  # not in runs saved before it
    if not bricked:
        return
    print("With a copy of the scalars in bricks (BrickedCopy), warm frames in the same rounds:")
    print()
    print("| volume | shading | " + " | ".join(
        "warm %d^2: PARC, PARC bricked median (min) (s) | PARC / bricked | FixedPoint / bricked"
        % p for p in images) + " | bricked ns per thread against the head's (x1) in turns "
          "| bricked GetMemorySize (x volume) | bricked first frame (s) | bricked resident "
          "growth (x volume) | bricked GetMemorySize / growth |")
    print("|---|---|" + "---|---|---|" * len(images) + "---|---|---|---|---|")
    for r in bricked:
        cells = []
        for p in images:
            f, c, b = r["warm_fixed_%d" % p], r["warm_parc_%d" % p], r["warm_bricked_%d" % p]
            cells += ["%.3f (%.3f), %.3f (%.3f)" % (c[1], c[0], b[1], b[0]),
                      "%.2fx" % (c[1] / b[1]), "%.2fx" % (f[1] / b[1])]
        keys = [k for k in SAMPLE_COSTS if "bricked_against_head_" + k in r]
        against = ", ".join("%.2fx" % r["bricked_against_head_" + k] for k in keys) or "-"
        fresh = "- | - | -"  # not in runs saved before the bricked copy had a fresh process
        if "growth_bricked" in r:
            fresh = "%.3f | %.2f | %.2f" % (r["first_bricked"], r["growth_bricked"] / r["bytes"],
                                          r["memory_size_bricked"] / max(r["growth_bricked"], 1))
        print("| %s | %s | %s | %s | %.2f | %s |" % (
            label(r), "shaded" if r["shade"] else "unshaded", " | ".join(cells), against,
            r["bricked_memory_size"] / r["bytes"], fresh))
    print()


def plots(outdir, rows, images):
    """Time against volume size per scalar type (warm frames solid, first frames dashed) and
    the memory a render adds (int16 dashed), one colour per mapper and shading; CSV beside."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from benchmark_report import PALETTE, draw
    mappers = (("fixed", "FixedPoint"), ("parc", "PARC Auto"))
    kinds = sorted(set(r["kind"] for r in rows), reverse=True)  # uint8 first
    csv_rows = []

    def line(name, select, value, colour, dashed):
        chosen = sorted((r for r in rows if select(r)), key=lambda r: r["voxels"])
        xs = [r["voxels"] for r in chosen]
        ys = [value(r) for r in chosen]
        csv_rows.extend((name, x, y) for x, y in zip(xs, ys))
        return (name, xs, ys, colour, dashed)

    for kind in kinds:
        series = []
        for i, (shade, shading) in enumerate(((0, "unshaded"), (1, "shaded"))):
            for j, (key, title) in enumerate(mappers):
                colour = PALETTE[2 * i + j]
                select = lambda r, shade=shade: r["kind"] == kind and r["shade"] == shade
                series.append(line("%s %s (dashed: first frame)" % (title, shading), select,
                                   lambda r, key=key: r["warm_%s_%d" % (key, images[0])][1], colour,
                                   False))
                series.append(line("%s %s first frame" % (title, shading), select,
                                   lambda r, key=key: first_frames(r, key)[1], colour, True))
            bricked = lambda r, shade=shade: (r["kind"] == kind and r["shade"] == shade and
                                              "warm_bricked_%d" % images[0] in r)
            series.append(line("PARC Auto, BrickedCopy, %s (warm)" % shading, bricked,
                               lambda r: r["warm_bricked_%d" % images[0]][1],
                               PALETTE[4 + 4 * i], False))
        name = "volume-size-time-%s.png" % kind
        title = "%s: warm frame (median) and first frame against volume size, %d^2" % (kind, images[0])
        draw(series, os.path.join(outdir, name), title, "voxels", "seconds", True, True,
             legend_left=True)
        print("![%s](%s)\n" % (title, name))
    series = []
    for i, (shade, shading) in enumerate(((0, "unshaded"), (1, "shaded"))):
        for j, (key, title) in enumerate(mappers):
            for kind in kinds:
                series.append(line("%s %s%s" % (title, shading, "" if kind == kinds[0] else " " + kind),
                                   lambda r, k=kind, s=shade: r["kind"] == k and r["shade"] == s,
                                   lambda r, key=key: r["growth_" + key] / 2**20,
                                   PALETTE[2 * i + j], kind != kinds[0]))
    for (key, title), colour in zip(mappers, (PALETTE[8], PALETTE[5])):
        for kind in kinds:
            series.append(line("%s unshaded, after a drawn outline" % title,
                               lambda r, k=kind: r["kind"] == k and r["shade"] == 0
                               and "growth_outlined_parc" in r,
                               lambda r, key=key: r["growth_outlined_" + key] / 2**20, colour,
                               kind != kinds[0]))
    for kind in kinds:
        series.append(line("PARC without acceleration unshaded, after a drawn outline",
                           lambda r, k=kind: r["kind"] == k and r["shade"] == 0
                           and "growth_outlined_none" in r,
                           lambda r: r["growth_outlined_none"] / 2**20, PALETTE[9],
                           kind != kinds[0]))
    for kind in kinds:
        series.append(line("a picture of the window's size alone, after a drawn outline",
                           lambda r, k=kind: r["kind"] == k and r["shade"] == 0
                           and "growth_outlined_picture" in r,
                           lambda r: r["growth_outlined_picture"] / 2**20, (0, 0, 0),
                           kind != kinds[0]))
    for kind in kinds:
        series.append(line("PARC Auto, BrickedCopy unshaded",
                           lambda r, k=kind: r["kind"] == k and r["shade"] == 0
                           and "growth_bricked" in r,
                           lambda r: r["growth_bricked"] / 2**20, PALETTE[6], kind != kinds[0]))
    for kind in kinds:
        series.append(line("PARC GetMemorySize", lambda r, k=kind: r["kind"] == k and r["shade"] == 0,
                           lambda r: r["memory_size_parc"] / 2**20, PALETTE[4], kind != kinds[0]))
    for kind in kinds:  # the goal: at most half the volume
        series.append(line("half the volume", lambda r, k=kind: r["kind"] == k and r["shade"] == 0,
                           lambda r: 0.5 * r["bytes"] / 2**20, PALETTE[7], kind != kinds[0]))
    title = "Memory a render adds against volume size (%s)" % (
        kinds[0] if len(kinds) == 1 else "%s solid, %s dashed" % (kinds[0], ", ".join(kinds[1:])))
    draw(series, os.path.join(outdir, "volume-size-memory.png"), title, "voxels", "MiB", True, True,
         legend_left=True)
    print("![%s](volume-size-memory.png)\n" % title)
    with open(os.path.join(outdir, "volume-size.csv"), "w") as f:
        f.write("series,x,y\n")
        for name, x, y in csv_rows:
            f.write("%s,%d,%g\n" % (name, x, y))


def main(argv):
    if argv[:1] == ["--make"]:
        make_volume(argv[1], int(argv[2]), argv[3])
    elif argv[:1] == ["--measure"]:
        measure(argv[1], int(argv[2]), argv[3], [int(p) for p in argv[4].split(",")], int(argv[5]))
    elif argv[:1] == ["--first"]:
        first(argv[1], int(argv[2]), argv[3], argv[4], int(argv[5]), int(argv[6]),
              argv[7:] == ["outlined"])
    elif len(argv) == 2 and argv[1].startswith("--from="):  # the report of a saved run
        with open(argv[1][len("--from="):]) as f:
            saved = json.load(f)
        tables(saved["rows"], saved["images"])
        plots(argv[0], saved["rows"], saved["images"])
    elif argv and not argv[0].startswith("--") and all(
            a == "--quick" or a.startswith(("--only=", "--images=")) for a in argv[1:]):
        if not os.path.exists(HEAD):
            print("(%s not found: skipped)" % HEAD)
            return
        options = dict(a[2:].split("=", 1) for a in argv[1:] if "=" in a)
        factors = None
        if "only" in options:  # --only=uint8:3,4;int16:3
            factors = {kind: [int(f) for f in fs.split(",")]
                       for kind, fs in (part.split(":") for part in options["only"].split(";"))}
        images = [int(p) for p in options["images"].split(",")] if "images" in options else None
        report(argv[0], "--quick" in argv, factors, images)
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main(sys.argv[1:])
