# SPDX-License-Identifier: GPL-3.0-or-later
"""Errors raise Python exceptions carrying the command line's messages (bad key with its "did you
mean", bad value, missing file), and nothing is written."""

import os

import pytest

import aquatoria as aq
from conftest import SOURCE_DIR, cli_error


def test_unknown_key_has_the_cli_message(tmp_path):
    code, message = cli_error(["mesh", "--set", "quadtree.levls=4"], tmp_path)
    assert code == 2 and "did you mean" in message
    with pytest.raises(aq.ConfigError) as e:
        aq.mesh(None, {"quadtree.levls": 4})
    assert str(e.value) == message
    assert isinstance(e.value, aq.Error)


def test_bad_value_has_the_cli_message(tmp_path):
    code, message = cli_error(["mesh", "--set", "mask.cursor=0"], tmp_path)
    assert code == 2 and "mask.cursor" in message
    with pytest.raises(aq.ConfigError) as e:
        aq.mesh(None, {"mask": {"cursor": 0}})
    assert str(e.value) == message


def test_bad_value_in_a_config_file_names_the_file(tmp_path):
    cfg = tmp_path / "bad.toml"
    cfg.write_text("[quadtree]\nstep_deg = 7.0\n")
    code, message = cli_error(["mesh", "-c", str(cfg)], tmp_path)
    assert code == 2 and str(cfg) in message
    with pytest.raises(aq.ConfigError) as e:
        aq.mesh(cfg)
    assert str(e.value) == message


def test_missing_raster_has_the_cli_message(tmp_path):
    missing = str(tmp_path / "no_such_raster.nc")
    code, message = cli_error(["mesh", "-o", str(tmp_path / "out"), "--set", "input.path=" + missing], tmp_path)
    assert code == 1 and missing in message
    with pytest.raises(aq.InputError) as e:
        aq.mesh(None, {"input.path": missing})
    assert str(e.value) == message
    assert not os.path.exists(tmp_path / "out") or not os.listdir(tmp_path / "out")


def test_missing_config_file_has_the_cli_message(tmp_path):
    missing = str(tmp_path / "none.toml")
    code, message = cli_error(["mesh", "-c", missing], tmp_path)
    with pytest.raises(aq.Error) as e:
        aq.mesh(missing)
    assert str(e.value) == message


def test_bad_format_writes_nothing(seed_run, tmp_path):
    with pytest.raises(aq.ConfigError) as e:
        seed_run.write(tmp_path / "x", formats=["msh", "nope"])
    assert "output.formats" in str(e.value) and "nope" in str(e.value)
    assert os.listdir(tmp_path) == []


def test_values_become_toml():
    from aquatoria._config import override_strings
    assert override_strings({"a.b": True, "a.c": 1.5, "a.d": "x\"y", "a.e": [1, 2], "s": {"k": 3}}) == [
        "a.b=true", "a.c=1.5", 'a.d="x\\"y"', "a.e=[1, 2]", "s.k=3"]
    assert override_strings({"q.r": [{"lon_min_deg": -45.0, "size_km": 100}]}) == [
        "q.r=[{lon_min_deg = -45.0, size_km = 100}]"]
