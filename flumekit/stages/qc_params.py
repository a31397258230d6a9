"""The ``[stages.qc]`` parameters.

The QC stage's and, for the UVP beams, the uvp stage's (whose rules check the beams they read).
"""

from __future__ import annotations

#: [stages.qc] parameters: the thresholds of flumekit.qc.record.Thresholds, the metadata checks
#: and optional gross ranges [channel units: V, counts, Pa, m s-1] (unset: not evaluated)
DEFAULTS = {"spike_suspect": 6.0, "spike_fail": 8.0, "rate_of_change": 10.0,
            "flat_line_suspect": 3.0, "flat_line_fail": 5.0, "flat_line_tolerance": 0.0,
            "dropout": 6.0, "hold": 0.2, "block": 10.0, "gap_tolerance": 0.5, "max_gap": 0.2,
            "period_tolerance": 0.1, "max_flat_fraction": 0.5, "despike_iterations": 1,
            "probe_range": None, "encoder_range": None, "pressure_range": None,
            "velocity_range": None, "clock_tolerance": 0.1, "noise_autocorrelation": 0.5,
            "noise_share": 0.1, "dropout_irregular": 12.0}
DOCS = {
    "spike_suspect": "spike test: suspect beyond this many robust local standard deviations of "
                     "x_n - (x_(n-1) + x_(n+1))/2 [-]",
    "spike_fail": "spike test: fail beyond this many [-]",
    "rate_of_change": "rate-of-change test: robust local standard deviations of the first "
                      "difference [-]",
    "flat_line_suspect": "flat-line test: suspect after this long without change [s]",
    "flat_line_fail": "flat-line test: fail after this long [s]",
    "flat_line_tolerance": "flat-line test: changes below this count as none [channel units]",
    "dropout": "dropout test: robust standard deviations of the record about its median [-]",
    "hold": "dropout test: a dropout holds its value at least this long [s]",
    "block": "length of the blocks of the local robust scale [s]",
    "gap_tolerance": "a time step longer than (1 + this) / rate is a gap [-]",
    "max_gap": "longest run of failed samples interpolated [s]",
    "period_tolerance": "declared period vs the probes' dominant period: relative difference "
                        "beyond which the run is refused [-]",
    "max_flat_fraction": "fraction of a record flat-lined (or failing the noise test) beyond "
                         "which the channel is dead, stuck (or noise): an error naming file "
                         "and channel [-]",
    "despike_iterations": "Goring-Nikora despiking iterations at most (UVP) [-]",
    "probe_range": "[min, max] gross range of the probe records [V or m]; none: not tested",
    "encoder_range": "[min, max] gross range of the encoder counts; none: not tested",
    "pressure_range": "[min, max] gross range of the chamber pressure [Pa]; none: not tested",
    "velocity_range": "[min, max] gross range of the UVP velocities [m s-1]; none: not tested",
    "noise_autocorrelation": "noise test: a block (of `block` seconds) whose lag-one "
                             "autocorrelation is below this [-] ...",
    "noise_share": "... and whose high-frequency energy (half the mean square first "
                   "difference) exceeds this share of the channel's variance fails: noise or "
                   "alternating spikes, not a signal sampled far above its band [-]",
    "dropout_irregular": "dropout test of an irregular run's probe and flap records: robust "
                         "standard deviations about the median [-]; an irregular sea's "
                         "largest waves, and the pressure peaks of a single-acting PTO in "
                         "them, lie 7 or more of them out",
    "clock_tolerance": "probe-to-flap lag departing from the lag expected for the run's wave "
                       "condition (its other runs, else the neighbouring conditions) by more "
                       "than this is reported as a possible clock offset [s]",
}
#: the [stages.qc] parameters of the UVP's quality control, which the uvp rules carry (they
#: check the beams they read: :func:`beam_checker`)
UVP_PARAMS = ("despike_iterations", "dropout", "gap_tolerance", "max_gap", "velocity_range")
