"""What several stages share beyond the run helpers (:mod:`flumekit.stages.runs`).

How a run's raw instrument files are read (by the qc rules and the QC figure), how a rule's
inputs are read whether processed datasets or raw files, and how a quality-controlled product
is written (by the qc rules and the uvp rule). No domain code needs this module.
"""

from __future__ import annotations

from flumekit.docstrings import doc

#: an input of this suffix is a raw instrument file (``<instrument>_raw``), read by its reader
RAW = "_raw"
#: whether each product's float arrays are deflated (flumekit.io.netcdf.write_dataset): not the
#: probe and flap records, written once and read once by the next stage, whose float records of
#: measured noise deflate by a third only and slowly (a large share of the rule's time)
COMPRESS = {"probes": False, "flap": False, "uvp": True}


@doc
def raw_reading(ctx, run) -> dict:
    """Return, per instrument, how its raw file is read.

    Parameters
    ----------
    ctx : flumekit.stages.context.Context
        The stage context (its campaign).
    %(campaign_run)s

    Returns
    -------
    dict
        ``"probes"`` (and ``"flap"`` when the campaign has the flap instruments) -> the
        parameters of :func:`read_raw` as the campaign declares them (``[files.<instrument>]``
        dialect, units, sampling rate [Hz], clock offset [s]).
    """
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
    """Read the raw record of an instrument with its instrument reader.

    Parameters
    ----------
    kind : {"probes", "flap"}
        The instrument.
    path : path-like
        Its raw file.
    reading : dict
        The parameters of :func:`raw_reading` for that instrument.

    Returns
    -------
    xarray.Dataset
        The record (:func:`flumekit.io.instruments.read_probes` or
        :func:`flumekit.io.instruments.read_flap`).

    Raises
    ------
    flumekit.errors.InputError
        For a file that does not hold the declared record.
    """
    from flumekit.io.instruments import read_flap, read_probes

    if kind == "probes":
        return read_probes(path, tuple(reading["probes"]), reading["sampling_rate"],
                           reading.get("dialect"), units=reading.get("units", "V"),
                           time_offset=reading.get("time_offset", 0.0))
    return read_flap(path, reading["sampling_rate"], reading.get("dialect"),
                     time_offset=reading.get("time_offset", 0.0))


def read_inputs(inputs: dict, reading: dict | None = None) -> dict:
    """Read a rule's inputs, processed datasets and raw instrument files alike.

    Parameters
    ----------
    inputs : dict of str to path-like
        The rule's inputs; a name ending in ``_raw`` (``<instrument>_raw``) is a raw file.
    reading : dict, optional
        :func:`raw_reading` of the run; needed when a raw file is among the inputs.

    Returns
    -------
    dict of str to xarray.Dataset
        Input name -> dataset.
    """
    from flumekit.io.netcdf import read_dataset

    return {k: read_raw(k.removesuffix(RAW), v, reading[k.removesuffix(RAW)])
            if k.endswith(RAW) else read_dataset(v) for k, v in inputs.items()}


def gross_range(value) -> tuple[float, float] | None:
    """Return a ``[min, max]`` gross-range parameter as floats (None: not tested).

    Examples
    --------
    >>> gross_range([0, 5]), gross_range(None)
    ((0.0, 5.0), None)
    """
    return None if value is None else (float(value[0]), float(value[1]))


@doc
def write_qc(ds, outputs, params, title, source, warnings=(), compress=True):
    """Write a quality-controlled product of one run, without run coordinates.

    Parameters
    ----------
    ds : xarray.Dataset
        The quality-controlled record.
    %(dataset_output)s
    params : dict
        The rule's parameters; ``max_gap`` [s], the interpolation limit, is recorded.
    title, source : str
        Global attributes of the product.
    warnings : sequence of str, optional
        Recorded as the dataset's warnings attribute.
    compress : bool, default True
        Deflate the float arrays (:data:`COMPRESS`).

    Returns
    -------
    flumekit.io.atomic.Written
        The file written and its content digest.
    """
    from flumekit.conventions import MAX_GAP, WARNINGS
    from flumekit.stages.runs import write_run

    if warnings:
        ds.attrs[WARNINGS] = "\n".join(warnings)
    ds.attrs[MAX_GAP] = float(params["max_gap"])
    # no run coordinates: qc_summary stacks its own counts, and the rule's title and
    # parameters name the run
    return write_run(ds, outputs, params, title, source, compress=compress, coords=False)
