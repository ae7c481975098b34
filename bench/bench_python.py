#!/usr/bin/env python3
"""A fit through Python against the same fit through the CLI (docs/python.md: a fit through
Python costs no more than through the CLI).

  PYTHONPATH=build/python python3 bench/bench_python.py build/brdfit [nbrdf:NAME | table] [budget]

For each of --repeat runs: `brdfit fit TABLE --model lambert+ggx --budget B --json ... -q` as a
process (wall time: start-up, load, prepare, fit, metrics, report and JSON written), and in
this process brdfit.load + brdfit.fit (wall time of the same steps but the report). Prints the
medians and checks both wrote the same JSON. Defaults: nbrdf:gold-metallic-paint, stride:4.
"""
import argparse
import os
import statistics
import subprocess
import tempfile
import time

import brdfit


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("cli")
    ap.add_argument("table", nargs="?", default="nbrdf:gold-metallic-paint")
    ap.add_argument("budget", nargs="?", default="stride:4")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--model", default="lambert+ggx")
    a = ap.parse_args()
    cli_s, py_s, py_fit_s = [], [], []
    with tempfile.TemporaryDirectory() as tmp:
        out_json = os.path.join(tmp, "fit.json")
        for _ in range(a.repeat):
            t0 = time.perf_counter()
            subprocess.run([a.cli, "fit", a.table, "--model", a.model, "--budget", a.budget,
                            "-o", os.path.join(tmp, "fits.h5"), "--force", "--json", out_json,
                            "-q"], check=True)
            cli_s.append(time.perf_counter() - t0)
            t0 = time.perf_counter()
            table = brdfit.load(a.table)
            t1 = time.perf_counter()
            r = brdfit.fit(table, model=a.model, budget=a.budget)
            py_s.append(time.perf_counter() - t0)
            py_fit_s.append(time.perf_counter() - t1)
        same = r.json == open(out_json).read()
    med = statistics.median
    print(f"table {a.table}, model {a.model}, budget {a.budget}, {a.repeat} runs, medians:")
    print(f"  CLI process (load + fit + report + JSON): {med(cli_s) * 1e3:9.1f} ms")
    print(f"  Python load + fit:                        {med(py_s) * 1e3:9.1f} ms")
    print(f"  Python fit alone (table in memory):       {med(py_fit_s) * 1e3:9.1f} ms")
    print(f"  same JSON: {same}")
    return 0 if same else 1


if __name__ == "__main__":
    raise SystemExit(main())
