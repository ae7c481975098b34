#!/usr/bin/python3
"""Which rough diffuse Blender 3.4 Cycles evaluates — its Diffuse BSDF with Roughness (an
Oren-Nayar) and its Principled BSDF with Specular 0 (a Burley) —, checked against Cycles renders.

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

Differences as mean / p99 / max 8-bit levels, measured with Debian 12's Blender 3.4:
sigma 0.5: Lambert 7.98 / 20.5 / 25.2, Fujii 0.23 / 0.6 / 6.6, brdfit oren-nayar 5.01 / 9.6 /
10.7; sigma 1: 14.54 / 38.8 / 41.0, 0.24 / 0.6 / 8.0, 11.06 / 24.1 / 27.6; sigma 0 (all three
Lambert): 0.23 / 0.6 / 4.6, the floor of Cycles' noise and its UV-sphere mesh. So the Diffuse
BSDF is Fujii's form exactly, and brdfit's `oren-nayar` is not it (not the same
parameterization: a fit of one to the other is nearer than the same sigma). The catalog's
`oren-nayar-fujii` is Fujii's form and exports to Cycles as a Diffuse BSDF with Roughness = sigma
(tests/export/check_blender.py renders it).

The same grey Lambert's Principled BSDF material (`--material principled`: metallic 0, specular
0 — so Cycles builds no specular closure —, sheen and clearcoat 0) with Roughness r in
{0, 0.5, 1}, against Burley 2012's diffuse (f = kd/pi F(cos_i) F(cos_o), F(c) = 1 + (F_D90 - 1)
(1 - c)^5, F_D90 = 0.5 + 2 r cos_d^2) and Frostbite's renormalized one (brdfit's `burley`,
models/burley.h, r = sqrt(alpha)). Measured: r 0: Lambert 2.54 / 11.1 / 13.7, Burley 2012
0.23 / 0.7 / 3.3, Frostbite 2.88 / 15.6 / 16.9; r 0.5: 1.45 / 6.3 / 7.4, 0.23 / 0.6 / 4.9,
10.82 / 16.7 / 18.8; r 1: 4.82 / 19.8 / 25.3, 0.24 / 0.6 / 8.0, 21.33 / 32.1 / 33.6. So Cycles'
Principled diffuse is Burley 2012 exactly (r = Roughness), and brdfit's Frostbite `burley` is
not it: the catalog's `burley-2012` (+ ggx) exports exactly as a Principled BSDF with Specular 0
plus a Glossy BSDF (tests/export/check_blender.py renders it).
Needs numpy (Debian's python3-numpy, hence /usr/bin/python3) and blender; exit 0, 1 on a failure.
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests",
                                "export"))
from check_threejs import read_png  # noqa: E402  (the tests' PNG reader)

SIZE, RADIUS, KD, IRRADIANCE = 256, 118, 0.5, 3.0
LIGHT = np.array([1.0, 1.0, 1.0]) / math.sqrt(3)
ROUGHNESS_LINE = '"body_roughness": 0,'


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


def burley_2012(r, nl, nv, cd):
    fd90 = 0.5 + 2 * r * cd * cd
    return KD / math.pi * (1 + (fd90 - 1) * (1 - nl) ** 5) * (1 + (fd90 - 1) * (1 - nv) ** 5)


def frostbite(r, nl, nv, cd):
    fd90 = 0.5 * r + 2 * r * cd * cd
    return (KD / math.pi * (1 + (fd90 - 1) * (1 - nl) ** 5) * (1 + (fd90 - 1) * (1 - nv) ** 5)
            * (1 + (1 / 1.51 - 1) * r))


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
        print(f"FAIL: {script} does not set the body's roughness as expected")
        return 1
    hit, inner, n, v = sphere()
    nl = np.maximum((n * LIGHT).sum(-1), 0)
    nv = np.maximum((n * v).sum(-1), 0)
    lv = (v * LIGHT).sum(-1)
    h = v + LIGHT
    cd = (LIGHT * (h / np.linalg.norm(h, axis=-1, keepdims=True))).sum(-1)

    def render(name, patched_text, material):
        patched = os.path.join(o.work, name + ".py")
        open(patched, "w").write(patched_text)
        png = os.path.join(o.work, name + ".png")
        subprocess.run([o.blender, "-b", "--factory-startup", "--python-exit-code", "1", "-P",
                        patched, "--", "--render", png, "--material", material, "--size",
                        str(SIZE), "--samples", "64", "--threads", "2"], check=True,
                       capture_output=True)
        w, h, ch, rows = read_png(png)
        return np.array([list(r) for r in rows], dtype=float).reshape(h, w, ch)[..., :3].mean(-1)

    def differences(got, formulas):
        out = []
        for name, fr in formulas:
            want = np.where(hit, srgb_levels(fr * nl * IRRADIANCE), 0)
            d = np.abs(got - want)[inner]
            out.append(f"{name} {d.mean():.2f} / {np.percentile(d, 99):.1f} / {d.max():.1f}")
        return "  ".join(out)

    for sigma in (0.0, 0.5, 1.0):
        got = render(f"grey-sigma{sigma}", text.replace(
            ROUGHNESS_LINE, f'"body_roughness": {sigma},'), "exact")
        print(f"Diffuse BSDF, Roughness {sigma}: " + differences(got, (
            ("Lambert", lambert(sigma, nl, nv, lv)), ("Fujii", fujii(sigma, nl, nv, lv)),
            ("brdfit oren-nayar", classic(sigma, nl, nv, lv)))))
    key = re.search(r'"roughness": [0-9.e+-]+,', text[text.find("\nPRINCIPLED = {"):])
    if not key:
        print(f"FAIL: {script} has no PRINCIPLED roughness")
        return 1
    for r in (0.0, 0.5, 1.0):
        got = render(f"grey-principled{r}", text.replace(key.group(0), f'"roughness": {r},'),
                     "principled")
        print(f"Principled (specular 0), Roughness {r}: " + differences(got, (
            ("Lambert", lambert(r, nl, nv, lv)), ("Burley 2012", burley_2012(r, nl, nv, cd)),
            ("brdfit burley (Frostbite)", frostbite(r, nl, nv, cd)))))
    return 0


if __name__ == "__main__":
    sys.exit(main())
