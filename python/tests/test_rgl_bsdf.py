"""RGL .bsdf files (Dupuy & Jakob 2018) through brdfit.load: a GGX stored as constant values on
the warped grid reads back as its closed form f_r = c D(theta_h) G1(wi) / (4 cos_i cos_o)
(io/rgl_bsdf_file.h, docs/formats.md); a damaged file raises naming the field."""
import math
import struct

import numpy as np
import pytest

import brdfit


def write_bsdf(path, fields):
    """A tensor file (io/tensor_file.h): header, then each field's data at its offset."""
    header = b"tensor_file\0" + bytes([1, 0]) + struct.pack("<I", len(fields))
    size = len(header) + sum(2 + len(n) + 2 + 1 + 8 + 8 * a.ndim for n, (a, _) in fields.items())
    meta, data, offset = b"", b"", size
    for name, (a, dtype) in fields.items():
        meta += struct.pack("<H", len(name)) + name.encode() + struct.pack("<HBQ", a.ndim, dtype, offset)
        meta += b"".join(struct.pack("<Q", s) for s in a.shape)
        raw = np.ascontiguousarray(a).tobytes()
        data += raw
        offset += len(raw)
    path.write_bytes(header + meta + data)


def ggx_fields(alpha, colour, n=96, res=16, n_theta=6):
    u = np.arange(n) / (n - 1)
    th = np.minimum(u * u * math.pi / 2, math.pi / 2 - 1e-4)
    c, t2 = np.cos(th), np.tan(th) ** 2
    d = alpha**2 / (math.pi * c**4 * (alpha**2 + t2) ** 2)           # Walter et al. 2007, Eq. 33
    sigma = np.maximum(c * 0.5 * (1 + np.sqrt(1 + alpha**2 * t2)), 1e-3)  # Heitz 2014, Eq. 72
    vndf = np.ones((2, n_theta, res, res), np.float32)
    rgb = np.zeros((2, n_theta, 3, res, res), np.float32)
    for k in range(3):
        rgb[:, :, k] = colour[k]
    f32 = 10
    return {"description": (np.frombuffer(b"ggx", np.uint8), 1), "jacobian": (np.array([1], np.uint8), 1),
            "theta_i": (np.linspace(0, math.radians(85), n_theta).astype(np.float32), f32),
            "phi_i": (np.array([-math.pi, math.pi], np.float32), f32),
            "ndf": (np.tile(d, (2, 1)).astype(np.float32), f32),
            "sigma": (np.tile(sigma, (2, 1)).astype(np.float32), f32),
            "vndf": (vndf, f32), "luminance": (vndf, f32), "rgb": (rgb, f32)}


def test_a_ggx_file_loads_as_its_closed_form(tmp_path):
    alpha, colour = 0.25, (0.9, 0.5, 0.2)
    path = tmp_path / "ggx.bsdf"
    write_bsdf(path, ggx_fields(alpha, colour))
    t = brdfit.load(str(path))
    th, td, pd = np.meshgrid(t.theta_h, t.theta_d, t.phi_d, indexing="ij")
    # The cell centre's directions with phi_h = 0 (models/geometry.h FromHalfDiff).
    wi = np.stack([np.cos(pd) * np.sin(td) * np.cos(th) + np.cos(td) * np.sin(th),
                   np.sin(pd) * np.sin(td), -np.cos(pd) * np.sin(td) * np.sin(th) + np.cos(td) * np.cos(th)], -1)
    h = np.stack([np.sin(th), np.zeros_like(th), np.cos(th)], -1)
    wo = 2 * np.sum(wi * h, -1, keepdims=True) * h - wi
    cos_i, cos_o = wi[..., 2], wo[..., 2]
    lam = (-1 + np.sqrt(1 + alpha**2 * (1 - cos_i**2) / np.maximum(cos_i, 1e-9) ** 2)) / 2
    d = alpha**2 / (math.pi * np.cos(th) ** 4 * (alpha**2 + np.tan(th) ** 2) ** 2)
    sel = t.valid & (th < 1.2) & (cos_o > 0.1)
    assert sel.sum() > 100000
    for k in range(3):
        ref = colour[k] * d / (4 * cos_i * (1 + lam) * cos_o)
        rel = np.abs(t.values[..., k][sel] / ref[sel] - 1)
        assert np.median(rel) < 2e-3 and np.percentile(rel, 99) < 2e-2, (k, np.median(rel))
    # Beyond the file's last theta_i (85 deg) nothing is made up: those cells are masked.
    assert not t.valid[(cos_i < math.cos(math.radians(85.01))) & (cos_i > 0)].any()


def test_a_damaged_file_names_its_field(tmp_path):
    fields = ggx_fields(0.3, (0.5, 0.5, 0.5))
    fields["sigma"] = (np.zeros_like(fields["sigma"][0]), 10)
    path = tmp_path / "bad.bsdf"
    write_bsdf(path, fields)
    with pytest.raises(Exception, match="field 'sigma'"):
        brdfit.load(str(path))
