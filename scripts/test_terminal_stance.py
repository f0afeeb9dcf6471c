"""Unit test of scripts/terminal_stance.py's reconstruction, without data or network:
python3 -m unittest scripts/test_terminal_stance.py"""
import math
import pathlib
import sys
import unittest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from terminal_stance import posture, segments  # noqa: E402


def curves(at0, at50):
    """Normative-style curves {(joint, 'X'): (pct, mean, sd)} holding (tilt, hip, knee, ankle)
    at 0 % and 50 % of the cycle."""
    names = ("PelvisAngles", "HipAngles", "KneeAngles", "AnkleAngles")
    return {(n, "X"): ([0.0, 50.0], [a, b], [0.0, 0.0]) for n, a, b in zip(names, at0, at50)}


class Reconstruction(unittest.TestCase):
    def test_a_compass_posture_puts_the_hip_midway_with_both_feet_flat(self):
        # straight legs at ±θ, the trailing foot flat (ankle θ), the leading foot flat (−θ):
        # the hip is l1 sin θ ahead of each ankle, l9 + l1 cos θ high, the leading heel on the
        # floor l8 behind its ankle (l8² + l9² = l11² on the body table)
        s = segments(1.8)
        for theta in (10.0, 20.0):
            for tilt in (0.0, 12.0):
                c = curves((tilt, theta + tilt, 0.0, -theta), (tilt, -theta + tilt, 0.0, theta))
                r = posture(c, s)
                l1, t = s["l3"] + s["l4"], math.radians(theta)
                self.assertAlmostEqual(r["phi"], 0.5, places=3)
                self.assertAlmostEqual(r["step"], 2 * l1 * math.sin(t), places=3)
                self.assertAlmostEqual(r["hip_y"], s["l9"] + l1 * math.cos(t), places=9)
                self.assertAlmostEqual(r["heel_y"], 0.0, places=9)
                self.assertEqual(r["pitch"], 0.0)

    def test_a_raised_heel_lengthens_the_trailing_leg(self):
        # the trailing ankle plantarflexed by 10° more raises the heel by 10° about the
        # metatarsal joint: the hip moves ahead and up, the step grows, φ > 1/2
        s = segments(1.8)
        flat = posture(curves((0, 20, 0, -20), (0, -20, 0, 20)), s)
        raised = posture(curves((0, 20, 0, -20), (0, -20, 0, 10)), s)
        self.assertAlmostEqual(raised["pitch"], 10.0)
        self.assertGreater(raised["hip_y"], flat["hip_y"])
        self.assertGreater(raised["phi"], 0.5)


if __name__ == "__main__":
    unittest.main()
