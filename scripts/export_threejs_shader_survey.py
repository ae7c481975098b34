#!/usr/bin/env python3
"""three.js ShaderMaterial modules (`brdfit export --format threejs`) against brdfit's preview
for the demo materials and five NBRDF proxies (docs/exports.md, "three.js ShaderMaterial"): the
lambert+ggx fits and the default factorization (`brdfit factor`, the best of four forms) of each
table, each exported as a module, rendered by three.js in headless Chromium and by
`brdfit render` (the scene of tests/export/check_threejs.py); prints mean / p99 / max
differences in 8-bit levels and the rendered error of each against its table.

Usage: scripts/export_threejs_shader_survey.py BUILD_DIR WORK_DIR
(after export.threejs_render ran once in BUILD_DIR; WORK_DIR as left by
scripts/export_blender_survey.py BUILD_DIR WORK_DIR: its tables and fits.json)."""
import json
import os
import subprocess
import sys
from types import SimpleNamespace

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests", "export"))
from check_threejs import brdfit_render, compare, render_three  # noqa: E402


def rendered(metrics):
    r = (metrics or {}).get("rendered", {})
    return f"{r.get('psnr_db', 0):.1f} dB, {100 * r.get('median_rel_error', 0):.1f} %"


def main():
    build, work = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    brdfit = os.path.join(build, "brdfit")
    tools = os.path.join(build, "tests/export/node-tools")
    os.chdir(work)
    o = SimpleNamespace(brdfit=brdfit, work=work)
    print("| material | fit vs table | fit module vs preview | factorization (form) vs table | "
          "factored module vs preview |")
    for f in json.load(open("fits.json"))["fits"]:
        name = f["material"]
        json.dump({"format": "brdfit-fit-params", "format_version": 1, "fits": [f]},
                  open(name + ".fit.json", "w"))
        subprocess.run([brdfit, "export", name + ".fit.json", "--format", "threejs", "-q", "-o",
                        name + ".mjs"], check=True, capture_output=True)
        ref = brdfit_render(o, name + "-fit",
                            {"type": "analytic", "model": f["model"], "params": f["params"]})
        a = compare(ref, render_three(tools, "chromium", name + ".mjs", name + "-fit-three.png"))
        table = f["source"]
        subprocess.run([brdfit, "factor", table, "-o", "fac", "-q"], check=True,
                       capture_output=True)
        stem = name
        sidecar = os.path.join("fac", stem + ".factor.json")
        sc = json.load(open(sidecar))
        subprocess.run([brdfit, "export", sidecar, "--format", "threejs", "-q", "-o",
                        name + "-factored.mjs"], check=True, capture_output=True)
        ref = brdfit_render(o, name + "-factored", {"type": "factored", "factors": sidecar})
        b = compare(ref, render_three(tools, "chromium", name + "-factored.mjs",
                                      name + "-factored-three.png"))
        form = f"{sc['parameterization']} rank {sc['rank']}" + \
            (" + diffuse" if any(sc["diffuse"]) else "")
        print(f"| {name} | {rendered(f['metrics'])} | {a[0]:.2f} / {a[1]} / {a[2]} | "
              f"{rendered(sc.get('metrics'))} ({form}) | {b[0]:.2f} / {b[1]} / {b[2]} |")


if __name__ == "__main__":
    main()
