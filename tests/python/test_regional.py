# SPDX-License-Identifier: GPL-3.0-or-later
"""aquatoria.regional: the grid equals the command line's files (xygrid supergrid, ROMS grid file's
C-grid) and check() its report's quality figures."""

import json
import os

import netCDF4
import numpy as np
import pytest

import aquatoria as aq
from conftest import SOURCE_DIR, cli, cli_error

CONFIG = os.path.join(SOURCE_DIR, "configs", "black_sea.toml")


@pytest.fixture(scope="module")
def cli_files(tmp_path_factory):
    folder = str(tmp_path_factory.mktemp("regional"))
    code, err = cli(["regional", "-q", "-c", CONFIG, "-o", folder, "--no-coastline"], folder)
    assert code == 0, err
    return folder


@pytest.fixture(scope="module")
def grid():
    return aq.regional(CONFIG)


def read(path, names):
    with netCDF4.Dataset(path) as nc:
        nc.set_auto_mask(False)
        return {n: nc[n][...] for n in names if n in nc.variables}


def test_supergrid_equals_the_xygrid_file(cli_files, grid):
    nc = [f for f in os.listdir(cli_files) if f.endswith("_xygrid.nc")]
    assert nc, os.listdir(cli_files)
    v = read(os.path.join(cli_files, nc[0]), ["x", "y"])
    np.testing.assert_array_equal(grid.x_plane, v["x"].reshape(grid.x_plane.shape))
    np.testing.assert_array_equal(grid.y_plane, v["y"].reshape(grid.y_plane.shape))


def test_cgrid_equals_the_roms_file(cli_files, grid):
    nc = [f for f in os.listdir(cli_files) if f.endswith("_grd.nc")]
    if not nc:
        pytest.skip("this configuration writes no ROMS grid file")
    names = ["lon_rho", "lat_rho", "lon_u", "lat_psi", "pm", "pn", "angle", "f"]
    v = read(os.path.join(cli_files, nc[0]), names)
    for n in names:
        np.testing.assert_array_equal(getattr(grid, n), v[n], err_msg=n)


def test_check_equals_the_report(cli_files, grid):
    rep = [f for f in os.listdir(cli_files) if f.endswith("_report.json")]
    with open(os.path.join(cli_files, rep[0])) as f:
        quality = json.load(f)["quality"]
    q = grid.check()
    assert q["passed"]
    for name, fig in quality.items():
        assert q[name]["worst"] == pytest.approx(fig["worst"], rel=1e-12, nan_ok=True), name
        assert list(q[name]["worst_cell"]) == fig["worst_cell"], name


def test_regional_errors_carry_the_cli_message(tmp_path):
    # a Python str is given as a TOML string: the command line's --set regional.nmae="x"
    code, message = cli_error(["regional", "-c", CONFIG, "--set", 'regional.nmae="x"'], tmp_path)
    assert code == 2 and "did you mean regional.name" in message
    with pytest.raises(aq.ConfigError) as e:
        aq.regional(CONFIG, {"regional.nmae": "x"})
    assert str(e.value) == message
