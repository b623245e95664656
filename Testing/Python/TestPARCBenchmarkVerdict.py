"""The benchmark report's verdict (scripts/benchmark_report.py): for each error, the mapper
that reaches it fastest, this mapper's acceleration modes counted as one contender, and
the mappers that never reach it."""
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "scripts"))
from benchmark_report import verdict  # noqa: E402


def row(mapper, distance, seconds, rmse):
    return {"mapper": mapper, "image_sample_distance": "1", "sample_distance": str(distance),
            "median_s": str(seconds), "rmse": str(rmse)}


ROWS = [
    row("PARC None", 1, 0.30, 3.0), row("PARC None", 0.5, 0.50, 0.4),
    row("PARC Auto", 1, 0.20, 3.0), row("PARC Auto", 0.5, 0.35, 0.4),
    row("vtkFixedPointVolumeRayCastMapper", 1, 0.10, 3.5),
    row("vtkFixedPointVolumeRayCastMapper", 0.5, 0.18, 1.5),
]


class TestPARCBenchmarkVerdict(unittest.TestCase):
    def lines_for(self, error):
        return next(line for line in verdict(ROWS) if line.startswith(f"- RMSE {error:g}:"))

    def test_fastest_to_each_error(self):
        # RMSE 4: FixedPoint at 0.10 s, this mapper's fastest mode (Auto, 0.20 s) 2x slower.
        line = self.lines_for(4)
        self.assertIn("**vtkFixedPointVolumeRayCastMapper 0.100 s", line)
        self.assertIn("PARC Auto 0.200 s (2.0x", line)
        self.assertNotIn("PARC None", line)
        # RMSE 2: FixedPoint at 0.5 voxel; this mapper needs 0.5 voxel too (0.35 s).
        self.assertIn("**vtkFixedPointVolumeRayCastMapper 0.180 s", self.lines_for(2))
        # RMSE 0.5: only this mapper reaches it.
        line = self.lines_for(0.5)
        self.assertIn("**PARC Auto 0.350 s", line)
        self.assertIn("never reached by vtkFixedPointVolumeRayCastMapper", line)

    def test_one_line_summary_and_unreached_errors(self):
        lines = verdict(ROWS)
        self.assertEqual(lines[0], "**Verdict: fastest vtkFixedPointVolumeRayCastMapper to RMSE "
                         "4, 2; PARC Auto to RMSE 1, 0.5.**")
        self.assertEqual(self.lines_for(0.25), "- RMSE 0.25: no mapper reaches it here.")


if __name__ == "__main__":
    unittest.main()
