"""The quantized-normal shading model (SetShadingModelToQuantizedNormals) in a VTK
pipeline: it replaces the per-sample gradients, stays close to exact shading, gives the
same float image in every acceleration mode, holds 2 bytes per voxel only while it is the
model, and leaves scenes with positional lights to exact shading."""
import unittest

import numpy as np
from parc import vtkPARCVolumeMapper
from parctesthelpers import ray_image
from TestPARCPipeline import make_scene
from vtkmodules.vtkRenderingCore import vtkLight

VOXELS = 41 ** 3  # make_scene's wavelet
# What the model holds: 2 bytes of normal per voxel, and a table of 32 bytes per normal
# (diffuse and specular factors) for the 128 x 128 normals and the zero one.
NORMALS_BYTES = 2 * VOXELS + 32 * (1 + 128 * 128)


class TestPARCShadingModel(unittest.TestCase):
    def render(self, mapper, window, mode=vtkPARCVolumeMapper.ACCELERATION_NONE):
        mapper.SetAccelerationMode(mode)
        window.Render()
        return ray_image(mapper)

    def test_quantized_normals_replace_gradients(self):
        mapper, window = make_scene()
        self.assertEqual(mapper.GetShadingModel(), vtkPARCVolumeMapper.SHADING_EXACT)
        exact = self.render(mapper, window)
        self.assertGreater(mapper.GetLastGradientCount(), 0)
        exact_memory = mapper.GetMemorySize()

        mapper.SetShadingModelToQuantizedNormals()
        quantized = self.render(mapper, window)
        self.assertEqual(mapper.GetLastShadingModel(),
                         vtkPARCVolumeMapper.SHADING_QUANTIZED_NORMALS)
        self.assertEqual(mapper.GetLastGradientCount(), 0)
        self.assertEqual(mapper.GetMemorySize() - exact_memory, NORMALS_BYTES)
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
        self.assertEqual(quantized_memory - mapper.GetMemorySize(), NORMALS_BYTES,
                         "the normals are freed")

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
