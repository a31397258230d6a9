"""Quality control of one instrument record: the QARTOD battery, aggregation, masking, filling.

:func:`check_series` runs the tests on a (channel, time) block of probe or flap records and
returns the per-test flags (:func:`check_beam` those of a UVP beam's velocities);
:func:`clean` masks what failed and interpolates gaps up to a declared length;
:func:`qc_dataset` does both for one variable of a dataset and returns it with its flags
(``<name>_qc``, CF flag attributes) and per-channel counts; the values as read are not repeated
(the raw file holds them: the QC figure reads it).
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np
import xarray as xr

from flumekit.qc import qartod
from flumekit.qc.despike import despike_flags
from flumekit.qc.fill import fill_gaps, gap_spans
from flumekit.qc.flags import (
    FAIL,
    FLAG_MEANINGS,
    FLAG_VALUES,
    GOOD,
    MISSING,
    NOT_EVALUATED,
    SUSPECT,
    aggregate,
    choose,
    flag_attrs,
)

#: profiles on each side of a boundary echo also left out of the despiking
BOUNDARY_PROFILES = 1


@dataclass(frozen=True)
class Thresholds:
    """Thresholds of the QC tests (the ``[stages.qc]`` parameters). Defaults pass clean
    virtual-flume records untouched (measured in tests/qc)."""

    spike_suspect: float = 6.0  # robust local std of x_n - (x_(n-1) + x_(n+1))/2 [-]
    spike_fail: float = 8.0  # [-]
    rate_of_change: float = 10.0  # robust local std of the first difference [-]
    flat_line_suspect: float = 3.0  # [s]
    flat_line_fail: float = 5.0  # [s]
    flat_line_tolerance: float = 0.0  # [units of the channel]
    dropout: float = 6.0  # robust std of the record about its median [-]
    hold: float = 0.2  # shortest run of identical values that can be a dropout [s]
    block: float = 10.0  # length of the blocks of the local robust scale [s]
    gap_tolerance: float = 0.5  # a time step longer than (1 + this) / rate is a gap [-]
    max_gap: float = 0.2  # longest run of failed samples interpolated [s]
    despike_iterations: int = 1  # Goring-Nikora iterations at most [-]
    noise_autocorrelation: float = 0.5  # noise test: lag-one autocorrelation below this [-]
    noise_share: float = 0.1  # noise test: and high-frequency energy above this share [-]

    @classmethod
    def from_params(cls, params: dict) -> Thresholds:
        cast = {"int": int, "float": float}
        return cls(**{f.name: cast[f.type](params[f.name]) for f in fields(cls)
                      if f.name in params})


def check_series(x: np.ndarray, time: np.ndarray, sampling_rate: float, th: Thresholds, *,
                 gross_range: tuple[float, float] | None = None, flat_line: bool = True,
                 floor: np.ndarray | float | None = None) -> dict[str, np.ndarray]:
    """Per-test QARTOD flags of a (channel, time) block of probe or flap records (time along
    the last axis): gap, gross range, spike, rate of change, flat line, dropout, noise.

    ``flat_line=False`` skips the flat-line test (a channel whose repeats are legitimate).
    Velocity records take :func:`check_beam` instead.
    """
    # time contiguous: every test runs along it
    x = np.ascontiguousarray(x, dtype=float)
    block = max(3, int(round(th.block * sampling_rate)))
    finite = np.isfinite(x)
    gap = qartod.gap_test(time, sampling_rate, th.gap_tolerance)
    # built as bytes (flags.choose), not as int64 then cast; a gap-free time axis (the rule)
    # makes the gap flags those of the missing samples
    if (gap == GOOD).all():
        gap = choose(finite, GOOD, MISSING)
    else:
        gap = np.where(finite, np.broadcast_to(gap.astype(np.uint8), x.shape), np.uint8(MISSING))
    out = {"gap": gap, "gross_range": qartod.gross_range_test(x, gross_range)}
    out["spike"] = qartod.spike_test(x, th.spike_suspect, th.spike_fail, block, floor)
    out["rate_of_change"] = qartod.rate_of_change_test(x, th.rate_of_change, block, floor)
    # runs of repeated values are judged without the spikes, which would cut them in two
    held = fill_gaps(x, out["spike"] != FAIL) if (out["spike"] == FAIL).any() else x
    if flat_line:
        out["flat_line"] = qartod.flat_line_test(held, sampling_rate, th.flat_line_suspect,
                                                 th.flat_line_fail, th.flat_line_tolerance)
    out["dropout"] = qartod.dropout_test(held, sampling_rate, th.dropout, th.hold)
    out["noise"] = qartod.noise_test(x, block, th.noise_autocorrelation, th.noise_share)
    return out


def check_beam(v: np.ndarray, time: np.ndarray, sampling_rate: float, th: Thresholds, *,
               floor: np.ndarray | float = 0.0, amplitude: np.ndarray | None = None,
               gross_range: tuple[float, float] | None = None) -> dict[str, np.ndarray]:
    """Per-test QARTOD flags of a UVP beam's (channel, time) velocities (quantised,
    turbulent, partly without echo): the gap (timing) test of the profiles, broadcast
    (read-only); the gross range test when a range is given; the Goring-Nikora phase-space
    despiking (:func:`flumekit.qc.despike.despike_flags`, which flags the missing samples).

    ``amplitude`` (echo amplitude, same shape): samples whose echo is far above the channel's
    usual one (:func:`~flumekit.qc.qartod.level_test` on the amplitude) see a solid boundary,
    such as the flap crossing the channel, not the fluid; they are not evaluated (2) by the
    despiking and do not enter its statistics, nor do the profiles next to them.
    """
    gap = qartod.gap_test(time, sampling_rate, th.gap_tolerance)
    out = {"gap": np.broadcast_to(choose(gap == FAIL, FAIL, GOOD), v.shape)}
    if gross_range is not None:  # unset, it evaluates nothing
        out["gross_range"] = qartod.gross_range_test(v, gross_range)
    exclude = None
    if amplitude is not None:
        # the level form of the dropout test: runs of repeated echo values say nothing
        # about a boundary
        boundary = qartod.level_fail(amplitude, th.dropout)
        if boundary.any():
            # the sampling volume straddles the boundary for a few profiles either side
            exclude = _widen(boundary, BOUNDARY_PROFILES)
    out["goring_nikora"] = despike_flags(v, floor, th.despike_iterations, exclude=exclude)
    return out


def _widen(mask: np.ndarray, k: int) -> np.ndarray:
    """``mask`` (time along the last axis) with ``k`` samples either side of each True also
    True (a maximum filter of width 2k + 1, by shifts: k is a few profiles)."""
    out = mask.copy()
    for s in range(1, k + 1):
        out[..., s:] |= mask[..., :-s]
        out[..., :-s] |= mask[..., s:]
    return out


def clean(x: np.ndarray, flags: np.ndarray, sampling_rate: float, max_gap: float, *,
          copy: bool = True) -> np.ndarray:
    """Values with FAIL and MISSING samples masked, then linearly interpolated across runs of
    at most ``max_gap`` seconds; longer runs stay NaN. ``copy=False``: ``x`` may be overwritten
    (a record read for the caller alone: no copy of it)."""
    bad = (flags == FAIL) | (flags == MISSING)
    if not bad.any():
        return np.asarray(x, dtype=float)
    return fill_gaps(x, ~bad, max_gap=int(np.floor(max_gap * sampling_rate + 1e-9)), copy=copy)


def qc_dataset(ds: xr.Dataset, name: str, th: Thresholds, *, channel_dim: str | None = None,
               gross_range: tuple[float, float] | None = None, flat_line: bool = True,
               floor=None) -> xr.Dataset:
    """QC of variable ``name`` of ``ds`` (dims (time,) or (channel_dim, time) in any order).

    Returns a dataset with ``name`` cleaned (:func:`clean`) and ``<name>_qc`` (aggregate
    flags), whose attributes ``flagged_by_<test>`` count the samples each test flagged suspect
    or fail, per channel (:func:`flag_counts` counts the aggregate flags). Attribute
    ``<name>_unfilled_gaps`` lists the runs of masked samples longer than ``max_gap``.

    Counts are attributes, not variables: every netCDF variable costs 0.5-1 ms to write,
    whatever its size, and these five would cost the product a quarter of its writing time.
    """
    da = ds[name]
    dims = (channel_dim, "time") if channel_dim else ("time",)
    da = da.transpose(*dims)
    x = np.atleast_2d(da.values.astype(float))
    t = ds["time"].values.astype(float)
    fs = float(ds.attrs.get("sampling_rate") or (t.size - 1) / (t[-1] - t[0]))
    per_test = check_series(x, t, fs, th, gross_range=gross_range, flat_line=flat_line,
                            floor=floor)
    flags = aggregate(*per_test.values())
    cleaned = clean(x, flags, fs, th.max_gap)
    chans = list(da[channel_dim].values) if channel_dim else [name]
    shape = (lambda a: a) if channel_dim else (lambda a: a[0])
    attrs = {k: v for k, v in da.attrs.items()}
    # count_nonzero, not sum: a bool array summed is converted to integers first (5x slower)
    by_test = {f"flagged_by_{k}": shape(np.count_nonzero((f == FAIL) | (f == SUSPECT),
                                                         axis=-1).astype(np.int32))
               for k, f in per_test.items()}
    data = {name: (dims, shape(cleaned), {**attrs, "ancillary_variables": f"{name}_qc",
                                          "comment": "QC'd: failed and missing samples masked, "
                                          f"gaps up to {th.max_gap:g} s interpolated linearly"}),
            f"{name}_qc": (dims, shape(flags), {
                **flag_attrs(name), **by_test,
                "comment": "flagged_by_<test>: samples each QC test flagged suspect or fail"
                + (f", per {channel_dim}" if channel_dim else "")})}
    coords = {"time": ds["time"], **({channel_dim: da[channel_dim]} if channel_dim else {})}
    # built in one call: assigning variable by variable aligned and merged each time, which
    # cost more than the tests themselves on a flap channel
    out = xr.Dataset(data, coords=coords)
    still = np.isnan(cleaned) & ~np.isnan(x)
    spans = [f"{chans[r]} {a:.3f}-{b:.3f} s" for r, a, b in gap_spans(still, t)]
    out.attrs[f"{name}_unfilled_gaps"] = "; ".join(spans)
    return out


def flag_counts(flags: np.ndarray) -> np.ndarray:
    """Samples per QARTOD flag (the order of FLAG_VALUES) along the last axis."""
    # count_nonzero, not sum: a bool array summed is converted to integers first (5x slower);
    # and without an axis where there is one (with one it sums: 3.7 against 0.5 ms a UVP beam)
    if np.ndim(flags) == 1:
        return np.array([np.count_nonzero(flags == v) for v in FLAG_VALUES])
    return np.stack([np.count_nonzero(flags == v, axis=-1) for v in FLAG_VALUES], axis=-1)


def unfilled_gaps(ds: xr.Dataset, name: str) -> list[str]:
    """The runs of masked samples of ``name`` longer than the interpolation limit."""
    text = ds.attrs.get(f"{name}_unfilled_gaps", "")
    return [s for s in text.split("; ") if s]


def beam_flags(beams: dict[str, xr.Dataset], span: tuple[float, float], th: Thresholds, *,
               time_offset: float = 0.0, gross_range: tuple[float, float] | None = None
               ) -> xr.Dataset:
    """QC flags of UVP beam velocities: the aggregate of the tests of :func:`check_beam`, per
    beam, over ``span`` only; the samples outside are neither evaluated nor stored.

    The UVP average reads N waves and the filter's pad either side
    (:func:`flumekit.stages.uvp.build`), so only those samples need checking: there the flow is
    stationary, as the despiking's universal threshold assumes (the ramp-up and the decay are
    not).

    Parameters
    ----------
    beams : Beam name -> beam record (``beam_velocity`` [m s-1] and optionally ``amplitude``
        on (time, channel) or (channel, time), ``time`` [s], attribute
        ``velocity_resolution`` [m s-1]), as read from the ``.mfprof`` files.
    span : (start, end) of the samples checked, on the probes' clock [s].
    th : Thresholds (``despike_iterations``, ``dropout`` for the echo level, ``gap_tolerance``).
    time_offset : Clock offset of the UVP: beam time + offset is on the probes' clock [s].
    gross_range : [min, max] of the velocities [m s-1]; None: not evaluated.

    Returns
    -------
    Dataset with ``beam_velocity_qc_<beam>`` on (channel, time_<beam>), the profiles of the
    beam within ``span`` (each beam keeps its own time axis: beams may differ in profile
    count), the samples per flag of each beam's evaluated span (``beam_velocity_qc_count``)
    and the ``evaluated_span``.
    """
    lo, hi = span
    names = sorted(beams)
    data, coords, counts = {}, {}, []
    for name in names:
        b = beams[name]
        t = b["time"].values
        fs = (t.size - 1) / (t[-1] - t[0])
        tc = t + float(time_offset)  # on the probes' clock
        i0, i1 = int(np.searchsorted(tc, lo)), int(np.searchsorted(tc, hi, side="right"))
        v = b["beam_velocity"].transpose("channel", "time").values[:, i0:i1]
        if i1 - i0 >= 5:
            amp = b["amplitude"].transpose("channel", "time").values[:, i0:i1] \
                if "amplitude" in b else None
            per = check_beam(v, t[i0:i1], fs, th, gross_range=gross_range, amplitude=amp,
                             floor=float(b.attrs.get("velocity_resolution", 0.0)))
            if gross_range is None and not (per["gap"] == FAIL).any():
                # the aggregate without its work: the gap test passes every sample of a
                # gap-free time axis, so a sample the despiking did not evaluate reads pass
                g = per["goring_nikora"]
                f = (g - (g == NOT_EVALUATED).view(np.uint8) * np.uint8(NOT_EVALUATED - GOOD)
                     ).view(np.int8)
            else:
                f = aggregate(*per.values())
        else:  # too short to test
            f = choose(np.isfinite(v), NOT_EVALUATED, MISSING).view(np.int8)
        counts.append(flag_counts(f.view(np.uint8).reshape(-1)))
        tdim = f"time_{name}"
        start = {k: v for k, v in b["time"].attrs.items() if k == "record_start"}
        data[f"beam_velocity_qc_{name}"] = (("channel", tdim), f,
                                            flag_attrs(f"beam_velocity of beam {name}"))
        coords[tdim] = (tdim, t[i0:i1], {
            "units": "s", "long_name": f"time of beam {name} (the profiles checked)", **start})
    c = np.array(counts)
    data["beam_velocity_qc_count"] = (("beam", "flag_meaning"), c, {
        "units": "1", "long_name": "UVP samples of the evaluated span per QC flag"})
    data["evaluated_span"] = (("bound",), np.array([lo, hi]), {
        "units": "s", "long_name": "span of the UVP records checked: the waves the average "
        "reads and the filter's pad (probes' clock)"})
    coords["beam"] = ("beam", names, {"long_name": "UVP transducer name"})
    coords["flag_meaning"] = ("flag_meaning", FLAG_MEANINGS.split(),
                              {"long_name": "QARTOD flag meaning"})
    # built in one call: assigned variable by variable, each aligned and merged anew
    return xr.Dataset(data, coords=coords)
