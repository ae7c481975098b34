"""brdfit.factor: textures as arrays, eval consistent with them, metrics as the CLI scores."""
import numpy as np

import brdfit


def test_factor_textures_eval_and_metrics(small_table):
    f = brdfit.factor(small_table, param="halfdiff", res=16)
    assert f.param == "halfdiff" and f.rank == 1 and f.resolution == 16
    (p, q), = f.textures
    assert p.dtype == np.float32 and p.ndim == 3 and p.shape[2] == 3 and q.shape[2] == 3
    assert np.all(np.isfinite(p)) and np.all(p >= 0) and np.all(q >= 0)
    # The factored form approximates the table: within a factor of ~1.5 at valid cells.
    t = small_table
    th, td, pd = np.meshgrid(t.theta_h, t.theta_d, t.phi_d, indexing="ij")
    approx = f.eval_halfdiff(th, td, pd)[t.valid]
    ratio = np.log(approx / t.values[t.valid])
    assert np.sqrt(np.mean(ratio**2)) < 0.5
    assert abs(np.sqrt(np.mean(ratio**2)) - f.metrics["ln_ratio_rmse"]) < 0.1
    assert "psnr_db" in f.metrics["rendered"]
    # eval by directions at a cell centre equals eval by its angles (isotropic factors).
    wi = np.array([[0.3, 0.1, 0.9486832980505138]])
    wo = np.array([[-0.2, 0.2, 0.9591663046625439]])
    assert f.eval(wi, wo).shape == (1, 3) and np.all(f.eval(wi, wo) > 0)
