"""Unit test of scripts/deepmimic_walk.py's kinematics, without data or network:
python3 -m unittest scripts/test_deepmimic_walk.py"""
import math
import pathlib
import sys
import unittest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from deepmimic_walk import (FRAME_LEN, OFFSETS, SCALE, header, leg_markers, quat_mul,  # noqa
                            quat_rotate, rows, urdf_geometry)

# the URDF's leg offsets and foot box (unscaled), as humanoid.urdf gives them
GEOMETRY = {side: {"hip": (0.0, 0.0, z), "knee": (0.0, -1.686184, 0.0),
                   "ankle": (0.0, -1.63948, 0.0)}
            for side, z in (("right", 0.339548), ("left", -0.339548))}
BOX = ((0.18, -0.09, 0.0), (0.708, 0.22, 0.36))
IDENTITY = (1.0, 0.0, 0.0, 0.0)


def about_z(angle):
    return (math.cos(angle / 2), 0.0, 0.0, math.sin(angle / 2))


def frame(root=(0.0, 1.0, 0.0), knee=0.0, hip=IDENTITY, ankle=IDENTITY):
    f = [0.0] * FRAME_LEN
    f[0] = 1 / 30
    f[OFFSETS["root_pos"]:OFFSETS["root_pos"] + 3] = root
    for part in ("root_rot", "right_hip", "right_ankle", "left_hip", "left_ankle"):
        f[OFFSETS[part]:OFFSETS[part] + 4] = IDENTITY
    f[OFFSETS["right_hip"]:OFFSETS["right_hip"] + 4] = hip
    f[OFFSETS["right_ankle"]:OFFSETS["right_ankle"] + 4] = ankle
    f[OFFSETS["right_knee"]] = knee
    return f


def close(a, b, places=12):
    return all(abs(x - y) < 10 ** -places for x, y in zip(a, b))


class Quaternions(unittest.TestCase):
    def test_a_quarter_turn_about_z_takes_x_to_y(self):
        self.assertTrue(close(quat_rotate(about_z(math.pi / 2), (1.0, 0.0, 0.0)), (0.0, 1.0, 0.0)))

    def test_products_compose_rotations(self):
        a, b = about_z(0.3), (math.cos(0.2), math.sin(0.2), 0.0, 0.0)
        v = (0.3, -1.2, 0.7)
        self.assertTrue(close(quat_rotate(quat_mul(a, b), v), quat_rotate(a, quat_rotate(b, v))))


class Legs(unittest.TestCase):
    def test_a_straight_leg_hangs_below_its_hip(self):
        p = leg_markers(frame(), "right", GEOMETRY, BOX)
        self.assertTrue(close(p["hip"], (0.0, 1.0, 0.339548 * SCALE)))
        self.assertTrue(close(p["knee"], (0.0, 1.0 - 1.686184 * SCALE, 0.339548 * SCALE)))
        ankle_y = 1.0 - (1.686184 + 1.63948) * SCALE
        self.assertTrue(close(p["ankle"], (0.0, ankle_y, 0.339548 * SCALE)))
        # the box's bottom edges, 0.2 below the ankle, from -0.174 to 0.534 (unscaled)
        self.assertTrue(close(p["heel"], (-0.174 * SCALE, ankle_y - 0.2 * SCALE, p["hip"][2])))
        self.assertTrue(close(p["toe"], (0.534 * SCALE, ankle_y - 0.2 * SCALE, p["hip"][2])))
        self.assertEqual(p["ball"], p["toe"])

    def test_a_bent_knee_swings_the_shank_by_its_angle(self):
        # DeepMimic's knees flex by negative angles about z: the ankle goes back (-x), the
        # thigh stays, the shank keeps its length
        k = -0.6
        p = leg_markers(frame(knee=k), "right", GEOMETRY, BOX)
        shank = 1.63948 * SCALE
        self.assertAlmostEqual(p["ankle"][0] - p["knee"][0], shank * math.sin(k), places=12)
        self.assertAlmostEqual(p["knee"][1] - p["ankle"][1], shank * math.cos(k), places=12)

    def test_the_hip_rotation_carries_the_whole_leg(self):
        q = about_z(0.4)
        straight = leg_markers(frame(), "right", GEOMETRY, BOX)
        flexed = leg_markers(frame(hip=q), "right", GEOMETRY, BOX)
        for m in ("knee", "ankle", "heel", "toe"):
            rel = tuple(a - b for a, b in zip(straight[m], straight["hip"]))
            want = tuple(h + r for h, r in zip(flexed["hip"], quat_rotate(q, rel)))
            self.assertTrue(close(flexed[m], want), m)


class Geometry(unittest.TestCase):
    def test_the_urdf_reader_finds_the_offsets(self):
        text = b"""<robot><joint name="right_hip" type="spherical"><parent link="root"/>
        <origin rpy = "0 0 0" xyz = "0.0 0.0 0.339548" /></joint>
        <joint name="right_knee" type="revolute"><origin xyz = "0 -1.686184 0" /></joint>
        <joint name="right_ankle" type="spherical"><origin xyz = "0 -1.63948 0" /></joint>
        <joint name="left_hip" type="spherical"><origin xyz = "0 0 -0.339548" /></joint>
        <joint name="left_knee" type="revolute"><origin xyz = "0 -1.686184 0" /></joint>
        <joint name="left_ankle" type="spherical"><origin xyz = "0 -1.63948 0" /></joint>
        <link name="right_ankle"><collision><origin rpy = "0 0 0" xyz = "0.18 -0.09 0" />
        <geometry><box size="0.708 0.22 0.36" /></geometry></collision></link></robot>"""
        geometry, centre, size = urdf_geometry(text)
        self.assertEqual(geometry, GEOMETRY)
        self.assertEqual((centre, size), BOX)

    def test_two_strides_share_their_seam(self):
        a = frame(root=(0.0, 1.0, 0.0))
        b = frame(root=(0.6, 1.0, 0.0))
        b[0] = 0.0  # the clip's last frame: the first moved on by the stride
        table, stride = rows({"Frames": [a, b]}, GEOMETRY, BOX, strides=2)
        self.assertAlmostEqual(stride, 0.6)
        self.assertEqual([r[0] for r in table], [0.0, 1 / 30, 2 / 30])
        self.assertAlmostEqual(table[2][1] - table[0][1], 1.2, places=12)
        self.assertEqual(len(table[0]), len(header()))


if __name__ == "__main__":
    unittest.main()
