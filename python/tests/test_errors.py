"""Bad input raises brdfit.InputError (a ValueError) with the CLI's message; never a crash."""
import numpy as np
import pytest

import brdfit


def test_missing_file_names_the_file_as_the_cli_does(cli, tmp_path):
    missing = tmp_path / "nope.binary"
    with pytest.raises(brdfit.InputError) as e:
        brdfit.load(str(missing))
    assert isinstance(e.value, ValueError)
    r = cli("info", missing, check=False)
    assert r.returncode == 2
    assert str(e.value) in r.stderr and str(missing) in str(e.value)


def test_garbage_file_raises(tmp_path):
    p = tmp_path / "junk.h5"
    p.write_bytes(b"\x89HDF\r\n\x1a\n" + b"\0" * 100)
    with pytest.raises(brdfit.InputError):
        brdfit.load(str(p))


def test_bad_fit_options_carry_the_cli_messages(cli, small_table, small_table_file, tmp_path):
    for kwargs, flag in [({"cutoff": 0.0}, ["--cutoff", "0"]),
                         ({"budget": "stride:x"}, ["--budget", "stride:x"]),
                         ({"loss": "cubic"}, ["--loss", "cubic"]),
                         ({"model": "nosuch"}, ["--model", "nosuch"])]:
        with pytest.raises(brdfit.InputError) as e:
            brdfit.fit(small_table, **kwargs)
        r = cli("fit", small_table_file, *flag, "-o", tmp_path / "r.h5", check=False)
        assert r.returncode == 2, r.stderr
        assert str(e.value) in r.stderr, (str(e.value), r.stderr)


def test_bad_arrays_and_params_raise(small_table):
    with pytest.raises(brdfit.InputError):
        brdfit.Table.from_arrays(np.zeros((2, 2, 2)), np.ones((2, 2, 2), bool))
    with pytest.raises(brdfit.InputError):
        brdfit.Table.from_arrays(np.zeros((2, 2, 2, 3)), np.ones((2, 2, 3), bool))
    with pytest.raises(brdfit.InputError):
        brdfit.Table.from_arrays(np.full((2, 2, 2, 3), np.inf), np.ones((2, 2, 2), bool))
    with pytest.raises(brdfit.InputError):
        brdfit.model("lambert+ggx").eval({"ggx.alpha": 5.0}, [0, 0, 1], [0, 0, 1])  # out of bounds
    with pytest.raises(brdfit.InputError):
        brdfit.model("lambert+ggx").eval({"nosuch": 1.0}, [0, 0, 1], [0, 0, 1])
    with pytest.raises(brdfit.InputError):
        brdfit.model("nosuch")
    with pytest.raises(brdfit.InputError):
        brdfit.factor(small_table, res=2)
    with pytest.raises(brdfit.OutputError):
        small_table.save("/nonexistent-dir/t.h5")


def test_wrong_types_raise_type_error():
    m = brdfit.model("lambert+ggx")
    with pytest.raises(TypeError):
        m.eval("x", [0, 0, 1], [0, 0, 1])
    with pytest.raises(TypeError):
        brdfit.Table.from_arrays(np.zeros((2, 2, 2, 3)), np.ones((2, 2, 2)), provenance={"seed": -1})
    with pytest.raises(TypeError):
        brdfit.fit(None)
    with pytest.raises(brdfit.InputError):
        brdfit.fit(brdfit.synth("lambert+ggx", grid=(4, 4, 8)), model="auto")  # five fits


def test_fit_of_a_factorization_points_to_factor(small_table):
    # `brdfit fit --model factorization` is a candidate of the CLI's choice; in Python a
    # factorization is brdfit.factor's.
    with pytest.raises(brdfit.InputError) as e:
        brdfit.fit(small_table, model="factorization")
    assert "brdfit.factor" in str(e.value)


def test_a_nul_byte_in_a_path_is_refused_not_cut(small_table_file, small_table, tmp_path):
    # The system would read "t.h5\0evil" as t.h5 and brdfit would record the whole string.
    with pytest.raises(brdfit.InputError) as e:
        brdfit.load(str(small_table_file) + "\0evil")
    assert "NUL byte" in str(e.value)
    with pytest.raises(brdfit.InputError) as e:
        small_table.save(str(tmp_path / "out.h5") + "\0x")
    assert "NUL byte" in str(e.value)
    assert not (tmp_path / "out.h5").exists()


def test_a_negative_value_in_a_valid_cell_is_refused(small_table):
    values = np.array(small_table.values, copy=True)
    valid = np.array(small_table.valid, copy=True)
    i = tuple(int(k) for k in np.argwhere(valid)[0])
    values[i + (1,)] = -0.5
    with pytest.raises(brdfit.InputError) as e:
        brdfit.Table.from_arrays(values, valid)
    assert "is negative in a valid cell" in str(e.value)
    valid[i] = False  # marked invalid, the same value is no longer a measurement
    assert brdfit.Table.from_arrays(values, valid).valid.sum() == small_table.valid.sum() - 1


def test_provenance_parameters_must_be_json(small_table):
    p = dict(small_table.provenance)
    p["parameters_json"] = "not json"
    with pytest.raises(brdfit.InputError) as e:
        brdfit.Table.from_arrays(small_table.values, small_table.valid, provenance=p)
    assert "is not JSON" in str(e.value)
