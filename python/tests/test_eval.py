"""Model.eval against an independent NumPy formula, and the (theta_h, theta_d, phi_d) form."""
import numpy as np
import pytest

import brdfit

P = {"lambert.kd_r": 0.3, "lambert.kd_g": 0.2, "lambert.kd_b": 0.1,
     "ggx.ks_r": 0.8, "ggx.ks_g": 0.7, "ggx.ks_b": 0.6, "ggx.alpha": 0.25}


def lambert_ggx_numpy(p, wi, wo):
    """Lambert + GGX written from the papers, not from brdfit's code: Walter et al. 2007,
    "Microfacet Models for Refraction through Rough Surfaces", eq. 20 (f = F G D / (4 |i.n||o.n|),
    F folded into ks), D eq. 33, separable Smith G = G1(i) G1(o) with G1 eq. 34; Lambert kd/pi."""
    a = p["ggx.alpha"]
    h = wi + wo
    h /= np.linalg.norm(h, axis=1, keepdims=True)
    cos_m = h[:, 2]
    tan2_m = (1 - cos_m**2) / cos_m**2
    d = a**2 / (np.pi * cos_m**4 * (a**2 + tan2_m) ** 2)

    def g1(v):
        c = v[:, 2]
        tan2 = (1 - c**2) / c**2
        return 2 / (1 + np.sqrt(1 + a**2 * tan2))

    spec = d * g1(wi) * g1(wo) / (4 * wi[:, 2] * wo[:, 2])
    kd = np.array([p["lambert.kd_r"], p["lambert.kd_g"], p["lambert.kd_b"]])
    ks = np.array([p["ggx.ks_r"], p["ggx.ks_g"], p["ggx.ks_b"]])
    return kd / np.pi + spec[:, None] * ks


def random_upper(rng, n):
    v = rng.normal(size=(n, 3))
    v[:, 2] = np.abs(v[:, 2]) + 0.05
    return v / np.linalg.norm(v, axis=1, keepdims=True)


def test_eval_matches_numpy_formula():
    rng = np.random.default_rng(7)
    wi, wo = random_upper(rng, 2000), random_upper(rng, 2000)
    got = brdfit.model("lambert+ggx").eval(P, wi, wo)
    assert got.shape == (2000, 3)
    np.testing.assert_allclose(got, lambert_ggx_numpy(P, wi, wo), rtol=1e-11, atol=0)


def test_eval_below_horizon_is_zero_and_broadcasts():
    m = brdfit.model("lambert+ggx")
    wo = np.array([[0.0, 0.0, 1.0], [0.0, 0.6, -0.8]])
    got = m.eval(P, [0.0, 0.0, 1.0], wo)  # one wi for both wo
    assert got.shape == (2, 3)
    assert np.all(got[1] == 0) and np.all(got[0] > 0)


def test_eval_halfdiff_equals_eval_at_the_same_directions():
    m = brdfit.model("lambert+ggx")
    th = np.linspace(0.01, 1.2, 7)[:, None]
    td = np.linspace(0.05, 1.0, 5)[None, :]
    got = m.eval_halfdiff(P, th, td, 0.7)
    assert got.shape == (7, 5, 3)
    # Rusinkiewicz 1998 at phi_h = 0: h = (sin th, 0, cos th); d = spherical(td, pd) in the
    # frame of h; wi = R_y(th) d, wo = 2 (wi.h) h - wi.
    TH, TD = np.broadcast_arrays(th, td)
    TH, TD = TH.ravel(), TD.ravel()
    d = np.stack([np.sin(TD) * np.cos(0.7), np.sin(TD) * np.sin(0.7), np.cos(TD)], axis=1)
    c, s = np.cos(TH), np.sin(TH)
    wi = np.stack([c * d[:, 0] + s * d[:, 2], d[:, 1], -s * d[:, 0] + c * d[:, 2]], axis=1)
    h = np.stack([s, 0 * s, c], axis=1)
    wo = 2 * np.sum(wi * h, axis=1, keepdims=True) * h - wi
    ok = (wi[:, 2] > 0) & (wo[:, 2] > 0)
    ref = np.where(ok[:, None], lambert_ggx_numpy(P, wi, wo), 0)
    np.testing.assert_allclose(got.reshape(-1, 3), ref, rtol=1e-10, atol=1e-14)


def test_models_publish_parameter_specs():
    names = [m.name for m in brdfit.models()]
    assert "lambert+ggx" in names and len(names) == len(set(names))
    m = brdfit.model("lambert+ggx")
    assert m.param_names == list(P)
    alpha = m.params[-1]
    assert alpha["name"] == "ggx.alpha" and alpha["log_scale"]
    assert alpha["lower"] < alpha["default"] < alpha["upper"]
    # Unqualified names work when unambiguous; a sequence gives every value in order.
    a = m.eval({"alpha": 0.25, **{k: v for k, v in P.items() if k != "ggx.alpha"}}, [0, 0, 1], [0, 0.6, 0.8])
    b = m.eval(list(P.values()), [0, 0, 1], [0, 0.6, 0.8])
    assert np.array_equal(a, b)


def test_fit_result_eval_is_the_model_at_the_fitted_params(small_table):
    r = brdfit.fit(small_table, model="lambert+ggx", loss="rel", budget="stride:8")
    wi = np.array([[0.0, 0.3, 0.9539392014169456]])
    wo = np.array([[0.2, -0.1, 0.9746794344808963]])
    assert np.array_equal(r.eval(wi, wo), brdfit.model(r.model).eval(r.params, wi, wo))


@pytest.mark.parametrize("bad", [np.zeros((2, 3)), np.full((1, 3), np.nan), np.zeros((2, 2))])
def test_bad_directions_raise(bad):
    with pytest.raises(brdfit.InputError):
        brdfit.model("lambert+ggx").eval(P, bad, [0, 0, 1])
