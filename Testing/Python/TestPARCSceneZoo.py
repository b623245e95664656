"""The scene zoo: the mapper in the GL contexts and passes VTK users set up (multisampling,
FXAA, depth peeling with and without volumes, several renderers, layers and viewports,
windows created before and after the first render, off-screen windows, window captures,
render-pass chains, volume picking), each scene rendered by vtkPARCVolumeMapper twice, each
time in a fresh process, and once by vtkFixedPointVolumeRayCastMapper (parcscenezoo.py).
PARC's two images are identical (nondeterminism is a bug) and within a stated tolerance of
FixedPoint's; the picker picks the same point. With dual depth peeling FixedPoint draws
garbage (VTK peels volumes with shader code only its GPU mapper has): PARC's image there is
compared with FixedPoint's of the same scene peeled without volumes, which it must equal
in kind (PARC draws its volume after the peels in both)."""
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from parcscenezoo import SCENES  # noqa: E402

ZOO = os.path.join(os.path.dirname(os.path.abspath(__file__)), "parcscenezoo.py")
# Mean absolute difference from FixedPoint's image in grey levels of 255, and the largest
# share of values more than 16 levels apart: the two mappers sample and interpolate
# differently, so their images are close, not equal (about 0.5 levels here).
MEAN_TOLERANCE = 2.0
OUTLIER_TOLERANCE = 0.01
# FixedPoint's scene to compare a PARC scene with, where they differ.
FIXED_POINT_SCENE = {"dual-depth-peeling": "depth-peeling"}


def read_png(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    return vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars()).astype(float)


class TestPARCSceneZoo(unittest.TestCase):
    def run_scene(self, scene, kind, path):
        result = subprocess.run([sys.executable, ZOO, scene, kind, path],
                                capture_output=True, text=True, timeout=300)
        self.assertEqual(result.returncode, 0, "%s with %s: %s" % (scene, kind, result.stderr))
        return read_png(path)

    def test_scenes(self):
        rows = []
        with tempfile.TemporaryDirectory() as folder:
            for scene in SCENES:
                with self.subTest(scene=scene):
                    first = self.run_scene(scene, "parc", os.path.join(folder, scene + "-1.png"))
                    second = self.run_scene(scene, "parc", os.path.join(folder, scene + "-2.png"))
                    self.assertTrue(np.array_equal(first, second),
                                    "%s: two runs drew different images" % scene)
                    reference_scene = FIXED_POINT_SCENE.get(scene, scene)
                    reference = self.run_scene(reference_scene, "fixed-point",
                                               os.path.join(folder, scene + "-fp.png"))
                    difference = np.abs(first - reference)
                    mean, outliers = difference.mean(), (difference > 16).mean()
                    rows.append((scene, reference_scene, mean, outliers))
                    self.assertGreater(first.max(), 64, "%s: the image is dark" % scene)
                    self.assertLessEqual(mean, MEAN_TOLERANCE, scene)
                    self.assertLessEqual(outliers, OUTLIER_TOLERANCE, scene)
                    if scene == "picker":
                        picks = [open(os.path.join(folder, scene + suffix + ".pick")).read()
                                 for suffix in ("-1.png", "-fp.png")]
                        self.assertEqual(picks[0], picks[1], "the picked points differ")
                        self.assertTrue(picks[0].startswith("1 True"), picks[0])
        print("| scene | FixedPoint's scene | mean difference (of 255) | values > 16 apart |")
        print("|---|---|---|---|")
        for scene, reference_scene, mean, outliers in rows:
            print("| %s | %s | %.3f | %.4f |" % (scene, reference_scene, mean, outliers))


if __name__ == "__main__":
    unittest.main()
