#!/usr/bin/env python3
"""Factorizations against the best single analytic lobe, by rendered score (docs/nbrdf-results.md).

  scripts/factor_vs_lobes.py --factors FACTORS.csv --lobes LOBES.csv [LOBES2.csv ...]
                             [--candidates mccool,mccool+d+r2+lr,...]

FACTORS.csv: bench_factor_accuracy's CSV (one row per material and form); LOBES.csv:
bench_accuracy's CSV (one row per material, model and loss), single-lobe models only. Every
row is scored as brdfit chooses (core/model_choice.h): S = psnr_db - 20 * median_rel_error.
Prints, per form, the mean PSNR, median of the median luminance errors, and on how many
materials it beats the best single lobe (S higher); then the same for the best factorization
of each material: the highest S over all forms, and over --candidates by `brdfit factor`'s own
rule (factor/factor_choice.h: the least texture memory within 0.5 dB of the best S).
"""
import argparse
import csv
import statistics
from collections import defaultdict


def score(row):
    return float(row["psnr_db"]) - 20.0 * float(row["median_rel_error"])


def texture_bytes(form, res):
    """Bytes of the float32 RGB textures (core/factor_form.h), 12 B more with a diffuse value."""
    parts = form.split("+")
    rank = next((int(p[1]) for p in parts[1:] if len(p) == 2 and p[0] == "r"), 1)
    return rank * 2 * res * res * 12 + (12 if "d" in parts[1:] else 0)


def choose(rows, tolerance=0.5):
    best = max(score(r) for r in rows)
    near = [r for r in rows if score(r) >= best - tolerance]
    return min(near, key=lambda r: (texture_bytes(r["param"], int(r["res"])), -score(r)))


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
    for label, pool, pick in (("best of all forms", sorted(forms), lambda rows: max(rows, key=score)),
                              ("chosen of candidates", [c for c in a.candidates.split(",") if c],
                               choose)):
        if not pool:
            continue
        best = {}
        for m in materials:
            rows = [forms[f][m] for f in pool if m in forms[f]]
            if rows:
                best[m] = pick(rows)
        line(label, best)
        if label.startswith("chosen"):
            counts = defaultdict(int)
            for r in best.values():
                counts[r["param"]] += 1
            print("  chosen: " + ", ".join(f"{f} {n}" for f, n in sorted(counts.items())))


if __name__ == "__main__":
    main()
