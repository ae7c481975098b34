#!/usr/bin/python3
"""Which Oren-Nayar Blender 3.4 Cycles' Diffuse BSDF evaluates, checked against Cycles renders.

    /usr/bin/python3 scripts/cycles_diffuse_roughness_check.py --brdfit build/brdfit [--work DIR]

A grey Lambert (kd 0.5, no specular) is exported for Blender (`brdfit export --format blender`),
its Diffuse BSDF's Roughness set to sigma in {0, 0.5, 1}, and rendered by Cycles (64 samples,
256 x 256, the export's scene: camera at (0, 0, 4), 30 deg, sun towards (1, 1, 1) of 3 W/m^2,
Standard view transform). Each render is compared, on the sphere's inner pixels (radius 118 px),
with this script's own evaluation of the analytic sphere under three formulas:

- Lambert, kd / pi;
- Fujii's improved Oren-Nayar (Y. Fujii, "A tiny improvement of Oren-Nayar reflectance model",
  2012), f = kd (a + b s / t), a = 1 / (pi + (pi/2 - 2/3) sigma), b = sigma a,
  s = wi.wo - cos_i cos_o, t = max(cos_i, cos_o) when s > 0 else 1 — the form Cycles 3.4's
  bsdf_oren_nayar.h implements, with (3 pi - 4) / 6 = pi/2 - 2/3;
- brdfit's `oren-nayar` (Oren & Nayar 1994 eq. 30, the qualitative model, models/oren_nayar.h)
  at the same sigma.

Differences as mean / p99 / max 8-bit levels. Measured (2026-12, Debian 12's Blender 3.4):
sigma 0.5: Lambert 7.98 / 20.5 / 25.2, Fujii 0.23 / 0.6 / 6.6, brdfit oren-nayar 5.01 / 9.6 /
10.7; sigma 1: 14.54 / 38.8 / 41.0, 0.24 / 0.6 / 8.0, 11.06 / 24.1 / 27.6; sigma 0 (all three
Lambert): 0.23 / 0.6 / 4.6, the floor of Cycles' noise and its UV-sphere mesh. So the Diffuse
BSDF is Fujii's form exactly, and brdfit's `oren-nayar` is not it (not the same
parameterization: a fit of one to the other is nearer than the same sigma). A catalog model of
Fujii's form would export exactly to Cycles as a Diffuse BSDF with Roughness = sigma in [0, 1].
Needs numpy (Debian's python3-numpy, hence /usr/bin/python3) and blender; exit 0, 1 on a failure.
"""
import argparse
import json
import math
import os
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests",
                                "export"))
from check_threejs import read_png  # noqa: E402  (the tests' PNG reader)

SIZE, RADIUS, KD, IRRADIANCE = 256, 118, 0.5, 3.0
LIGHT = np.array([1.0, 1.0, 1.0]) / math.sqrt(3)
ROUGHNESS_LINE = 'diffuse.inputs["Roughness"].default_value = 0.0'


def sphere():
    """Per pixel of the export's camera: hit mask, normal n and direction to the camera v."""
    t = math.tan(math.radians(15))
    j, i = np.mgrid[0:SIZE, 0:SIZE]
    x, y = ((i + 0.5) / SIZE * 2 - 1) * t, (1 - (j + 0.5) / SIZE * 2) * t
    d = np.stack([x, y, -np.ones_like(x)], -1)
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    o = np.array([0.0, 0.0, 4.0])
    b = (d * o).sum(-1)
    disc = b * b - (o @ o - 1)
    hit = disc > 0
    p = o + (-b - np.sqrt(np.maximum(disc, 0)))[..., None] * d
    n = p / np.linalg.norm(p, axis=-1, keepdims=True)
    c0 = (SIZE - 1) / 2
    inner = ((i - c0) ** 2 + (j - c0) ** 2) <= RADIUS ** 2
    return hit, inner, n, -d


def lambert(sigma, nl, nv, lv):
    return KD / math.pi * np.ones_like(nl)


def fujii(sigma, nl, nv, lv):
    s = lv - nl * nv
    s = np.where(s > 0, s / np.maximum(np.maximum(nl, nv), 1e-30), s)
    a = 1 / (math.pi + (math.pi / 2 - 2 / 3) * sigma)
    return KD * (a + sigma * a * s)


def classic(sigma, nl, nv, lv):
    s2 = sigma * sigma
    a, b = 1 - 0.5 * s2 / (s2 + 0.33), 0.45 * s2 / (s2 + 0.09)
    s = np.maximum(lv - nl * nv, 0) / np.maximum(np.maximum(nl, nv), 1e-30)
    return KD / math.pi * (a + b * s)


def srgb_levels(c):
    c = np.clip(c, 0, 1)
    return np.where(c <= 0.0031308, 12.92 * c, 1.055 * c ** (1 / 2.4) - 0.055) * 255


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--brdfit", required=True)
    ap.add_argument("--blender", default="blender")
    ap.add_argument("--work", default="/tmp/cycles-diffuse-roughness")
    o = ap.parse_args()
    os.makedirs(o.work, exist_ok=True)
    fit = {"source": "synthetic", "material": "grey", "model": "lambert+ggx",
           "status": "converged", "message": "",
           "params": {"lambert.kd_r": KD, "lambert.kd_g": KD, "lambert.kd_b": KD,
                      "ggx.ks_r": 0.0, "ggx.ks_g": 0.0, "ggx.ks_b": 0.0, "ggx.alpha": 0.1},
           "metrics": {"log_rmse": 0, "cbrt_rmse": 0, "rel_l2": 0, "weighting": "none",
                       "cutoff_deg": 90}}
    fits = os.path.join(o.work, "grey.json")
    json.dump({"format": "brdfit-fit-params", "format_version": 1, "fits": [fit]},
              open(fits, "w"))
    script = os.path.join(o.work, "grey.py")
    subprocess.run([o.brdfit, "export", fits, "--format", "blender", "-q", "-o", script],
                   check=True)
    text = open(script).read()
    if text.count(ROUGHNESS_LINE) != 1:
        print(f"FAIL: {script} does not set the Diffuse BSDF's roughness as expected")
        return 1
    hit, inner, n, v = sphere()
    nl = np.maximum((n * LIGHT).sum(-1), 0)
    nv = np.maximum((n * v).sum(-1), 0)
    lv = (v * LIGHT).sum(-1)
    for sigma in (0.0, 0.5, 1.0):
        patched = os.path.join(o.work, f"grey-sigma{sigma}.py")
        open(patched, "w").write(text.replace(
            ROUGHNESS_LINE, f'diffuse.inputs["Roughness"].default_value = {sigma}'))
        png = os.path.join(o.work, f"grey-sigma{sigma}.png")
        subprocess.run([o.blender, "-b", "--factory-startup", "--python-exit-code", "1", "-P",
                        patched, "--", "--render", png, "--size", str(SIZE), "--samples", "64",
                        "--threads", "2"], check=True, capture_output=True)
        w, h, ch, rows = read_png(png)
        got = np.array([list(r) for r in rows], dtype=float).reshape(h, w, ch)[..., :3].mean(-1)
        line = [f"sigma {sigma}:"]
        for name, f in (("Lambert", lambert), ("Fujii (Cycles 3.4)", fujii),
                        ("brdfit oren-nayar", classic)):
            want = np.where(hit, srgb_levels(f(sigma, nl, nv, lv) * nl * IRRADIANCE), 0)
            d = np.abs(got - want)[inner]
            line.append(f"{name} {d.mean():.2f} / {np.percentile(d, 99):.1f} / {d.max():.1f}")
        print("  ".join(line))
    return 0


if __name__ == "__main__":
    sys.exit(main())
