"""Quality control of instrument records.

QARTOD-style tests, Goring-Nikora despiking, flags, masking and gap filling, and checks of
the metadata against the records.
"""


from flumekit.lazy import lazy_names

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
    "clock_departures": "clock",
    "check_beam": "record",
    "beam_flags": "record",
    "unfilled_gaps": "record",
    "level_test": "qartod",
    "dropout_test": "qartod",
    "gap_test": "qartod",
    "noise_test": "qartod",
    "despike_flags": "despike",
    "flag_attrs": "flags",
    "aggregate": "flags",
}

__all__ = sorted(_LAZY)


__getattr__, __dir__ = lazy_names(__name__, _LAZY, globals())
