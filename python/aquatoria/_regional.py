# SPDX-License-Identifier: GPL-3.0-or-later
"""aquatoria.regional: a regional orthogonal curvilinear grid and its C-grid as arrays."""

import os

from . import _core
from ._config import emit_warnings, override_strings, threads_arg
from ._interrupt import call

_ARRAYS = ("lon_rho", "lat_rho", "lon_u", "lat_u", "lon_v", "lat_v", "lon_psi", "lat_psi",
           "pm", "pn", "dndx", "dmde", "angle", "f", "x_plane", "y_plane")


def regional(config, overrides=None, *, threads=None, verbose=False):
    """Builds a regional orthogonal grid the way ``aquatoria regional -c config`` does (the
    izogrid method or regional.method), up to the complete grid, and its ROMS C-grid.

    Parameters
    ----------
    config : str or os.PathLike
        A regional TOML configuration (configs/example_regional.toml) or a seed-format .izogrid file.
    overrides : dict or list of str, optional
        Keys as for ``aquatoria regional --set``.
    threads : int, optional
        OpenMP threads for this call.
    verbose : bool
        Print the stage lines on stderr.

    Returns
    -------
    Grid

    Raises
    ------
    ConfigError, InputError, NumericalError
        With the command line's messages. A refinement grid ([nesting] refine_factor) is refused
        with ConfigError: it is made by ``aquatoria regional``.
    """
    core = call(_core.RegionalRun, os.fspath(config), override_strings(overrides), bool(verbose), threads_arg(threads))
    emit_warnings(core.take_log())
    return Grid(core)


class Grid:
    """A regional grid: (eta, xi) arrays, read-only views of the C++ grid.

    Attributes
    ----------
    lon_rho, lat_rho, lon_u, lat_u, lon_v, lat_v, lon_psi, lat_psi : numpy.ndarray
        Geographic coordinates (degrees) of the ROMS C-grid points, as in the ROMS grid file.
    pm, pn : numpy.ndarray
        1/Δξ, 1/Δη at ρ points (1/m); ``dndx``, ``dmde`` (m); ``angle`` (radians, from east to ξ);
        ``f`` (Coriolis, 1/s).
    x_plane, y_plane : numpy.ndarray
        The supergrid in the projection plane (the xygrid file's x, y).
    xl_m, el_m : float
        Domain lengths along ξ and η (m).
    """

    def __init__(self, core):
        self._core = core
        for name in _ARRAYS:
            setattr(self, name, getattr(core, name))
        self.xl_m = core.xl_m
        self.el_m = core.el_m

    def check(self, threads=None):
        """The grid checks of ``aquatoria regional`` / ``aquatoria check``: orthogonality (46),
        (50), (52), isotropy (51), Laplace residual and the seed-004 criteria f1-f4, each with
        worst, average, rms and the worst cell; ``passed`` is False when a criterion is not finite
        or a cell is not convex."""
        return call(self._core.check, threads_arg(threads))

    @property
    def report(self):
        """The run report as a dict."""
        return self._core.report()

    def __repr__(self):
        return "<aquatoria.Grid: %d x %d rho points>" % (self.lon_rho.shape[1], self.lon_rho.shape[0])
