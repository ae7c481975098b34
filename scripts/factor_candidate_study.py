#!/usr/bin/env python3
"""What a factorization among the candidates of `brdfit fit` changes (docs/accuracy.md,
"Factorizations among the candidates").

Reads the JSON parameters of one run that fitted the candidates and the factorization
(`brdfit fit nbrdf:all --model auto,factorization -j 2 --json all.json`), applies the choice
rule of core/model_choice.h per material (S = min(PSNR, 60) - 20 x median luminance error; the
fewest parameters within the tolerance of the best S; a factorization's parameters are its
texture values) with and without the factorization, and prints the summary columns of
docs/accuracy.md: mean linear PSNR, mean S, the median and worst of the materials' median
luminance errors, how many reach 30 dB and 15 %, and how often the factorization is chosen.

  scripts/factor_candidate_study.py all.json
  scripts/factor_candidate_study.py all.json --tolerance 0.5 --list
"""
import argparse
import json
import statistics


def score(fit):
    r = fit["metrics"]["rendered"]
    return min(r["psnr_db"], 60.0) - 20.0 * r["median_rel_error"]


def parameters(fit):
    if fit["model"] == "factorization":
        return fit["factorization"]["values"]
    return len(fit["params"])


def choose(fits, tolerance):
    usable = [f for f in fits if f["status"] != "failed" and f["metrics"].get("rendered", {}).get("ok")]
    if not usable:
        return None
    best = max(score(f) for f in usable)
    near = [f for f in usable if score(f) >= best - tolerance]
    return min(near, key=lambda f: (parameters(f), -score(f), f["model"]))


def summary(chosen):
    psnr = [c["metrics"]["rendered"]["psnr_db"] for c in chosen]
    med = [c["metrics"]["rendered"]["median_rel_error"] for c in chosen]
    s = [score(c) for c in chosen]
    return {
        "materials": len(chosen),
        "mean PSNR dB": statistics.mean(psnr),
        "worst PSNR dB": min(psnr),
        "mean S dB": statistics.mean(s),
        "median of median lum err %": 100 * statistics.median(med),
        "worst median lum err %": 100 * max(med),
        ">= 30 dB": sum(p >= 30 for p in psnr),
        "<= 15 %": sum(m <= 0.15 for m in med),
        "factorization chosen": sum(c["model"] == "factorization" for c in chosen),
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("json", help="brdfit fit --json output (format brdfit-fit-params)")
    ap.add_argument("--tolerance", type=float, default=0.5, help="dB (core/model_choice.h)")
    ap.add_argument("--list", action="store_true", help="the materials where the choice changes")
    a = ap.parse_args()
    with open(a.json) as f:
        fits = json.load(f)["fits"]
    by_material = {}
    for fit in fits:
        by_material.setdefault(fit["material"], []).append(fit)
    rows = {}
    for label, keep in (("analytic candidates", lambda f: f["model"] != "factorization"),
                        ("with the factorization", lambda f: True),
                        ("the factorization alone", lambda f: f["model"] == "factorization")):
        chosen = [choose([f for f in fs if keep(f)], a.tolerance) for fs in by_material.values()]
        rows[label] = summary([c for c in chosen if c])
    keys = list(next(iter(rows.values())).keys())
    print("| | " + " | ".join(keys) + " |")
    print("|---" * (len(keys) + 1) + "|")
    for label, r in rows.items():
        cells = [f"{v:.2f}" if isinstance(v, float) else str(v) for v in r.values()]
        print(f"| {label} | " + " | ".join(cells) + " |")
    if a.list:
        print()
        print("| material | analytic choice | S | with the factorization | S | gain dB |")
        print("|---|---|---|---|---|---|")
        for m, fs in sorted(by_material.items()):
            a0 = choose([f for f in fs if f["model"] != "factorization"], a.tolerance)
            a1 = choose(fs, a.tolerance)
            if a0 and a1 and a0 is not a1:
                name = a1["model"] + (" " + a1["factorization"]["form"] if a1["model"] == "factorization" else "")
                print(f"| {m} | {a0['model']} | {score(a0):.2f} | {name} | {score(a1):.2f} | "
                      f"{score(a1) - score(a0):+.2f} |")


if __name__ == "__main__":
    main()
