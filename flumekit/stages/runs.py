"""What every per-run stage shares: run parameters as coordinates, and stacking runs."""

from __future__ import annotations

from flumekit.docstrings import doc
from flumekit.io.atomic import Written
from flumekit.stages.record_start import declared_start


@doc
def run_params(run, campaign=None) -> dict:
    """Return the parameters of a run that every per-run rule carries.

    :func:`run_coords` makes coordinates of them; the records' start, when run.toml declares
    one, is applied by :func:`write_run`.

    Parameters
    ----------
    %(campaign_run)s
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


@doc
def write_run(ds, outputs: dict, params: dict, title: str, source: str, record=None, *,
              compress: bool = True, coords: bool = True) -> Written:
    """Write one run's dataset with its run coordinates, attributes and record start.

    The start of its time axis is the one its record carries (from the raw file, through every
    stage), else the one run.toml declares (``start``).

    Parameters
    ----------
    ds : xarray.Dataset
        The run's product.
    %(dataset_output)s
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
        ds = declared_start(ds, declared, params["run"])
    return write_product(ds, outputs["dataset"], f"{title} of run {params['run']}", source,
                         params, compress=compress)
