#!/usr/bin/env python3
"""klaw's body tables from de Leva (1996): models/body-deleva-male.toml and -female.toml.

Source: P. de Leva, "Adjustments to Zatsiorsky-Seluyanov's segment inertia parameters",
J Biomech 29(9):1223-1230, 1996, Table 4 (the adjusted parameters of young adult men and
women: segment lengths in mm for the table's mean stature, masses in % of body mass, centres of
mass in % of the segment length from the first-named end point, radii of gyration in % of the
segment length). The numbers below are that table's, retyped; nothing else is measured.

klaw's table (models/body-winter.toml's layout, fractions of the stature H and the mass M) is
derived from them by the rules below (docs/bodies.md says why each one):

- thigh = HJC-KJC; shank = KJC-LMAL (the lateral malleolus for the ankle joint); both /H.
- foot: de Leva gives only its length, heel to toe tip. The foot's shape is Table B-1's (Winter),
  scaled so that klaw's flat foot (l8 + sqrt(l12^2 - l9^2) + l13) is de Leva's foot long.
- klaw's segment 4 is the shank with the foot: mass m_shank + m_foot; centre of mass the
  mass-weighted mean of the shank's and of the foot's, the foot's put on the shank's axis at the
  sole, l4 + l9 from the knee (the rule that turns Winter's separate shank and foot into
  Dempster's 0.606 for "leg and foot", to 0.001: tested); radius of gyration by the parallel
  axis theorem from the two segments' own (the transverse column: rotation in the sagittal
  plane is about the transverse, medio-lateral axis).
- klaw's whole leg (segment 1, ankle to hip) is the straight composite of thigh and segment 4.
- the upper body (segment 2, hip to the top of the head) is head, trunk and both arms hanging
  from shoulders at the suprasternale's level: its length is H minus the standing hip height
  (l9 + l3 + l4), its mass 1 - 2 (thigh + shank + foot) (de Leva's 14 segments sum to 1 within
  their rounding), its centre of mass and radius of gyration the composite's.
- the figure: spine = trunk (MIDH-SUPR); head = VERT-MIDG; neck = the rest up to the stature;
  upper arm and forearm from de Leva; shoulder width, hand (to the finger tip: de Leva's hand
  ends at the 3rd metacarpal) and the pelvis width from Table B-1, which de Leva lacks.

Usage: python3 scripts/body_deleva.py [--write]  (prints both tables; --write replaces the two
files in models/). python3 -m unittest scripts/test_body_deleva.py checks the rules.
"""
import argparse
import math
import pathlib
import tomllib

ROOT = pathlib.Path(__file__).resolve().parent.parent

# de Leva 1996, Table 4: (length mm, mass %, CM % from the first end point, transverse r %)
# for the (male, female) columns; stature mm; body mass kg.
DE_LEVA = {
    "male": {
        "stature": 1741.0, "body_mass": 73.0,
        "head": (203.3, 6.94, 59.76, 37.6),       # VERT-MIDG
        "trunk": (531.9, 43.46, 44.86, 34.7),     # SUPR-MIDH
        "upper_arm": (281.7, 2.71, 57.72, 26.9),  # SJC-EJC
        "forearm": (268.9, 1.62, 45.74, 26.5),    # EJC-WJC
        "hand": (86.2, 0.61, 79.00, 51.3),        # WJC-MET3
        "thigh": (422.2, 14.16, 40.95, 32.9),     # HJC-KJC
        "shank": (434.0, 4.33, 44.59, 24.9),      # KJC-LMAL
        "foot": (258.1, 1.37, 44.15, 24.5),       # HEEL-TTIP
    },
    "female": {
        "stature": 1735.0, "body_mass": 61.9,
        "head": (200.2, 6.68, 58.94, 35.9),
        "trunk": (529.3, 42.57, 41.51, 33.9),
        "upper_arm": (275.1, 2.55, 57.54, 26.0),
        "forearm": (264.3, 1.38, 45.59, 25.7),
        "hand": (78.0, 0.56, 74.74, 45.4),
        "thigh": (368.5, 14.78, 36.12, 36.4),
        "shank": (432.3, 4.81, 44.16, 26.7),
        "foot": (228.3, 1.29, 40.14, 27.9),
    },
}


def winter():
    return tomllib.loads((ROOT / "models" / "body-winter.toml").read_text())


def flat_foot_length(foot):
    """klaw's flat foot, heel to toe tip: l8 + sqrt(l12^2 - l9^2) + l13 (fractions of H)."""
    return (foot["hind_foot"] + math.sqrt(foot["ankle_to_metatarsal"] ** 2
                                          - foot["ankle_height"] ** 2)
            + foot["metatarsal_to_toe"])


def composite(parts):
    """Mass, centre and radius of gyration of rigid parts on one line: each part is (mass,
    position of its centre along the line, its own radius of gyration); returns (m, y, k)."""
    m = sum(p[0] for p in parts)
    y = sum(p[0] * p[1] for p in parts) / m
    i = sum(p[0] * (p[2] ** 2 + (p[1] - y) ** 2) for p in parts)
    return m, y, math.sqrt(i / m)


def shank_with_foot(l4, c4, k4, m4, m_foot, k_foot, l9):
    """klaw's segment 4 from a shank (length l4, CM c4 l4 from the knee, gyration k4, mass m4)
    and a foot (mass, gyration about its own CM) whose CM sits on the shank's axis at the sole,
    l4 + l9 from the knee; returns (mass, r from the knee, gyration), lengths as given."""
    return composite([(m4, c4 * l4, k4), (m_foot, l4 + l9, k_foot)])


def table(sex):
    d, w = DE_LEVA[sex], winter()
    h = d["stature"]
    frac = lambda name: d[name][0] / h
    mass = lambda name: d[name][1] / 100.0
    cm = lambda name: d[name][2] / 100.0
    gyr = lambda name: d[name][3] / 100.0

    scale = frac("foot") / flat_foot_length(w["foot"])
    foot = {k: v * scale for k, v in w["foot"].items()}
    l9 = foot["ankle_height"]
    l3, l4 = frac("thigh"), frac("shank")

    m_s, r_s, k_s = shank_with_foot(l4, cm("shank"), gyr("shank") * l4, mass("shank"),
                                    mass("foot"), gyr("foot") * frac("foot"), l9)
    # the whole leg from the ankle: thigh CM at l4 + (1 - c3) l3, segment 4's at l4 - r4
    m_t, k_t = mass("thigh"), gyr("thigh") * l3
    m1, y1, k1 = composite([(m_t, l4 + (1 - cm("thigh")) * l3, k_t), (m_s, l4 - r_s, k_s)])
    l1 = l3 + l4

    # the upper body from the hip joints up, arms hanging from the suprasternale's level
    l2 = 1.0 - (l9 + l1)
    trunk, arm = frac("trunk"), frac("upper_arm")
    fore, hand = frac("forearm"), frac("hand")
    parts = [
        (mass("trunk"), (1 - cm("trunk")) * trunk, gyr("trunk") * trunk),
        (mass("head"), l2 - cm("head") * frac("head"), gyr("head") * frac("head")),
    ]
    for _ in range(2):
        parts += [
            (mass("upper_arm"), trunk - cm("upper_arm") * arm, gyr("upper_arm") * arm),
            (mass("forearm"), trunk - arm - cm("forearm") * fore, gyr("forearm") * fore),
            (mass("hand"), trunk - arm - fore - cm("hand") * hand, gyr("hand") * hand),
        ]
    _, y2, k2 = composite(parts)
    m2 = 1.0 - 2.0 * (mass("thigh") + mass("shank") + mass("foot"))

    fig = w["figure"]
    return {
        "pelvis": {"length": w["pelvis"]["length"]},
        "leg": {"r": y1 / l1, "gamma": k1 / l1},
        "upper_body": {"length": l2, "mass": m2, "r": y2 / l2, "gamma": k2 / l2},
        "thigh": {"length": l3, "mass": m_t, "r": cm("thigh"), "gamma": gyr("thigh")},
        "shank": {"length": l4, "mass": m_s, "r": r_s / l4, "gamma": k_s / l4},
        "foot": foot,
        "figure": {
            "spine": trunk,
            "shoulder_width": fig["shoulder_width"],
            "neck": l2 - trunk - frac("head"),
            "head": frac("head"),
            "upper_arm": arm,
            "forearm": fore,
            "hand": fig["hand"],
        },
        "limits": w["limits"],
        "composite_upper_body_mass": composite(parts)[0],
    }


SEGMENT_NOTES = {
    "pelvis": "0: pelvis width, hip joint to hip joint (Table B-1: de Leva has none)",
    "leg": "1: whole leg, ankle to hip, the composite of 3 and 4; r from the distal end",
    "upper_body": "2: head, trunk and arms (composite), hip joint level to the top of the head",
    "thigh": "3: HJC-KJC",
    "shank": "4: KJC-LMAL with the foot (composite, the foot's CM at the sole on the axis)",
    "foot": "Table B-1's foot shape scaled to de Leva's heel-to-toe length",
    "figure": "spine MIDH-SUPR, head VERT-MIDG, neck the rest; shoulder width and hand Table B-1's",
    "limits": "bodies the table is meant for",
}


def toml_text(sex):
    t = table(sex)
    d = DE_LEVA[sex]
    lines = [
        f"# Body segment table: de Leva 1996 (J Biomech 29:1223, Table 4), {sex}s "
        f"(stature {d['stature']:.0f} mm, {d['body_mass']} kg),",
        "# in the layout of body-winter.toml. Generated by scripts/body_deleva.py, which holds "
        "the published",
        "# numbers and the derivation rules (docs/bodies.md); do not edit by hand.",
        f'name = "de Leva 1996, {sex}s (Table 4), derived by scripts/body_deleva.py"',
    ]
    for seg in ("pelvis", "leg", "upper_body", "thigh", "shank", "foot", "figure", "limits"):
        lines += ["", f"[{seg}]  # {SEGMENT_NOTES[seg]}"]
        for k, v in t[seg].items():
            if isinstance(v, list):
                lines.append(f"{k} = [{v[0]}, {v[1]}]")
            else:
                lines.append(f"{k} = {v!r}")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--write", action="store_true", help="write models/body-deleva-*.toml")
    args = ap.parse_args()
    for sex in ("male", "female"):
        text = toml_text(sex)
        if args.write:
            (ROOT / "models" / f"body-deleva-{sex}.toml").write_text(text)
        else:
            print(text)


if __name__ == "__main__":
    main()
