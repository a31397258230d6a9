"""Readers and writers: instrument tables, Met-Flow ``.mfprof`` files, flumekit netCDF.

One reader per instrument, each returning an :class:`xarray.Dataset` in SI units with CF
attributes: :func:`read_probes` (wave probe voltages), :func:`read_calibration` (static probe
submersions), :func:`read_flap` (encoder counts and chamber pressure), :func:`read_mfprof`
(UVP profiles; also ``xr.open_dataset(path, engine="mfprof")``). :func:`open_processed` opens
what the pipeline wrote; :func:`read_dataset` and :func:`write_dataset` read and write one
netCDF file.
"""

from flumekit.io.instruments import read_calibration, read_flap, read_probes
from flumekit.io.mfprof import read_mfprof, write_mfprof
from flumekit.io.netcdf import read_dataset, write_dataset
from flumekit.io.processed import open_processed, processed_names

__all__ = [
    "open_processed", "processed_names", "read_calibration", "read_dataset", "read_flap",
    "read_mfprof", "read_probes", "write_dataset", "write_mfprof",
]
