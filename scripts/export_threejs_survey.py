#!/usr/bin/env python3
"""three.js against brdfit's preview for the glTF exports of the demo materials and five NBRDF
proxies (docs/exports.md, "Rendered in three.js"): synthesizes the demo tables (brdfit demo's
lambert+ggx parameters), fits lambert+ggx-hc, exports each fit as .glb, renders it with three.js
in headless Chromium and with `brdfit render` (the scene of tests/export/check_threejs.py), and
prints the fit's rendered error against its table and the image difference in 8-bit levels.

Usage: scripts/export_threejs_survey.py BUILD_DIR WORK_DIR
(after the export tests ran once in BUILD_DIR, so that BUILD_DIR/tests/export/node-tools holds
three.js; needs ../shared/data/merl_nbrdf.zip for the nbrdf: inputs)."""
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests", "export"))
from check_threejs import analytic, compare, preview_scene  # noqa: E402

DEMO = {
    "red-plastic": ("0.45 0.06 0.05", "0.04 0.04 0.04", 0.08, 0.0, 0.0),
    "blue-rough": ("0.05 0.12 0.40", "0.03 0.03 0.03", 0.35, 0.0, 0.0),
    "gold-noisy-holes": ("0.02 0.015 0.005", "0.95 0.65 0.25", 0.12, 0.03, 0.2),
}
NBRDF = ["gold-metallic-paint", "red-phenolic", "blue-acrylic", "chrome-steel", "pink-fabric"]


def survey_fits(brdfit, model):
    """Synthesizes the demo tables in the working folder, fits `model` to them and the NBRDF
    proxies (fits.h5, fits.json) and returns the JSON's fits."""
    inputs = []
    for name, (kd, ks, alpha, noise, missing) in DEMO.items():
        args = [brdfit, "synth", "--model", "lambert+ggx", "-o", name + ".binary",
                "--noise", str(noise), "--missing", str(missing), "--param", f"ggx.alpha={alpha}"]
        for c, v in zip("rgb", kd.split()):
            args += ["--param", f"lambert.kd_{c}={v}"]
        for c, v in zip("rgb", ks.split()):
            args += ["--param", f"ggx.ks_{c}={v}"]
        subprocess.run(args, check=True, capture_output=True)
        inputs.append(name + ".binary")
    inputs += ["nbrdf:" + m for m in NBRDF]
    subprocess.run([brdfit, "fit", *inputs, "--model", model, "-j", "2", "-o", "fits.h5",
                    "--json", "fits.json", "-q", "--no-progress", "--force"], check=True)
    return json.load(open("fits.json"))["fits"]


def main():
    build, work = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    brdfit, tools = os.path.join(build, "brdfit"), os.path.join(build, "tests/export/node-tools")
    os.makedirs(work, exist_ok=True)
    os.chdir(work)
    for f in survey_fits(brdfit, "ggx-hc"):
        name = f["material"]
        json.dump({"format": "brdfit-fit-params", "format_version": 1, "fits": [f]},
                  open(name + ".fit.json", "w"))
        e = subprocess.run([brdfit, "export", name + ".fit.json", "--format", "glb", "-q", "-o",
                            name + ".glb"], capture_output=True, text=True, check=True)
        scene = preview_scene(analytic(f))
        json.dump(scene, open(name + ".scene.json", "w"))
        subprocess.run([brdfit, "render", name + ".scene.json", "-o", name + "-brdfit.png"],
                       check=True, capture_output=True)
        subprocess.run(["node", os.path.join(tools, "render_three.cjs"), name + ".glb",
                        name + "-three.png", "256", "1,1,1", "3"], check=True, capture_output=True)
        mean, p99, worst = compare(name + "-brdfit.png", name + "-three.png")
        r = f["metrics"].get("rendered", {})
        p = f["params"]
        print(f"| {name} | {p['ggx-hc.alpha']:.3f} | "
              f"{p['ggx-hc.ks_r']:.3f} {p['ggx-hc.ks_g']:.3f} {p['ggx-hc.ks_b']:.3f} | "
              f"{r.get('psnr_db', 0):.1f} dB, {100 * r.get('median_rel_error', 0):.1f} % | "
              f"{'approximate' if 'approximate' in e.stderr else 'exact'} | "
              f"{mean:.2f} / {p99} / {worst} |")


if __name__ == "__main__":
    main()
