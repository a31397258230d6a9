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
target, :func:`flumekit.performance.matrix.edges_around`):

>>> from flumekit.performance.matrix import edges_around
>>> edges_around([1.0, 2.0, 2.0, 4.0])
[0.5, 1.5, 3.0, 5.0]
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
    """Return the rule ``power_matrix``; none without irregular runs (:mod:`flumekit.stages`)."""
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


def build(inputs, outputs, params) -> None:
    """Bin the irregular runs' power by incident Hm0 and Te and write the power matrix.

    An action of :mod:`flumekit.stages` (returning None: the engine identifies the output by its
    bytes): reads each irregular run's ``waves:<run>``, ``flap:<run>`` and ``comparison:<run>``,
    writes ``power_matrix.nc`` with the bins ``hm0_edges`` [m] and ``te_edges`` [s] (None: from
    the ``targets``; IEC TS 62600-100). A run outside the bins is in no cell: it is named in the
    product and warned about. A product lacking a variable, or runs whose comparison sources
    differ, is an :class:`~flumekit.errors.InputError`.
    """
    import numpy as np
    import xarray as xr

    from flumekit import conventions
    from flumekit.errors import InputError
    from flumekit.io.netcdf import read_dataset, write_product
    from flumekit.performance import power_matrix
    from flumekit.performance.matrix import edges_around, target_te

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
