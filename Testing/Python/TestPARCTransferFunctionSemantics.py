"""The transfer functions mean what VTK's GetColor and GetValue say, in every setting that
changes them, for every blend mode that maps a sample through them and for independent
components: a volume of one scalar value v draws, in its ray-cast image, the colour
GetColor(v) (premultiplied colour over alpha) and alpha > 0 exactly where GetValue(v) > 0.
Settings: colour clamping on (the first node's colour below it: VTK 9.1's GetTable gives
black there) and off, a node's midpoint and sharpness, the Lab, diverging, HSV and step
colour spaces, below- and above-range colours, opacity clamping off, and an opacity node's
midpoint and sharpness. The gradient opacity function measures gradients as VTK's mappers
do: scalar units per mean voxel spacing."""
import unittest

import numpy as np
from parc import vtkPARCVolumeMapper
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPiecewiseFunction
from vtkmodules.vtkRenderingCore import vtkColorTransferFunction, vtkVolumeProperty
from parctesthelpers import offscreen_window, ray_image

# The colour table has 1024 entries over the data range, interpolated linearly; an exact
# value at each entry. Between entries a colour function's curve differs from the chord.
COLOUR_TOLERANCE = 2e-3
# A node's midpoint and sharpness make an opacity segment a curve the mapper follows with
# 32 linear pieces (classification needs piecewise-linear opacity).
OPACITY_TOLERANCE = 0.02
# The blend modes that map samples through the functions (average and additive blending
# give grey images of the scalars, as VTK defines them).
BLENDS = {"composite": vtkPARCVolumeMapper.COMPOSITE_BLEND,
          "maximum": vtkPARCVolumeMapper.MAXIMUM_INTENSITY_BLEND,
          "minimum": vtkPARCVolumeMapper.MINIMUM_INTENSITY_BLEND}
# The other value of the volume, in a corner far from the rays: the colour table spans the
# data range, from it to the value or from the value to it. From 0, the value is the
# table's last entry (where VTK 9.1's GetTable gave black at a first node).
CORNERS = (0.0, 200.0)


def constant_volume(value, corner, components=1):
    """16^3 points of value (each component), one corner point of corner."""
    n = 16
    data = np.full((n * n * n, components), value, dtype=np.float32)
    data[0, :] = corner
    image = vtkImageData()
    image.SetDimensions(n, n, n)
    array = numpy_to_vtk(data, deep=1)
    array.SetName("value")
    image.GetPointData().SetScalars(array)
    return image


def colours():
    """Colour functions by name: nodes at 50 (red), 100 (green) and 150 (blue)."""
    def make(setup=None, midpoint=0.5, sharpness=0.0):
        c = vtkColorTransferFunction()
        c.AddRGBPoint(50, 1, 0, 0, midpoint, sharpness)
        c.AddRGBPoint(100, 0, 1, 0, midpoint, sharpness)
        c.AddRGBPoint(150, 0, 0, 1)
        if setup:
            setup(c)
        return c

    def below_above(c):
        c.SetBelowRangeColor(1, 1, 0)
        c.SetAboveRangeColor(0, 1, 1)
        c.UseBelowRangeColorOn()
        c.UseAboveRangeColorOn()

    return {
        "clamped": make(),
        "not clamped": make(lambda c: c.ClampingOff()),
        "midpoint and sharpness": make(midpoint=0.25, sharpness=0.6),
        "Lab": make(lambda c: c.SetColorSpaceToLab()),
        "diverging": make(lambda c: c.SetColorSpaceToDiverging()),
        "HSV": make(lambda c: c.SetColorSpaceToHSV()),
        "step": make(lambda c: c.SetColorSpaceToStep()),
        "below and above range": make(below_above),
    }


def opacities():
    """Opacity functions by name: nonzero from 40 to 160."""
    def make(clamping=True, midpoint=0.5, sharpness=0.0):
        o = vtkPiecewiseFunction()
        o.AddPoint(40, 0.1, midpoint, sharpness)
        o.AddPoint(120, 0.9, midpoint, sharpness)
        o.AddPoint(160, 0.4)
        o.SetClamping(clamping)
        return o

    return {"clamped": make(), "not clamped": make(clamping=False),
            "midpoint and sharpness": make(midpoint=0.3, sharpness=0.5)}


# Scalar values to look at: below, on and between the nodes, and above them.
VALUES = [20.0, 50.0, 62.5, 75.0, 100.0, 137.0, 150.0, 180.0]


class TestPARCTransferFunctionSemantics(unittest.TestCase):
    def render(self, value, corner, colour, opacity, blend, components=1):
        mapper = vtkPARCVolumeMapper()
        mapper.SetInputData(constant_volume(value, corner, components))
        mapper.SetBlendMode(blend)
        prop = vtkVolumeProperty()
        prop.SetInterpolationTypeToLinear()
        for c in range(components):
            prop.SetColor(c, colour)
            prop.SetScalarOpacity(c, opacity)
        if components > 1:
            prop.IndependentComponentsOn()
            prop.SetComponentWeight(1, 0.0)  # component 0 alone decides
        window = offscreen_window(mapper, prop, 24)
        window.Render()
        side = int(round(np.sqrt(len(ray_image(mapper)))))  # a square window's image
        return ray_image(mapper).reshape(side, side, 4)[side // 2, side // 2]

    def check(self, name, value, colour, opacity, blend_name, components=1):
        for corner in CORNERS:
            self.check_one(name, value, corner, colour, opacity, blend_name, components)

    def check_one(self, name, value, corner, colour, opacity, blend_name, components):
        rgba = self.render(value, corner, colour, opacity, BLENDS[blend_name], components)
        expected_colour = np.array(colour.GetColor(value))
        expected_opacity = opacity.GetValue(value)
        where = "%s, value %g (data range to %g), %s, %d component(s)" % (
            name, value, corner, blend_name, components)
        if expected_opacity <= 0.0:
            self.assertEqual(rgba[3], 0.0, where + ": alpha where the opacity is 0")
            return
        self.assertGreater(rgba[3], 0.0, where + ": no alpha where the opacity is not 0")
        drawn = rgba[:3] / rgba[3]
        self.assertLess(np.abs(drawn - expected_colour).max(), COLOUR_TOLERANCE,
                        "%s: colour %s, GetColor %s" % (where, drawn, expected_colour))
        if blend_name in ("maximum", "minimum"):  # one sample's opacity, uncorrected
            self.assertLess(abs(rgba[3] - expected_opacity), OPACITY_TOLERANCE,
                            "%s: alpha %g, GetValue %g" % (where, rgba[3], expected_opacity))

    def test_colour_settings(self):
        opacity = opacities()["clamped"]
        for name, colour in colours().items():
            for blend in BLENDS:
                for value in VALUES:
                    if opacity.GetValue(value) > 0:
                        self.check(name, value, colour, opacity, blend)

    def test_opacity_settings(self):
        colour = colours()["clamped"]
        for name, opacity in opacities().items():
            for blend in BLENDS:
                for value in VALUES:
                    self.check(name, value, colour, opacity, blend)

    def test_independent_components(self):
        for name, colour in colours().items():
            for value in (50.0, 75.0, 180.0):
                self.check(name, value, colour, opacities()["not clamped"], "maximum", 2)
                self.check(name, value, colour, opacities()["clamped"], "composite", 2)

    def test_gradient_opacity_per_mean_spacing(self):
        # A ramp of 10 scalar units per voxel along x: 10 / sx per world unit, 10 / sx *
        # mean(spacing) as VTK's mappers measure it; the gradient opacity opens between.
        for spacing in ((4.0, 1.0, 1.0), (1.0, 1.0, 4.0)):
            n = 16
            ramp = np.tile(10.0 * np.arange(n, dtype=np.float32), n * n)
            image = vtkImageData()
            image.SetDimensions(n, n, n)
            image.SetSpacing(*spacing)
            array = numpy_to_vtk(ramp, deep=1)
            image.GetPointData().SetScalars(array)
            world = 10.0 / spacing[0]
            vtk_measure = world * sum(spacing) / 3.0
            threshold = 0.5 * (world + vtk_measure)
            for opens_at, visible in ((threshold, True), (1.5 * vtk_measure, False)):
                gradient = vtkPiecewiseFunction()
                gradient.AddPoint(0.0, 0.0)
                gradient.AddPoint(opens_at, 0.0)
                gradient.AddPoint(opens_at * 1.01, 1.0)
                gradient.AddPoint(1e6, 1.0)
                opacity = vtkPiecewiseFunction()
                opacity.AddPoint(0.0, 1.0)
                opacity.AddPoint(200.0, 1.0)
                prop = vtkVolumeProperty()
                prop.SetScalarOpacity(opacity)
                prop.SetGradientOpacity(gradient)
                mapper = vtkPARCVolumeMapper()
                mapper.SetInputData(image)  # composite: maximum intensity has none
                window = offscreen_window(mapper, prop, 24)
                window.Render()
                shown = bool((ray_image(mapper)[:, 3] > 0).any())
                self.assertEqual(shown, visible, "spacing %s: gradient %g a world unit, %g "
                                 "as VTK measures it, opacity from %g" % (
                                     spacing, world, vtk_measure, opens_at))


if __name__ == "__main__":
    unittest.main()
