#!/usr/bin/env python3
"""DeepMimic's walking clip in 3-D: its poulaine and its own clinical angles, for klaw's IK.

The clip and its character are scripts/deepmimic_walk.py's (pybullet 3.2.7's pybullet_data,
zlib licence; the same forward kinematics at the URDF's scaling 0.25). This script writes two
files (once, by hand; it never runs in CI, the derived files are committed):

1. The poulaine (`klaw ik --poulaine`, docs/ik.md's layout): per frame of one stride (38
   samples at 30 Hz; the clip's 39th frame is its first moved on), the right and left ankle
   joint centres minus the pelvis centre (the hip-joint midpoint, which is the clip's root: the
   hips sit symmetrically at ±z of it), and the pelvis centre's forward speed (central
   differences, cyclic across the seam).
2. The clip's clinical angles (`klaw evaluate --against`, docs/criteria.md's frame CSV without
   a step column), 4 strides, with the pelvis centre's position.

Axes. The clip's are x forward (its walking direction: the root moves along +x and comes back to
z = 0 after a stride), y up, z to the right (the right hip is at +z): exactly klaw's (x forward,
y up, z right), so no axis is mapped. The walking-direction frame is the world's (the clip walks
along x), not turned with the pelvis.

Angles. At zero rotations every segment of the clip is upright and faces +x, as klaw's are at
zero angles, so the segments' world rotations are decomposed as figure::clinical does: the
pelvis (the clip's root) R_p = R_y(r) R_x(p) R_z(q), tilt −q, list −p, rotation r; the hip
Rpᵀ R_thigh = R_z(a) R_x(b) R_y(c), flexion a, adduction s b, rotation s c (s = +1 right, −1
left); the knee R_thighᵀ R_shank = R_z(a) …, flexion −a. A constant offset between the clip's
zero and klaw's anatomical zero (e.g. the pelvis's 9° standing tilt) is what eq. 7 removes.

Usage: python3 scripts/deepmimic_poulaine.py SOURCE [--poulaine FILE] [--angles FILE]
SOURCE: pybullet_data folder or pybullet .whl. Defaults:
models/prototypes/deepmimic-walk-poulaine.csv, models/prototypes/deepmimic-walk-angles.csv.
python3 -m unittest scripts/test_deepmimic_poulaine.py checks it without the data.
"""
import argparse
import hashlib
import json
import math
import pathlib

from deepmimic_walk import (FRAME_LEN, OFFSETS, SCALE, leg_markers, normalized, quat_mul,
                            read_source, urdf_geometry)

ROOT = pathlib.Path(__file__).resolve().parent.parent
SIDES = (("r", "right", 1.0), ("l", "left", -1.0))
ANGLE_STRIDES = 4


def matrix(q):
    """The rotation matrix (rows) of the unit quaternion q = (w, x, y, z)."""
    w, x, y, z = q
    return ((1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)),
            (2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)),
            (2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)))


def relative(p, c):
    """pᵀ c: the child's rotation in the parent's frame."""
    return tuple(tuple(sum(p[k][i] * c[k][j] for k in range(3)) for j in range(3))
                 for i in range(3))


def zxy(m):
    """[a, b, c] with m = R_z(a) R_x(b) R_y(c)."""
    return (math.atan2(-m[0][1], m[1][1]), math.asin(max(-1.0, min(1.0, m[2][1]))),
            math.atan2(-m[2][0], m[2][2]))


def yxz(m):
    """[r, p, q] with m = R_y(r) R_x(p) R_z(q)."""
    return (math.atan2(m[0][2], m[2][2]), math.asin(max(-1.0, min(1.0, -m[1][2]))),
            math.atan2(m[1][0], m[1][1]))


def segment_rotations(frame):
    """The world rotations (quaternions) of the pelvis and of each side's thigh and shank."""
    o = OFFSETS
    pelvis = normalized(frame[o["root_rot"]:o["root_rot"] + 4])
    out = {"pelvis": pelvis}
    for _, side, _ in SIDES:
        thigh = quat_mul(pelvis, normalized(frame[o[f"{side}_hip"]:o[f"{side}_hip"] + 4]))
        a = frame[o[f"{side}_knee"]]
        out[f"{side}_thigh"] = thigh
        out[f"{side}_shank"] = quat_mul(thigh, (math.cos(a / 2), 0.0, 0.0, math.sin(a / 2)))
    return out


def clinical(frame):
    """klaw's eleven clinical angles (rad) of one clip frame, figure::clinical's order and
    signs: pelvis tilt, list, rotation, then per side (r, l) hip flexion, adduction, rotation
    and knee flexion."""
    rot = {k: matrix(v) for k, v in segment_rotations(frame).items()}
    r, p, q = yxz(rot["pelvis"])
    out = [-q, -p, r]
    for _, side, s in SIDES:
        a, b, c = zxy(relative(rot["pelvis"], rot[f"{side}_thigh"]))
        knee = zxy(relative(rot[f"{side}_thigh"], rot[f"{side}_shank"]))[0]
        out += [a, s * b, s * c, -knee]
    return out


def ankles(frame, geometry, box):
    """(pelvis centre, right ankle − pelvis centre, left ankle − pelvis centre), metres."""
    pelvis = tuple(frame[OFFSETS["root_pos"]:OFFSETS["root_pos"] + 3])
    rel = []
    for _, side, _ in SIDES:
        a = leg_markers(frame, side, geometry, box)["ankle"]
        rel.append(tuple(a[i] - pelvis[i] for i in range(3)))
    return pelvis, rel[0], rel[1]


def check_frames(frames):
    if any(len(f) != FRAME_LEN for f in frames):
        raise SystemExit(f"the clip's frames must hold {FRAME_LEN} numbers")
    steps = {round(f[0], 9) for f in frames[:-1]}
    if len(steps) != 1:
        raise SystemExit(f"the clip's frame durations must be uniform, found {sorted(steps)}")
    return frames[0][0]


def poulaine_rows(frames, geometry, box):
    """One row per sample of the stride (the last frame, the first moved on, left out): time,
    right x y z, left x y z, pelvis forward speed (cyclic central differences)."""
    dt = check_frames(frames)
    cycle = frames[:-1]
    stride = frames[-1][1] - frames[0][1]
    n = len(cycle)
    x = [f[1] for f in cycle]
    out = []
    for i, f in enumerate(cycle):
        _, r, l = ankles(f, geometry, box)
        ahead = x[(i + 1) % n] + (stride if i + 1 == n else 0.0)
        behind = x[i - 1] - (stride if i == 0 else 0.0)
        out.append([i * dt, *r, *l, (ahead - behind) / (2 * dt)])
    return out


ANGLE_NAMES = ["pelvis_tilt", "pelvis_list", "pelvis_rotation"] + [
    f"{n}_{s}" for s, _, _ in SIDES
    for n in ("hip_flexion", "hip_adduction", "hip_rotation", "knee_flexion")]


def angle_rows(frames, strides=ANGLE_STRIDES):
    """The clip's angles over `strides` strides: time, pelvis centre (m), angles (deg)."""
    dt = check_frames(frames)
    stride = frames[-1][1] - frames[0][1]
    out = []
    for k in range(strides):
        for i, f in enumerate(frames[:-1]):
            t = (k * (len(frames) - 1) + i) * dt
            pelvis = (f[1] + k * stride, f[2], f[3])
            out.append([t, *pelvis, *(math.degrees(a) for a in clinical(f))])
    return out


def write(path, preamble, header, rows):
    path = pathlib.Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    lines = [f"# {p}" for p in preamble] + [",".join(header)]
    lines += [",".join(f"{v:.6f}" for v in r) for r in rows]
    path.write_text("\n".join(lines) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("source", help="pybullet_data folder or pybullet .whl")
    proto = ROOT / "models" / "prototypes"
    ap.add_argument("--poulaine", default=str(proto / "deepmimic-walk-poulaine.csv"))
    ap.add_argument("--angles", default=str(proto / "deepmimic-walk-angles.csv"))
    args = ap.parse_args()
    motion_bytes, urdf_bytes = read_source(args.source)
    geometry, centre, size = urdf_geometry(urdf_bytes)
    frames = json.loads(motion_bytes)["Frames"]
    sha = lambda b: hashlib.sha256(b).hexdigest()
    thigh = -geometry["right"]["knee"][1] * SCALE
    shank = -geometry["right"]["ankle"][1] * SCALE
    width = 2 * geometry["right"]["hip"][2] * SCALE
    source = [
        "DeepMimic's walking clip (Peng et al. 2018, ACM TOG 37(4)), as shipped in the PyPI "
        "package pybullet 3.2.7",
        "(pybullet_data/data/motions/humanoid3d_walk.txt, sha256 " + sha(motion_bytes) + ";",
        "pybullet_data/humanoid/humanoid.urdf, sha256 " + sha(urdf_bytes) + "),",
        "zlib licence (Bullet Physics, https://github.com/bulletphysics/bullet3). Altered: 3-D "
        "forward kinematics at the URDF's scaling 0.25 by scripts/deepmimic_poulaine.py.",
        f"Body: thigh {thigh:.5f} m, shank {shank:.5f} m (leg {thigh + shank:.5f} m, klaw's "
        f"at H = {(thigh + shank) / 0.48225:.3f} m), hip width {width:.5f} m.",
        "Axes: the clip's and klaw's: x forward (the walking direction), y up, z right.",
    ]
    p_rows = poulaine_rows(frames, geometry, (centre, size))
    write(args.poulaine, source + [
        "The poulaine (docs/ik.md): ankle joint centres minus the pelvis centre (hip-joint "
        "midpoint), one stride; pelvis_speed_m_s by central differences."],
        ["time_s", "right_x_m", "right_y_m", "right_z_m", "left_x_m", "left_y_m", "left_z_m",
         "pelvis_speed_m_s"], p_rows)
    a_rows = angle_rows(frames)
    write(args.angles, source + [
        f"The clip's clinical angles (klaw's signs, figure::clinical), {ANGLE_STRIDES} strides; "
        "layout docs/criteria.md (no step column: heel strikes from the kinematics)."],
        ["time_s", "pelvis_tx_m", "pelvis_ty_m", "pelvis_tz_m"] + [f"{n}_deg"
                                                                   for n in ANGLE_NAMES],
        a_rows)
    speed = sum(r[7] for r in p_rows) / len(p_rows)
    print(f"{args.poulaine}: {len(p_rows)} samples, mean pelvis speed {speed:.4f} m/s")
    print(f"{args.angles}: {len(a_rows)} frames")


if __name__ == "__main__":
    main()
