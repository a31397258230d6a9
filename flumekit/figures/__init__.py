"""The papers' figures, drawn from processed datasets only.

The waves (Figs. 5a, 6a), the flap (Figs. 5b, 6b-d, 7-10), the UVP field (Figs. 11, 12), the
power matrix and capture width ratio, and the quality-control summary of a run. Each returns
a matplotlib Figure.
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
