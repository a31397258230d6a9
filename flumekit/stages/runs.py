"""What every per-run stage shares: run parameters as coordinates, and stacking runs."""

from __future__ import annotations

from flumekit.io.atomic import Written


def run_params(run, campaign=None) -> dict:
    """The parameters of a run that every per-run rule carries (and :func:`run_coords` uses),
    with the records' start when run.toml declares one (:func:`write_run` applies it).

    ``kind`` is the run's kind ("waves", "uvp", "irregular"), ``sea_state`` the target sea
    state of an irregular run (a dict, else None); ``sea_state_coords``: whether the runs of
    ``campaign`` carry the target sea state as coordinates (when any run is irregular, so
    that every run of a mixed campaign has the same coordinates); ``uvp_coords`` False (set
    only then): the campaign declares no UVP, so its runs carry no ``uvp_elevation``.
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
    """Run parameters as scalar coordinates, so runs concatenate along ``run``.

    ``uvp_elevation`` (present when the campaign declares the UVP) is NaN for runs without
    UVP, the target period and height NaN for an
    irregular run and its target Hm0, Tp and Te (``wave_hm0``, ``wave_tp``, ``wave_te``,
    present when the campaign has irregular runs) NaN for a regular one, so every run has the
    same coordinates.
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
    """Write one run's dataset: run coordinates (those the dataset lacks), global attributes,
    and the start of its time axis: the one its record carries (from the raw file, through
    every stage; ``record``: the dataset whose time axis ``ds``'s was computed from, when a
    domain function made it from plain numbers), else the one run.toml declares (``start``).
    ``compress``: as :func:`flumekit.io.netcdf.write_dataset`. ``coords=False``: no run
    coordinates (a product that no summary stacks along ``run``; each variable costs 0.5-1 ms
    to write, and its title and parameters name the run). Returns the written file
    (:class:`~flumekit.io.atomic.Written`), for the action to return to its rule."""
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
    """``ds`` with the start run.toml declares, where its record gives none; a record whose
    own start departs from the declared one by more than 1 s (both in UTC, or both on the
    lab's clock) is an error: metadata that contradicts the record is not used silently."""
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
    """The summary rule of a per-run stage: ``<stage>_summary`` from every ``<stage>/<run>.nc``,
    built by ``summary`` of ``flumekit.stages.<module>`` (default: the stage's name)."""
    from flumekit.pipeline.rules import Rule

    return Rule(f"{stage}_summary", f"flumekit.stages.{module or stage}:summary",
                inputs={r.id: ctx.out(stage, f"{r.id}.nc") for r in ctx.campaign.runs},
                outputs={"dataset": ctx.out(f"{stage}_summary.nc")}, version=version)


def stack_runs(inputs: dict, outputs: dict, title: str, keep=None, drop_dims=()) -> Written:
    """Write the per-run datasets ``inputs`` stacked along ``run`` (a campaign summary).

    ``keep(ds)`` names the variables to keep (default: every scalar); ``drop_dims`` are dropped
    first.
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
    """``WARNINGS`` and ``run_warnings``, which live in :mod:`flumekit.conventions`, for the
    callers outside ``stages/`` that still import them from here (loaded on use: planning
    imports no xarray)."""
    if name in ("WARNINGS", "run_warnings"):
        from flumekit import conventions

        return getattr(conventions, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
