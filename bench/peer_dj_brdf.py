#!/usr/bin/env python3
"""Whole-command timings of brdfit against the fastest peer, jdupuy/dj_brdf's GGX fit
(docs/fitting.md, "Against the fastest peer"): medians of alternating runs and their paired
ratios, per MERL table.

    bench/peer_dj_brdf.py --brdfit build/brdfit [--dj-header PATH/dj_brdf.h] \\
        [--repeat 11] TABLE.binary...

The peer is built here (g++ -O3) from a dj_brdf.h the user fetched from
https://github.com/jdupuy/dj_brdf (it is never copied into this repository); without
--dj-header, or when the header is missing or does not build, the peer's rows are skipped with a
message and brdfit's own rows are still timed. Every run of a command is a fresh process with
a fresh output (brdfit fit resumes an existing report, so the report is removed first); the runs
of the commands alternate, so that a change in the machine's load falls on all of them. The
ratios are medians of the per-round ratios (paired), not ratios of medians.

Rows: cat (the file read from the page cache: the memory-speed floor of `info`), brdfit info,
dj_brdf's whole GGX fit, brdfit fit --model ggx --diffuse none --polish none (the same job),
brdfit fit --model lambert+ggx, and the default brdfit fit. Prints a Markdown table and the
load average. Exit 0; 1 when a brdfit command fails.
"""
import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time


def build_peer(header, work):
    """The peer's binary, or None with the reason printed."""
    if not header:
        print("peer: skipped (no --dj-header: fetch dj_brdf.h from "
              "https://github.com/jdupuy/dj_brdf)", file=sys.stderr)
        return None
    if not os.path.isfile(header):
        print(f"peer: skipped ({header}: no such file)", file=sys.stderr)
        return None
    src = os.path.join(os.path.dirname(os.path.abspath(__file__)), "peers", "dj_ggx_fit.cc")
    exe = os.path.join(work, "dj_ggx_fit")
    r = subprocess.run(["g++", "-O3", "-std=c++17", "-w", "-I", os.path.dirname(
        os.path.abspath(header)), src, "-o", exe, "-lm"], capture_output=True, text=True)
    if r.returncode != 0:
        print(f"peer: skipped (dj_ggx_fit.cc does not build against {header}):\n"
              f"{r.stderr[-2000:]}", file=sys.stderr)
        return None
    return exe


def timed(cmd, before=None):
    if before:
        before()
    t0 = time.perf_counter()
    r = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    dt = time.perf_counter() - t0
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed: {r.stderr[-1000:]}")
    return dt


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--brdfit", required=True)
    ap.add_argument("--dj-header")
    ap.add_argument("--repeat", type=int, default=11)
    ap.add_argument("tables", nargs="+")
    o = ap.parse_args()
    work = tempfile.mkdtemp(prefix="brdfit-peer-")
    try:
        peer = build_peer(o.dj_header, work)
        out = os.path.join(work, "fit.h5")

        def fresh():
            if os.path.exists(out):
                os.remove(out)

        print("| table | command | median (s) | paired ratio |")
        print("|---|---|---|---|")
        for table in o.tables:
            runs = {
                "cat": (["cat", table], None),
                "brdfit info": ([o.brdfit, "info", table], None),
                "brdfit fit --model ggx --diffuse none --polish none":
                    ([o.brdfit, "fit", table, "--model", "ggx", "--diffuse", "none",
                      "--polish", "none", "-q", "-o", out], fresh),
                "brdfit fit --model lambert+ggx":
                    ([o.brdfit, "fit", table, "--model", "lambert+ggx", "-q", "-o", out], fresh),
                "brdfit fit (default)": ([o.brdfit, "fit", table, "-q", "-o", out], fresh),
            }
            if peer:
                runs["dj_brdf GGX fit"] = ([peer, table], None)
            times = {k: [] for k in runs}
            for _ in range(o.repeat):
                for k, (cmd, before) in runs.items():
                    times[k].append(timed(cmd, before))
            # Each row's ratio against its reference, round by round: info against cat, the
            # fits against the peer's fit when it was built.
            ref = {"brdfit info": "cat"}
            if peer:
                for k in runs:
                    if k.startswith("brdfit fit"):
                        ref[k] = "dj_brdf GGX fit"
            for k in runs:
                ratio = ""
                if k in ref:
                    r = statistics.median(a / b for a, b in zip(times[k], times[ref[k]]))
                    ratio = f"{r:.2f}x {ref[k]}"
                print(f"| {os.path.basename(table)} | {k} | {statistics.median(times[k]):.4f} | "
                      f"{ratio} |")
        print(f"\nload average: {os.getloadavg()[0]:.2f} {os.getloadavg()[1]:.2f}; "
              f"{o.repeat} alternating rounds")
    except RuntimeError as e:
        print(f"error: {e}", file=sys.stderr)
        return 1
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
