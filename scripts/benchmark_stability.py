#!/usr/bin/python3
"""Numerical stability of hard cases, as numbers (scripts/benchmark.sh; run under Xvfb with
the build's Python packages on PYTHONPATH). Prints markdown:

1. A constant slab's opacity against the closed form 1 - (1 - a)^(L / unit), over sample
   distances from 1e-3 to 2 voxels, for this mapper and vtkFixedPointVolumeRayCastMapper.
2. The same scene far from the origin and with tiny or huge spacings, against the scene
   near the origin with unit spacing (8-bit images).
3. Extreme camera clipping ranges around the same scene (8-bit images).

  benchmark_stability.py [--quick]
"""
import math
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPiecewiseFunction
from vtkmodules.vtkImagingCore import vtkImageShiftScale
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
from vtkmodules.vtkRenderingCore import (vtkColorTransferFunction, vtkRenderWindow, vtkRenderer,
                                         vtkVolume, vtkVolumeProperty, vtkWindowToImageFilter)
from vtkmodules.vtkRenderingVolume import vtkFixedPointVolumeRayCastMapper
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: F401
from parc import vtkPARCVolumeMapper

SLAB_OPACITY = 0.05  # a, per unit distance (the property's ScalarOpacityUnitDistance, 1)
SLAB_DEPTH = 40      # voxels along the rays
SLAB_PIXELS = 16
SCENE_PIXELS = 200
# Clipping ranges around a camera about 500 world units from the volume's centre.
CLIPPING_RANGES = [(300.0, 700.0), (10.0, 1e4), (1.0, 1e5), (1e-2, 1e6), (1e-4, 1e7)]


def window_for(volume, size, parallel):
    renderer = vtkRenderer()
    renderer.AddVolume(volume)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(size, size)
    window.AddRenderer(renderer)
    renderer.GetActiveCamera().SetParallelProjection(1 if parallel else 0)
    return window, renderer


def pixels(window):
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.SetInputBufferTypeToRGB()
    grab.ReadFrontBufferOff()
    grab.Update()
    return vtk_to_numpy(grab.GetOutput().GetPointData().GetScalars()).astype(np.float64)


def differences(a, b):
    d = np.abs(a - b)
    return float(np.sqrt(np.mean(d * d))), int(d.max())


def vtk_like(mapper_class, distance):
    m = mapper_class()
    m.SetAutoAdjustSampleDistances(0)
    m.SetSampleDistance(distance)
    if mapper_class is vtkFixedPointVolumeRayCastMapper:
        m.SetLockSampleDistanceToInputSpacing(0)
        m.SetImageSampleDistance(1.0)
    return m


def slab_section(quick):
    image = vtkImageData()
    image.SetDimensions(8, 8, SLAB_DEPTH + 1)
    image.AllocateScalars(3, 1)  # unsigned char
    image.GetPointData().GetScalars().Fill(100)
    prop = vtkVolumeProperty()
    opacity = vtkPiecewiseFunction()
    opacity.AddPoint(0, SLAB_OPACITY)
    opacity.AddPoint(255, SLAB_OPACITY)
    colour = vtkColorTransferFunction()
    colour.AddRGBPoint(0, 1, 1, 1)
    prop.SetScalarOpacity(opacity)
    prop.SetColor(colour)
    prop.SetInterpolationTypeToLinear()
    expected = 1.0 - (1.0 - SLAB_OPACITY) ** SLAB_DEPTH
    print(f"A slab of {SLAB_DEPTH} voxels (spacing 1), opacity a = {SLAB_OPACITY} per unit "
          f"distance, seen face on in a parallel view: the centre pixel's opacity against "
          f"1 - (1 - a)^L = {expected:.9f}. This mapper's from its float image, FixedPoint's from "
          f"the 8-bit window over a black background (its resolution is 1/255).\n")
    print("| sample distance (voxels) | this mapper | relative error | FixedPoint | "
          "relative error |")
    print("|---|---|---|---|---|")
    distances = [2, 1, 0.5, 0.25, 0.1, 0.01] + ([] if quick else [0.001])
    for d in distances:
        row = [f"{d:g}"]
        for cls in (vtkPARCVolumeMapper, vtkFixedPointVolumeRayCastMapper):
            mapper = vtk_like(cls, d)
            mapper.SetInputData(image)
            volume = vtkVolume()
            volume.SetMapper(mapper)
            volume.SetProperty(prop)
            window, renderer = window_for(volume, SLAB_PIXELS, True)
            renderer.ResetCamera()
            renderer.GetActiveCamera().Zoom(2.0)  # every pixel inside the slab
            window.Render()
            centre = (SLAB_PIXELS // 2) * SLAB_PIXELS + SLAB_PIXELS // 2
            if cls is vtkPARCVolumeMapper:
                rgba = vtkImageData()
                mapper.GetLastRayCastImage(rgba)
                alpha = float(vtk_to_numpy(rgba.GetPointData().GetScalars())[centre, 3])
            else:
                alpha = float(pixels(window)[centre, 0]) / 255.0
            row += [f"{alpha:.9f}", f"{(alpha - expected) / expected:+.2e}"]
        print("| " + " | ".join(row) + " |")
    print()


def wavelet(origin, spacing):
    source = vtkRTAnalyticSource()
    source.SetWholeExtent(-31, 32, -31, 32, -31, 32)
    to_bytes = vtkImageShiftScale()
    to_bytes.SetInputConnection(source.GetOutputPort())
    to_bytes.SetShift(-37.0)
    to_bytes.SetScale(255.0 / (277.0 - 37.0))
    to_bytes.SetOutputScalarTypeToUnsignedChar()
    to_bytes.ClampOverflowOn()
    to_bytes.Update()
    image = vtkImageData()
    image.DeepCopy(to_bytes.GetOutput())
    image.SetOrigin(origin)
    image.SetSpacing(spacing, spacing, spacing)
    return image


def wavelet_property(spacing):
    """Opacity per voxel, whatever the spacing: the unit distance scales with it."""
    prop = vtkVolumeProperty()
    prop.SetScalarOpacityUnitDistance(spacing)
    opacity = vtkPiecewiseFunction()
    opacity.AddPoint(0, 0.0)
    opacity.AddPoint(100, 0.0)
    opacity.AddPoint(180, 0.1)
    opacity.AddPoint(255, 0.6)
    colour = vtkColorTransferFunction()
    colour.AddRGBPoint(0, 0.1, 0.2, 1.0)
    colour.AddRGBPoint(255, 1.0, 0.7, 0.2)
    prop.SetScalarOpacity(opacity)
    prop.SetColor(colour)
    prop.SetInterpolationTypeToLinear()
    prop.ShadeOn()
    return prop


def scene_image(cls, origin, spacing, clipping=None):
    """The wavelet at origin and spacing, 0.5 voxel sample distance, camera from the same
    direction at the same distance in voxels (or at a fixed distance with clipping)."""
    image = wavelet(origin, spacing)
    mapper = vtk_like(cls, 0.5 * spacing)
    mapper.SetInputData(image)
    volume = vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(wavelet_property(spacing))
    window, renderer = window_for(volume, SCENE_PIXELS, False)
    camera = renderer.GetActiveCamera()
    centre = image.GetCenter()
    camera.SetFocalPoint(centre)
    distance = 500.0 * spacing
    camera.SetPosition(centre[0] + 0.3 * distance, centre[1] + 0.4 * distance,
                       centre[2] + math.sqrt(1 - 0.25) * distance)
    camera.SetViewUp(0, 1, 0)
    camera.SetViewAngle(12.0)
    if clipping:
        camera.SetClippingRange(*clipping)
    else:
        renderer.ResetCameraClippingRange()
    window.Render()
    return pixels(window)


def placement_section():
    print("The wavelet (64^3 voxels, shaded) rendered with its origin and spacing changed and "
          "the camera moved with it: 8-bit RMSE and largest difference against the scene at "
          "the origin with unit spacing.\n")
    print("| origin | spacing | this mapper: RMSE | max | FixedPoint: RMSE | max |")
    print("|---|---|---|---|---|---|")
    base = {cls: scene_image(cls, (0.0, 0.0, 0.0), 1.0)
            for cls in (vtkPARCVolumeMapper, vtkFixedPointVolumeRayCastMapper)}
    for origin, spacing in [(1e4, 1.0), (1e6, 1.0), (1e8, 1.0), (0.0, 1e-6), (0.0, 1e6),
                            (1e6, 1e-3)]:
        row = [f"{origin:g}", f"{spacing:g}"]
        for cls, reference in base.items():
            rmse, largest = differences(scene_image(cls, (origin,) * 3, spacing), reference)
            row += [f"{rmse:.3f}", str(largest)]
        print("| " + " | ".join(row) + " |")
    print()


def clipping_section():
    print("The same scene, camera 500 world units from the centre, with the clipping range set "
          "(and not reset): 8-bit RMSE and largest difference against the range "
          f"{CLIPPING_RANGES[0]}.\n")
    print("| near | far | this mapper: RMSE | max | FixedPoint: RMSE | max |")
    print("|---|---|---|---|---|---|")
    base = {}
    for near, far in CLIPPING_RANGES:
        row = [f"{near:g}", f"{far:g}"]
        for cls in (vtkPARCVolumeMapper, vtkFixedPointVolumeRayCastMapper):
            image = scene_image(cls, (0.0, 0.0, 0.0), 1.0, (near, far))
            base.setdefault(cls, image)
            rmse, largest = differences(image, base[cls])
            row += [f"{rmse:.3f}", str(largest)]
        print("| " + " | ".join(row) + " |")
    print()


def main():
    quick = "--quick" in sys.argv[1:]
    print("### A constant slab against the closed form\n")
    slab_section(quick)
    print("### Far origins, tiny and huge spacings\n")
    placement_section()
    print("### Extreme clipping ranges\n")
    clipping_section()


if __name__ == "__main__":
    main()
