"""Readers and writers: instrument tables, Met-Flow ``.mfprof`` files, flumekit netCDF.

One reader per instrument, each returning an :class:`xarray.Dataset` in SI units with CF
attributes: :func:`read_probes` (wave probe voltages), :func:`read_calibration` (static probe
submersions), :func:`read_flap` (encoder counts and chamber pressure), :func:`read_mfprof`
(UVP profiles; also ``xr.open_dataset(path, engine="mfprof")``). :func:`open_processed` opens
what the pipeline wrote; :func:`read_dataset` and :func:`write_dataset` read and write one
netCDF file.
"""

from flumekit.lazy import lazy_names

#: public name -> module (imported on first use: the pipeline's planning imports
#: flumekit.io.atomic, and must not pay for numpy and xarray on a no-op make)
_LAZY = {
    "read_calibration": "instruments", "read_flap": "instruments", "read_probes": "instruments",
    "read_mfprof": "mfprof", "write_mfprof": "mfprof",
    "read_dataset": "netcdf", "write_dataset": "netcdf",
    "open_processed": "processed", "processed_names": "processed",
    "stack_files": "processed", "write_product": "netcdf",
}

__all__ = sorted(_LAZY)


__getattr__, __dir__ = lazy_names(__name__, _LAZY, globals())
