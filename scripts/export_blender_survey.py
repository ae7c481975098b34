#!/usr/bin/env python3
"""Blender 3.4 Cycles against brdfit's preview for the Blender exports of the demo materials and
five NBRDF proxies (docs/exports.md, "Rendered in Blender"): synthesizes the demo tables (as
scripts/export_threejs_survey.py does), fits lambert+ggx (the model Blender's Diffuse + Glossy
node tree evaluates exactly), exports each fit with `brdfit export --format blender`, renders the
script's exact node tree and its Principled BSDF with Cycles (the scene and settings of
tests/export/check_blender.py) and the fit with `brdfit render`, and prints the fit's rendered
error against its table and the image differences in 8-bit levels.

Usage: scripts/export_blender_survey.py BUILD_DIR WORK_DIR
(needs blender, and ../shared/data/merl_nbrdf.zip for the nbrdf: inputs)."""
import os
import sys
from types import SimpleNamespace

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests", "export"))
from check_blender import Bench  # noqa: E402
from check_threejs import compare  # noqa: E402
from export_threejs_survey import survey_fits  # noqa: E402


def main():
    build, work = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    brdfit = os.path.join(build, "brdfit")
    os.makedirs(work, exist_ok=True)
    os.chdir(work)
    fits = survey_fits(brdfit, "ggx")
    b = Bench(SimpleNamespace(brdfit=brdfit, work=work), "blender")
    print("| material | alpha | ks | fit vs table (PSNR, median) | node tree vs preview | "
          "Principled vs preview |")
    for f in fits:
        name = f["material"]
        script, ref = b.export(name, f), b.preview(name, f)
        exact = compare(ref, b.render(script, name + "-blender.png"))
        princ = compare(ref, b.render(script, name + "-principled.png", material="principled"))
        r, p = f["metrics"].get("rendered", {}), f["params"]
        print(f"| {name} | {p['ggx.alpha']:.3f} | "
              f"{p['ggx.ks_r']:.3f} {p['ggx.ks_g']:.3f} {p['ggx.ks_b']:.3f} | "
              f"{r.get('psnr_db', 0):.1f} dB, {100 * r.get('median_rel_error', 0):.1f} % | "
              f"{exact[0]:.2f} / {exact[1]} / {exact[2]} | "
              f"{princ[0]:.2f} / {princ[1]} / {princ[2]} |")


if __name__ == "__main__":
    main()
