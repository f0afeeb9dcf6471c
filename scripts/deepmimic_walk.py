#!/usr/bin/env python3
"""DeepMimic's walking clip as klaw's measured-walk CSV (docs/generalize.md's layout).

The clip `data/motions/humanoid3d_walk.txt` and its character `humanoid/humanoid.urdf` ship in
the PyPI package pybullet (3.2.7: pybullet_data/, zlib licence, Bullet Physics; the clip is
DeepMimic's, Peng, Abbeel, Levine & van de Panne 2018, "DeepMimic: example-guided deep
reinforcement learning of physics-based character skills", ACM TOG 37(4)). It is one stride
(39 frames at 30 Hz, the last the first moved on by the stride, "Loop": "wrap") of a humanoid
with spherical hips and ankles, hinge knees and a rigid box foot (no toe joint).

What this script does, once, by hand (it never runs in CI; the derived file is committed):

1. Forward kinematics of the legs: the root at the clip's position and orientation, the hips at
   the URDF's joint offsets, each joint's local rotation from the clip (quaternions w, x, y, z;
   the knees a rotation about the lateral z axis), all lengths times the URDF's global scaling
   0.25 that pybullet's DeepMimic environment loads it with (its check: the feet stand on the
   floor, below).
2. The markers: hip, knee and ankle joint centres; the heel and the toe tip are the rear and
   front bottom edges of the foot box in the ankle's frame; the foot has no toe joint, so the
   ball is the toe (docs/generalize.md accepts ball = toe).
3. The sagittal projection: x forward (DeepMimic's x), y up (its y); the lateral z is dropped.
4. Two strides: the clip, then the clip again moved on by its own stride (its last frame, the
   first moved on, is the seam), so the file holds a whole step between any two events.

Usage: python3 scripts/deepmimic_walk.py SOURCE [--out FILE]
SOURCE: an installed pybullet's `pybullet_data` folder, or the pybullet wheel (.whl) itself.
Default out: models/prototypes/deepmimic-walk.csv. python3 -m unittest
scripts/test_deepmimic_walk.py checks the kinematics without the data.
"""
import argparse
import hashlib
import json
import math
import pathlib
import re
import sys
import zipfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
MOTION = "data/motions/humanoid3d_walk.txt"
URDF = "humanoid/humanoid.urdf"
SCALE = 0.25  # pybullet's DeepMimic environment: loadURDF(..., globalScaling=0.25)

# the clip's frame layout (DeepMimic's humanoid3d): duration, root position (3), root rotation
# (4), chest (4), neck (4), right hip (4), right knee (1), right ankle (4), right shoulder (4),
# right elbow (1), left hip (4), left knee (1), left ankle (4), left shoulder (4), left elbow (1)
OFFSETS = {"root_pos": 1, "root_rot": 4, "right_hip": 16, "right_knee": 20, "right_ankle": 21,
           "left_hip": 30, "left_knee": 34, "left_ankle": 35}
FRAME_LEN = 44


def read_source(source):
    """(motion text, urdf text) from a pybullet_data folder or a pybullet wheel."""
    path = pathlib.Path(source)
    if path.suffix == ".whl":
        with zipfile.ZipFile(path) as z:
            read = lambda name: z.read(f"pybullet_data/{name}")
            return read(MOTION), read(URDF)
    return (path / MOTION).read_bytes(), (path / URDF).read_bytes()


def urdf_geometry(text):
    """The leg offsets of the URDF (unscaled): hip from the root, knee from the hip, ankle from
    the knee, per side; and the foot box (centre, size) in the ankle's frame."""
    text = text.replace(b"\x00", b"").decode("utf-8", "replace")

    def joint(name):
        m = re.search(r'<joint name="%s".*?<origin[^>]*xyz\s*=\s*"([^"]+)"' % name, text, re.S)
        return tuple(float(v) for v in m.group(1).split())

    link = re.search(r'<link name="right_ankle".*?</link>', text, re.S).group(0)
    collision = re.search(r"<collision.*?</collision>", link, re.S).group(0)
    centre = tuple(float(v) for v in re.search(r'xyz\s*=\s*"([^"]+)"', collision).group(1).split())
    size = tuple(float(v) for v in re.search(r'box size\s*=\s*"([^"]+)"', collision).group(1).split())
    geometry = {side: {part: joint(f"{side}_{part}") for part in ("hip", "knee", "ankle")}
                for side in ("right", "left")}
    return geometry, centre, size


def quat_rotate(q, v):
    """v rotated by the unit quaternion q = (w, x, y, z)."""
    w, x, y, z = q
    # v + 2 w (u × v) + 2 u × (u × v), u = (x, y, z)
    ux = (y * v[2] - z * v[1], z * v[0] - x * v[2], x * v[1] - y * v[0])
    uux = (y * ux[2] - z * ux[1], z * ux[0] - x * ux[2], x * ux[1] - y * ux[0])
    return tuple(v[i] + 2 * w * ux[i] + 2 * uux[i] for i in range(3))


def quat_mul(a, b):
    """The rotation a then, in a's frame, b: the Hamilton product a b."""
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return (aw * bw - ax * bx - ay * by - az * bz,
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw)


def normalized(q):
    n = math.sqrt(sum(c * c for c in q))
    return tuple(c / n for c in q)


def add(a, b):
    return tuple(x + y for x, y in zip(a, b))


def scaled(v, s):
    return tuple(x * s for x in v)


def leg_markers(frame, side, geometry, box):
    """The side's hip, knee, ankle, heel, ball and toe (3-D, metres) in one clip frame."""
    o = OFFSETS
    root = tuple(frame[o["root_pos"]:o["root_pos"] + 3])
    q_root = normalized(frame[o["root_rot"]:o["root_rot"] + 4])
    g = geometry[side]
    hip = add(root, quat_rotate(q_root, scaled(g["hip"], SCALE)))
    q_hip = quat_mul(q_root, normalized(frame[o[f"{side}_hip"]:o[f"{side}_hip"] + 4]))
    knee = add(hip, quat_rotate(q_hip, scaled(g["knee"], SCALE)))
    angle = frame[o[f"{side}_knee"]]
    q_knee = quat_mul(q_hip, (math.cos(angle / 2), 0.0, 0.0, math.sin(angle / 2)))
    ankle = add(knee, quat_rotate(q_knee, scaled(g["ankle"], SCALE)))
    q_ankle = quat_mul(q_knee, normalized(frame[o[f"{side}_ankle"]:o[f"{side}_ankle"] + 4]))
    centre, size = box
    bottom = centre[1] - size[1] / 2
    heel = add(ankle, quat_rotate(q_ankle, scaled((centre[0] - size[0] / 2, bottom, 0.0), SCALE)))
    toe = add(ankle, quat_rotate(q_ankle, scaled((centre[0] + size[0] / 2, bottom, 0.0), SCALE)))
    return {"hip": hip, "knee": knee, "ankle": ankle, "heel": heel, "ball": toe, "toe": toe}


MARKERS = ("hip", "knee", "ankle", "heel", "ball", "toe")
SIDES = (("r", "right"), ("l", "left"))


def header():
    cols = ["time_s"]
    for s, _ in SIDES:
        for m in MARKERS:
            cols += [f"{m}_{s}_x_m", f"{m}_{s}_y_m"]
    return cols


def rows(motion, geometry, box, strides=2):
    """One row per frame over `strides` repetitions of the clip (the last frame of each is the
    next one's first, moved on by the stride, and is written once)."""
    frames = motion["Frames"]
    if any(len(f) != FRAME_LEN for f in frames):
        raise SystemExit(f"the clip's frames must hold {FRAME_LEN} numbers")
    stride = frames[-1][1] - frames[0][1]
    out, t = [], 0.0
    for k in range(strides):
        last = k == strides - 1
        for i, f in enumerate(frames if last else frames[:-1]):
            f = list(f)
            f[1] += k * stride
            row = [t]
            for _, side in SIDES:
                pts = leg_markers(f, side, geometry, box)
                for m in MARKERS:
                    row += [pts[m][0], pts[m][1]]
            out.append(row)
            t += frames[i][0]
    return out, stride


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("source", help="pybullet_data folder or pybullet .whl")
    ap.add_argument("--out", default=str(ROOT / "models" / "prototypes" / "deepmimic-walk.csv"))
    args = ap.parse_args()
    motion_bytes, urdf_bytes = read_source(args.source)
    geometry, centre, size = urdf_geometry(urdf_bytes)
    motion = json.loads(motion_bytes)
    table, stride = rows(motion, geometry, (centre, size))
    lowest = min(min(r[2::2]) for r in table)
    if abs(lowest) > 0.01:
        sys.exit(f"the feet do not stand on the floor (lowest marker y = {lowest:.4f} m): "
                 "check the scale")
    toe = min(min(r[header().index(f"toe_{s}_y_m")] for r in table) for s, _ in SIDES)
    sha = lambda b: hashlib.sha256(b).hexdigest()
    lines = [
        "# DeepMimic's walking clip (Peng et al. 2018, ACM TOG 37(4)), as shipped in the PyPI "
        "package pybullet 3.2.7",
        "# (pybullet_data/data/motions/humanoid3d_walk.txt, sha256 " + sha(motion_bytes) + ";",
        "# pybullet_data/humanoid/humanoid.urdf, sha256 " + sha(urdf_bytes) + "),",
        "# zlib licence (Bullet Physics, https://github.com/bulletphysics/bullet3). Altered: "
        "sagittal landmarks by",
        "# forward kinematics at the URDF's scaling 0.25, the clip written twice "
        f"(stride {stride:.5f} m), by scripts/deepmimic_walk.py.",
        "# The foot is a rigid box: ball = toe. Layout: docs/generalize.md. The clip's feet touch "
        f"the floor with the heel (lowest {lowest * 1000:+.1f} mm)",
        f"# but pivot on a toe tip that stays {toe * 1000:.1f} mm or more above it: a "
        "toe-off needs a contact height above that.",
        ",".join(header()),
    ]
    for r in table:
        lines.append(",".join(f"{v:.6f}" for v in r))
    out = pathlib.Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text("\n".join(lines) + "\n")
    print(f"{out}: {len(table)} frames, stride {stride:.4f} m, lowest marker {lowest:+.4f} m, "
          f"lowest toe {toe:+.4f} m")


if __name__ == "__main__":
    main()
