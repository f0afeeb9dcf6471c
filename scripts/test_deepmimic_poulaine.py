"""Unit test of scripts/deepmimic_poulaine.py, without data or network:
python3 -m unittest scripts/test_deepmimic_poulaine.py"""
import math
import pathlib
import random
import sys
import unittest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from deepmimic_poulaine import (ankles, angle_rows, clinical, matrix, poulaine_rows,  # noqa
                                yxz, zxy)
from deepmimic_walk import FRAME_LEN, OFFSETS, SCALE, normalized  # noqa
from test_deepmimic_walk import BOX, GEOMETRY, IDENTITY  # noqa


def rx(a):
    return ((1, 0, 0), (0, math.cos(a), -math.sin(a)), (0, math.sin(a), math.cos(a)))


def ry(a):
    return ((math.cos(a), 0, math.sin(a)), (0, 1, 0), (-math.sin(a), 0, math.cos(a)))


def rz(a):
    return ((math.cos(a), -math.sin(a), 0), (math.sin(a), math.cos(a), 0), (0, 0, 1))


def mul(*ms):
    out = ms[0]
    for m in ms[1:]:
        out = tuple(tuple(sum(out[i][k] * m[k][j] for k in range(3)) for j in range(3))
                    for i in range(3))
    return out


def apply(m, v):
    return tuple(sum(m[i][k] * v[k] for k in range(3)) for i in range(3))


def random_frame(rng, small=0.5):
    f = [0.0] * FRAME_LEN
    f[0] = 1 / 30
    f[OFFSETS["root_pos"]:OFFSETS["root_pos"] + 3] = (rng.uniform(-1, 1), 0.85, rng.uniform(-.1, .1))
    for part in ("root_rot", "right_hip", "right_ankle", "left_hip", "left_ankle"):
        q = (1.0, *(rng.uniform(-small, small) for _ in range(3)))
        f[OFFSETS[part]:OFFSETS[part] + 4] = normalized(q)
    for side in ("right", "left"):
        f[OFFSETS[f"{side}_knee"]] = -rng.uniform(0.0, 1.2)
    return f


class Euler(unittest.TestCase):
    def test_decompositions_invert_their_products(self):
        a, b, c = 0.4, -0.3, 0.2
        self.assertTrue(all(abs(x - y) < 1e-12 for x, y in zip(zxy(mul(rz(a), rx(b), ry(c))), (a, b, c))))
        self.assertTrue(all(abs(x - y) < 1e-12 for x, y in zip(yxz(mul(ry(a), rx(b), rz(c))), (a, b, c))))

    def test_quaternion_matrix_turns_x_to_y_about_z(self):
        m = matrix((math.cos(math.pi / 4), 0.0, 0.0, math.sin(math.pi / 4)))
        self.assertTrue(all(abs(x - y) < 1e-12 for x, y in zip(apply(m, (1, 0, 0)), (0, 1, 0))))


class Angles(unittest.TestCase):
    def test_the_chain_at_the_angles_gives_back_the_ankles(self):
        """docs/ik.md's chain (klaw's, the decomposition's inverse), posed at the clinical
        angles with the clip's lengths, puts the ankles where the clip's kinematics does."""
        rng = random.Random(7)
        thigh, shank = 1.686184 * SCALE, 1.63948 * SCALE
        half = 0.339548 * SCALE
        for _ in range(20):
            f = random_frame(rng)
            tilt, lst, rot, *legs = clinical(f)
            rp = mul(ry(rot), rx(-lst), rz(-tilt))
            _, right, left = ankles(f, GEOMETRY, BOX)
            for k, (s, want) in enumerate(((1.0, right), (-1.0, left))):
                flex, add, hrot, knee = legs[4 * k:4 * k + 4]
                rt = mul(rp, rz(flex), rx(s * add), ry(s * hrot))
                rs = mul(rt, rz(-knee))
                hip = apply(rp, (0, 0, s * half))
                kn = tuple(h + d for h, d in zip(hip, apply(rt, (0, -thigh, 0))))
                an = tuple(h + d for h, d in zip(kn, apply(rs, (0, -shank, 0))))
                self.assertTrue(all(abs(x - y) < 1e-12 for x, y in zip(an, want)), (an, want))

    def test_a_bent_knee_is_positive_flexion(self):
        f = random_frame(random.Random(1), small=0.0)
        f[OFFSETS["right_knee"]] = -0.5
        self.assertAlmostEqual(clinical(f)[6], 0.5, places=12)
        self.assertAlmostEqual(clinical(f)[3], 0.0, places=12)

    def test_a_thigh_forward_is_positive_flexion(self):
        f = random_frame(random.Random(1), small=0.0)
        f[OFFSETS["right_hip"]:OFFSETS["right_hip"] + 4] = (math.cos(0.2), 0, 0, math.sin(0.2))
        f[OFFSETS["right_knee"]] = 0.0
        self.assertAlmostEqual(clinical(f)[3], 0.4, places=12)
        _, right, _ = ankles(f, GEOMETRY, BOX)
        self.assertGreater(right[0], 0.0)


class Files(unittest.TestCase):
    def clip(self, n=5):
        """A stride of n + 1 frames walking straight at 1 m/s, the last the first moved on."""
        rng = random.Random(3)
        frames = [random_frame(rng) for _ in range(n)]
        for i, f in enumerate(frames):
            f[OFFSETS["root_pos"]] = i / 30
        last = list(frames[0])
        last[OFFSETS["root_pos"]] += n / 30
        return frames + [last]

    def test_the_poulaine_is_one_stride_with_the_pelvis_speed(self):
        rows = poulaine_rows(self.clip(), GEOMETRY, BOX)
        self.assertEqual(len(rows), 5)
        self.assertTrue(all(abs(r[7] - 1.0) < 1e-12 for r in rows))
        self.assertTrue(all(abs(r[0] - i / 30) < 1e-12 for i, r in enumerate(rows)))

    def test_the_angles_repeat_each_stride_and_carry_the_pelvis_on(self):
        rows = angle_rows(self.clip(), strides=3)
        self.assertEqual(len(rows), 15)
        for a, b in zip(rows[:5], rows[5:10]):
            self.assertAlmostEqual(b[1] - a[1], 5 / 30, places=12)
            self.assertEqual(a[4:], b[4:])


if __name__ == "__main__":
    unittest.main()
