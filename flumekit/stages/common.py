"""What several stages share beyond the run helpers (:mod:`flumekit.stages.runs`): how a run's
raw instrument files are read (by the qc rules and the QC figure), how a rule's inputs are
read whether processed datasets or raw files, and how a quality-controlled product is written
(by the qc rules and the uvp rule). No domain code needs this module."""

from __future__ import annotations

#: an input of this suffix is a raw instrument file (``<instrument>_raw``), read by its reader
RAW = "_raw"
#: whether each product's float arrays are deflated (flumekit.io.netcdf.write_dataset): not the
#: probe and flap records, written once and read once by the next stage, whose float records of
#: measured noise deflate by a third only and slowly (6-10 ms a product, a third of the rule)
COMPRESS = {"probes": False, "flap": False, "uvp": True}


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


def gross_range(value) -> tuple[float, float] | None:
    """A ``[min, max]`` gross-range parameter as floats (None: not tested)."""
    return None if value is None else (float(value[0]), float(value[1]))


def write_qc(ds, outputs, params, title, source, warnings=(), compress=True):
    """Write a quality-controlled product of one run: its ``warnings`` and the interpolation
    limit ``params["max_gap"]`` [s] as attributes, no run coordinates."""
    from flumekit.conventions import MAX_GAP, WARNINGS
    from flumekit.stages.runs import write_run

    if warnings:
        ds.attrs[WARNINGS] = "\n".join(warnings)
    ds.attrs[MAX_GAP] = float(params["max_gap"])
    # no run coordinates: qc_summary stacks its own counts, and the rule's title and
    # parameters name the run (3 ms a product: a tenth of a probe or flap QC rule)
    return write_run(ds, outputs, params, title, source, compress=compress, coords=False)
