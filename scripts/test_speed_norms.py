"""Unit test of scripts/speed_norms.py's reading and writing, without the workbook, xlrd or
network: python3 -m unittest scripts/test_speed_norms.py"""
import os
import sys
import tomllib
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import speed_norms as sn  # noqa: E402

CATS = sn.CATEGORIES


def anova_rows(params):
    """ANOVA-sheet-like rows: two header rows, then per parameter one row per category (the
    name in the first) and a Total row: name, category, N, mean, SD, SE, CI low, CI high, min,
    max, then the post-hoc columns."""
    rows = [[" ", " ", "N", "Mean", "Std. Deviation"] + [""] * 12, [""] * 17]
    for name, values in params.items():
        for k, (mean, sd, lo, hi) in enumerate(values):
            rows.append([name if k == 0 else "", CATS[k], 10.0, mean, sd, 0.1, 0.0, 0.0, lo, hi,
                         "", "", "", "", "", "", ""])
        rows.append(["", "Total", 50.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0] + [""] * 7)
    return rows


SPEEDS = [(0.2 + 0.1 * k, 0.01, 0.15 + 0.1 * k, 0.25 + 0.1 * k) for k in range(5)]


def params():
    """Every ANOVA parameter the rows read: parameter i has mean 10 i + k and SD 1 + k / 10 at
    category k."""
    names = [k for k, *_ in sn.ROWS if isinstance(k, str)]
    p = {sn.SPEED: SPEEDS}
    for i, n in enumerate(dict.fromkeys(names)):
        p[n] = [(10.0 * i + k, 1.0 + k / 10, 0.0, 0.0) for k in range(5)]
    return p


def curve_rows():
    """Joint Rotations rows of the knee at 10, 12 and 14 %: category k has mean 20 + k and
    mean ± (2 + k)."""
    rows = []
    for pct in (0.10, 0.12, 0.14):
        r = ["Knee Flex/Extension", pct]
        for k in range(5):
            m = 20.0 + k + (pct - 0.12) * 100
            r += [m - (2 + k), m, m + (2 + k)]
        rows.append(r)
    return rows


class Reading(unittest.TestCase):
    def test_anova_blocks_are_read_by_category(self):
        a = sn.parse_anova(anova_rows({"A": [(1.0, 0.5, 0.0, 2.0)] * 5,
                                       "B": [(float(k), 1.0, -1.0, 9.0) for k in range(5)]}))
        self.assertEqual(set(a), {"A", "B"})
        self.assertEqual(a["B"]["Fast"], (10.0, 3.0, 1.0, -1.0, 9.0))
        self.assertNotIn("Total", a["B"])

    def test_a_curve_point_gives_mean_and_half_the_band(self):
        c = sn.parse_curve(curve_rows(), "Knee Flex/Extension", 0.12)
        self.assertEqual(c, [(20.0 + k, 2.0 + k) for k in range(5)])
        with self.assertRaises(sn.InputError):
            sn.parse_curve(curve_rows(), "Knee Flex/Extension", 0.5)

    def test_a_missing_parameter_is_an_input_error(self):
        with self.assertRaises(sn.InputError):
            sn.series({}, {}, "Max Knee Flex (swing)  [deg]", 1)


class Writing(unittest.TestCase):
    def setUp(self):
        self.anova = sn.parse_anova(anova_rows(params()))
        self.curves = {("Knee Flex/Extension", 0.12):
                       sn.parse_curve(curve_rows(), "Knee Flex/Extension", 0.12)}

    def test_the_rows_are_toml_with_the_numbers(self):
        t = tomllib.loads(sn.toml_rows(self.anova, self.curves))["norm"]
        self.assertEqual(len(t), len(sn.ROWS))
        for row, (key, sign, panel, name, *_) in zip(t, sn.ROWS):
            b = row["by_speed"]
            self.assertEqual(row["panel"], panel)
            self.assertEqual(row["name"], name)
            self.assertEqual(b["speed"], [round(s[0], 3) for s in SPEEDS])
            self.assertEqual(b["span"], [0.15, 0.65])
            self.assertEqual(b["sd_multiple"], 1.0)
            means, sds = sn.series(self.anova, self.curves, key, sign)
            self.assertEqual(b["mean"], [round(m, 2) for m in means])
            self.assertEqual(b["sd"], [round(s, 2) for s in sds])
        mirrored = [r for r, spec in zip(t, sn.ROWS) if spec[1] < 0]
        self.assertTrue(mirrored and all(m < 0 for m in mirrored[0]["by_speed"]["mean"][1:]))
        knee = next(r for r in t if r["name"].startswith("knee loading"))
        self.assertEqual(knee["by_speed"]["mean"], [20.0, 21.0, 22.0, 23.0, 24.0])
        self.assertEqual(knee["by_speed"]["sd"], [2.0, 3.0, 4.0, 5.0, 6.0])

    def test_the_markdown_has_a_row_per_quantity(self):
        md = sn.markdown(self.anova, self.curves).splitlines()
        self.assertEqual(len(md), 2 + len(sn.ROWS))
        self.assertIn("Free (v̂ 0.400)", md[0])


if __name__ == "__main__":
    unittest.main()
