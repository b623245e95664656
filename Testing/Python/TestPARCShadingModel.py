"""The quantized-normal shading model (SetShadingModelToQuantizedNormals) in a VTK
pipeline: it replaces the per-sample gradients, stays close to exact shading, gives the
same float image in every acceleration mode, holds 2 bytes per voxel only while it is the
model, and leaves scenes with positional lights to exact shading. The ambient model: with
the lights' ambient (FixedPoint's), VTK's default lights give no ambient term and a
light's ambient colour tints it; with the material's (the default), white ambient light."""
import unittest

import numpy as np
from parc import vtkPARCVolumeMapper
from parctesthelpers import ray_image
from TestPARCPipeline import make_scene
from vtkmodules.vtkRenderingCore import vtkLight

VOXELS = 41 ** 3  # make_scene's wavelet
NORMALS = 1 + 128 * 128  # the 128 x 128 directions and the zero normal
# What the model holds: 2 bytes of normal per voxel, and a table of the diffuse and
# specular factors of each normal: one of each under white lights (8 bytes), one of each
# per colour channel otherwise (32 bytes).
NORMALS_BYTES = 2 * VOXELS + 8 * NORMALS
COLOURED_TABLE_BYTES = 32 * NORMALS


class TestPARCShadingModel(unittest.TestCase):
    def render(self, mapper, window, mode=vtkPARCVolumeMapper.ACCELERATION_NONE):
        mapper.SetAccelerationMode(mode)
        window.Render()
        return ray_image(mapper)

    def test_ambient_from_the_lights(self):
        def image(model, ambient=0.4, light_ambient=None):
            mapper, window = make_scene()
            renderer = window.GetRenderers().GetFirstRenderer()
            renderer.GetVolumes().GetItemAsObject(0).GetProperty().SetAmbient(ambient)
            if light_ambient is not None:
                light = vtkLight()
                light.SetLightTypeToHeadlight()
                light.SetAmbientColor(*light_ambient)
                renderer.AddLight(light)
            mapper.SetAmbientModel(model)
            return self.render(mapper, window)

        material = vtkPARCVolumeMapper.AMBIENT_MATERIAL
        lights = vtkPARCVolumeMapper.AMBIENT_LIGHTS
        # VTK's default light has a black ambient colour: no ambient term.
        self.assertTrue(np.array_equal(image(lights), image(material, ambient=0.0)))
        self.assertFalse(np.array_equal(image(lights), image(material)))
        # A white ambient light is the material model's.
        self.assertTrue(np.array_equal(image(lights, light_ambient=(1, 1, 1)),
                                       image(material, light_ambient=(1, 1, 1))))
        # A red ambient light adds to red only.
        red = image(lights, light_ambient=(1, 0, 0))
        dark = image(lights, light_ambient=(0, 0, 0))
        self.assertTrue((red[:, 0] >= dark[:, 0]).all() and (red[:, 0] > dark[:, 0]).any())
        self.assertTrue(np.array_equal(red[:, 1:], dark[:, 1:]))

    def test_quantized_normals_replace_gradients(self):
        mapper, window = make_scene()
        self.assertEqual(mapper.GetShadingModel(), vtkPARCVolumeMapper.SHADING_EXACT)
        exact = self.render(mapper, window)
        self.assertGreater(mapper.GetLastGradientCount(), 0)
        exact_memory = mapper.GetMemorySize()
        caches = mapper.GetLastGradientCacheSize()  # the gradients' cell caches
        self.assertGreater(caches, 0)

        mapper.SetShadingModelToQuantizedNormals()
        quantized = self.render(mapper, window)
        self.assertEqual(mapper.GetLastShadingModel(),
                         vtkPARCVolumeMapper.SHADING_QUANTIZED_NORMALS)
        self.assertEqual(mapper.GetLastGradientCount(), 0)
        self.assertEqual(mapper.GetLastGradientCacheSize(), 0)
        self.assertEqual(mapper.GetMemorySize() - exact_memory, NORMALS_BYTES - caches)
        difference = np.abs(quantized - exact)
        self.assertGreater(difference.max(), 0.0, "the quantized model is in use")
        self.assertLess(difference.mean(), 0.005)
        self.assertLess(difference.max(), 0.1)
        self.assertIn("ShadingModel: QuantizedNormals", str(mapper))

        for mode in (vtkPARCVolumeMapper.ACCELERATION_DEPTH_BUFFER,
                     vtkPARCVolumeMapper.ACCELERATION_COLOR_BUFFER,
                     vtkPARCVolumeMapper.ACCELERATION_BOTH,
                     vtkPARCVolumeMapper.ACCELERATION_SUPERCELL_WALK,
                     vtkPARCVolumeMapper.ACCELERATION_AUTO):
            image = self.render(mapper, window, mode)
            self.assertTrue(np.array_equal(image, quantized),
                            vtkPARCVolumeMapper.GetAccelerationModeAsString(mode))

        self.render(mapper, window)
        quantized_memory = mapper.GetMemorySize()
        mapper.SetShadingModelToExact()
        self.assertTrue(np.array_equal(self.render(mapper, window), exact))
        self.assertEqual(mapper.GetLastShadingModel(), vtkPARCVolumeMapper.SHADING_EXACT)
        self.assertEqual(mapper.GetLastGradientCacheSize(), caches)
        self.assertEqual(quantized_memory - mapper.GetMemorySize(), NORMALS_BYTES - caches,
                         "the normals are freed")

    def test_coloured_lights_take_a_table_per_channel(self):
        mapper, window = make_scene()
        mapper.SetShadingModelToQuantizedNormals()
        white = self.render(mapper, window)
        white_memory = mapper.GetMemorySize()
        renderer = window.GetRenderers().GetFirstRenderer()
        light = vtkLight()
        light.SetLightTypeToCameraLight()
        light.SetColor(1.0, 0.5, 0.25)
        renderer.AddLight(light)
        coloured = self.render(mapper, window)
        self.assertEqual(mapper.GetLastShadingModel(),
                         vtkPARCVolumeMapper.SHADING_QUANTIZED_NORMALS)
        self.assertEqual(mapper.GetMemorySize() - white_memory,
                         COLOURED_TABLE_BYTES - 8 * NORMALS)
        self.assertFalse(np.array_equal(coloured, white))
        # The orange light lights red more than blue: the channels are shaded apart.
        lit = white[..., 3] > 0.1

        def red_over_blue(image):
            return image[..., 0][lit].sum() / image[..., 2][lit].sum()
        self.assertGreater(red_over_blue(coloured), 1.05 * red_over_blue(white))
        for mode in (vtkPARCVolumeMapper.ACCELERATION_DEPTH_BUFFER,
                     vtkPARCVolumeMapper.ACCELERATION_COLOR_BUFFER):
            self.assertTrue(np.array_equal(self.render(mapper, window, mode), coloured),
                            vtkPARCVolumeMapper.GetAccelerationModeAsString(mode))

    def test_positional_lights_are_shaded_exactly(self):
        mapper, window = make_scene()
        renderer = window.GetRenderers().GetFirstRenderer()
        light = vtkLight()
        light.SetPositional(True)
        light.SetPosition(renderer.GetActiveCamera().GetPosition())
        renderer.AddLight(light)
        exact = self.render(mapper, window)
        memory = mapper.GetMemorySize()
        mapper.SetShadingModelToQuantizedNormals()
        self.assertTrue(np.array_equal(self.render(mapper, window), exact))
        self.assertEqual(mapper.GetLastShadingModel(), vtkPARCVolumeMapper.SHADING_EXACT)
        self.assertEqual(mapper.GetMemorySize(), memory, "no normals made for nothing")

    def test_unshaded_volumes_make_no_normals(self):
        mapper, window = make_scene()
        volume = window.GetRenderers().GetFirstRenderer().GetVolumes().GetItemAsObject(0)
        volume.GetProperty().ShadeOff()
        mapper.SetShadingModelToQuantizedNormals()
        self.render(mapper, window)
        memory = mapper.GetMemorySize()
        self.assertEqual(mapper.GetLastShadingModel(), vtkPARCVolumeMapper.SHADING_EXACT)
        volume.GetProperty().ShadeOn()
        self.render(mapper, window)
        self.assertEqual(mapper.GetMemorySize() - memory, NORMALS_BYTES)


if __name__ == "__main__":
    unittest.main()
