#!/usr/bin/env python3
"""What `brdfit export` takes from a default fit report, per target (docs/exports.md, "Which fits
export").

    scripts/export_selection_survey.py --brdfit build/brdfit --fits all.json [--work /tmp/sel]

FITS is `brdfit fit ... --json` output (the 100 proxies: `brdfit fit nbrdf:all -j 2
--no-timings -o all.h5 --json all.json`). For each target, every material is exported as a
user would (`brdfit export FITS --format F -o DIR/`, no --model), and its stderr read: the
note naming the chosen fit and the gap of the exported one (the choice score S, dB,
core/model_choice.h), and whether the file is exact. An exact export renders as the fit it
carries (the render checks of tests/export: Cycles, three.js, pbrt-v4), so for those the gap
is the whole loss; an approximate one loses its approximation on top.

Prints per target: materials, exports exact, exported fit = chosen, mean gap, and how many are
within 1 and 2 dB of the chosen fit. Exit 0; 1 when brdfit fails.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys

TARGETS = ("gltf", "blender", "mitsuba", "pbrt", "threejs")
NOTE = re.compile(r"^brdfit: export: note: (.*?): brdfit chose (\S+) for this material, .*"
                  r"exporting ([^;\s]+)(?:; \S+ scores (-?[0-9.]+) dB, (-?[0-9.]+) dB below)?")
WRITTEN = re.compile(r"^(\S+) (\S+) \(.*\) -> .* \[(exact|approximate)\]$")


def survey(brdfit, fits, work, target):
    out = os.path.join(work, target) + "/"
    shutil.rmtree(out, ignore_errors=True)
    r = subprocess.run([brdfit, "export", fits, "--format", target, "-o", out],
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"brdfit export --format {target}: {r.stderr[-2000:]}")
    gaps, exact, models = {}, {}, {}
    for line in (r.stderr + r.stdout).splitlines():
        if m := NOTE.match(line):
            gaps[m.group(1)] = float(m.group(5)) if m.group(5) else float("nan")
        elif m := WRITTEN.match(line):
            exact[m.group(1)] = m.group(3) == "exact"
            models[m.group(1)] = m.group(2)
    rows = []
    for material in sorted(exact):
        rows.append((material, models[material], exact[material], gaps.get(material, 0.0)))
    return rows


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--brdfit", required=True)
    ap.add_argument("--fits", required=True)
    ap.add_argument("--work", default="/tmp/export-selection")
    ap.add_argument("--per-material", action="store_true")
    o = ap.parse_args()
    os.makedirs(o.work, exist_ok=True)
    print("| target | materials | exact exports | exported = chosen | mean gap (dB) | "
          "within 1 dB | within 2 dB | worst (dB) |")
    print("|---|---|---|---|---|---|---|---|")
    for target in TARGETS:
        rows = survey(o.brdfit, o.fits, o.work, target)
        n = len(rows)
        gaps = [g for _, _, _, g in rows if g == g]
        same = sum(1 for _, _, _, g in rows if g == 0.0)
        print(f"| {target} | {n} | {sum(e for _, _, e, _ in rows)} | {same} | "
              f"{sum(gaps) / max(len(gaps), 1):.2f} | {sum(g <= 1 for g in gaps)} | "
              f"{sum(g <= 2 for g in gaps)} | {max(gaps, default=0):.2f} |")
        if o.per_material:
            for material, model, exact, gap in rows:
                print(f"    {target:8s} {material:32s} {model:20s} "
                      f"{'exact' if exact else 'approx':7s} {gap:6.2f}")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except RuntimeError as e:
        print(f"FAIL: {e}")
        sys.exit(1)
