"""The object-factory drop-in from Python: parc.enable_overrides() makes
vtkGPUVolumeRayCastMapper() a PARC mapper whose images are vtkPARCVolumeMapper's, a
vtkSmartVolumeMapper made then renders through PARC, parc.disable_overrides() restores VTK's
mapper; and a program that never imports parc gets the PARC mapper with
PARC_OVERRIDE_GPU_MAPPER=1 and the library preloaded (LD_PRELOAD), VTK's without."""
import os
import subprocess
import sys
import unittest

import numpy as np
import parc
from parc import vtkPARCOverrides, vtkPARCVolumeMapper
from vtkmodules.vtkRenderingVolume import vtkGPUVolumeRayCastMapper
from vtkmodules.vtkRenderingVolumeOpenGL2 import vtkSmartVolumeMapper
from parctesthelpers import offscreen_window, ray_image
from TestPARCPipeline import make_scene

# A program written for VTK alone: it never imports parc.
UNMODIFIED_PROGRAM = """
from vtkmodules.vtkRenderingVolume import vtkGPUVolumeRayCastMapper
import vtkmodules.vtkRenderingOpenGL2
import vtkmodules.vtkRenderingVolumeOpenGL2
print(vtkGPUVolumeRayCastMapper().GetClassName())
"""


class TestPARCOverrides(unittest.TestCase):
    def tearDown(self):
        parc.disable_overrides()

    def test_enable_and_disable(self):
        parc.enable_overrides()
        self.assertTrue(parc.overrides_enabled())
        gpu = vtkGPUVolumeRayCastMapper()
        self.assertEqual(gpu.GetClassName(), "vtkPARCGPUVolumeRayCastMapper")
        reference, window = make_scene(64)
        window.Render()
        expected = ray_image(reference)
        volume = window.GetRenderers().GetFirstRenderer().GetVolumes().GetItemAsObject(0)
        gpu.SetInputConnection(reference.GetInputConnection(0, 0))
        volume.SetMapper(gpu)
        window.Render()
        self.assertTrue(np.array_equal(ray_image(vtkPARCOverrides.GetPARCMapper(gpu)), expected))
        smart = vtkSmartVolumeMapper()
        smart.SetInputConnection(reference.GetInputConnection(0, 0))
        volume.SetMapper(smart)
        window.Render()
        self.assertEqual(smart.GetLastUsedRenderMode(), vtkSmartVolumeMapper.GPURenderMode)
        self.assertGreater(vtkPARCOverrides.GetPARCMapper(smart).GetLastSampleCount(), 0)
        parc.disable_overrides()
        self.assertFalse(parc.overrides_enabled())
        self.assertEqual(vtkGPUVolumeRayCastMapper().GetClassName(),
                         "vtkOpenGLGPUVolumeRayCastMapper")
        self.assertIsNone(vtkPARCOverrides.GetPARCMapper(vtkSmartVolumeMapper()))

    def test_environment_variable(self):
        library = os.environ["PARC_LIBRARY"]
        for value, expected in (("1", "vtkPARCGPUVolumeRayCastMapper"),
                                ("0", "vtkOpenGLGPUVolumeRayCastMapper")):
            environment = dict(os.environ, PARC_OVERRIDE_GPU_MAPPER=value, LD_PRELOAD=library)
            environment.pop("PYTHONPATH", None)  # the program knows nothing of parc
            out = subprocess.run([sys.executable, "-c", UNMODIFIED_PROGRAM], env=environment,
                                 capture_output=True, text=True, check=True).stdout
            self.assertEqual(out.strip(), expected, "PARC_OVERRIDE_GPU_MAPPER=" + value)


if __name__ == "__main__":
    unittest.main()
