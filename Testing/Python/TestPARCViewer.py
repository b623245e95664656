"""parc-render --interactive, driven by a recorded interaction (vtkInteractorEventRecorder
playback) in an on-screen window under Xvfb: a trackball drag and the viewer's keys. Checks
that the frames are rendered (interactive ones held to the budget, at a coarser image sample
distance), that each key acts, and that the still frame's screenshot equals a fresh exact
render of the final settings and camera (parc-render, no acceleration)."""
import json
import os
import subprocess
import tempfile
import unittest

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter
from vtkmodules.vtkRenderingVolume import vtkVolumeMapper

PARC_RENDER = os.environ["PARC_RENDER"]
SIZE = 160
ACCELERATION_NONE, ACCELERATION_DEPTH_BUFFER = 0, 1  # vtkPARCVolumeMapper's enumeration

# A drag of the left button (trackball rotation), then: b (composite -> maximum intensity),
# a twice (Auto -> None -> DepthBuffer), l (unshaded -> exact shading), - (still frames at
# image sample distance 1.5), c (screenshot).
DRAG = ["LeftButtonPressEvent 80 80 0 0 0 0"] + [
    "MouseMoveEvent %d %d 0 0 0 0" % (80 + 6 * i, 80 + 3 * i) for i in range(1, 9)] + [
    "LeftButtonReleaseEvent 128 104 0 0 0 0"]
KEYS = [("b", 98), ("a", 97), ("a", 97), ("l", 108), ("minus", 45), ("c", 99)]
EVENTS = ["# StreamVersion 1.1"] + DRAG + [
    "CharEvent 128 104 0 %d 1 %s" % (code, sym) for sym, code in KEYS]


def png_pixels(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    return vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())


class TestPARCViewer(unittest.TestCase):
    def test_recorded_interaction(self):
        with tempfile.TemporaryDirectory() as tmp:
            volume = os.path.join(tmp, "wavelet.vti")
            source = vtkRTAnalyticSource()
            source.SetWholeExtent(-20, 20, -20, 20, -20, 20)
            writer = vtkXMLImageDataWriter()
            writer.SetFileName(volume)
            writer.SetInputConnection(source.GetOutputPort())
            writer.Write()
            log = os.path.join(tmp, "events.log")
            with open(log, "w") as f:
                f.write("\n".join(EVENTS) + "\n")
            prefix = os.path.join(tmp, "shot")
            run = subprocess.run(
                [PARC_RENDER, volume, "--size", str(SIZE), "--interactive", "--playback", log,
                 "--screenshot-prefix", prefix], capture_output=True, text=True, check=True)
            self.assertNotIn("ERR", run.stderr)
            output = run.stdout
            state = json.loads(output[output.index("{"):])

            # The first frame, frames while dragging, one per key, two for the screenshot.
            self.assertGreaterEqual(state["frames"], 1 + len(DRAG) - 1 + len(KEYS) - 1)
            self.assertEqual(state["blend"], vtkVolumeMapper.MAXIMUM_INTENSITY_BLEND)
            self.assertEqual(state["acceleration"], ACCELERATION_DEPTH_BUFFER)
            self.assertEqual(state["shading"], 1)
            self.assertEqual(state["image_sample_distance"], 1.5)
            self.assertGreaterEqual(state["interactive_frames"], len(DRAG) - 2,
                                    "the drag's frames are interactive (held to the budget)")
            self.assertEqual(state["last_interactive"], 0, "the last frame is a still one")
            self.assertEqual(state["last_image_sample_distance"], 1.5)
            self.assertNotEqual(state["view_up"], [0.0, 1.0, 0.0], "the drag turned the camera")
            shot = prefix + "-1.png"
            self.assertIn("wrote " + shot, output)

            fresh = os.path.join(tmp, "fresh.png")
            triple = lambda v: ",".join(repr(x) for x in v)  # noqa: E731
            subprocess.run(
                [PARC_RENDER, volume, "--size", str(SIZE), "--blend", "mip", "--shade",
                 "--acceleration", "none", "--image-sample-distance", "1.5",
                 "--camera-position", triple(state["camera_position"]),
                 "--focal-point", triple(state["focal_point"]),
                 "--view-up", triple(state["view_up"]), "--output", fresh],
                capture_output=True, text=True, check=True)
            mine, theirs = png_pixels(shot), png_pixels(fresh)
            self.assertGreater(int(mine.max()), 0, "the screenshot shows the volume")
            self.assertTrue(np.array_equal(mine, theirs),
                            "the still frame equals a fresh exact render (%d values differ)"
                            % int((mine != theirs).sum()))


if __name__ == "__main__":
    unittest.main()
