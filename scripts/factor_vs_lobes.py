#!/usr/bin/env python3
"""Factorizations against the best single analytic lobe, by rendered score (docs/nbrdf-results.md).

  scripts/factor_vs_lobes.py --factors FACTORS.csv --lobes LOBES.csv [LOBES2.csv ...]
                             [--candidates mccool,mccool+d+r2+lr,...]

FACTORS.csv: bench_factor_accuracy's CSV (one row per material and form); LOBES.csv:
bench_accuracy's CSV (one row per material, model and loss), single-lobe models only. Every
row is scored as brdfit chooses (core/model_choice.h): S = psnr_db - 20 * median_rel_error.
Prints, per form, the mean PSNR, median of the median luminance errors, and on how many
materials it beats the best single lobe (S higher); then the same for the best factorization
of each material (over all forms, or over --candidates: what `brdfit factor` tries).
"""
import argparse
import csv
import statistics
from collections import defaultdict


def score(row):
    return float(row["psnr_db"]) - 20.0 * float(row["median_rel_error"])


def ok(row):
    return row.get("status", "ok") in ("ok", "converged", "no_convergence")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--factors", required=True)
    ap.add_argument("--lobes", required=True, nargs="+")
    ap.add_argument("--candidates", default="")
    a = ap.parse_args()

    lobe = {}  # material -> (S, model loss)
    for path in a.lobes:
        for r in csv.DictReader(open(path)):
            if not ok(r):
                continue
            s = score(r)
            if r["material"] not in lobe or s > lobe[r["material"]][0]:
                lobe[r["material"]] = (s, r["model"] + " " + r["loss"])
    forms = defaultdict(dict)  # form -> material -> row
    for r in csv.DictReader(open(a.factors)):
        if ok(r):
            forms[r["param"]][r["material"]] = r
    materials = sorted(set(lobe) & set().union(*[set(m) for m in forms.values()]))
    print(f"{len(materials)} materials with both; best single lobe: mean S "
          f"{statistics.mean(lobe[m][0] for m in materials):.2f} dB")
    print(f"{'form':<22} {'n':>4} {'mean dB':>8} {'med lum':>8} {'mean S':>8} {'beats lobe':>10}"
          f" {'ms med':>8}")

    def line(name, rows):
        ms = [m for m in materials if m in rows]
        wins = sum(score(rows[m]) > lobe[m][0] for m in ms)
        t = [float(rows[m]["factor_ms"]) for m in ms if "factor_ms" in rows[m]]
        print(f"{name:<22} {len(ms):>4} {statistics.mean(float(rows[m]['psnr_db']) for m in ms):>8.2f}"
              f" {100 * statistics.median(float(rows[m]['median_rel_error']) for m in ms):>7.1f}%"
              f" {statistics.mean(score(rows[m]) for m in ms):>8.2f} {wins:>5} / {len(ms):<4}"
              f" {statistics.median(t) if t else 0:>8.0f}")

    for f in sorted(forms):
        line(f, forms[f])
    for label, pool in (("best of all forms", sorted(forms)),
                        ("best of candidates", [c for c in a.candidates.split(",") if c])):
        if not pool:
            continue
        best = {}
        for m in materials:
            rows = [forms[f][m] for f in pool if m in forms[f]]
            if rows:
                best[m] = max(rows, key=score)
        line(label, best)


if __name__ == "__main__":
    main()
