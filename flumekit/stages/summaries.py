"""A per-run stage's campaign summary: its rule, and its action's stacking of the runs."""

from __future__ import annotations

from flumekit.io.atomic import Written


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
    from flumekit.conventions import WARNINGS, run_warnings
    from flumekit.io.netcdf import write_product

    names = sorted(inputs)
    if keep is None and not drop_dims:  # the runs' scalars, their records never read
        from flumekit.io.processed import stack_files

        attrs: list[dict] = []
        out = stack_files([inputs[name] for name in names], scalars=True, coords="all",
                          run_attrs=attrs)
        warned = [w for name, a in zip(names, attrs, strict=True)
                  for w in run_warnings(name, a.get(WARNINGS, ""))]
        out.attrs = {}
    else:
        import xarray as xr

        from flumekit.io.netcdf import read_dataset

        rows, warned = [], []
        for name in names:
            ds = read_dataset(inputs[name]).drop_dims(list(drop_dims), errors="ignore")
            warned += run_warnings(name, ds.attrs.get(WARNINGS, ""))
            rows.append(ds[list(keep(ds) if keep else
                                [v for v in ds.data_vars if ds[v].ndim == 0])].expand_dims("run"))
        out = xr.concat(rows, dim="run", coords="all", compat="override")
    # every run's warnings kept where a campaign is read, each naming its run once
    out.attrs = {WARNINGS: "\n".join(dict.fromkeys(warned))} if warned else {}
    return write_product(out, outputs["dataset"], title,
                         f"flumekit campaign summary of {len(names)} runs", {"runs": names})
