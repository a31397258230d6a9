"""flumekit: wave-flume experiments on wave energy converters, from raw recordings to figures.

The names an analyst needs are here or one package down; they are imported on first use, so
``import flumekit`` stays fast (the command line imports it on every call).

Reading data: :func:`read_probes`, :func:`read_calibration`, :func:`read_flap`,
:func:`read_mfprof`, :func:`load_campaign`, and :func:`open_processed` for what
``flumekit make`` wrote. Analysis packages: :mod:`flumekit.waves` (``flumekit.waves.separate``),
:mod:`flumekit.flap`, :mod:`flumekit.uvp`, :mod:`flumekit.hydro`, :mod:`flumekit.ballscrew`,
:mod:`flumekit.signal`, :mod:`flumekit.synth` (the virtual flume). Figures:
:mod:`flumekit.plot` (``flumekit.plot.separation(result)``).
"""

from __future__ import annotations

import importlib

from flumekit.errors import FlumekitError, InputError

__version__ = "0.1.0"

#: public name -> module that defines it (imported on first access)
_LAZY = {
    "read_probes": "flumekit.io.instruments",
    "read_calibration": "flumekit.io.instruments",
    "read_flap": "flumekit.io.instruments",
    "read_mfprof": "flumekit.io.mfprof",
    "read_dataset": "flumekit.io.netcdf",
    "write_dataset": "flumekit.io.netcdf",
    "open_processed": "flumekit.io.processed",
    "load_campaign": "flumekit.campaign",
    "scale": "flumekit.scaling",
}
_SUBPACKAGES = ("ballscrew", "conventions", "flap", "hydro", "io", "plot", "signal", "synth",
                "uvp", "waves", "performance")

__all__ = ["FlumekitError", "InputError", "__version__", *sorted(_LAZY), *_SUBPACKAGES]


def __getattr__(name: str):
    if name in _LAZY:
        value = getattr(importlib.import_module(_LAZY[name]), name)
    elif name in _SUBPACKAGES:
        value = importlib.import_module(f"flumekit.{name}")
    else:
        raise AttributeError(f"module 'flumekit' has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
