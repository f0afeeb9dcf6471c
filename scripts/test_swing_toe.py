"""Unit test of scripts/swing_toe.py's geometry, without data or network:
python3 -m unittest scripts/test_swing_toe.py"""
import math
import pathlib
import sys
import unittest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from swing_toe import best_in_band, segments, toe_below_hip  # noqa: E402


class Geometry(unittest.TestCase):
    def test_straight_leg_and_flat_foot_reach_the_standing_height(self):
        s = segments(1.8)
        self.assertAlmostEqual(toe_below_hip(s, 0, 0, 0), s["l3"] + s["l4"] + s["l9"], places=12)

    def test_a_vertical_shank_keeps_the_foot_flat(self):
        # thigh θ forward, knee θ: the shank hangs vertical, the foot lies flat at ankle 0
        s = segments(1.8)
        for theta in (10.0, 30.0):
            below = s["l3"] * math.cos(math.radians(theta)) + s["l4"] + s["l9"]
            self.assertAlmostEqual(toe_below_hip(s, theta, theta, 0), below, places=12)

    def test_a_horizontal_shank_hangs_the_foot_toe_down(self):
        # thigh vertical, knee 90°: the shank points back, the foot square to it points down
        s = segments(1.8)
        self.assertAlmostEqual(toe_below_hip(s, 0, 90, 0), s["l3"] + s["toe"], places=12)

    def test_the_band_search_contains_the_mean(self):
        # a band of zero width gives the mean posture itself
        s = segments(1.8)
        curves = {(j, "X"): ([76.0], [m], [0.0]) for j, m in
                  (("HipAngles", 27.0), ("KneeAngles", 57.0), ("PelvisAngles", 11.0))}
        self.assertAlmostEqual(best_in_band(s, curves, 76), toe_below_hip(s, 16, 57, 5),
                               places=12)


if __name__ == "__main__":
    unittest.main()
