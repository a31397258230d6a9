"""The figures stage's action (:mod:`flumekit.stages.figures` declares its rules)."""

from __future__ import annotations

from flumekit.stages.common import read_inputs


def draw(inputs, outputs, params) -> None:
    """Draw the registered figure ``params["figure"]`` and save it in every format.

    The figure is drawn from the rule's inputs (processed datasets, stacked along ``run`` for
    a figure registered so; raw files through their readers) and saved after passing the
    figure test (:mod:`flumekit.figures.check`), without the cyclic garbage collector
    (:func:`flumekit.figures.style.without_collector`).
    """
    from flumekit.figures.check import assert_passes
    from flumekit.figures.registry import figure
    from flumekit.figures.style import laid_out, save, style, without_collector

    with without_collector():
        entry = figure(params["figure"])
        if entry.stacked:
            from flumekit.io.processed import stack_files

            data = {"runs": stack_files([inputs[k] for k in sorted(inputs)])}
        else:
            data = read_inputs(inputs, params.get("reading"))
        with style():
            fig = entry.draw(data, params)
        with laid_out(fig):  # one layout, and one drawing for the check and the PNG
            save(fig, *outputs.values(),
                 check=lambda f: assert_passes(f, f"figure {entry.name}"),
                 description=entry.description)
