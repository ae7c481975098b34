"""Tables: NumPy views, the arrays -> table -> file round trip, and agreement with the CLI."""
import math

import numpy as np

import brdfit
from conftest import GRID, TRUTH


def test_views_share_the_table_storage(small_table):
    t = small_table.copy()
    assert t.values.shape == GRID + (3,) and t.values.dtype == np.float64
    assert t.valid.shape == GRID and t.valid.dtype == np.bool_
    t.values[0, 0, 0, 0] = 42.0
    assert t.values[0, 0, 0, 0] == 42.0 and small_table.values[0, 0, 0, 0] != 42.0


def test_axes_are_the_cell_centres(small_table):
    n_h, n_d, n_p = GRID
    # core/table.h: sqrt mapping u = N sqrt(theta_h / (pi/2)), centre u = i + 0.5.
    np.testing.assert_allclose(small_table.theta_h, (np.arange(n_h) + 0.5) ** 2 / n_h**2 * math.pi / 2,
                               rtol=1e-14)
    np.testing.assert_allclose(small_table.theta_d, (np.arange(n_d) + 0.5) / n_d * math.pi / 2, rtol=1e-14)
    np.testing.assert_allclose(small_table.phi_d, (np.arange(n_p) + 0.5) / n_p * math.pi, rtol=1e-14)


def test_cell_measures_sum_to_four_pi_squared(small_table):
    # fit/bin_measure.h: over all cells the measure is exactly 4 pi^2.
    assert small_table.cell_measure.shape == GRID
    assert abs(small_table.cell_measure.sum() - 4 * math.pi**2) < 1e-9


def test_values_are_the_model_at_the_cell_centres(small_table):
    m = brdfit.model("lambert+ggx")
    th, td, pd = np.meshgrid(small_table.theta_h, small_table.theta_d, small_table.phi_d, indexing="ij")
    ref = m.eval_halfdiff(TRUTH, th, td, pd)
    v = small_table.valid
    assert 0 < v.sum() < v.size
    assert np.array_equal(small_table.values[v], ref[v])


def test_arrays_to_table_to_file_round_trip_is_exact(small_table, tmp_path):
    t = small_table
    back = brdfit.Table.from_arrays(t.values, t.valid, theta_h_mapping=t.theta_h_mapping,
                                    provenance=t.provenance)
    assert back == t
    path = tmp_path / "back.h5"
    back.save(str(path))
    loaded = brdfit.load(str(path))
    assert np.array_equal(loaded.values[loaded.valid], t.values[t.valid])
    assert np.array_equal(loaded.valid, t.valid)
    assert loaded.provenance["model"] == "lambert+ggx"


def test_synth_equals_the_cli_synth(cli, tmp_path):
    path = tmp_path / "cli.h5"
    params = [f"{k}={v}" for k, v in TRUTH.items()]
    cli("synth", "--model", "lambert+ggx", *sum((["--param", p] for p in params), []),
        "--grid", ",".join(map(str, GRID)), "-o", path)
    mine = brdfit.synth("lambert+ggx", TRUTH, grid=GRID)
    theirs = brdfit.load(str(path))
    assert np.array_equal(theirs.valid, mine.valid)
    assert np.array_equal(theirs.values[mine.valid], mine.values[mine.valid])
    assert theirs.provenance["parameters_json"] == mine.provenance["parameters_json"]
