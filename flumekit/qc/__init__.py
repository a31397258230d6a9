"""Quality control of instrument records: QARTOD-style tests, Goring-Nikora despiking, flags,
masking and gap filling, and checks of the metadata against the records."""


import importlib

#: public name -> module of this package (imported on first use, so that importing the
#: package stays cheap)
_LAZY = {
    "Thresholds": "record",
    "qc_dataset": "record",
    "clean": "record",
    "check_series": "record",
    "flag_counts": "record",
    "gross_range_test": "qartod",
    "spike_test": "qartod",
    "rate_of_change_test": "qartod",
    "flat_line_test": "qartod",
    "goring_nikora": "despike",
    "fill_gaps": "fill",
    "probe_flap_lag": "clock",
}

__all__ = sorted(_LAZY)


def __getattr__(name: str):
    if name not in _LAZY:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f"{__name__}.{_LAZY[name]}"), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
