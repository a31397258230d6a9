"""Quality control of instrument records.

QARTOD-style tests, Goring-Nikora despiking, flags, masking and gap filling, and checks of
the metadata against the records.
"""


from flumekit.lazy import attach

# public names by the module that defines them, each imported on first use so that
# importing the package stays cheap
__getattr__, __dir__, __all__ = attach(
    __name__, globals(),
    record=["Thresholds", "qc_dataset", "clean", "check_series", "flag_counts", "check_beam",
            "beam_flags", "unfilled_gaps"],
    qartod=["gross_range_test", "spike_test", "rate_of_change_test", "flat_line_test", "level_test",
            "dropout_test", "gap_test", "noise_test"],
    despike=["goring_nikora", "despike_flags"],
    fill=["fill_gaps"],
    clock=["probe_flap_lag", "clock_departures"],
    flags=["flag_attrs", "aggregate"],
)
