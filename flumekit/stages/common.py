"""What several stages share beyond the run helpers (:mod:`flumekit.stages.runs`): how a run's
raw instrument files are read, by the qc rules and the QC figure alike, and how a rule's
inputs are read whether processed datasets or raw files. No domain code needs this module."""

from __future__ import annotations

#: an input of this suffix is a raw instrument file (``<instrument>_raw``), read by its reader
RAW = "_raw"


def raw_reading(ctx, run) -> dict:
    """Per instrument, how its raw file is read: the parameters of :func:`read_raw` as the
    campaign declares them ([files.<instrument>], dialect, units, clocks)."""
    c = ctx.campaign
    out = {"probes": {"probes": list(c.probes.names), "sampling_rate": c.probes.sampling_rate,
                      "dialect": c.dialect("probes", run), "units": c.probes.units,
                      "time_offset": run.clock.get("probes", 0.0)}}
    if "flap" in c.instruments:
        out["flap"] = {"sampling_rate": c.encoder.sampling_rate,
                       "dialect": c.dialect("flap", run),
                       "time_offset": run.clock.get("flap", 0.0)}
    return out


def read_raw(kind: str, path, reading: dict):
    """The raw record of instrument ``kind`` ("probes" or "flap") read by its instrument
    reader with the parameters of :func:`raw_reading`."""
    from flumekit.io.instruments import read_flap, read_probes

    if kind == "probes":
        return read_probes(path, tuple(reading["probes"]), reading["sampling_rate"],
                           reading.get("dialect"), units=reading.get("units", "V"),
                           time_offset=reading.get("time_offset", 0.0))
    return read_flap(path, reading["sampling_rate"], reading.get("dialect"),
                     time_offset=reading.get("time_offset", 0.0))


def read_inputs(inputs: dict, reading: dict | None = None) -> dict:
    """A rule's inputs read: processed datasets read back, raw files (``<instrument>_raw``)
    through their instrument readers with ``reading[<instrument>]`` (:func:`raw_reading`)."""
    from flumekit.io.netcdf import read_dataset

    return {k: read_raw(k.removesuffix(RAW), v, reading[k.removesuffix(RAW)])
            if k.endswith(RAW) else read_dataset(v) for k, v in inputs.items()}
