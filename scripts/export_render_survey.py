#!/usr/bin/env python3
"""How a default fit report's glTF exports render in a real viewer, against the measured table
(docs/exports.md, "Which fits export").

    scripts/export_render_survey.py --brdfit build/brdfit --fits all.json \
        --tools build/tests/export/node-tools [--work /tmp/ers] [--materials a,b,...]

FITS is `brdfit fit ... --json` output over tables `brdfit render` can read (nbrdf:NAME needs
BRDFIT_NBRDF_ZIP). For each material, in the scene of tests/export/check_threejs.py (unit
sphere, camera at (0, 0, 4), 30 deg, one directional light from (1, 1, 1), linear -> sRGB 8 bit,
256 x 256):
  - the measured table, rendered by `brdfit render` (the reference);
  - the chosen fit, rendered by `brdfit render` (what brdfit itself shows);
  - `brdfit export FITS --material M --format glb --no-fit` (the fits the report holds) and
    `brdfit export FITS --material M --format glb` (the target's own model fitted on the spot
    when the report has none), each rendered by three.js (GLTFLoader -> MeshPhysicalMaterial in
    headless Chromium, tests/export/node-tools/render_three.cjs).
Each image is scored against the reference inside the sphere (radius 118 px): PSNR of the 8-bit
sRGB values. Prints one line per material and the means. Needs node, chromium and the node
tools `ctest -R export.threejs_render` installs. Exit 0; 1 when a command fails.
"""
import argparse
import json
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests",
                                "export"))
from check_threejs import SIZE, preview_scene, read_png, render_three  # noqa: E402


def psnr(a_path, b_path):
    wa, ha, ca, a = read_png(a_path)
    wb, hb, cb, b = read_png(b_path)
    c0, sq, n = (wa - 1) / 2, 0.0, 0
    for y in range(ha):
        for x in range(wa):
            if (x - c0) ** 2 + (y - c0) ** 2 > 118 ** 2:
                continue
            for k in range(3):
                d = a[y][x * ca + k] - b[y][x * cb + k]
                sq += d * d
                n += 1
    mse = sq / n
    return 99.0 if mse == 0 else 10 * math.log10(255 ** 2 / mse)


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)}: {r.stderr[-2000:]}")
    return r


def render(o, name, material):
    scene = os.path.join(o.work, name + ".scene.json")
    json.dump(preview_scene(material), open(scene, "w"))
    png = os.path.join(o.work, name + ".png")
    run([o.brdfit, "render", scene, "-o", png])
    return png


def main():
    ap = argparse.ArgumentParser()
    for a in ("--brdfit", "--fits", "--tools"):
        ap.add_argument(a, required=True)
    ap.add_argument("--work", default="/tmp/export-render-survey")
    ap.add_argument("--materials", default="")
    o = ap.parse_args()
    os.makedirs(o.work, exist_ok=True)
    chromium = os.environ.get("CHROMIUM", "chromium")
    os.environ["CHROMIUM"] = chromium
    fits = json.load(open(o.fits))["fits"]
    materials = sorted({f["material"] for f in fits})
    if o.materials:
        materials = [m for m in materials if m in o.materials.split(",")]
    rows = []
    for m in materials:
        mine = [f for f in fits if f["material"] == m]
        chosen = [f for f in mine if f.get("chosen")][0]
        safe = "".join(c if c.isalnum() or c in "-_" else "_" for c in m)
        one = os.path.join(o.work, safe + ".json")
        json.dump({"format": "brdfit-fit-params", "format_version": 1, "fits": mine},
                  open(one, "w"))
        ref = render(o, safe + "-measured", {"type": "measured", "table": chosen["source"]})
        fit = render(o, safe + "-fit", {"type": "analytic", "model": chosen["model"],
                                        "params": chosen["params"]})
        row = [m, chosen["model"], psnr(ref, fit)]
        for rule, extra in (("held", ["--no-fit"]), ("spot", [])):
            glb = os.path.join(o.work, f"{safe}-{rule}.glb")
            r = run([o.brdfit, "export", one, "--format", "glb", "-o", glb] + extra)
            model = r.stdout.split()[1] if r.stdout.split() else "?"
            png = render_three(o.tools, chromium, glb, os.path.join(o.work, f"{safe}-{rule}.png"))
            row += [model, psnr(ref, png)]
        rows.append(row)
        print(f"{m:28s} chosen {row[1]:22s} {row[2]:6.2f} dB | held {row[3]:20s} {row[4]:6.2f} dB "
              f"| on the spot {row[5]:16s} {row[6]:6.2f} dB", flush=True)
    n = len(rows)
    if n:
        mean = lambda i: sum(r[i] for r in rows) / n
        better = sum(r[6] > r[4] + 0.05 for r in rows)
        worse = sum(r[6] < r[4] - 0.05 for r in rows)
        print(f"MEAN n {n} | chosen fit (brdfit render) {mean(2):.2f} dB | glTF of the held fits "
              f"{mean(4):.2f} dB | glTF with the on-the-spot fit {mean(6):.2f} dB | on the spot "
              f"better on {better}, worse on {worse} (by > 0.05 dB)")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except RuntimeError as e:
        print(f"FAIL: {e}")
        sys.exit(1)
