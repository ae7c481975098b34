"""brdfit.fit: the CLI's fit, bit for bit, and parameter recovery on a synthetic table.

The CLI runs with --no-timings: its JSON then carries the version but not the command line or
the date (core/provenance.h), as the module's does."""
import json
from concurrent.futures import ThreadPoolExecutor

import brdfit
from conftest import TRUTH

FIT_ARGS = dict(model="lambert+ggx", loss="rel", budget="stride:4")


def test_fit_equals_cli_json(cli, small_table_file, tmp_path):
    out_json = tmp_path / "fit.json"
    cli("fit", small_table_file, "--model", "lambert+ggx", "--loss", "rel", "--budget", "stride:4",
        "-o", tmp_path / "fits.h5", "--json", out_json, "--quiet", "--no-timings")
    r = brdfit.fit(brdfit.load(str(small_table_file)), **FIT_ARGS)
    # The JSON holds no timings (io/fit_report.h FitParamsJson): the whole text must agree.
    assert r.json == out_json.read_text()
    cli_fit = json.loads(out_json.read_text())["fits"][0]
    assert r.params == cli_fit["params"]
    assert r.metrics == cli_fit["metrics"]
    assert r.status == cli_fit["status"] == "converged"
    assert set(r.timings) >= {"prepare_ms", "init_ms", "solve_ms", "metrics_ms"}


def test_default_names_resolve_as_the_cli(cli, small_table_file, tmp_path):
    # `--model ggx` is lambert+ggx under the default --diffuse lambert; loss defaults to rel.
    out_json = tmp_path / "fit.json"
    cli("fit", small_table_file, "--model", "ggx", "--budget", "stride:4", "-o",
        tmp_path / "fits.h5", "--json", out_json, "--quiet", "--no-timings")
    r = brdfit.fit(brdfit.load(str(small_table_file)), model="ggx", budget="stride:4")
    assert r.model == "lambert+ggx"
    assert r.json == out_json.read_text()


def test_fit_recovers_the_synthesized_parameters(small_table):
    r = brdfit.fit(small_table, **FIT_ARGS)
    for name, truth in TRUTH.items():
        assert abs(r.params[name] - truth) < 1e-3 * max(truth, 1), (name, r.params[name], truth)
    assert r.metrics["log_rmse"] < 1e-4
    # The rendered metric per region of the domain (docs/accuracy.md, "Every light"): an exact
    # model renders near the PSNR cap under light from the front, the side and behind, and in
    # the environment (docs/accuracy.md, "The environment").
    regions = r.metrics["rendered"]["regions"]
    assert set(regions) == {"front", "side", "rim", "environment"}
    for name, region in regions.items():
        assert region["lights"] >= 1, name
        assert region["psnr_db"] > 40, (name, region)
    assert r.metrics["rendered"]["score_db"] > 40


def test_fits_in_threads_equal_serial_fits(small_table):
    """The GIL is released during a fit: two fits in a thread pool give the serial results."""
    kinds = [dict(FIT_ARGS), dict(FIT_ARGS, model="lambert+beckmann")]
    serial = [brdfit.fit(small_table, **k).json for k in kinds]
    with ThreadPoolExecutor(max_workers=2) as pool:
        threaded = list(pool.map(lambda k: brdfit.fit(small_table, **k).json, kinds))
    assert threaded == serial


def test_main_thread_runs_while_a_fit_runs(small_table):
    """With the GIL held for the whole fit, the main thread would stall for the fit's duration;
    released, its loop keeps iterating (largest gap far below the fit's time)."""
    import threading
    import time
    done = threading.Event()
    span = []

    def work():
        t0 = time.perf_counter()
        brdfit.fit(small_table, model="lambert+ggx", loss="rel", budget="full")
        span.append(time.perf_counter() - t0)
        done.set()

    th = threading.Thread(target=work)
    stamps = []
    th.start()
    while not done.is_set():
        stamps.append(time.perf_counter())
    th.join()
    gaps = [b - a for a, b in zip(stamps, stamps[1:])]
    assert span[0] > 0.02, "the fit is too short to tell"
    assert max(gaps) < 0.5 * span[0], (max(gaps), span[0])


def test_nbrdf_fit_equals_cli_json(cli, tmp_path):
    """A measured-material proxy on the MERL grid (the archive is third-party data, not in the
    repository: skipped without it)."""
    import os
    import pytest
    zip_path = os.environ.get("BRDFIT_NBRDF_ZIP", "")
    if not os.path.isfile(zip_path):
        pytest.skip(f"no NBRDF archive at BRDFIT_NBRDF_ZIP='{zip_path}' (../shared/data)")
    name = "nbrdf:gold-metallic-paint"
    out_json = tmp_path / "fit.json"
    cli("fit", name, "--model", "lambert+ggx", "--budget", "stride:32", "-o", tmp_path / "f.h5",
        "--json", out_json, "--quiet", "--no-timings")
    table = brdfit.load(name)
    assert table.shape == (90, 90, 180) and table.input == name
    r = brdfit.fit(table, model="lambert+ggx", budget="stride:32")
    assert r.json == out_json.read_text()


def test_polish_is_the_clis_and_recorded_in_the_options(cli, small_table_file, tmp_path):
    # The rendered polish is on by default, as in `brdfit fit`; "none" leaves it out of the
    # options (fit/options.h OptionsJson), and a bad name is the CLI's error.
    table = brdfit.load(str(small_table_file))
    assert brdfit.fit(table, **FIT_ARGS).options.get("polish") == "rendered"
    assert "polish" not in brdfit.fit(table, polish="none", **FIT_ARGS).options
    try:
        brdfit.fit(table, polish="bogus", **FIT_ARGS)
    except Exception as e:  # brdfit.InputError
        assert "unknown polish 'bogus'" in str(e)
    else:
        raise AssertionError("polish='bogus' was accepted")
