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

from flumekit.docstrings import filler
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

#: docstring text that several functions of this module share
_doc = filler(
    gross_range=("gross_range : tuple of float, optional\n"
                 "    (min, max) of the velocities [m s-1]; None: not evaluated."),
    name=("name : str\n"
          "    The variable checked."),
    th=("th : Thresholds\n"
        "    Thresholds of the tests."))

#: profiles on each side of a boundary echo also left out of the despiking
BOUNDARY_PROFILES = 1


@dataclass(frozen=True)
class Thresholds:
    """Thresholds of the QC tests (the ``[stages.qc]`` parameters).

    The defaults pass clean virtual-flume records untouched (tests/qc measure it).

    Parameters
    ----------
    spike_suspect : float
        Robust local standard deviations of x_n - (x_(n-1) + x_(n+1))/2 beyond which a spike is
        suspect [-] (:func:`~flumekit.qc.qartod.spike_test`).
    spike_fail : float
        The same, beyond which a spike fails [-].
    rate_of_change : float
        Robust local standard deviations of the first difference [-]
        (:func:`~flumekit.qc.qartod.rate_of_change_test`).
    flat_line_suspect : float
        Shortest suspect flat line [s].
    flat_line_fail : float
        Shortest failing flat line [s].
    flat_line_tolerance : float
        Largest step that counts as flat [unit of the channel].
    dropout : float
        Robust standard deviations of the record about its median [-]
        (:func:`~flumekit.qc.qartod.dropout_test`; also the echo-level test of a UVP beam).
    hold : float
        Shortest run of identical values that can be a dropout [s].
    block : float
        Length of the blocks of the local robust scale [s].
    gap_tolerance : float
        A time step longer than (1 + this) / rate is a gap [-].
    max_gap : float
        Longest run of failed samples interpolated [s].
    despike_iterations : int
        Goring-Nikora iterations at most [-].
    noise_autocorrelation : float
        Noise test: lag-one autocorrelation below this [-].
    noise_share : float
        Noise test: and high-frequency energy above this share of the variance [-].

    Examples
    --------
    >>> from flumekit.qc import Thresholds
    >>> Thresholds.from_params({"max_gap": "0.5", "despike_iterations": 2.0}).max_gap
    0.5
    """

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
        """Build the thresholds from ``[stages.qc]`` parameters, each cast to its field's type.

        Parameters
        ----------
        params : dict
            Parameter name -> value; names that are not fields are ignored, fields missing take
            their defaults.

        Returns
        -------
        Thresholds
            The thresholds.
        """
        cast = {"int": int, "float": float}
        return cls(**{f.name: cast[f.type](params[f.name]) for f in fields(cls)
                      if f.name in params})


@_doc
def check_series(x: np.ndarray, time: np.ndarray, sampling_rate: float, th: Thresholds, *,
                 gross_range: tuple[float, float] | None = None, flat_line: bool = True,
                 floor: np.ndarray | float | None = None) -> dict[str, np.ndarray]:
    """Return the per-test QARTOD flags of a (channel, time) block of probe or flap records.

    The tests, time along the last axis: gap, gross range, spike, rate of change, flat line,
    dropout, noise (:mod:`flumekit.qc.qartod`). The flat-line and dropout tests see the record
    with its failed spikes interpolated over, since a spike would cut a run of repeated values
    in two. Velocity records take :func:`check_beam` instead.

    Parameters
    ----------
    x : array_like
        Records (channel, time) or 1-D [any unit].
    %(time)s
    %(sampling_rate)s
    %(th)s
    gross_range : tuple of float, optional
        (min, max) of the sensor [unit of x]; None: not evaluated.
    flat_line : bool
        False skips the flat-line test (a channel whose repeats are legitimate).
    floor : float or numpy.ndarray, optional
        Lower bound of the local scales [unit of x]; None: each channel's resolution.

    Returns
    -------
    dict of str to numpy.ndarray
        Test name (``gap``, ``gross_range``, ``spike``, ``rate_of_change``, ``flat_line``,
        ``dropout``, ``noise``) -> its flags, of x's shape.

    %(references_qartod)s.

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.qc import Thresholds, check_series
    >>> t = np.arange(2000) / 100.0
    >>> x = np.sin(2 * np.pi * t / 2.0)[None]
    >>> x[0, 700] += 1.0
    >>> f = check_series(x, t, 100.0, Thresholds())
    >>> sorted(f), np.flatnonzero(f["spike"] == 4).tolist()
    (['dropout', 'flat_line', 'gap', 'gross_range', 'noise', 'rate_of_change', 'spike'], [700])
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


@_doc
def check_beam(v: np.ndarray, time: np.ndarray, sampling_rate: float, th: Thresholds, *,
               floor: np.ndarray | float = 0.0, amplitude: np.ndarray | None = None,
               gross_range: tuple[float, float] | None = None) -> dict[str, np.ndarray]:
    """Return the per-test QARTOD flags of a UVP beam's (channel, time) velocities.

    The velocities are quantised, turbulent and partly without echo: the gap (timing) test of
    the profiles, broadcast (read-only); the gross range test when a range is given; the
    Goring-Nikora phase-space despiking (:func:`flumekit.qc.despike.despike_flags`, which flags
    the missing samples). Samples whose echo is far above the channel's usual one
    (:func:`~flumekit.qc.qartod.level_test` on ``amplitude``) see a solid boundary, such as the
    flap crossing the channel, not the fluid; they are not evaluated (2) by the despiking and do
    not enter its statistics, nor do the ``BOUNDARY_PROFILES`` profiles next to them.

    Parameters
    ----------
    v : numpy.ndarray
        Velocities (channel, time) [m s-1].
    time : numpy.ndarray
        Profile times [s].
    sampling_rate : float
        Profile rate [Hz].
    th : Thresholds
        Thresholds (``gap_tolerance``, ``dropout``, ``despike_iterations``).
    floor : float or numpy.ndarray
        Velocity resolution [m s-1], one or one per channel.
    amplitude : numpy.ndarray, optional
        Echo amplitude, of v's shape [counts]; None: no boundary test.
    %(gross_range)s

    Returns
    -------
    dict of str to numpy.ndarray
        Test name (``gap``, ``gross_range`` when tested, ``goring_nikora``) -> its flags.

    %(references_goring_nikora2002)s.

    Examples
    --------
    Two channels of an oscillating velocity quantised to the UVP's 0.7 mm s-1, 50 profiles a
    second; channel 1 has one spike, and the echo of channel 0 rises far above its usual level
    for 0.1 s, as when the flap crosses the beam. The spike fails (4); the samples at the
    boundary and one profile either side are not evaluated (2).

    >>> import numpy as np
    >>> from flumekit.qc import Thresholds, check_beam
    >>> t = np.arange(500) / 50.0
    >>> phase = np.array([[0.0], [1.0]])
    >>> v = np.round(0.1 * np.sin(2 * np.pi * t / 3.5 + phase) / 0.7e-3) * 0.7e-3
    >>> v[1, 200] = 0.5
    >>> echo = 40.0 + np.random.default_rng(1).integers(-3, 4, v.shape)
    >>> echo[0, 300:305] = 200.0
    >>> f = check_beam(v, t, 50.0, Thresholds(), floor=0.7e-3, amplitude=echo)
    >>> sorted(f), np.argwhere(f["goring_nikora"] == 4).tolist()
    (['gap', 'goring_nikora'], [[1, 200]])
    >>> np.flatnonzero(f["goring_nikora"][0] == 2).tolist()
    [299, 300, 301, 302, 303, 304, 305]
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
    """Return ``mask`` (time along the last axis) with ``k`` samples either side of each True set.

    A maximum filter of width 2k + 1, by shifts: k is a few profiles.
    """
    out = mask.copy()
    for s in range(1, k + 1):
        out[..., s:] |= mask[..., :-s]
        out[..., :-s] |= mask[..., s:]
    return out


@_doc
def clean(x: np.ndarray, flags: np.ndarray, sampling_rate: float, max_gap: float, *,
          copy: bool = True) -> np.ndarray:
    """Mask the FAIL and MISSING samples of a record and interpolate across short runs of them.

    Runs of at most ``max_gap`` seconds are interpolated linearly
    (:func:`~flumekit.qc.fill.fill_gaps`); longer runs stay NaN.

    Parameters
    ----------
    %(record)s
    flags : numpy.ndarray
        QARTOD flags, of x's shape.
    %(sampling_rate)s
    max_gap : float
        Longest run interpolated [s].
    copy : bool
        False: ``x`` may be overwritten (a record read for the caller alone: no copy of it).

    Returns
    -------
    numpy.ndarray
        The cleaned record [unit of x].

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.qc import clean
    >>> clean(np.array([0.0, 5.0, 2.0, 3.0]), np.array([1, 4, 1, 9]), 10.0, 0.1).tolist()
    [0.0, 1.0, 2.0, 2.0]
    """
    bad = (flags == FAIL) | (flags == MISSING)
    if not bad.any():
        return np.asarray(x, dtype=float)
    return fill_gaps(x, ~bad, max_gap=int(np.floor(max_gap * sampling_rate + 1e-9)), copy=copy)


@_doc
def qc_dataset(ds: xr.Dataset, name: str, th: Thresholds, *, channel_dim: str | None = None,
               gross_range: tuple[float, float] | None = None, flat_line: bool = True,
               floor=None) -> xr.Dataset:
    """Run the QC of variable ``name`` of ``ds``: flags, masking and filling.

    :func:`check_series`, the flags aggregated (:func:`~flumekit.qc.flags.aggregate`), then
    :func:`clean` with ``th.max_gap``. The values as read are not repeated (the raw file holds
    them). Counts are attributes, not variables: every netCDF variable costs a fixed time to
    write, whatever its size.

    Parameters
    ----------
    ds : xarray.Dataset
        Dataset with ``name`` on (time,) or (channel_dim, time) in any order, coordinate
        ``time`` [s] and optionally attribute ``sampling_rate`` [Hz] (else from the time axis).
    %(name)s
    %(th)s
    channel_dim : str, optional
        Channel dimension of ``name``; None: one channel.
    gross_range : tuple of float, optional
        (min, max) of the sensor [unit of the variable]; None: not evaluated.
    flat_line : bool
        False skips the flat-line test.
    floor : float or numpy.ndarray, optional
        Lower bound of the local scales [unit of the variable]; None: each channel's resolution.

    Returns
    -------
    xarray.Dataset
        ``name`` cleaned and ``<name>_qc`` (aggregate flags, CF flag attributes), whose
        attributes ``flagged_by_<test>`` count the samples each test flagged suspect or fail, per
        channel (:func:`flag_counts` counts the aggregate flags). Attribute
        ``<name>_unfilled_gaps`` lists the runs of masked samples longer than ``max_gap``
        (:func:`unfilled_gaps`).

    Examples
    --------
    >>> import numpy as np
    >>> import xarray as xr
    >>> from flumekit.qc import Thresholds, qc_dataset
    >>> t = np.arange(2000) / 100.0
    >>> eta = np.sin(2 * np.pi * t / 2.0)
    >>> eta[700] += 1.0
    >>> out = qc_dataset(xr.Dataset({"eta": ("time", eta)}, coords={"time": t}), "eta",
    ...                  Thresholds())
    >>> int(out.eta_qc[700]), round(float(out.eta[700]), 6) == round(float(np.sin(7 * np.pi)), 6)
    (4, True)
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
    # count_nonzero, not sum: a bool array summed is converted to integers first
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
    # built in one call: assigning variable by variable aligns and merges each time
    out = xr.Dataset(data, coords=coords)
    still = np.isnan(cleaned) & ~np.isnan(x)
    spans = [f"{chans[r]} {a:.3f}-{b:.3f} s" for r, a, b in gap_spans(still, t)]
    out.attrs[f"{name}_unfilled_gaps"] = "; ".join(spans)
    return out


def flag_counts(flags: np.ndarray) -> np.ndarray:
    """Count the samples per QARTOD flag along the last axis.

    Parameters
    ----------
    flags : numpy.ndarray
        QARTOD flags.

    Returns
    -------
    numpy.ndarray
        Counts, the flag along the last axis in the order of
        :data:`~flumekit.qc.flags.FLAG_VALUES` (1, 2, 3, 4, 9).

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.qc import flag_counts
    >>> flag_counts(np.array([1, 1, 4, 9], np.int8)).tolist()
    [2, 0, 0, 1, 1]
    """
    # count_nonzero, not sum: a bool array summed is converted to integers first; and
    # without an axis where there is one (given an axis, count_nonzero sums)
    if np.ndim(flags) == 1:
        return np.array([np.count_nonzero(flags == v) for v in FLAG_VALUES])
    return np.stack([np.count_nonzero(flags == v, axis=-1) for v in FLAG_VALUES], axis=-1)


@_doc
def unfilled_gaps(ds: xr.Dataset, name: str) -> list[str]:
    """Return the runs of masked samples of ``name`` longer than the interpolation limit.

    Parameters
    ----------
    ds : xarray.Dataset
        A dataset written by :func:`qc_dataset`.
    %(name)s

    Returns
    -------
    list of str
        One text per run ("<channel> <start>-<end> s"), empty when every gap was filled.
        Samples missing from the record as read are not among them (their flag says missing).

    Examples
    --------
    Two probes at 100 Hz; WP2 reads 0.5 m for 0.03 s (spikes: failed, then interpolated,
    ``max_gap`` being 0.2 s), then holds its value for a second (a dropout: failed, too long
    to interpolate, left NaN):

    >>> import numpy as np
    >>> import xarray as xr
    >>> from flumekit.qc import Thresholds, qc_dataset, unfilled_gaps
    >>> t = np.arange(1000) / 100.0
    >>> eta = np.cos(2 * np.pi * t / 2.5) * [[0.05], [0.04]]
    >>> eta[1, 200:203] = 0.5
    >>> eta[1, 500:600] = eta[1, 500]
    >>> ds = xr.Dataset({"eta": (("probe", "time"), eta)},
    ...                 coords={"time": t, "probe": ["WP1", "WP2"]})
    >>> unfilled_gaps(qc_dataset(ds, "eta", Thresholds(), channel_dim="probe"), "eta")
    ['WP2 5.000-6.000 s']
    """
    text = ds.attrs.get(f"{name}_unfilled_gaps", "")
    return [s for s in text.split("; ") if s]


@_doc
def beam_flags(beams: dict[str, xr.Dataset], span: tuple[float, float], th: Thresholds, *,
               time_offset: float = 0.0, gross_range: tuple[float, float] | None = None
               ) -> xr.Dataset:
    """Return the QC flags of UVP beam velocities over ``span`` only.

    The aggregate of the tests of :func:`check_beam`, per beam; the samples outside ``span``
    are neither evaluated nor stored. The UVP average reads N waves and the filter's pad either
    side (:mod:`flumekit.uvp.run_window`), so only those samples need checking: there the flow
    is stationary, as the despiking's universal threshold assumes (the ramp-up and the decay are
    not).

    Parameters
    ----------
    beams : dict of str to xarray.Dataset
        Beam name -> beam record (``beam_velocity`` [m s-1] and optionally ``amplitude`` on
        (time, channel) or (channel, time), ``time`` [s], attribute ``velocity_resolution``
        [m s-1]), as read from the ``.mfprof`` files.
    span : tuple of float
        (start, end) of the samples checked, on the probes' clock [s].
    th : Thresholds
        Thresholds (``despike_iterations``, ``dropout`` for the echo level, ``gap_tolerance``).
    time_offset : float
        Clock offset of the UVP: beam time + offset is on the probes' clock [s].
    %(gross_range)s

    Returns
    -------
    xarray.Dataset
        ``beam_velocity_qc_<beam>`` on (channel, time_<beam>), the profiles of the beam within
        ``span`` (each beam keeps its own time axis: beams may differ in profile count), the
        samples per flag of each beam's evaluated span (``beam_velocity_qc_count`` on (beam,
        flag_meaning)) and the ``evaluated_span`` [s].

    Examples
    --------
    A beam of three channels, 20 profiles a second for 10 s, on a clock 0.5 s behind the
    probes'. The span 2-4 s of the probes' clock keeps the beam's profiles of 1.5-3.5 s (41 of
    them); of its two spikes, the one at 2.5 s fails, the one at 8 s is not even looked at.

    >>> import numpy as np
    >>> import xarray as xr
    >>> from flumekit.qc import Thresholds, beam_flags
    >>> t = np.arange(200) / 20.0
    >>> u = np.round(np.cos(np.pi * t) * np.array([[0.05], [0.08], [0.1]]), 3)
    >>> u[2, [50, 160]] = 0.9
    >>> beam = xr.Dataset({"beam_velocity": (("channel", "time"), u)}, coords={"time": t},
    ...                   attrs={"velocity_resolution": 1e-3})
    >>> qc = beam_flags({"UP1": beam}, (2.0, 4.0), Thresholds(), time_offset=0.5)
    >>> qc["time_UP1"].values[[0, -1]].tolist(), qc.sizes["time_UP1"]
    ([1.5, 3.5], 41)
    >>> qc["flag_meaning"].values.tolist(), qc["beam_velocity_qc_count"].values.tolist()
    (['pass', 'not_evaluated', 'suspect', 'fail', 'missing_data'], [[122, 0, 0, 1, 0]])
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
