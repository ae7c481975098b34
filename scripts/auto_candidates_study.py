#!/usr/bin/env python3
"""Which (model, loss) candidates `brdfit fit --model auto` should fit (docs/accuracy.md).

Reads bench_accuracy CSVs (one row per material x model x loss x budget), applies the choice
rule of core/model_choice.h per material (S = PSNR - 20 x median luminance error; the fewest
parameters within --tolerance dB of the best S) over a candidate set, and prints the summary
columns of docs/accuracy.md. With --greedy K, candidates are added one at a time, each the one
that most raises the mean of the materials' best S.

  scripts/auto_candidates_study.py s8a.csv full1.csv --greedy 6
  scripts/auto_candidates_study.py s8a.csv --candidates lambert+ggx+ggx:rel,lambert+abc:rel
"""
import argparse
import csv
import statistics


def load(paths, budget):
    rows = {}
    for p in paths:
        with open(p, newline="") as f:
            for r in csv.DictReader(f):
                if r["status"] == "failed" or not r["psnr_db"]:
                    continue
                if budget and r["budget"] != budget:
                    continue
                key = (r["material"], r["model"], r["loss"])
                # One row per (material, model, loss): the first file given wins.
                rows.setdefault(key, r)
    return rows


def num_params(row):
    return len([p for p in row["params"].split(";") if p])


def score(row, weight):
    # core/model_choice.h: a PSNR beyond 60 dB counts as 60.
    return min(float(row["psnr_db"]), 60.0) - weight * float(row["median_rel_error"])


def choose(rows, materials, cands, tol, weight):
    chosen = []
    for m in materials:
        fits = [rows[(m, mod, loss)] for mod, loss in cands if (m, mod, loss) in rows]
        if not fits:
            continue
        best = max(score(r, weight) for r in fits)
        ok = [r for r in fits if score(r, weight) >= best - tol]
        ok.sort(key=lambda r: (num_params(r), -score(r, weight), r["model"]))
        chosen.append(ok[0])
    return chosen


def summary(name, chosen, rows, cands):
    ps = [float(r["psnr_db"]) for r in chosen]
    ls = [float(r["median_rel_error"]) for r in chosen]
    times = []
    for m in {r["material"] for r in chosen}:
        times.append(sum(float(rows[(m, a, b)]["fit_ms"]) for a, b in cands if (m, a, b) in rows))
    print(f"| {name} | {statistics.mean(ps):.2f} | {min(ps):.2f} | "
          f"{100 * statistics.median(ls):.1f} % | {100 * max(ls):.1f} % | "
          f"{sum(p >= 30 for p in ps)} | {sum(l <= 0.15 for l in ls)} | "
          f"{statistics.median(times) / 1000:.1f} s |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("csv", nargs="+")
    ap.add_argument("--candidates", help="model:loss,... (default: every pair in the CSVs)")
    ap.add_argument("--greedy", type=int, default=0, help="add K candidates greedily")
    ap.add_argument("--tolerance", type=float, default=0.5, help="dB (core/model_choice.h)")
    ap.add_argument("--weight", type=float, default=20.0, help="dB per unit median error")
    ap.add_argument("--budget", help="only rows of this budget")
    a = ap.parse_args()
    rows = load(a.csv, a.budget)
    materials = sorted({k[0] for k in rows})
    pool = sorted({(k[1], k[2]) for k in rows})
    if a.candidates:
        pool = [tuple(c.split(":", 1)) for c in a.candidates.split(",")]
    print("| candidates | mean dB | min dB | median lum | worst lum | >= 30 dB | <= 15 % | "
          "fit time per table (sum, median) |")
    print("|---|---|---|---|---|---|---|---|")
    if not a.greedy:
        summary(", ".join(f"{m} {l}" for m, l in pool),
                choose(rows, materials, pool, a.tolerance, a.weight), rows, pool)
        return
    sel = []
    for _ in range(min(a.greedy, len(pool))):
        def mean_best(c):
            return statistics.mean(
                max(score(rows[(m, mod, loss)], a.weight) for mod, loss in c
                    if (m, mod, loss) in rows) for m in materials)
        nxt = max((c for c in pool if c not in sel), key=lambda c: mean_best(sel + [c]))
        sel.append(nxt)
        summary(("+ " if len(sel) > 1 else "") + f"{nxt[0]}, {nxt[1]}",
                choose(rows, materials, sel, a.tolerance, a.weight), rows, sel)


if __name__ == "__main__":
    main()
