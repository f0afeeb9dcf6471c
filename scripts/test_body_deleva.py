"""Unit test of scripts/body_deleva.py's derivation rules, without data or network:
python3 -m unittest scripts/test_body_deleva.py"""
import math
import pathlib
import sys
import tomllib
import unittest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from body_deleva import (DE_LEVA, ROOT, composite, flat_foot_length, shank_with_foot,  # noqa
                         table, toml_text, winter)


class Rules(unittest.TestCase):
    def test_composite_of_two_point_masses(self):
        # two unit point masses 2 apart: centre midway, gyration 1 about it
        m, y, k = composite([(1.0, 0.0, 0.0), (1.0, 2.0, 0.0)])
        self.assertEqual((m, y), (2.0, 1.0))
        self.assertAlmostEqual(k, 1.0, places=12)
        # a rod's own gyration adds in quadrature (parallel axis theorem)
        _, _, k = composite([(1.0, 0.0, 0.3), (1.0, 2.0, 0.4)])
        self.assertAlmostEqual(k, math.sqrt(1.0 + (0.09 + 0.16) / 2), places=12)

    def test_the_foot_rule_turns_winters_parts_into_dempsters_leg_and_foot(self):
        # Winter (2009, Table 4.1): leg (knee-ankle) 0.0465 M, CM 0.433 from the knee, gyration
        # 0.302; foot 0.0145 M, gyration 0.475 of its 0.152 H length; "leg and foot" 0.061 M,
        # CM 0.606 from the knee, gyration 0.416 (klaw's Table B-1 row for the shank)
        w = winter()
        l4, l9 = w["shank"]["length"], w["foot"]["ankle_height"]
        m, r, k = shank_with_foot(l4, 0.433, 0.302 * l4, 0.0465, 0.0145, 0.475 * 0.152, l9)
        self.assertAlmostEqual(m, w["shank"]["mass"], places=12)
        self.assertLess(abs(r / l4 - w["shank"]["r"]), 0.002)
        self.assertLess(abs(k / l4 - w["shank"]["gamma"]), 0.02)

    def test_flat_foot_length_of_winters_foot(self):
        f = winter()["foot"]
        horizontal = math.sqrt(f["ankle_to_metatarsal"] ** 2 - f["ankle_height"] ** 2)
        self.assertAlmostEqual(flat_foot_length(f),
                               f["hind_foot"] + horizontal + f["metatarsal_to_toe"], places=15)


class Tables(unittest.TestCase):
    def test_published_lengths_come_back(self):
        for sex, d in DE_LEVA.items():
            t = table(sex)
            h = d["stature"]
            self.assertAlmostEqual(t["thigh"]["length"] * h, d["thigh"][0], places=9)
            self.assertAlmostEqual(t["shank"]["length"] * h, d["shank"][0], places=9)
            self.assertAlmostEqual(flat_foot_length(t["foot"]) * h, d["foot"][0], places=9)
            self.assertAlmostEqual(t["figure"]["upper_arm"] * h, d["upper_arm"][0], places=9)

    def test_masses_add_up(self):
        for sex in DE_LEVA:
            t = table(sex)
            total = t["upper_body"]["mass"] + 2 * (t["thigh"]["mass"] + t["shank"]["mass"])
            self.assertAlmostEqual(total, 1.0, places=12)
            # de Leva's own 14 segments sum to 1 within their rounding
            self.assertLess(abs(t["composite_upper_body_mass"] - t["upper_body"]["mass"]), 2e-4)

    def test_the_stature_closes(self):
        # ankle height + leg + upper body = H; the figure's spine, neck and head fill the
        # upper body
        for sex in DE_LEVA:
            t = table(sex)
            leg = t["thigh"]["length"] + t["shank"]["length"]
            self.assertAlmostEqual(t["foot"]["ankle_height"] + leg + t["upper_body"]["length"],
                                   1.0, places=12)
            f = t["figure"]
            self.assertAlmostEqual(f["spine"] + f["neck"] + f["head"],
                                   t["upper_body"]["length"], places=12)
            self.assertGreater(f["neck"], 0.0)

    def test_the_bodies_are_not_similar(self):
        # thigh/shank ratios differ (ψ of Ko & Badler 1992 needs bodies of other proportions)
        ratios = [table(s)["thigh"]["length"] / table(s)["shank"]["length"] for s in DE_LEVA]
        w = winter()
        ratios.append(w["thigh"]["length"] / w["shank"]["length"])
        self.assertGreater(max(ratios) - min(ratios), 0.1)

    def test_the_committed_files_are_the_scripts_output(self):
        for sex in DE_LEVA:
            path = ROOT / "models" / f"body-deleva-{sex}.toml"
            self.assertEqual(path.read_text(), toml_text(sex), f"regenerate {path.name}")
            tomllib.loads(path.read_text())


if __name__ == "__main__":
    unittest.main()
