# SPDX-License-Identifier: GPL-3.0-or-later
"""Configuration plumbing shared by aquatoria.mesh and aquatoria.mask: Python overrides become the
``--set section.key=value`` strings of the command line (values as TOML), an in-memory raster
becomes an ``input.path`` override, and the run's log lines become Python warnings."""

import math
import os
import warnings

from . import _core

#: Log levels of the C++ logger (core/log.hpp LogLevel).
_WARNING = 2


class AquatoriaWarning(UserWarning):
    """A warning of the pipeline (the lines the command line prints as "warning: ...")."""


def toml_value(value):
    """The TOML text of a Python value (bool, int, float, str, list/tuple, dict)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, (str, os.PathLike)):
        text = os.fspath(value)
        out = ['"']
        for ch in text:
            if ch == '"':
                out.append('\\"')
            elif ch == "\\":
                out.append("\\\\")
            elif ord(ch) < 0x20 or ord(ch) == 0x7F:
                out.append("\\u%04x" % ord(ch))
            else:
                out.append(ch)
        out.append('"')
        return "".join(out)
    if isinstance(value, dict):
        return "{" + ", ".join("%s = %s" % (k, toml_value(v)) for k, v in value.items()) + "}"
    if hasattr(value, "tolist"):  # numpy arrays and scalars
        return toml_value(value.tolist())
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    raise TypeError("cannot give %r (%s) as a configuration value" % (value, type(value).__name__))


def override_strings(overrides):
    """``--set`` strings from a dict ({"section.key": value} or {"section": {"key": value}}), a
    list of "section.key=value" strings, or None."""
    if overrides is None:
        return []
    if isinstance(overrides, str):
        return [overrides]
    if isinstance(overrides, dict):
        out = []
        for key, value in overrides.items():
            if isinstance(value, dict) and "." not in key:
                for name, v in value.items():
                    out.append("%s.%s=%s" % (key, name, toml_value(v)))
            else:
                out.append("%s=%s" % (key, toml_value(value)))
        return out
    return [str(o) for o in overrides]


def _axis(da, names, units, standard_name):
    """The dimension of DataArray `da` that is the longitude (or latitude) axis, or None."""
    for d in da.dims:
        if str(d).lower() in names:
            return d
    for d in da.dims:
        if d in da.coords:
            attrs = da.coords[d].attrs
            if attrs.get("units") == units or attrs.get("standard_name") == standard_name:
                return d
    return None


def memory_raster(raster, lon=None, lat=None):
    """An in-memory GeoTIFF (kept alive by the returned object) from a 2-D array with its lon and
    lat vectors, or from an xarray DataArray with longitude and latitude coordinates."""
    import numpy as np

    if lon is None and lat is None and hasattr(raster, "dims") and hasattr(raster, "coords"):
        lon_name = _axis(raster, ("lon", "longitude", "x"), "degrees_east", "longitude")
        lat_name = _axis(raster, ("lat", "latitude", "y"), "degrees_north", "latitude")
        if lon_name is None or lat_name is None or raster.ndim != 2:
            raise _core.InputError(
                "in-memory raster: the DataArray needs a longitude and a latitude dimension (named "
                "lon/longitude/x and lat/latitude/y, or with units degrees_east / degrees_north); "
                "it has %s" % (list(raster.dims),))
        raster = raster.transpose(lat_name, lon_name)
        lon = raster[lon_name].values
        lat = raster[lat_name].values
        values = raster.values
    else:
        if lon is None or lat is None:
            raise _core.InputError("in-memory raster: give lon and lat with a numpy array")
        values = np.asarray(raster)
    values = np.asarray(values)
    if values.dtype.kind == "u" or values.dtype.kind == "b":
        values = values.astype(np.int32)
    elif values.dtype.kind == "f" and values.dtype.itemsize not in (4, 8):
        values = values.astype(np.float64)
    elif values.dtype.kind == "i" and values.dtype.itemsize not in (2, 4):
        values = values.astype(np.float64)
    return _core.MemoryRaster(values, np.asarray(lon, dtype=np.float64), np.asarray(lat, dtype=np.float64))


def prepare(config, overrides, raster, lon, lat):
    """(config path or None, --set strings, the in-memory raster to keep alive or None)."""
    sets = override_strings(overrides)
    mem = None
    if raster is not None:
        mem = memory_raster(raster, lon, lat)
        sets = sets + ['input.path=%s' % toml_value(mem.path), 'input.variable=""']
    if config is not None:
        config = os.fspath(config)
    return config, sets, mem


def threads_arg(threads):
    """The OpenMP team size of a call: 0 = the default (OMP_NUM_THREADS)."""
    if threads is None:
        return 0
    threads = int(threads)
    if threads < 1:
        raise ValueError("threads = %d: must be at least 1" % threads)
    return threads


def emit_warnings(lines):
    """Turns the run's warning lines into Python warnings."""
    for level, text in lines:
        if level >= _WARNING:
            warnings.warn(text, AquatoriaWarning, stacklevel=3)
