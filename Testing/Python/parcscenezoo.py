"""One scene of the scene zoo (TestPARCSceneZoo.py) in a fresh process: the GL contexts and
passes VTK users set up around a volume, with the volume drawn by vtkPARCVolumeMapper
("parc") or by VTK's vtkFixedPointVolumeRayCastMapper ("fixed-point"). Writes the window's
pixels (vtkWindowToImageFilter) as a PNG, and for the picker scene the picked point.

Usage: python3 parcscenezoo.py SCENE MAPPER OUTPUT.png
"""
import sys

from parc import vtkPARCVolumeMapper
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkColorTransferFunction, vtkPolyDataMapper,
                                         vtkRenderWindow, vtkRenderer, vtkVolume,
                                         vtkVolumeProperty, vtkWindowToImageFilter)
from vtkmodules.vtkRenderingOpenGL2 import (vtkCameraPass, vtkRenderStepsPass)
from vtkmodules.vtkRenderingVolume import vtkFixedPointVolumeRayCastMapper, vtkVolumePicker
import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: F401 (the volumetric pass's mappers)

SIZE = 160
SCENES = ["plain", "offscreen", "multisamples", "fxaa", "depth-peeling",
          "dual-depth-peeling", "viewports", "layers", "window-after", "windows-before",
          "render-passes", "picker"]


def make_volume(kind):
    source = vtkRTAnalyticSource()
    source.SetWholeExtent(-24, 24, -24, 24, -24, 24)
    mapper = vtkPARCVolumeMapper() if kind == "parc" else vtkFixedPointVolumeRayCastMapper()
    if kind == "parc":
        mapper.SetAccelerationModeToDepthBuffer()  # the GL pass in every frame, the first too
    mapper.SetInputConnection(source.GetOutputPort())
    opacity = vtkPiecewiseFunction()
    opacity.AddPoint(120, 0.0)
    opacity.AddPoint(200, 0.06)
    opacity.AddPoint(280, 0.3)
    color = vtkColorTransferFunction()
    color.AddRGBPoint(120, 0.2, 0.3, 1.0)
    color.AddRGBPoint(200, 1.0, 0.6, 0.2)
    color.AddRGBPoint(280, 1.0, 1.0, 0.9)
    prop = vtkVolumeProperty()
    prop.SetScalarOpacity(opacity)
    prop.SetColor(color)
    prop.SetInterpolationTypeToLinear()
    volume = vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    return volume


def sphere(centre, radius, opacity, colour=(0.2, 0.7, 0.3)):
    source = vtkSphereSource()
    source.SetCenter(*centre)
    source.SetRadius(radius)
    source.SetThetaResolution(32)
    source.SetPhiResolution(32)
    mapper = vtkPolyDataMapper()
    mapper.SetInputConnection(source.GetOutputPort())
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetColor(*colour)
    actor.GetProperty().SetOpacity(opacity)
    return actor


def renderer_with(volume, viewport=(0, 0, 1, 1), azimuth=30):
    renderer = vtkRenderer()
    renderer.SetViewport(*viewport)
    renderer.AddVolume(volume)
    renderer.ResetCamera()
    renderer.GetActiveCamera().Azimuth(azimuth)
    renderer.GetActiveCamera().Elevation(20)
    renderer.GetActiveCamera().OrthogonalizeViewUp()
    renderer.ResetCameraClippingRange()
    return renderer


def new_window(offscreen=False, samples=0, position=0):
    """A window at the given place from the screen's left (windows must not overlap: the
    pixels of a covered on-screen window are undefined)."""
    window = vtkRenderWindow()
    window.SetSize(SIZE, SIZE)
    window.SetPosition(position * (SIZE + 20), 0)
    window.SetMultiSamples(samples)
    window.SetOffScreenRendering(1 if offscreen else 0)
    return window


def build(scene, kind):
    """The window to capture (rendered already where the scene needs earlier frames)."""
    volume = make_volume(kind)
    if scene in ("plain", "offscreen", "multisamples", "fxaa"):
        window = new_window(scene == "offscreen", 8 if scene == "multisamples" else 0)
        renderer = renderer_with(volume)
        renderer.SetUseFXAA(scene == "fxaa")
        window.AddRenderer(renderer)
        return window
    if scene in ("depth-peeling", "dual-depth-peeling"):
        window = new_window()
        window.SetAlphaBitPlanes(1)
        renderer = renderer_with(volume)
        renderer.AddActor(sphere((20, 0, 10), 14, 0.4))  # translucent, half in the volume
        renderer.AddActor(sphere((-22, -18, 0), 8, 1.0, (0.9, 0.9, 0.2)))  # opaque
        renderer.SetUseDepthPeeling(1)
        renderer.SetUseDepthPeelingForVolumes(scene == "dual-depth-peeling")
        renderer.SetMaximumNumberOfPeels(8)
        renderer.SetOcclusionRatio(0.0)
        renderer.ResetCameraClippingRange()
        return window.AddRenderer(renderer) or window
    if scene == "viewports":  # two renderers side by side, each with the volume
        window = new_window()
        window.AddRenderer(renderer_with(volume, (0, 0, 0.5, 1), 30))
        window.AddRenderer(renderer_with(make_volume(kind), (0.5, 0, 1, 1), 120))
        return window
    if scene == "layers":  # the volume in layer 0, an opaque sphere in layer 1 over it
        window = new_window()
        window.SetNumberOfLayers(2)
        bottom = renderer_with(volume)
        top = vtkRenderer()
        top.SetLayer(1)
        top.SetActiveCamera(bottom.GetActiveCamera())
        top.AddActor(sphere((0, 0, 30), 6, 1.0, (0.9, 0.2, 0.2)))
        window.AddRenderer(bottom)
        window.AddRenderer(top)
        return window
    if scene == "window-after":  # the mapper in a first window, then in a later one
        first = new_window()
        first.AddRenderer(renderer_with(volume))
        first.Render()
        window = new_window(position=1)
        later = make_volume(kind)
        later.SetMapper(volume.GetMapper())
        window.AddRenderer(renderer_with(later))
        window.first = first  # kept alive
        return window
    if scene == "windows-before":  # two windows shown first; the mapper moves to the second
        first, window = new_window(), new_window(position=1)
        first.AddRenderer(renderer_with(volume))
        other = make_volume(kind)
        window.AddRenderer(renderer_with(other))
        window.Render()
        first.Render()
        other.SetMapper(volume.GetMapper())
        window.first = first
        return window
    if scene == "render-passes":  # a camera pass over VTK's render steps
        window = new_window()
        renderer = renderer_with(volume)
        steps = vtkRenderStepsPass()
        camera = vtkCameraPass()
        camera.SetDelegatePass(steps)
        renderer.SetPass(camera)
        window.AddRenderer(renderer)
        return window
    if scene == "picker":
        window = new_window()
        renderer = renderer_with(volume)
        window.AddRenderer(renderer)
        return window
    raise SystemExit("unknown scene " + scene)


def main(scene, kind, output):
    window = build(scene, kind)
    window.Render()  # the first frame is captured: it must be right too
    capture = vtkWindowToImageFilter()
    capture.SetInput(window)
    capture.ShouldRerenderOff()
    capture.ReadFrontBufferOff()
    capture.Update()
    writer = vtkPNGWriter()
    writer.SetFileName(output)
    writer.SetInputConnection(capture.GetOutputPort())
    writer.Write()
    if scene == "picker":
        picker = vtkVolumePicker()
        picker.SetTolerance(1e-6)
        renderer = window.GetRenderers().GetFirstRenderer()
        picked = picker.Pick(SIZE / 2, SIZE / 2, 0, renderer)
        with open(output + ".pick", "w") as out:
            out.write("%d %s %.4f %.4f %.4f\n" % (
                picked, picker.GetVolume() is not None, *picker.GetPickPosition()))
    window.Finalize()


if __name__ == "__main__":
    main(*sys.argv[1:4])
