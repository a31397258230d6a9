"""Stage: the power matrix of the campaign's irregular runs (IEC TS 62600-100).

``power_matrix``: the irregular runs binned by their measured incident Hm0 and Te (the waves
stage's ``hm0`` and ``te`` at the flap), with per cell the count, mean and standard deviation
(ddof = 0) of the mean power, the capture width and the capture width ratio, for the experiment
(the flap product) and the models (the comparison product) along ``source``
(:func:`flumekit.performance.power_matrix`); the per-run values beside it, over ``run``. No
rule when the campaign has no irregular run.

The bin edges are parameters; unset, each distinct target of the runs (``hm0``; ``te``, or
the Te of the JONSWAP spectrum of the declared ``tp`` and ``gamma``) gets its own bin, with
edges halfway between neighbouring targets and the outer edges as far out (±10 % of a lone
target).
"""

from __future__ import annotations

from flumekit.pipeline.rules import Rule
from flumekit.stages.context import Context

VERSION = "1"
NEEDS = "flap"  # the instrument this stage reads (stages.build_rules)
DEFAULTS = {"hm0_edges": None, "te_edges": None}
DOCS = {
    "hm0_edges": "power matrix: edges of the Hm0 bins [m], increasing, half-open bins; none: "
                 "one bin per target Hm0 of the irregular runs",
    "te_edges": "power matrix: edges of the energy period Te bins [s], increasing, half-open "
                "bins; none: one bin per target Te of the irregular runs",
}


def rules(ctx: Context, p: dict) -> list[Rule]:
    """Return the power-matrix rule over the campaign's irregular runs.

    Parameters
    ----------
    ctx : flumekit.stages.context.Context
        The campaign, the processed folder and the pipeline's parameters.
    p : dict
        The stage's ``[stages.<stage>]`` parameters over its ``DEFAULTS``.

    Returns
    -------
    list of flumekit.pipeline.Rule
        One rule, ``power_matrix``; none without irregular runs.
    """
    irregular = [r for r in ctx.campaign.runs if r.irregular]
    if not irregular:
        return []
    inputs = {}
    for r in irregular:
        inputs[f"flap:{r.id}"] = ctx.out("flap", f"{r.id}.nc")
        inputs[f"comparison:{r.id}"] = ctx.out("comparison", f"{r.id}.nc")
        inputs[f"waves:{r.id}"] = ctx.out("waves", f"{r.id}.nc")
    targets = [{k: getattr(r.sea_state, k) for k in ("hm0", "tp", "te", "gamma")}
               for r in irregular]
    return [Rule("power_matrix", "flumekit.stages.performance:build", inputs=inputs,
                 outputs={"dataset": ctx.out("power_matrix.nc")},
                 params={"hm0_edges": p["hm0_edges"], "te_edges": p["te_edges"],
                         "targets": targets, "runs": [r.id for r in irregular]},
                 version=VERSION)]


def target_te(target: dict) -> float:
    """Return the energy period of a target sea state.

    Parameters
    ----------
    target : dict
        ``te`` [s] when declared, else ``tp`` [s] and ``gamma`` [-] (default 3.3) of a
        JONSWAP spectrum.

    Returns
    -------
    float
        Te = m_-1 / m0 [s], the declared one or that of the JONSWAP spectrum (integrated
        to 20 fp).

    References
    ----------
    IEC TS 62600-100:2012, Marine energy - Wave, tidal and other water current converters -
    Part 100: Electricity producing wave energy converters - Power performance assessment.

    Examples
    --------
    >>> target_te({"te": 2.5})
    2.5
    >>> round(target_te({"tp": 2.0, "gamma": 3.3}) / 2.0, 2)
    0.9
    """
    import numpy as np

    from flumekit.synth.waves import jonswap

    if target.get("te"):
        return float(target["te"])
    tp = float(target["tp"])
    f = np.linspace(0.0, 20.0 / tp, 20001)[1:]  # to 20 fp: the f^-5 tail beyond is < 1e-5
    s = jonswap(f, 1.0, tp, target.get("gamma") or 3.3)
    return float(np.trapezoid(s / f, f) / np.trapezoid(s, f))


def edges_around(values) -> list[float]:
    """Return bin edges that give each distinct value its own bin.

    Inner edges lie halfway between neighbours, the outer edges as far out as the nearest
    inner one (±10 % around a lone value).

    Parameters
    ----------
    values : array_like
        The values (e.g. target Hm0 [m] or Te [s]); equal to 9 decimals counts as one.

    Returns
    -------
    list of float
        Increasing edges, one more than the distinct values.

    Examples
    --------
    >>> edges_around([1.0, 2.0, 2.0, 4.0])
    [0.5, 1.5, 3.0, 5.0]
    >>> edges_around([2.0])
    [1.8, 2.2]
    """
    import numpy as np

    v = np.unique(np.round(np.asarray(values, dtype=float), 9))
    if v.size == 1:
        return [float(v[0] * 0.9), float(v[0] * 1.1)]
    mid = 0.5 * (v[1:] + v[:-1])
    return [float(2 * v[0] - mid[0]), *map(float, mid), float(2 * v[-1] - mid[-1])]


def build(inputs, outputs, params) -> None:
    """Bin the irregular runs' power by incident Hm0 and Te and write the power matrix.

    A run outside the bins is in no cell: it is named in the product and warned about.

    Parameters
    ----------
    inputs : dict of str to pathlib.Path
        ``waves:<run>``, ``flap:<run>``, ``comparison:<run>``: the products of each irregular
        run.
    outputs : dict of str to pathlib.Path
        ``dataset``: ``power_matrix.nc``.
    params : dict
        ``hm0_edges`` [m] and ``te_edges`` [s] (None: from the targets), ``targets``, ``runs``.

    Raises
    ------
    flumekit.errors.InputError
        When a product lacks a variable, or the runs' comparison sources differ.

    References
    ----------
    IEC TS 62600-100:2012, Power performance assessment of electricity producing wave
    energy converters.
    """
    import numpy as np
    import xarray as xr

    from flumekit import conventions
    from flumekit.errors import InputError
    from flumekit.io.netcdf import read_dataset, write_product
    from flumekit.performance import power_matrix

    runs = params["runs"]
    names = ("mean_power", "capture_width", "capture_width_ratio")
    hm0, te, rows, sources = [], [], {n: [] for n in names}, None
    for run in runs:
        waves = read_dataset(inputs[f"waves:{run}"])
        flap = read_dataset(inputs[f"flap:{run}"])
        comp = read_dataset(inputs[f"comparison:{run}"])
        for key, ds in (("waves", waves), ("flap", flap)):
            need = ("hm0", "te") if key == "waves" else names
            missing = [n for n in need if n not in ds]
            if missing:
                raise InputError(inputs[f"{key}:{run}"], f"the {key} product of irregular run "
                                 f"{run} lacks {', '.join(missing)}")
        found = [str(s) for s in comp["source"].values]
        if sources is None:
            sources = found
        elif found != sources:
            raise InputError(inputs[f"comparison:{run}"], f"sources {found} differ from the "
                             f"other runs' {sources} (rebuild the comparisons with the same "
                             "[stages.models] simulator setting)")
        hm0.append(float(waves["hm0"]))
        te.append(float(waves["te"]))
        for n in names:  # the experiment as the flap stage measured it, the models beside it
            rows[n].append([float(flap[n]) if s == "experiment" else float(comp[n].sel(source=s))
                            for s in sources])
    values = {n: np.array(v) for n, v in rows.items()}
    targets = params["targets"]
    he = params["hm0_edges"] or edges_around([t["hm0"] for t in targets])
    tb = params["te_edges"] or edges_around([target_te(t) for t in targets])
    ds = power_matrix(hm0, te, values, he, tb, sources=sources)
    per_run = xr.Dataset({"run_hm0": ("run", hm0), "run_te": ("run", te),
                          **{f"run_{n}": (("run", "source"), values[n]) for n in names}},
                         coords={"run": runs, "source": sources})
    ds = conventions.annotate(ds.merge(per_run))
    he, tb = np.asarray(he, dtype=float), np.asarray(tb, dtype=float)
    out = [f"{r} (Hm0 {h:.3g} m, Te {t:.3g} s)" for r, h, t in zip(runs, hm0, te)
           if not (he[0] <= h < he[-1] and tb[0] <= t < tb[-1])]
    if out:  # said in the product and the build's output, never dropped silently
        import warnings

        ds.attrs["runs_outside_the_bins"] = "; ".join(out)
        warnings.warn(f"power matrix: {len(out)} run(s) outside the bins, in no cell: "
                      f"{'; '.join(out)} (widen [stages.performance] hm0_edges or te_edges)",
                      UserWarning, stacklevel=2)
    ds.attrs["hm0_edges"] = "given" if params["hm0_edges"] else "from the targets"
    ds.attrs["te_edges"] = "given" if params["te_edges"] else "from the targets"
    write_product(ds, outputs["dataset"], "Power matrix of the irregular runs",
                  f"flumekit performance stage from {len(runs)} irregular runs",
                  {k: params[k] for k in ("hm0_edges", "te_edges", "runs")})
