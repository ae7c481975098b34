#!/usr/bin/env python3
"""Metric tables over the 100 NBRDF materials (closing notes of issues 4 and 5).

Reads the parameters JSON of `brdfit fit nbrdf:all ... --json FITS.json` and, optionally, the
sidecars of `brdfit factor nbrdf:all ... -o DIR` (one folder per parameterization), and prints
Markdown tables:
  1. per model: fits, failures, mean / median / 90th percentile of log_rmse (Low 2012 E2),
     cbrt_rmse and rel_l2 (all bin-measure weighted, cut-off as in the fits), how often the
     model is the best of all (solve times are in the HDF5 report and the summary that
     `brdfit fit` prints; the JSON holds none, so that reruns are byte-identical);
  2. factorization against the best single-lobe analytic fit, per material and in summary.
Usage: scripts/nbrdf_tables.py FITS.json [FACTOR_DIR ...]
Needs only python3's standard library.
"""
import json
import pathlib
import statistics
import sys

SINGLE_LOBE = ["lambert+ggx", "lambert+beckmann", "lambert+ward", "lambert+blinn-phong",
               "lambert+phong", "lambert+cook-torrance", "lambert+lafortune"]


def pct(values, q):
    v = sorted(values)
    if not v:
        return float("nan")
    k = (len(v) - 1) * q
    lo, hi = int(k), min(int(k) + 1, len(v) - 1)
    return v[lo] + (v[hi] - v[lo]) * (k - lo)


def main(argv):
    fits = json.loads(pathlib.Path(argv[1]).read_text())["fits"]
    by_material = {}
    for f in fits:
        by_material.setdefault(f["material"], {})[f["model"]] = f
    models = sorted({f["model"] for f in fits})
    best = {}
    for material, entries in by_material.items():
        ok = {m: e for m, e in entries.items() if e["status"] != "failed"}
        if ok:
            best[material] = min(ok, key=lambda m: ok[m]["metrics"]["log_rmse"])
    print(f"{len(by_material)} materials, {len(fits)} fits; options of the first fit: "
          f"{json.dumps(fits[0].get('options', {}), sort_keys=True)}\n")
    print("| model | fits | failed | log_rmse mean | median | p90 | cbrt_rmse median | "
          "rel_l2 median | best for |")
    print("|---|---|---|---|---|---|---|---|---|")
    rows = []
    for m in models:
        es = [by_material[mat][m] for mat in by_material if m in by_material[mat]]
        good = [e for e in es if e["status"] != "failed"]
        lr = [e["metrics"]["log_rmse"] for e in good]
        cr = [e["metrics"]["cbrt_rmse"] for e in good]
        rl = [e["metrics"]["rel_l2"] for e in good]
        wins = sum(1 for mat in best if best[mat] == m)
        rows.append((statistics.mean(lr) if lr else float("inf"), m, len(es), len(es) - len(good),
                     lr, cr, rl, wins))
    for mean_lr, m, n, failed, lr, cr, rl, wins in sorted(rows):
        print(f"| {m} | {n} | {failed} | {mean_lr:.5f} | {statistics.median(lr):.5f} | "
              f"{pct(lr, 0.9):.5f} | {statistics.median(cr):.5f} | {statistics.median(rl):.4f} | "
              f"{wins} |")

    for folder in argv[2:]:
        sidecars = sorted(pathlib.Path(folder).glob("*.factor.json"))
        if not sidecars:
            continue
        rows = []
        for s in sidecars:
            j = json.loads(s.read_text())
            material = j["source"]["file"].removeprefix("nbrdf:")
            fm = j["metrics"]["fit_metrics"]
            entries = by_material.get(material, {})
            singles = {m: entries[m] for m in SINGLE_LOBE
                       if m in entries and entries[m]["status"] != "failed"}
            if not singles or not fm.get("ok"):
                continue
            bm = min(singles, key=lambda m: singles[m]["metrics"]["log_rmse"])
            rows.append((material, fm["log_rmse"], bm, singles[bm]["metrics"]["log_rmse"],
                         j["stats"]["seconds"] * 1e3))
        param = json.loads(sidecars[0].read_text())["parameterization"]
        res = json.loads(sidecars[0].read_text())["solver"]["resolution"]
        ratios = [r[1] / r[3] for r in rows]
        better = sum(1 for r in ratios if r < 1)
        print(f"\n### factorization {param} {res}x{res} against the best single-lobe fit "
              f"({len(rows)} materials)\n")
        print(f"factorization log_rmse: median {statistics.median([r[1] for r in rows]):.5f}, "
              f"mean {statistics.mean([r[1] for r in rows]):.5f}; best single lobe: median "
              f"{statistics.median([r[3] for r in rows]):.5f}, mean "
              f"{statistics.mean([r[3] for r in rows]):.5f}; ratio factor/single median "
              f"{statistics.median(ratios):.3f} (p10 {pct(ratios, 0.1):.3f}, p90 "
              f"{pct(ratios, 0.9):.3f}); factorization better on {better} of {len(rows)}; "
              f"factor time median {statistics.median([r[4] for r in rows]):.0f} ms\n")
        print("| material | factor log_rmse | best single-lobe model | its log_rmse | ratio |")
        print("|---|---|---|---|---|")
        for material, fl, bm, bl, _ in sorted(rows, key=lambda r: r[1] / r[3]):
            print(f"| {material} | {fl:.5f} | {bm} | {bl:.5f} | {fl / bl:.3f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
