"""A VTK pipeline in Python through `from parc import vtkPARCVolumeMapper`: a procedural
source feeds the mapper, the render draws something, statistics and the float ray-cast image
are reachable, progress events arrive in order, and an abort request stops the cast early."""
import sys
import unittest

from parc import vtkPARCVolumeMapper
from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.util.vtkConstants import VTK_DOUBLE
from vtkmodules.vtkRenderingCore import vtkLight
from parctesthelpers import offscreen_window, ray_image, wavelet_property


def make_scene(size=120, transparent_below=100):
    source = vtkRTAnalyticSource()  # the "wavelet": smooth, values about 37..277
    source.SetWholeExtent(-20, 20, -20, 20, -20, 20)
    mapper = vtkPARCVolumeMapper()
    mapper.SetInputConnection(source.GetOutputPort())
    prop = wavelet_property(transparent_below)
    prop.ShadeOn()
    return mapper, offscreen_window(mapper, prop, size)


class TestPARCPipeline(unittest.TestCase):
    def test_renders_and_reports(self):
        mapper, window = make_scene()
        window.Render()
        self.assertEqual(mapper.GetClassName(), "vtkPARCVolumeMapper")
        self.assertGreater(mapper.GetLastRayCount(), 0)
        self.assertGreaterEqual(mapper.GetLastSampleCount(), mapper.GetLastContributingSampleCount())
        self.assertGreater(mapper.GetLastContributingSampleCount(), 0)
        self.assertGreater(mapper.GetLastGradientCount(), 0, "shading needs gradients")
        self.assertGreater(mapper.GetLastRenderTime(), 0.0)
        image = vtkImageData()
        mapper.GetLastRayCastImage(image)
        self.assertEqual(image.GetDimensions(), (120, 120, 1))
        rgba = image.GetPointData().GetScalars()
        self.assertEqual(rgba.GetNumberOfComponents(), 4)
        alpha = rgba.GetRange(3)
        self.assertGreater(alpha[1], 0.1)
        self.assertLessEqual(alpha[1], 1.0)
        # Auto: no pass when every supercell may contribute (none can help); otherwise the
        # first frame tries depth PARC.
        all_pc = mapper.GetLastContributingSupercellCount() == mapper.GetLastSupercellCount()
        self.assertEqual(vtkPARCVolumeMapper.GetAccelerationModeAsString(
            mapper.GetLastAccelerationMode()), "None" if all_pc else "DepthBuffer")
        self.assertGreater(mapper.GetLastSupercellCount(), 0)

    def test_empty_cells_left_out(self):
        """Composite rays leave out the samples of cells that cannot contribute, in every
        acceleration mode; the cells are classified again only when the ray function
        changes, and not at all for a ray function that does not use them. (Transparent
        below 160, so that some nodes of 4x4x4 cells are wholly transparent: below 100
        none is.)"""
        mapper, window = make_scene(transparent_below=160)
        volume = window.GetRenderers().GetFirstRenderer().GetVolumes().GetItemAsObject(0)
        volume.GetProperty().SetInterpolationTypeToNearest()
        mapper.SetAccelerationModeToNone()
        window.Render()
        self.assertEqual(mapper.GetCellClassificationCount(), 0, "nearest samples: no cells")
        volume.GetProperty().SetInterpolationTypeToLinear()
        window.Render()
        self.assertEqual(mapper.GetCellClassificationCount(), 1)
        self.assertEqual(mapper.GetClassificationCount(), 0, "no supercells without passes")
        empty = mapper.GetLastEmptyCellSampleCount()
        self.assertGreater(empty, 0)
        self.assertLessEqual(empty + mapper.GetLastContributingSampleCount(),
                             mapper.GetLastSampleCount())
        window.GetRenderers().GetFirstRenderer().GetActiveCamera().Azimuth(30)
        window.Render()
        self.assertEqual(mapper.GetCellClassificationCount(), 1, "a new view keeps the cells")
        mapper.SetAccelerationModeToDepthBuffer()
        window.Render()
        self.assertEqual(mapper.GetCellClassificationCount(), 1, "so does a new mode")
        mapper.SetSupercellSize(3, 3, 3)
        window.Render()
        self.assertEqual(mapper.GetCellClassificationCount(), 1, "and new supercells")
        self.assertGreater(mapper.GetLastEmptyCellSampleCount(), 0)
        volume.GetProperty().GetScalarOpacity().AddPoint(120, 0.0)
        window.Render()
        self.assertEqual(mapper.GetCellClassificationCount(), 2, "an edit classifies again")
        mapper.SetBlendModeToMaximumIntensity()
        window.Render()
        self.assertEqual(mapper.GetCellClassificationCount(), 2)
        self.assertEqual(mapper.GetLastEmptyCellSampleCount(), 0)

    def test_light_specular_colour(self):
        # A green specular colour keeps the red and blue of a light without highlights and
        # the green of a white one, bit for bit.
        mapper, window = make_scene()
        renderer = window.GetRenderers().GetFirstRenderer()
        volume = renderer.GetVolumes().GetItemAsObject(0)
        volume.GetProperty().SetSpecular(0.8)
        window.Render()  # creates the headlight
        light = renderer.GetLights().GetItemAsObject(0)

        def ray_image(specular):
            light.SetSpecularColor(*specular)
            window.Render()
            image = vtkImageData()
            mapper.GetLastRayCastImage(image)
            return vtk_to_numpy(image.GetPointData().GetScalars()).copy()
        white, green, black = ray_image((1, 1, 1)), ray_image((0, 1, 0)), ray_image((0, 0, 0))
        self.assertTrue((green[:, 1] == white[:, 1]).all())
        self.assertTrue((green[:, [0, 2]] == black[:, [0, 2]]).all())
        self.assertGreater(white[:, 0].sum(), green[:, 0].sum() + 1.0, "highlights show")

    def test_auto_settles(self):
        """Auto starts with depth (a frame that also builds or uploads a model is tried
        again), tries in turn only the passes its measurements predict faster (and, when it
        would keep none only for the depth pass's projection, that pass at larger
        supercells), then keeps one; every frame gives the same float image; neither a
        transfer-function edit nor a new ray image size brings new trials."""
        mapper, window = make_scene()
        volume = window.GetRenderers().GetFirstRenderer().GetVolumes().GetItemAsObject(0)
        opacity = volume.GetProperty().GetScalarOpacity()
        opacity.RemoveAllPoints()
        opacity.AddPoint(200, 0.0)  # only the wavelet's centre may contribute
        opacity.AddPoint(270, 0.5)
        order = ["DepthBuffer", "ColorBuffer", "DepthAndColorBuffer", "None"]
        used, images = [], []
        for _ in range(30):  # the trials, and a search of the depth pass against None
            window.Render()
            used.append(vtkPARCVolumeMapper.GetAccelerationModeAsString(
                mapper.GetLastAccelerationMode()))
            image = vtkImageData()
            mapper.GetLastRayCastImage(image)
            images.append(vtk_to_numpy(image.GetPointData().GetScalars()).tobytes())
            if mapper.GetAutoTrialsRemaining() == 0:
                break
        self.assertLess(mapper.GetLastContributingSupercellCount(), mapper.GetLastSupercellCount())
        self.assertEqual(mapper.GetAutoTrialsRemaining(), 0, used)
        self.assertEqual(used[0], "DepthBuffer", used)
        self.assertTrue(set(used) <= set(order), used)
        for _ in range(3):
            window.Render()
            chosen = vtkPARCVolumeMapper.GetAccelerationModeAsString(mapper.GetLastAccelerationMode())
            self.assertIn(chosen, order)
            used.append(chosen)
        self.assertEqual(len(set(used[-3:])), 1, "the choice is kept")
        self.assertTrue(all(i == images[0] for i in images), "every pass gives the same image")
        opacity.AddPoint(240, 0.2)  # an edit brings no trials: Auto predicts from its estimates
        before = mapper.GetClassificationCount()
        window.Render()
        self.assertEqual(mapper.GetClassificationCount(), before + 1)
        self.assertEqual(mapper.GetAutoTrialsRemaining(), 0)
        self.assertIn(vtkPARCVolumeMapper.GetAccelerationModeAsString(
            mapper.GetLastAccelerationMode()), order)
        window.SetSize(window.GetSize()[0] + 8, window.GetSize()[1])
        window.Render()  # a new ray image size: predicted from the measured frames
        self.assertEqual(mapper.GetAutoTrialsRemaining(), 0)
        self.assertIn(vtkPARCVolumeMapper.GetAccelerationModeAsString(
            mapper.GetLastAccelerationMode()), order)

    def test_light_passes_are_counted_and_released(self):
        # A shadow-casting light: its PARC buffers count in GetMemorySize, and releasing the
        # window's graphics resources drops them with the light's GL models, so that the
        # next render draws the light passes again, in the window's new context.
        mapper, window = make_scene()
        renderer = window.GetRenderers().GetFirstRenderer()
        window.Render()
        unshadowed = mapper.GetMemorySize()
        light = vtkLight()
        light.SetPosition(60, 40, 80)
        light.SetFocalPoint(0, 0, 0)
        light.SetPositional(True)
        light.SetConeAngle(180)
        light.SetShadowAttenuation(1.0)
        renderer.AddLight(light)
        renderer.UseShadowsOn()
        window.Render()
        self.assertGreater(mapper.GetLastLightFrustumCount(), 0)
        self.assertGreater(mapper.GetLastShadowRayCount(), 0)
        shadowed = ray_image(mapper)
        self.assertGreater(mapper.GetMemorySize(), unshadowed, "the light buffers count")
        window.Render()
        self.assertEqual(mapper.GetLastLightFrustumCount(), 0, "the light buffers are cached")
        mapper.ReleaseGraphicsResources(window)
        window.Render()
        self.assertGreater(mapper.GetLastLightFrustumCount(), 0, "released, then drawn again")
        self.assertTrue((ray_image(mapper) == shadowed).all())

    def test_progress_and_abort(self):
        mapper, window = make_scene(size=256)
        fractions = []
        mapper.AddObserver(vtkCommand.ProgressEvent,
                           lambda obj, event: fractions.append(obj.GetProgress()))
        window.Render()
        self.assertGreater(len(fractions), 2)
        self.assertEqual(fractions, sorted(fractions))
        self.assertAlmostEqual(fractions[-1], 1.0)
        full = mapper.GetLastSampleCount()

        def abort(obj, event):
            obj.SetAbortExecute(1)
        mapper.AddObserver(vtkCommand.ProgressEvent, abort)
        window.Render()
        self.assertLess(mapper.GetLastSampleCount(), full)

    def test_volume_mapper_render_events(self):
        # What VTK's ray cast mappers emit: start, progress with the fraction done as call
        # data, end; the fractions rise to 1.
        mapper, window = make_scene(size=256)
        events = []

        @calldata_type(VTK_DOUBLE)
        def on_progress(obj, event, fraction):
            events.append(fraction)
        mapper.AddObserver(vtkCommand.VolumeMapperRenderProgressEvent, on_progress)
        mapper.AddObserver(vtkCommand.VolumeMapperRenderStartEvent,
                           lambda obj, event: events.append("start"))
        mapper.AddObserver(vtkCommand.VolumeMapperRenderEndEvent,
                           lambda obj, event: events.append("end"))
        window.Render()
        self.assertEqual(events[0], "start")
        self.assertEqual(events[-1], "end")
        fractions = events[1:-1]
        self.assertGreater(len(fractions), 2)
        self.assertTrue(all(isinstance(f, float) for f in fractions))
        self.assertEqual(fractions, sorted(fractions))
        self.assertGreater(fractions[0], 0.0)
        self.assertAlmostEqual(fractions[-1], 1.0)
        mapper.SetReportProgress(False)
        events.clear()
        window.Render()
        self.assertEqual(events, ["start", "end"], "no progress events when not reported")


if __name__ == "__main__":
    result = unittest.main(exit=False).result
    sys.exit(0 if result.wasSuccessful() else 1)
