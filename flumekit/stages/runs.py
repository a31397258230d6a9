"""What every per-run stage shares: run parameters as coordinates, and stacking runs."""

from __future__ import annotations

from flumekit.io.atomic import Written


def run_params(run, campaign=None) -> dict:
    """Return the parameters of a run that every per-run rule carries.

    :func:`run_coords` makes coordinates of them; the records' start, when run.toml declares
    one, is applied by :func:`write_run`.

    Parameters
    ----------
    run : flumekit.campaign.Run
        The run.
    campaign : flumekit.campaign.Campaign, optional
        Its campaign, which decides the coordinates every run carries.

    Returns
    -------
    dict
        ``run``, ``kind`` ("waves", "uvp", "irregular"), ``period`` [s], ``height`` [m],
        ``repeat``, ``uvp_elevation`` [m], ``sea_state`` (the target sea state of an
        irregular run as a dict, else None), ``sea_state_coords`` (whether the runs of
        ``campaign`` carry the target sea state as coordinates: when any run is irregular, so
        that every run of a mixed campaign has the same coordinates), ``start`` when declared,
        and ``uvp_coords`` False when the campaign declares no UVP (its runs carry no
        ``uvp_elevation``).
    """
    sea = run.sea_state
    return {"run": run.id, "kind": run.kind, "period": run.period, "height": run.height,
            "repeat": run.repeat, "uvp_elevation": run.uvp_elevation,
            "sea_state": None if sea is None else dict(sea.__dict__),
            "sea_state_coords": bool(campaign is not None
                                     and any(r.irregular for r in campaign.runs)),
            **({"start": run.start} if run.start else {}),
            **({"uvp_coords": False} if campaign is not None
               and "uvp" not in campaign.instruments else {})}


def run_coords(params: dict) -> dict:
    """Return run parameters as scalar coordinates, so runs concatenate along ``run``.

    ``uvp_elevation`` (present when the campaign declares the UVP) is NaN for runs without
    UVP, the target period and height NaN for an irregular run and its target Hm0, Tp and Te
    (``wave_hm0``, ``wave_tp``, ``wave_te``, present when the campaign has irregular runs) NaN
    for a regular one, so every run has the same coordinates.

    Parameters
    ----------
    params : dict
        The run's parameters (:func:`run_params`).

    Returns
    -------
    dict
        Coordinate name -> scalar: ``run``, ``wave_period`` [s], ``wave_height`` [m],
        ``repeat``, and where they apply ``uvp_elevation`` [m], ``wave_hm0`` [m],
        ``wave_tp`` [s], ``wave_te`` [s].

    Examples
    --------
    >>> run_coords({"run": "R01", "period": 2.0, "height": None, "repeat": 0,
    ...             "uvp_coords": False})
    {'run': 'R01', 'wave_period': 2.0, 'wave_height': nan, 'repeat': 0}
    """
    def nan(v):
        return float("nan") if v is None else v

    out = {"run": params["run"], "wave_period": nan(params["period"]),
           "wave_height": nan(params["height"]), "repeat": params["repeat"]}
    if params.get("uvp_coords", True):
        out["uvp_elevation"] = nan(params.get("uvp_elevation"))
    if params.get("sea_state_coords"):
        sea = params.get("sea_state") or {}
        out.update({f"wave_{k}": nan(sea.get(k)) for k in ("hm0", "tp", "te")})
    return out


def write_run(ds, outputs: dict, params: dict, title: str, source: str, record=None, *,
              compress: bool = True, coords: bool = True) -> Written:
    """Write one run's dataset with its run coordinates, attributes and record start.

    The start of its time axis is the one its record carries (from the raw file, through every
    stage), else the one run.toml declares (``start``).

    Parameters
    ----------
    ds : xarray.Dataset
        The run's product.
    outputs : dict of str to pathlib.Path
        ``dataset``: the file to write.
    params : dict
        The rule's parameters, with the run's (:func:`run_params`).
    title, source : str
        Global attributes; the title gets the run's name appended.
    record : xarray.Dataset, optional
        The dataset whose time axis ``ds``'s was computed from, when a domain function made
        it from plain numbers: its record start is carried over.
    compress : bool, default True
        As :func:`flumekit.io.netcdf.write_dataset`.
    coords : bool, default True
        Add the run coordinates (those the dataset lacks); False for a product that no
        summary stacks along ``run`` (each coordinate costs a variable to write, and the
        title and parameters name the run).

    Returns
    -------
    flumekit.io.atomic.Written
        The file written and its content digest, for the action to return to its rule.

    Raises
    ------
    flumekit.errors.InputError
        When the record's own start departs from the declared one by more than 1 s.
    """
    from flumekit import conventions
    from flumekit.io.netcdf import write_product

    if coords:
        ds = ds.assign_coords({k: v for k, v in run_coords(params).items()
                               if k not in ds.coords})
    carried = None if record is None else conventions.record_start(record)
    if carried and "time" in ds.coords and conventions.record_start(ds) is None:
        ds = ds.copy()
        ds["time"].attrs[conventions.RECORD_START] = carried
    declared = params.get("start")
    if declared and "time" in ds.coords:
        ds = _declared_start(ds, declared, params["run"])
    return write_product(ds, outputs["dataset"], f"{title} of run {params['run']}", source,
                         params, compress=compress)


def _declared_start(ds, declared: str, run: str):
    """Return ``ds`` with the start run.toml declares, where its record gives none.

    A record whose own start departs from the declared one by more than 1 s (both in UTC, or
    both on the lab's clock) is an error: metadata that contradicts the record is not used
    silently.
    """
    import numpy as np

    from flumekit import conventions
    from flumekit.errors import InputError

    found = conventions.record_start(ds)
    if found is None:
        ds = ds.copy()
        ds["time"].attrs[conventions.RECORD_START] = declared
        return ds
    if found.endswith("Z") == declared.endswith("Z"):
        gap = abs(np.datetime64(found.rstrip("Z"), "ns") - np.datetime64(declared.rstrip("Z"),
                                                                         "ns"))
        if gap > np.timedelta64(1, "s"):
            raise InputError(ds.attrs.get(conventions.SOURCE_FILE) or f"run {run}",
                             f"the record starts at {found}, but run.toml of run {run} declares "
                             f"start = {declared}: correct or remove 'start' in run.toml",
                             field="start")
    return ds


def summary_rule(ctx, stage: str, version: str, module: str | None = None):
    """Return the summary rule of a per-run stage.

    Parameters
    ----------
    ctx : flumekit.stages.context.Context
        The stage context.
    stage : str
        The stage; the rule ``<stage>_summary`` reads every ``<stage>/<run>.nc``.
    version : str
        The stage's rule version.
    module : str, optional
        The stage module whose ``summary`` builds it (default: the stage's name).

    Returns
    -------
    flumekit.pipeline.Rule
        The summary rule.
    """
    from flumekit.pipeline.rules import Rule

    return Rule(f"{stage}_summary", f"flumekit.stages.{module or stage}:summary",
                inputs={r.id: ctx.out(stage, f"{r.id}.nc") for r in ctx.campaign.runs},
                outputs={"dataset": ctx.out(f"{stage}_summary.nc")}, version=version)


def stack_runs(inputs: dict, outputs: dict, title: str, keep=None, drop_dims=()) -> Written:
    """Write the per-run datasets stacked along ``run`` (a campaign summary).

    Every run's warnings are kept, each naming its run once.

    Parameters
    ----------
    inputs : dict of str to pathlib.Path
        Run -> its product.
    outputs : dict of str to pathlib.Path
        ``dataset``: the summary file.
    title : str
        The summary's title.
    keep : callable, optional
        ``keep(ds)`` names the variables to keep (default: every scalar).
    drop_dims : sequence of str, optional
        Dimensions dropped first.

    Returns
    -------
    flumekit.io.atomic.Written
        The file written and its content digest.
    """
    import xarray as xr

    from flumekit.conventions import WARNINGS, run_warnings
    from flumekit.io.netcdf import read_dataset, write_product

    rows, warned = [], []
    for name in sorted(inputs):
        ds = read_dataset(inputs[name]).drop_dims(list(drop_dims), errors="ignore")
        warned += run_warnings(name, ds.attrs.get(WARNINGS, ""))
        names = keep(ds) if keep else [v for v in ds.data_vars if ds[v].ndim == 0]
        rows.append(ds[list(names)].expand_dims("run"))
    out = xr.concat(rows, dim="run", coords="all", compat="override")
    # every run's warnings kept where a campaign is read, each naming its run once
    out.attrs = {WARNINGS: "\n".join(dict.fromkeys(warned))} if warned else {}
    return write_product(out, outputs["dataset"], title,
                         f"flumekit campaign summary of {len(rows)} runs", {"runs": sorted(inputs)})


def __getattr__(name: str):
    """Return ``WARNINGS`` or ``run_warnings`` of :mod:`flumekit.conventions`.

    For the callers outside ``stages/`` that import them from here (loaded on use: planning
    imports no xarray).
    """
    if name in ("WARNINGS", "run_warnings"):
        from flumekit import conventions

        return getattr(conventions, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
