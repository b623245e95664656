#!/usr/bin/python3
"""The demo's scenes (scripts/demo.sh; run under Xvfb with the build's Python packages on
PYTHONPATH): real volumes drawn by vtkPARCVolumeMapper (acceleration Auto) beside the VTK
mapper a user would otherwise pick: vtkFixedPointVolumeRayCastMapper, or
vtkGPUVolumeRayCastMapper where FixedPoint lacks the ray function (isosurfaces), or, for
the scenes no VTK mapper draws (two volumes with different ray functions, shadows), this
mapper without acceleration.

For each scene it writes OUTDIR/demo-SCENE.png: this mapper's image, the other one and
their difference magnified, captioned with the warm frame times (medians of interleaved
frames), the speed ratio and each image's error against a fine reference (this mapper,
unaccelerated, at an eighth of the sample distance). It prints a table: times, ratio, the
acceleration mode Auto chose, the samples taken against those of no acceleration, whether
the image equals the unaccelerated one bit for bit, and the errors.

  demo.py OUTDIR [--size N] [--rounds R] [--only SCENE,...]
"""
import argparse
import functools
import os
import statistics
import sys
import time

import numpy as np

from parc import vtkPARCMultiVolume, vtkPARCVolumeMapper
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPiecewiseFunction
from vtkmodules.vtkIOImage import vtkNIFTIImageReader
from vtkmodules.vtkRenderingCore import (vtkColorTransferFunction, vtkLight, vtkRenderWindow,
                                         vtkRenderer, vtkVolume, vtkVolumeProperty,
                                         vtkWindowToImageFilter)
from vtkmodules.vtkRenderingVolume import (vtkFixedPointVolumeRayCastMapper,
                                           vtkGPUVolumeRayCastMapper, vtkVolumeMapper)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the render window's implementation)
import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: F401 (the GPU mapper's implementation)

HEAD = "/usr/share/mricron/templates/ch2.nii.gz"
DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "data")
WARM_UP_FRAMES = 16       # enough for Auto's trials and its supercell search
REFERENCE_DIVISOR = 8     # the fine reference's sample distance: the scene's over this
MAX_DIFFERENCE_GAIN = 16  # the difference image's largest magnification


def data_file(name):
    path = os.path.join(DATA, name)
    return path if os.path.exists(path) else None


def read_head():
    reader = vtkNIFTIImageReader()
    reader.SetFileName(HEAD)
    reader.Update()
    return reader.GetOutput()


def read_raw(path, dims):
    values = np.fromfile(path, dtype=np.uint8)
    image = vtkImageData()
    image.SetDimensions(*dims)
    image.GetPointData().SetScalars(numpy_to_vtk(values, deep=1))
    return image


def floor_under(bounds, samples=(57, 12, 57)):
    """The paper's Figure 13 floor: a slab 1.2 times the object's width under its lowest y,
    its density falling from 255 inside to 0 outside over two samples (surface at 127.5)."""
    ramp, thickness = 2.0, 6.0
    width = 1.2 * max(bounds[1] - bounds[0], bounds[5] - bounds[4])
    spacing = width / (samples[0] - 1)
    top = samples[1] - 1 - ramp - 1.0
    bottom = top - thickness
    i, j, k = np.meshgrid(*[np.arange(n, dtype=float) for n in samples], indexing="ij")
    inside = np.minimum.reduce([np.minimum(i - ramp, samples[0] - 1 - ramp - i),
                                np.minimum(j - bottom, top - j),
                                np.minimum(k - ramp, samples[2] - 1 - ramp - k)])
    density = np.rint(255 * np.clip(0.5 + inside / ramp, 0, 1)).astype(np.uint8)
    image = vtkImageData()
    image.SetDimensions(*samples)
    image.SetSpacing(spacing, spacing, spacing)
    image.SetOrigin(0.5 * (bounds[0] + bounds[1] - width), bounds[2] - top * spacing,
                    0.5 * (bounds[4] + bounds[5] - width))
    image.GetPointData().SetScalars(numpy_to_vtk(density.transpose(2, 1, 0).ravel(), deep=1))
    return image


def volume_property(opacity, colors, shade=True, iso=None, ambient=0.25, diffuse=0.75,
                    specular=0.3):
    """opacity: (value, opacity) nodes; colors: (value, r, g, b) nodes."""
    o, c = vtkPiecewiseFunction(), vtkColorTransferFunction()
    for node in opacity:
        o.AddPoint(*node)
    for node in colors:
        c.AddRGBPoint(*node)
    prop = vtkVolumeProperty()
    prop.SetScalarOpacity(o)
    prop.SetColor(c)
    prop.SetInterpolationTypeToLinear()
    prop.SetShade(shade)
    prop.SetAmbient(ambient)
    prop.SetDiffuse(diffuse)
    prop.SetSpecular(specular)
    prop.SetSpecularPower(24)
    if iso is not None:
        prop.GetIsoSurfaceValues().SetValue(0, iso)
    return prop


# Each scene: title, reference mapper ("fixed", "gpu" or "none": this mapper unaccelerated),
# and a function that builds the scene's props around a mapper of a given kind, returning
# (props, lights, camera set-up, sample distance).

def head_skin_brain():
    image = read_head()
    # Skin a translucent peach, the brain's grey and white matter brighter and opaque.
    prop = volume_property(
        [(0, 0), (30, 0), (45, 0.03), (80, 0.03), (95, 0.0), (105, 0.25), (255, 0.6)],
        [(0, 0, 0, 0), (45, 0.9, 0.6, 0.5), (95, 0.9, 0.7, 0.6), (110, 0.95, 0.9, 0.8),
         (255, 1, 1, 1)])
    return [(image, prop, vtkVolumeMapper.COMPOSITE_BLEND)], front_of_head


def head_isosurface():
    image = read_head()
    prop = volume_property([(0, 1), (255, 1)], [(0, 0.95, 0.8, 0.7), (255, 0.95, 0.8, 0.7)],
                           iso=40, ambient=0.15, diffuse=0.8)
    return [(image, prop, vtkVolumeMapper.ISOSURFACE_BLEND)], side_of_head


def tooth():
    image = read_raw(data_file("tooth_103x94x161_uint8.raw"), (103, 94, 161))
    # The background (64-95) clear, dentin (145-175) ivory, enamel (over 220) white.
    prop = volume_property(
        [(0, 0), (110, 0), (150, 0.15), (175, 0.2), (215, 0.3), (230, 0.85), (255, 0.9)],
        [(0, 0, 0, 0), (110, 0.8, 0.5, 0.35), (160, 0.95, 0.85, 0.7), (230, 1, 1, 0.95),
         (255, 1, 1, 1)])
    return [(image, prop, vtkVolumeMapper.COMPOSITE_BLEND)], from_the_side(30, 1.1)


def proteins():
    """The paper's Figure 12: the positive potential of a protein as a surface inside the
    cloud of its negative potential."""
    surface = read_raw(data_file("poship_66x66x66_uint8.raw"), (66, 66, 66))
    cloud = read_raw(data_file("neghip_64x64x64_uint8.raw"), (64, 64, 64))
    cloud.SetOrigin(1, 1, 1)  # centred on the surface's volume
    surface_prop = volume_property([(0, 1), (255, 1)], [(0, 1, 0.35, 0.2), (255, 1, 0.35, 0.2)],
                                   iso=60)
    cloud_prop = volume_property([(0, 0), (30, 0), (120, 0.06), (255, 0.2)],
                                 [(0, 0.2, 0.4, 1), (255, 0.6, 0.8, 1)], shade=False)
    return [(surface, surface_prop, vtkVolumeMapper.ISOSURFACE_BLEND),
            (cloud, cloud_prop, vtkVolumeMapper.COMPOSITE_BLEND)], oblique(25, 30)


def shadows_on_floor():
    """The paper's Figure 13: a volume's surface casting shadows on a floor, lit by a point
    light."""
    bolt = read_raw(data_file("bolt_70x123x66_uint8.raw"), (70, 123, 66))
    prop = volume_property([(0, 1), (255, 1)], [(0, 0.85, 0.6, 0.3), (255, 0.85, 0.6, 0.3)],
                           iso=100)
    floor = floor_under(bolt.GetBounds())
    floor_prop = volume_property([(0, 1), (255, 1)], [(0, 0.85, 0.85, 0.8), (255, 0.85, 0.85, 0.8)],
                                 iso=127.5)
    return [(bolt, prop, vtkVolumeMapper.ISOSURFACE_BLEND),
            (floor, floor_prop, vtkVolumeMapper.ISOSURFACE_BLEND)], lit_from_above(oblique(20, 35))


def from_the_side(azimuth, zoom):
    """Seen along -y (the head from the front), +z up, turned by azimuth degrees."""
    def set_up(renderer, bounds):
        camera = renderer.GetActiveCamera()
        centre = [0.5 * (bounds[2 * a] + bounds[2 * a + 1]) for a in range(3)]
        camera.SetFocalPoint(*centre)
        camera.SetPosition(centre[0], centre[1] + 1, centre[2])
        camera.SetViewUp(0, 0, 1)
        renderer.ResetCamera(bounds)
        camera.Azimuth(azimuth)
        camera.Zoom(zoom)
    return set_up


front_of_head = from_the_side(-25, 1.25)
side_of_head = from_the_side(-75, 1.25)


def oblique(elevation, azimuth):
    def set_up(renderer, bounds):
        renderer.ResetCamera(bounds)
        camera = renderer.GetActiveCamera()
        camera.Elevation(elevation)
        camera.Azimuth(azimuth)
        camera.OrthogonalizeViewUp()
        camera.Zoom(1.15)
    return set_up


def lit_from_above(camera_set_up):
    def set_up(renderer, bounds):
        camera_set_up(renderer, bounds)
        light = vtkLight()
        light.SetLightTypeToSceneLight()
        light.SetPositional(1)
        light.SetConeAngle(180)
        centre = [0.5 * (bounds[2 * a] + bounds[2 * a + 1]) for a in range(3)]
        size = max(bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4])
        light.SetPosition(centre[0] - 0.8 * size, centre[1] + 1.5 * size, centre[2] + 0.6 * size)
        light.SetFocalPoint(*centre)
        renderer.AddLight(light)
        renderer.SetUseShadows(1)
    return set_up


SCENES = {
    "head": ("MRI head, shaded composite", "fixed", head_skin_brain, None),
    "head-surface": ("MRI head, isosurface", "gpu", head_isosurface, None),
    "tooth": ("CT tooth, shaded composite", "fixed", tooth, "tooth_103x94x161_uint8.raw"),
    "proteins": ("Figure 12: a surface in a cloud", "none", proteins, "poship_66x66x66_uint8.raw"),
    "shadows": ("Figure 13: shadows on a floor", "none", shadows_on_floor,
                "bolt_70x123x66_uint8.raw"),
}
MAPPER_NAMES = {"parc": "PARC (Auto)", "fixed": "FixedPoint", "gpu": "GPU ray cast",
                "none": "PARC, no acceleration"}


def new_mapper(kind, spacing):
    if kind == "fixed":
        mapper = vtkFixedPointVolumeRayCastMapper()
        mapper.SetAutoAdjustSampleDistances(0)
        mapper.SetLockSampleDistanceToInputSpacing(0)
    elif kind == "gpu":
        mapper = vtkGPUVolumeRayCastMapper()
        mapper.SetAutoAdjustSampleDistances(0)
        mapper.SetLockSampleDistanceToInputSpacing(0)
    else:
        mapper = vtkPARCVolumeMapper()
        if kind == "parc":
            mapper.SetAccelerationModeToAuto()
        else:
            mapper.SetAccelerationModeToNone()
    mapper.SetSampleDistance(0.5 * spacing)
    return mapper


@functools.lru_cache(maxsize=None)
def scene_members(scene):
    """The scene's volumes (read once, shared by its views) and its camera set-up."""
    return SCENES[scene][2]()


class View:
    """One scene in an offscreen window, drawn by a mapper of one kind."""

    def __init__(self, scene, kind, size, distance_divisor=1):
        members, set_up_camera = scene_members(scene)
        spacing = min(members[0][0].GetSpacing())
        self.mapper = new_mapper(kind, spacing / distance_divisor)
        renderer = vtkRenderer()
        if len(members) == 1:
            image, prop, blend = members[0]
            self.mapper.SetInputData(image)
            self.mapper.SetBlendMode(blend)
            prop_shown = vtkVolume()
            prop_shown.SetMapper(self.mapper)
            prop_shown.SetProperty(prop)
        else:  # several volumes: this mapper and vtkPARCMultiVolume
            prop_shown = vtkPARCMultiVolume()
            prop_shown.SetMapper(self.mapper)
            for port, (image, prop, blend) in enumerate(members):
                self.mapper.SetInputDataObject(port, image)
                self.mapper.SetInputBlendMode(port, blend)
                volume = vtkVolume()
                volume.SetProperty(prop)
                prop_shown.SetVolume(volume, port)
        renderer.AddVolume(prop_shown)
        renderer.SetBackground(0, 0, 0)
        self.window = vtkRenderWindow()
        self.window.SetOffScreenRendering(1)
        self.window.SetMultiSamples(0)
        self.window.SetSize(size, size)
        self.window.AddRenderer(renderer)
        set_up_camera(renderer, prop_shown.GetBounds())
        renderer.ResetCameraClippingRange()

    def frame(self):
        start = time.perf_counter()
        self.window.Render()
        return time.perf_counter() - start

    def pixels(self):
        grab = vtkWindowToImageFilter()
        grab.SetInput(self.window)
        grab.ReadFrontBufferOff()
        grab.Update()
        image = grab.GetOutput()
        w, h, _ = image.GetDimensions()
        rgb = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(h, w, -1)[:, :, :3]
        return np.flipud(rgb).copy()

    def ray_image(self):
        image = vtkImageData()
        self.mapper.GetLastRayCastImage(image)
        return vtk_to_numpy(image.GetPointData().GetScalars()).copy()


def warm_up(view):
    """Renders until Auto's mode and supercell size have held for 4 frames."""
    held, last = 0, None
    for _ in range(WARM_UP_FRAMES):
        view.frame()
        if not view.mapper.IsA("vtkPARCVolumeMapper"):
            return
        now = (view.mapper.GetLastAccelerationMode(), tuple(view.mapper.GetLastSupercellSize()))
        held = held + 1 if now == last else 0
        last = now
        if held >= 4:
            return


def rmse(a, b):
    return float(np.sqrt(np.mean((a.astype(float) - b.astype(float)) ** 2)))


def run_scene(scene, size, rounds):
    title, reference, _, _ = SCENES[scene]
    parc, other = View(scene, "parc", size), View(scene, reference, size)
    for view in (parc, other):
        warm_up(view)
    times = {"parc": [], "other": []}
    for _ in range(rounds):  # interleaved: A B A B
        times["parc"].append(parc.frame())
        times["other"].append(other.frame())
    none = View(scene, "none", size)
    none.frame()
    # Each mapper's error against its own cast at a fine sample distance: what its
    # sampling costs, apart from the conventions (lighting) in which mappers differ.
    truths = {}
    for kind in ("none", reference):
        if kind not in truths:
            fine = View(scene, kind, size, REFERENCE_DIVISOR)
            fine.frame()
            truths[kind] = fine.pixels()
    mapper = parc.mapper
    row = {
        "scene": scene, "title": title, "reference": reference,
        "parc_s": statistics.median(times["parc"]), "other_s": statistics.median(times["other"]),
        "mode": mapper.GetAccelerationModeAsString(mapper.GetLastAccelerationMode()),
        "samples": mapper.GetLastSampleCount(), "samples_none": none.mapper.GetLastSampleCount(),
        "exact": bool(np.array_equal(parc.ray_image(), none.ray_image())),
    }
    mine, theirs = parc.pixels(), other.pixels()
    row["parc_error"] = rmse(mine, truths["none"])
    row["other_error"] = rmse(theirs, truths[reference])
    row["ratio"] = row["other_s"] / row["parc_s"]
    return row, mine, theirs


def write_picture(path, row, mine, theirs):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    difference = np.abs(mine.astype(int) - theirs.astype(int))
    largest = int(difference.max())
    # Magnified so that the largest differences (99th percentile) show, at most 16 times.
    top = np.percentile(difference[difference > 0], 99) if largest else 1
    gain = int(max(1, min(MAX_DIFFERENCE_GAIN, 255 // max(top, 1))))
    what = "largest %d of 255" % largest if largest else "none: the same pixels"
    other = MAPPER_NAMES[row["reference"]]
    panels = [
        (mine, "PARC (Auto: %s)\n%.3f s, error %.2f" % (row["mode"], row["parc_s"], row["parc_error"])),
        (theirs, "%s\n%.3f s, error %.2f" % (other, row["other_s"], row["other_error"])),
        (np.clip(gain * difference, 0, 255).astype(np.uint8),
         "difference x%d (%s)\nPARC %.2fx faster" % (gain, what, row["ratio"])),
    ]
    figure, axes = plt.subplots(1, 3, figsize=(12, 4.6), facecolor="white")
    for axis, (pixels, caption) in zip(axes, panels):
        axis.imshow(pixels)
        axis.set_title(caption, fontsize=11)
        axis.axis("off")
    figure.suptitle(row["title"] + "\n(warm frames, medians; error: RMSE of 8-bit RGB against "
                    "the mapper's own cast at 1/%d of the sample distance)" % REFERENCE_DIVISOR,
                    fontsize=12)
    figure.tight_layout(rect=(0, 0, 1, 0.9))
    figure.savefig(path, dpi=80)
    plt.close(figure)


def print_table(rows):
    print("| scene | PARC (s) | other mapper (s) | other / PARC | Auto's mode | samples / "
          "samples of None | = None bit for bit | error PARC, other (each against its own fine cast) |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        print("| %s | %.3f | %s %.3f | %.2fx | %s | %.2f | %s | %.2f, %.2f |" % (
            r["title"], r["parc_s"], MAPPER_NAMES[r["reference"]], r["other_s"], r["ratio"],
            r["mode"], r["samples"] / max(r["samples_none"], 1), "yes" if r["exact"] else "NO",
            r["parc_error"], r["other_error"]))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("outdir")
    parser.add_argument("--size", type=int, default=360)
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--only", default=",".join(SCENES))
    args = parser.parse_args()
    os.makedirs(args.outdir, exist_ok=True)
    rows = []
    for scene in args.only.split(","):
        needs = SCENES[scene][3]
        if needs and not data_file(needs):
            print("(%s: %s not found in %s, skipped)" % (scene, needs, DATA), flush=True)
            continue
        start = time.perf_counter()
        row, mine, theirs = run_scene(scene, args.size, args.rounds)
        path = os.path.join(args.outdir, "demo-%s.png" % scene)
        write_picture(path, row, mine, theirs)
        rows.append(row)
        print("(%s: %s, %.0f s)" % (row["title"], path, time.perf_counter() - start), flush=True)
    print()
    print_table(rows)
    return 0 if all(r["exact"] for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
