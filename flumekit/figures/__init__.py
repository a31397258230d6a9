"""The papers' figures, drawn from processed datasets only.

The waves (Figs. 5a, 6a), the flap (Figs. 5b, 6b-d, 7-10), the UVP field (Figs. 11, 12), the
power matrix and capture width ratio, and the quality-control summary of a run. Each returns
a matplotlib Figure built without pyplot: nothing to show or close, it is saved.

Each takes what ``flumekit make`` wrote under ``processed/<pipeline>/``, as the rules of
:mod:`flumekit.stages.figures` give it:

- :func:`figure_5a`, :func:`figure_6a`: ``waves/<run>.nc``;
- :func:`figure_5b`, :func:`figure_6bcd`: ``flap/<run>.nc``;
- :func:`figure_7`: a list of ``flap/<run>.nc``, one run per condition;
- :func:`figure_8`, :func:`figure_9`: ``comparison/<run>.nc`` of every regular run, stacked
  along ``run``: its ``source="experiment"``, and its other sources as ``models``;
- :func:`figure_10`: ``flap/<run>.nc``; the ``eta`` of the probe nearest the flap from
  ``waves/<run>.nc`` and the ``models`` from ``comparison/<run>.nc``;
- :func:`fig11`, :func:`fig12`: ``uvp_field.nc``;
- :func:`figure_power_matrix`, :func:`figure_capture_width_ratio`: ``power_matrix.nc``;
- :func:`figure_qc`: ``qc/probes/<run>.nc`` (and ``qc/flap/``, ``qc/uvp/``), with the raw
  files as the instrument readers read them.

Each function's own example draws it from a small dataset built on the spot.

Examples
--------
Fig. 5a of the paper's run, drawn and saved as ``flumekit make`` does: every figure function
builds its figure in the package style (:func:`flumekit.figures.style.styled`), and
:func:`~flumekit.figures.style.save` writes PNG at 300 dpi and PDF, with the registry's
description as the caption the campaign report reads. The files are those of
``flumekit make``, byte for byte:

>>> from flumekit import open_processed
>>> from flumekit.figures import figure_5a
>>> from flumekit.figures.registry import figure
>>> from flumekit.figures.style import save
>>> figure("fig05a").function is figure_5a
True
>>> waves = open_processed("processed/default", "waves/T3.50_H0.250_r0")  # doctest: +SKIP
>>> fig = figure_5a(waves)  # doctest: +SKIP
>>> save(fig, "fig05a.png", "fig05a.pdf",
...      description=figure("fig05a").description)  # doctest: +SKIP

A figure of several datasets through the registry, which makes its arguments out of them as
the pipeline does (for Fig. 10: the probe nearest the flap, the models of the comparison):

>>> from flumekit.io.netcdf import read_dataset
>>> data = {stage: read_dataset(f"processed/default/{stage}/T3.50_H0.250_r0.nc")
...         for stage in ("flap", "waves", "comparison")}  # doctest: +SKIP
>>> fig = figure("fig10").draw(data)  # doctest: +SKIP
"""


from flumekit.lazy import lazy_names

#: public name -> module of this package (imported on first use, so that importing the
#: package stays cheap)
_LAZY = {
    "figure_5a": "waves",
    "figure_6a": "waves",
    "figure_5b": "flap",
    "figure_6bcd": "flap",
    "figure_7": "flap",
    "figure_8": "flap",
    "figure_9": "flap",
    "figure_10": "flap",
    "fig11": "uvp",
    "fig12": "uvp",
    "figure_power_matrix": "performance",
    "figure_capture_width_ratio": "performance",
    "figure_qc": "qc",
}

__all__ = sorted(_LAZY)


__getattr__, __dir__ = lazy_names(__name__, _LAZY, globals())
