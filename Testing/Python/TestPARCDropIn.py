"""The settings of VTK's own volume mappers that programs call when they swap in
vtkPARCVolumeMapper: render-time budgets (AutoAdjustSampleDistances, the image and
interactive sample distances), the number of threads, a sample distance locked to the
spacing, IsRenderSupported and the vtkSmartVolumeMapper render modes. Each has a meaning
that can be seen in the render's statistics or image."""
import sys
import unittest

import numpy

from parc import vtkPARCVolumeMapper
from vtkmodules.vtkCommonCore import vtkCommand, vtkFloatArray, vtkUnsignedCharArray
from vtkmodules.vtkCommonDataModel import (vtkImageData, vtkPiecewiseFunction,
                                            vtkRectilinearGrid)
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkRenderingCore import vtkColorTransferFunction

from parctesthelpers import ray_image
from TestPARCPipeline import make_scene

STILL_RATE = 0.0001  # vtkRenderWindowInteractor's still update rate
INTERACTIVE_RATE = 1000.0  # a budget of 1 ms: no render fits it


def messages(obj, event):
    """The texts of the event (ErrorEvent, WarningEvent) obj emits, as a list that fills."""
    texts = []

    @calldata_type(VTK_STRING)
    def on_message(caller, name, text):
        texts.append(text)
    obj.AddObserver(event, on_message)
    return texts


def left_mask(inside):
    """A mask of the wavelet's 41^3 voxels: inside where the x index is below 20, else 0."""
    x = numpy.tile(numpy.arange(41), 41 * 41)
    mask = vtkImageData()
    mask.SetDimensions(41, 41, 41)
    mask.GetPointData().SetScalars(
        numpy_to_vtk(numpy.where(x < 20, inside, 0).astype(numpy.uint8), deep=True))
    return mask


class TestPARCDropIn(unittest.TestCase):
    def render_every_mode(self, mapper, window):
        """Renders with each acceleration mode; asserts that the float images are the same
        and returns it, as (120, 120, 4)."""
        images = []
        for mode in (vtkPARCVolumeMapper.ACCELERATION_NONE,
                     vtkPARCVolumeMapper.ACCELERATION_DEPTH_BUFFER,
                     vtkPARCVolumeMapper.ACCELERATION_COLOR_BUFFER,
                     vtkPARCVolumeMapper.ACCELERATION_BOTH,
                     vtkPARCVolumeMapper.ACCELERATION_SUPERCELL_WALK):
            mapper.SetAccelerationMode(mode)
            window.Render()
            images.append(ray_image(mapper).reshape(120, 120, 4))
            self.assertTrue((images[-1] == images[0]).all(), mode)
        return images[0]

    def test_budget_coarsens_interactive_renders_only(self):
        mapper, window = make_scene(size=240)
        self.assertTrue(mapper.GetAutoAdjustSampleDistances())
        window.SetDesiredUpdateRate(STILL_RATE)
        window.Render()
        still_distance = mapper.GetLastSampleDistance()
        self.assertFalse(mapper.GetLastInteractive())
        self.assertEqual(mapper.GetLastImageSampleDistance(), 1.0)
        self.assertEqual(ray_image(mapper).shape[0], 240 * 240)

        window.SetDesiredUpdateRate(INTERACTIVE_RATE)
        steps = []
        for _ in range(3):
            window.Render()
            self.assertTrue(mapper.GetLastInteractive())
            self.assertEqual(mapper.GetLastSampleDistance(),
                             max(still_distance, mapper.GetInteractiveSampleDistance()))
            steps.append(mapper.GetLastImageSampleDistance())
        self.assertGreater(steps[0], 1.0, "coarser rays to meet the budget")
        self.assertLessEqual(max(steps), mapper.GetMaximumImageSampleDistance())
        self.assertLess(ray_image(mapper).shape[0], 240 * 240)

        # The interactive render is exact for its own settings: every mode agrees on it.
        interactive = ray_image(mapper)
        step, distance = steps[-1], mapper.GetLastSampleDistance()
        mapper.AutoAdjustSampleDistancesOff()
        mapper.SetImageSampleDistance(step)
        mapper.SetSampleDistance(distance)
        for mode in (vtkPARCVolumeMapper.ACCELERATION_NONE,
                     vtkPARCVolumeMapper.ACCELERATION_DEPTH_BUFFER,
                     vtkPARCVolumeMapper.ACCELERATION_COLOR_BUFFER):
            mapper.SetAccelerationMode(mode)
            window.Render()
            self.assertTrue((ray_image(mapper) == interactive).all(), mode)

        # Interaction ends: the still render is at full quality again.
        mapper.AutoAdjustSampleDistancesOn()
        mapper.SetSampleDistance(0.0)
        mapper.SetAccelerationModeToAuto()
        window.SetDesiredUpdateRate(STILL_RATE)
        window.Render()
        self.assertFalse(mapper.GetLastInteractive())
        self.assertEqual(mapper.GetLastImageSampleDistance(), 1.0)
        self.assertEqual(mapper.GetLastSampleDistance(), still_distance)

    def test_interactive_adjustment_as_the_smart_mapper_has_it(self):
        # vtkSmartVolumeMapper's way: AutoAdjustSampleDistances off and
        # InteractiveAdjustSampleDistances on adjust interactive renders only; the still
        # render keeps ImageSampleDistance as set.
        mapper, window = make_scene(size=240)
        self.assertFalse(mapper.GetInteractiveAdjustSampleDistances())
        mapper.AutoAdjustSampleDistancesOff()
        mapper.SetImageSampleDistance(1.5)
        window.SetDesiredUpdateRate(INTERACTIVE_RATE)
        window.Render()
        self.assertFalse(mapper.GetLastInteractive(), "no adjustment at all")
        self.assertEqual(mapper.GetLastImageSampleDistance(), 1.5)
        mapper.InteractiveAdjustSampleDistancesOn()
        window.Render()
        window.Render()
        self.assertTrue(mapper.GetLastInteractive())
        self.assertGreater(mapper.GetLastImageSampleDistance(), 1.5)
        window.SetDesiredUpdateRate(STILL_RATE)
        window.Render()
        self.assertFalse(mapper.GetLastInteractive())
        self.assertEqual(mapper.GetLastImageSampleDistance(), 1.5)

    def test_no_auto_trial_while_interacting(self):
        mapper, window = make_scene(size=200)
        mapper.SetSupercellSize(2, 2, 2)  # some supercells empty: passes may pay off
        window.SetDesiredUpdateRate(INTERACTIVE_RATE)
        modes = set()
        for _ in range(4):
            window.Render()
            modes.add(mapper.GetLastAccelerationMode())
        self.assertEqual(len(modes), 1, "one mode while interacting")
        self.assertGreater(mapper.GetAutoTrialsRemaining(), 0, "trials left for still frames")
        window.SetDesiredUpdateRate(STILL_RATE)
        for _ in range(6):
            window.Render()
        self.assertEqual(mapper.GetAutoTrialsRemaining(), 0, "still renders try the modes")
        mapper.SetSupercellSize(4, 4, 4)  # every supercell may contribute: nothing to try
        window.Render()
        self.assertEqual(mapper.GetLastAccelerationMode(), mapper.ACCELERATION_NONE)
        self.assertEqual(mapper.GetAutoTrialsRemaining(), 0)

    def test_threads(self):
        mapper, window = make_scene()
        window.Render()
        everyone = ray_image(mapper)
        mapper.SetNumberOfThreads(1)
        window.Render()
        self.assertEqual(mapper.GetLastNumberOfThreads(), 1)
        self.assertTrue((ray_image(mapper) == everyone).all())
        mapper.SetNumberOfThreads(0)
        window.Render()
        self.assertGreaterEqual(mapper.GetLastNumberOfThreads(), 1)

    def test_sample_distance_locked_to_spacing(self):
        mapper, window = make_scene()
        mapper.SetSampleDistance(3.0)
        mapper.LockSampleDistanceToInputSpacingOn()
        window.Render()
        # The wavelet: 41^3 voxels of spacing 1, so min(1/2, 41 / 200) = 0.205.
        self.assertAlmostEqual(mapper.GetLastSampleDistance(), 0.205, places=12)

    def test_render_support_and_modes(self):
        mapper, window = make_scene()
        self.assertEqual(mapper.IsRenderSupported(window, None), 1)
        flat = vtkImageData()
        flat.SetDimensions(8, 8, 1)
        flat.AllocateScalars(3, 1)  # VTK_UNSIGNED_CHAR, one slice
        other = vtkPARCVolumeMapper()
        other.SetInputData(flat)
        self.assertEqual(other.IsRenderSupported(window, None), 0)
        self.assertEqual(mapper.GetLastUsedRenderMode(), 5)  # InvalidRenderMode
        mapper.SetRequestedRenderModeToRayCast()
        window.Render()
        self.assertEqual(mapper.GetLastUsedRenderMode(), 1)  # RayCastRenderMode
        before = ray_image(mapper)
        mapper.UseJitteringOn()  # warns once; the lattice stays exact
        mapper.UseDepthPassOn()  # no effect on the picture, nor have the memory limits
        mapper.SetMaxMemoryInBytes(1 << 20)
        mapper.SetMaxMemoryFraction(0.5)
        mapper.SetInterpolationModeToCubic()
        self.assertEqual((mapper.GetMaxMemoryInBytes(), mapper.GetMaxMemoryFraction(),
                          mapper.GetInterpolationMode()), (1 << 20, 0.5, 2))
        window.Render()
        self.assertTrue((ray_image(mapper) == before).all())

    def test_cell_scalars_are_voxels_at_the_cell_centres(self):
        # Cell scalars of a 21^3 image render as the point scalars of the 20^3 image of its
        # cell centres.
        mapper, window = make_scene()
        centres = numpy.arange(20) - 9.5
        z, y, x = numpy.meshgrid(centres, centres, centres, indexing="ij")
        values = (250 * numpy.exp(-(x * x + y * y + z * z) / 60.0)).ravel().astype(numpy.float32)
        cells = vtkImageData()
        cells.SetDimensions(21, 21, 21)
        cells.SetOrigin(-10, -10, -10)
        cells.GetCellData().SetScalars(numpy_to_vtk(values, deep=True))
        points = vtkImageData()
        points.SetDimensions(20, 20, 20)
        points.SetOrigin(-9.5, -9.5, -9.5)
        points.GetPointData().SetScalars(numpy_to_vtk(values, deep=True))
        images = []
        for image in (cells, points):
            mapper.SetInputData(image)
            mapper.SetScalarModeToDefault()
            window.Render()
            images.append(ray_image(mapper))
            self.assertGreater(images[-1][:, 3].max(), 0.1)
        self.assertLess(numpy.abs(images[0] - images[1]).max(), 1e-5)

    def test_rectilinear_grid_gets_a_way_out(self):
        mapper, window = make_scene()
        grid = vtkRectilinearGrid()
        grid.SetDimensions(4, 4, 4)
        for axis in (grid.SetXCoordinates, grid.SetYCoordinates, grid.SetZCoordinates):
            coordinates = vtkFloatArray()
            for c in (0.0, 1.0, 3.0, 7.0):
                coordinates.InsertNextValue(c)
            axis(coordinates)
        mapper.SetInputData(grid)
        errors = messages(mapper, vtkCommand.ErrorEvent)
        window.Render()
        self.assertEqual(mapper.GetLastRayCount(), 0)
        self.assertTrue(any("vtkRectilinearGrid" in e and "vtkResampleToImage" in e
                            for e in errors), errors)

    def test_two_dimensional_transfer_function_warns(self):
        mapper, window = make_scene()
        volume = window.GetRenderers().GetFirstRenderer().GetVolumes().GetItemAsObject(0)
        volume.GetProperty().SetTransferFunctionMode(1)  # vtkVolumeProperty.TF_2D
        warnings = messages(mapper, vtkCommand.WarningEvent)
        window.Render()
        window.Render()
        self.assertEqual(len([w for w in warnings if "2-D transfer functions" in w]), 1)
        self.assertGreater(mapper.GetLastContributingSampleCount(), 0, "1-D functions used")

    def test_dependent_components(self):
        # RGBA (4 unsigned char components) and colour + opacity (2 components), with
        # IndependentComponentsOff: opacity from the last component, bit for bit as that
        # component alone, colour from the others; the same image in every mode.
        mapper, window = make_scene()
        volume = window.GetRenderers().GetFirstRenderer().GetVolumes().GetItemAsObject(0)
        prop = volume.GetProperty()
        prop.ShadeOff()
        axis = numpy.arange(24) - 11.5
        z, y, x = numpy.meshgrid(axis, axis, axis, indexing="ij")
        density = (250 * numpy.exp(-(x * x + y * y + z * z) / 50.0)).ravel()

        def image_of(columns, dtype):
            data = numpy.ascontiguousarray(numpy.stack(columns, axis=1).astype(dtype))
            image = vtkImageData()
            image.SetDimensions(24, 24, 24)
            image.GetPointData().SetScalars(numpy_to_vtk(data, deep=True))
            return image

        def render(image, modes=(vtkPARCVolumeMapper.ACCELERATION_NONE,)):
            mapper.SetInputData(image)
            images = []
            for mode in modes:
                mapper.SetAccelerationMode(mode)
                window.Render()
                images.append(ray_image(mapper))
            for other in images[1:]:
                self.assertTrue((other == images[0]).all(), "every mode alike")
            return images[0]

        alone = render(image_of([density], numpy.uint8))
        self.assertGreater(alone[:, 3].max(), 0.1)
        prop.IndependentComponentsOff()
        red = numpy.full_like(density, 255)
        zero = numpy.zeros_like(density)
        rgba = render(image_of([red, zero, zero, density], numpy.uint8),
                      (vtkPARCVolumeMapper.ACCELERATION_NONE,
                       vtkPARCVolumeMapper.ACCELERATION_DEPTH_BUFFER,
                       vtkPARCVolumeMapper.ACCELERATION_COLOR_BUFFER))
        self.assertTrue((rgba[:, 3] == alone[:, 3]).all(), "opacity from the fourth")
        self.assertTrue((rgba[:, 0] == rgba[:, 3]).all(), "red, unshaded: red = alpha")
        self.assertEqual(rgba[:, 1:3].max(), 0.0)

        colour = render(image_of([numpy.full_like(density, 250), density], numpy.uint8))
        self.assertTrue((colour[:, 3] == alone[:, 3]).all(), "opacity from the second")
        expected = numpy.array(prop.GetRGBTransferFunction().GetColor(250.0))
        lit = colour[:, 3] > 0.05
        ratio = colour[lit, :3] / colour[lit, 3:4]
        self.assertLess(numpy.abs(ratio - expected).max(), 2e-3, "colour of the first")

        errors = messages(mapper, vtkCommand.ErrorEvent)
        render(image_of([red, zero, density], numpy.uint8))  # 3 dependent components
        self.assertEqual(mapper.GetLastRayCount(), 0)
        self.assertTrue(any("Dependent components" in e for e in errors), errors)

    def test_independent_components(self):
        # Two independent components (IndependentComponentsOn, VTK's default), each with
        # its own transfer functions, shading and weight: both show, every acceleration
        # mode gives the same float image, a component of weight 0 costs no gradient, and
        # what cannot be combined is refused with an error that says so.
        mapper, window = make_scene()
        volume = window.GetRenderers().GetFirstRenderer().GetVolumes().GetItemAsObject(0)
        prop = volume.GetProperty()
        axis = numpy.arange(24) - 11.5
        z, y, x = numpy.meshgrid(axis, axis, axis, indexing="ij")
        left = (250 * numpy.exp(-((x + 5) ** 2 + y * y + z * z) / 20.0)).ravel()
        right = (250 * numpy.exp(-((x - 5) ** 2 + y * y + z * z) / 20.0)).ravel()
        image = vtkImageData()
        image.SetDimensions(24, 24, 24)
        image.GetPointData().SetScalars(numpy_to_vtk(numpy.ascontiguousarray(
            numpy.stack([left, right], axis=1).astype(numpy.uint8)), deep=True))
        mapper.SetInputData(image)
        window.GetRenderers().GetFirstRenderer().ResetCamera()
        for c in (0, 1):
            opacity = vtkPiecewiseFunction()
            opacity.AddPoint(60, 0.0)
            opacity.AddPoint(250, 0.6)
            colour = vtkColorTransferFunction()
            colour.AddRGBPoint(0, 1.0 - c, 0.0, float(c))  # red, blue
            prop.SetScalarOpacity(c, opacity)
            prop.SetColor(c, colour)
        prop.SetShade(1, 0)

        def render_modes():
            return self.render_every_mode(mapper, window), mapper.GetLastGradientCount()

        both, gradients = render_modes()
        left_half, right_half = both[:, :60], both[:, 60:]
        self.assertGreater(left_half[..., 0].max(), 0.3, "component 0 red, on the left")
        self.assertGreater(right_half[..., 2].max(), 0.3, "component 1 blue, on the right")
        self.assertGreater(left_half[..., 0].sum(), 5 * left_half[..., 2].sum())
        self.assertGreater(right_half[..., 2].sum(), 5 * right_half[..., 0].sum())
        self.assertGreater(gradients, 0, "component 0 is shaded")
        renderer = window.GetRenderers().GetFirstRenderer()
        renderer.UseShadowsOn()
        self.assertTrue((render_modes()[0] == both).all(), "no shadows with components")
        self.assertEqual(mapper.GetLastShadowRayCount(), 0)
        self.assertEqual(mapper.GetLastLightFrustumCount(), 0, "no light passes for nothing")
        renderer.UseShadowsOff()

        prop.SetComponentWeight(0, 0.0)
        weighted, gradients = render_modes()
        self.assertEqual(weighted[..., 0].max(), 0.0, "component 0 of weight 0: no red")
        self.assertTrue((weighted[..., 3] > 0).any())
        self.assertEqual(gradients, 0, "only component 0 is shaded, and it is not sampled")
        prop.SetComponentWeight(0, 1.0)

        errors = messages(mapper, vtkCommand.ErrorEvent)
        mapper.SetBlendModeToIsoSurface()
        prop.GetIsoSurfaceValues().SetValue(0, 120.0)
        window.Render()
        self.assertEqual(mapper.GetLastRayCount(), 0)
        self.assertTrue(any("Independent components" in e for e in errors), errors)
        mapper.SetBlendModeToComposite()
        five = numpy.ascontiguousarray(numpy.stack([left] * 5, axis=1).astype(numpy.uint8))
        image.GetPointData().SetScalars(numpy_to_vtk(five, deep=True))
        window.Render()
        self.assertEqual(mapper.GetLastRayCount(), 0)
        self.assertTrue(any("5 components" in e for e in errors), errors)

    def test_binary_mask(self):
        # The wavelet (41^3, seen along z) behind a mask that keeps x indices below 20: the
        # left of the image as without the mask, the right empty, every mode alike.
        mapper, window = make_scene()
        window.Render()
        plain = ray_image(mapper).reshape(120, 120, 4)
        plain_contributing = mapper.GetLastContributingSampleCount()
        mapper.SetMaskInput(left_mask(255))
        window.Render()  # VTK's default mask type, a label map without label functions
        self.assertTrue((ray_image(mapper).reshape(120, 120, 4) == plain).all())
        mapper.SetMaskTypeToBinary()
        masked = self.render_every_mode(mapper, window)
        self.assertLess(mapper.GetLastContributingSampleCount(), plain_contributing)
        self.assertGreater(plain[:, :30, 3].max(), 0.05)
        self.assertTrue((masked[:, :30] == plain[:, :30]).all(), "left: as without the mask")
        self.assertGreater(plain[:, 90:, 3].max(), 0.05)
        self.assertEqual(masked[:, 90:, 3].max(), 0.0, "right: masked away")
        mapper.SetMaskInput(None)
        window.Render()
        self.assertTrue((ray_image(mapper).reshape(120, 120, 4) == plain).all())

    def test_label_map(self):
        # A label map (VTK's default mask type): label 1 on the left (x indices below 20)
        # with its own red colour and denser opacity, label 0 on the right with the default
        # functions; MaskBlendFactor blends them; every mode alike.
        mapper, window = make_scene()
        window.Render()
        plain = ray_image(mapper).reshape(120, 120, 4)
        mapper.SetMaskInput(left_mask(1))
        volume = window.GetRenderers().GetFirstRenderer().GetVolumes().GetItemAsObject(0)
        prop = volume.GetProperty()
        red = vtkColorTransferFunction()
        red.AddRGBPoint(0, 1.0, 0.0, 0.0)
        dense = vtkPiecewiseFunction()
        dense.AddPoint(60, 0.0)
        dense.AddPoint(250, 0.8)
        prop.SetLabelColor(1, red)
        prop.SetLabelScalarOpacity(1, dense)

        def render_modes():
            return self.render_every_mode(mapper, window)

        labelled = render_modes()
        self.assertTrue((labelled[:, 90:] == plain[:, 90:]).all(), "right: label 0, default")
        left = labelled[:, :30]
        self.assertGreater(left[..., 3].sum(), 1.5 * plain[:, :30, 3].sum(), "denser")
        self.assertGreater(left[..., 0].sum(), 20 * left[..., 2].sum(), "red")
        mapper.SetMaskBlendFactor(0.5)
        half = render_modes()[:, :30]
        self.assertGreater(half[..., 2].sum(), 5 * left[..., 2].sum(), "half the default blue")
        mapper.SetMaskBlendFactor(0.0)
        self.assertTrue((render_modes() == plain).all(), "blend factor 0: the default")
        mapper.SetMaskBlendFactor(1.0)
        errors = messages(mapper, vtkCommand.ErrorEvent)
        mapper.SetBlendModeToMaximumIntensity()
        window.Render()
        self.assertEqual(mapper.GetLastRayCount(), 0)
        self.assertTrue(any("label-map" in e for e in errors), errors)

    def test_final_color_window_level(self):
        # Window 0.5 and level 0.25 brighten the displayed image (rgb / window + (1/2 -
        # level / window) alpha); window 1 and level 0.5 change nothing; the float
        # ray-cast image is never adjusted.
        mapper, window = make_scene()
        window.GetRenderers().GetFirstRenderer().SetBackground(0, 0, 0)

        def shown():
            pixels = vtkUnsignedCharArray()
            window.GetPixelData(0, 0, 119, 119, 0, pixels, 0)
            return vtk_to_numpy(pixels).astype(int)
        window.Render()
        plain, plain_shown = ray_image(mapper), shown()
        mapper.SetFinalColorWindow(0.5)
        mapper.SetFinalColorLevel(0.25)
        window.Render()
        self.assertTrue((ray_image(mapper) == plain).all(), "the float image is not adjusted")
        self.assertGreater(shown().mean(), 1.3 * plain_shown.mean())
        mapper.SetFinalColorWindow(1.0)
        mapper.SetFinalColorLevel(0.5)
        window.Render()
        self.assertTrue((shown() == plain_shown).all())

if __name__ == "__main__":
    result = unittest.main(exit=False).result
    sys.exit(0 if result.wasSuccessful() else 1)
