# SPDX-License-Identifier: GPL-3.0-or-later
"""aquatoria in Python: global ocean meshes and their stages as numpy arrays and xarray datasets.

The same pipeline as the ``aquatoria`` command, compiled into this package (``aquatoria._core``)
and run in the calling process::

    import aquatoria as aq
    run = aq.mesh("configs/global_mercator.toml", {"quadtree.size_km": 110})
    run.nodes, run.triangles, run.depth, run.level, run.boundaries, run.report  # the UGRID file's mesh
    m = run.model_mesh("fort14")               # the mesh the .14 file holds, node for node
    m.nodes, m.triangles, m.depth, m.open_segments, m.land_segments
    ds = run.to_xarray()                       # UGRID-1.0 / CF dataset, made in memory
    run.write("out/gm", formats=["msh", "fort14"])
    m = aq.mask("configs/global_mercator.toml")  # classes, filled area, levels; no mesh
    g = aq.regional("configs/black_sea.toml")     # g.lon_rho, g.pm, g.check()

Configuration: a TOML file (or None for the built-in defaults, the seed's reference run) and
overrides with the keys of ``aquatoria mesh --set`` (``{"quadtree.size_km": 110}``, or nested
``{"quadtree": {"size_km": 110}}``). Errors raise :class:`ConfigError` (exit code 2 of the command),
:class:`InputError`, :class:`OutputError`, ... with the command line's messages.

The C++ work runs with the GIL released and uses OpenMP threads (``OMP_NUM_THREADS``, or
``threads=`` per call); calls from several Python threads run one after another. Ctrl-C stops a
long call with KeyboardInterrupt and leaves no file behind.
"""

from ._import_check import check_interpreter as _check_interpreter

_check_interpreter()  # numpy and the interpreter the module was built for, with one clear message
del _check_interpreter

from ._core import (  # noqa: E402 (after the check)
    ConfigError,
    Error,
    InputError,
    InternalError,
    NumericalError,
    OutputError,
    __version__,
)
from ._config import AquatoriaWarning
from ._mesh import Mesh, ModelMesh, Run, mesh
from ._mask import Mask, mask
from ._regional import Grid, regional

Error.__doc__ = "Base of every error aquatoria raises; the message names the file, key or value at fault."
ConfigError.__doc__ = "A bad configuration key or value (the command line's exit code 2)."
InputError.__doc__ = "Missing, unreadable or unusable input data: a raster, a contour, an in-memory raster."
OutputError.__doc__ = "A file could not be written (nothing of the call is left behind)."
NumericalError.__doc__ = "A numerical method failed (no convergence, degenerate geometry)."
InternalError.__doc__ = "A broken internal invariant, reported instead of bad output (please report it)."

__all__ = [
    "AquatoriaWarning",
    "mesh",
    "mask",
    "Run",
    "Mesh",
    "ModelMesh",
    "Mask",
    "regional",
    "Grid",
    "Error",
    "ConfigError",
    "InputError",
    "OutputError",
    "NumericalError",
    "InternalError",
    "__version__",
]
