"""Benchmark: incident/reflected separation, run time against error.

Knobs that trade time for accuracy: record length, analysis band, taper (window), regular-wave
statistics, wavenumbers (linear or nonlinear); and the stream-function solve's number of modes.
Records are virtual-flume waves (3 probes at the paper's L/10, L/4 layout, 25 Hz, 0.5 mm probe
noise) with a known truth. Target: a 10-minute 3-probe record in under 10 ms.
"""

from __future__ import annotations

import time

import numpy as np
import xarray as xr

from flumekit.synth.waves import irregular_wave_field, regular_wave_field
from flumekit.waves import probe_spacing, separate

DEPTH = 0.825
FS = 25.0


def _probes(field: xr.Dataset, rng: np.random.Generator) -> xr.DataArray:
    eta = field.eta.values + rng.normal(0.0, 5e-4, field.eta.shape)
    return xr.DataArray(eta, dims=("probe", "time"),
                        coords={"x": ("probe", field.x.values), "time": field.time.values})


def _time(fn, repeats: int) -> tuple[float, float]:
    """Median and best wall time [s] (the machine is shared: the best is the cost of the code)."""
    fn()  # warm-up
    out = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        out.append(time.perf_counter() - t0)
    return float(np.median(out)), float(np.min(out))


def run(quick: bool = False) -> str:
    """Run the benchmark and return the tables as text.

    Parameters
    ----------
    quick : bool
        Fewer record lengths, seeds and repeats.

    Returns
    -------
    str
        The printed report: the separation's knobs, the irregular-run analysis, the comparison
        with the Deltares wave toolbox and the stream-function solve.

    References
    ----------
    Mansard, E. P. D. and Funke, E. R. (1980). The measurement of incident and reflected spectra
    using a least squares method. Proc. 17th Int. Conf. Coastal Eng., 154-172.

    Zelt, J. A. and Skjelbreia, J. E. (1992). Estimating incident and reflected wave fields
    using an arbitrary number of wave gauges. Proc. 23rd Int. Conf. Coastal Eng., 777-789.
    """
    repeats = 5 if quick else 25
    seeds = [3] if quick else [3, 4, 5, 6]
    tp, hm0, kr = 2.5, 0.12, 0.25
    x12, x23 = probe_spacing(tp, DEPTH)
    x = np.array([-6.0, -6.0 + x12, -6.0 + x12 + x23])
    rows = []
    minutes = [2.5, 10.0] if quick else [1.0, 2.5, 5.0, 10.0, 20.0]
    for length in minutes:
        t = np.arange(int(length * 60 * FS)) / FS
        data = [_probes(irregular_wave_field(t, x, hm0=hm0, peak_period=tp, depth=DEPTH,
                                             reflection=kr, rng=s), np.random.default_rng(s))
                for s in seeds]
        for band in (None, (0.2, 1.2)):
            for window in (None, "hann"):
                kw = dict(band=band, window=window)
                res = [separate(d, DEPTH, **kw) for d in data]
                e_kr = np.sqrt(np.mean([(float(r.reflection_coefficient) - kr) ** 2 for r in res]))
                e_h = np.sqrt(np.mean([(float(r.incident_height) / hm0 - 1) ** 2 for r in res]))
                dt = _time(lambda d=data[0], kw=kw: separate(d, DEPTH, **kw), repeats)
                label = "all" if band is None else f"{band[0]}-{band[1]} Hz"
                rows.append(("JONSWAP", length, label, window or "none", dt[0] * 1e3,
                             dt[1] * 1e3, e_kr, 100 * e_h))
    # regular waves, Kr = 0.1, statistics from the harmonic fit
    for length in ([10.0] if quick else [2.5, 10.0]):
        period = 3.5
        x12, x23 = probe_spacing(period, DEPTH)
        xr_ = np.array([-6.0, -6.0 + x12, -6.0 + x12 + x23])
        n = int(round(int(length * 60 / period / 2) * 2 * period * FS))  # whole periods
        t = 300 * period + np.arange(n) / FS
        d = _probes(regular_wave_field(t, xr_, period=period, height=0.2, depth=DEPTH,
                                       reflection=0.1, theory="stokes2"),
                    np.random.default_rng(0))
        for bound in (False, True):
            kw = dict(regular=True, period=period, bound_harmonics=bound,
                      band=(0.5 / period, 4.5 / period), x_ref=0.0)
            r = separate(d, DEPTH, **kw)
            dt = _time(lambda d=d, kw=kw: separate(d, DEPTH, **kw), repeats)
            rows.append((f"regular{' bound' if bound else ''}", length, "4 harmonics", "none",
                         dt[0] * 1e3, dt[1] * 1e3, abs(float(r.reflection_coefficient) - 0.1),
                         100 * abs(float(r.incident_height) / 0.2 - 1)))
        # the flume's stream-function wave (Ursell 34): the linear wavenumber against the
        # nonlinear ones of the incident and reflected waves (amplitude dispersion)
        field = regular_wave_field(t, xr_, period=period, height=0.2, depth=DEPTH,
                                   reflection=0.1)
        d = _probes(field, np.random.default_rng(0))
        for label, ks in (("stream lin k", None),
                          ("stream nl k", (field.attrs["wave_number"],
                                           field.attrs["reflected_wave_number"]))):
            kw = dict(regular=True, period=period, bound_harmonics=True, wavenumbers=ks,
                      band=(0.5 / period, 8.5 / period), x_ref=0.0)
            r = separate(d, DEPTH, **kw)
            dt = _time(lambda d=d, kw=kw: separate(d, DEPTH, **kw), repeats)
            rows.append((label, length, "8 harmonics", "none", dt[0] * 1e3, dt[1] * 1e3,
                         abs(float(r.reflection_coefficient) - 0.1),
                         100 * abs(float(r.incident_height) / 0.2 - 1)))
    head = (f"{'waves':<14}{'record':>8}{'band':>14}{'window':>8}{'median':>9}{'best':>8}"
            f"{'|dKr|':>9}{'dH/H':>8}\n{'':<14}{'[min]':>8}{'':>14}{'':>8}{'[ms]':>9}{'[ms]':>8}"
            f"{'[-]':>9}{'[%]':>8}")
    lines = [f"{w:<14}{m:>8.1f}{b:>14}{win:>8}{med:>9.2f}{best:>8.2f}{ek:>9.4f}{eh:>8.2f}"
             for w, m, b, win, med, best, ek, eh in rows]
    ten = [r[4] for r in rows if r[0] == "JONSWAP" and r[1] == 10.0 and r[3] == "none"]
    note = (f"separation of a 10-min, 3-probe, 25 Hz record: median {min(ten):.2f}-{max(ten):.2f}"
            f" ms (target < 10 ms). Errors: RMS over {len(seeds)} seed(s), 0.5 mm probe noise; H"
            " is Hm0 for JONSWAP, crest-to-trough for regular waves (Kr = 0.1, H = 0.2 m, T = 3.5"
            " s; 'regular': second-order Stokes, 'stream': the stream-function wave separated "
            "with the linear or the true nonlinear wavenumbers). The synthetic JONSWAP records are "
            "periodic with deterministic amplitudes, so the untapered transform is exact and a "
            "Hann taper only adds sampling variability (wave groups weighted unevenly); on real "
            "records it reduces leakage.")
    return "\n".join([head, *lines, note, "", _irregular_table(quick),
                      "", _toolbox_table(repeats), "", _stream_function_table(repeats)])


def _irregular_table(quick: bool) -> str:
    """Return the errors and run time of the irregular-run analysis against its knobs.

    :func:`flumekit.waves.analyse_irregular_run`: errors of Hm0, Te, Tp and the bulk Kr against
    the record length, the smoothing (bins per band) and the number of probes, with its run
    time; and the separation's cost in FFTs of the record.

    Records: linear JONSWAP seas (Hm0 0.12 m, Tp 2.5 s, gamma 3.3, Kr 0.25) at probes 6 m
    before the reflector, 25 Hz, 0.5 mm noise. The truth is the incident wave's exact
    spectrum (its components lie on the record's Fourier bins).
    """
    from flumekit.waves import analyse_irregular_run, spectral_parameters

    tp, hm0, kr = 2.5, 0.12, 0.25
    x12, x23 = probe_spacing(tp, DEPTH)
    layouts = {2: [-6.0, -6.0 + x12], 3: [-6.0, -6.0 + x12, -6.0 + x12 + x23],
               4: [-6.0, -6.0 + x12, -6.0 + x12 + x23, -1.5]}
    seeds = [3] if quick else [3, 4, 5, 6]
    cases = [(m, 3, None) for m in ((10.0, 30.0) if quick else (5.0, 10.0, 20.0, 30.0))]
    cases += [(10.0, 3, nb) for nb in ((8, 32) if quick else (4, 8, 16, 32, 64))]
    cases += [(10.0, p, None) for p in (2, 4)]
    rows = []
    for minutes, probes, n_bins in cases:
        t = np.arange(int(minutes * 60 * FS)) / FS
        x = np.array(layouts[probes])
        err = []
        for s in seeds:
            field = irregular_wave_field(t, x, hm0=hm0, peak_period=tp, depth=DEPTH,
                                         reflection=kr, rng=s)
            eta = _probes(field, np.random.default_rng(s))
            inc = field.eta_incident.values[0]
            f = np.fft.rfftfreq(t.size, 1 / FS)
            spec = np.abs(np.fft.rfft(inc)) ** 2 * 2 / (t.size ** 2 * f[1])
            truth = spectral_parameters(xr.DataArray(spec[1:], dims="frequency",
                                                     coords={"frequency": f[1:]}))
            r = analyse_irregular_run(eta, DEPTH, x_ref=float(x[0]), span=(0.0, None),
                                      n_bins=n_bins, method="zelt_skjelbreia")
            err.append((float(r.hm0) / float(truth.hm0) - 1, float(r.te) / float(truth.tm_10)
                        - 1, float(r.tp) / float(truth.tp) - 1,
                        float(r.reflection_coefficient) - kr))
        e = np.sqrt(np.mean(np.square(err), axis=0))
        dt = _time(lambda eta=eta, x=x, n_bins=n_bins: analyse_irregular_run(
            eta, DEPTH, x_ref=float(x[0]), span=(0.0, None), n_bins=n_bins), 3)
        rows.append(f"{minutes:>8.0f}{probes:>7}{n_bins or 'auto':>7}{dt[1] * 1e3:>9.1f}"
                    f"{100 * e[0]:>8.2f}{100 * e[1]:>8.2f}{100 * e[2]:>8.2f}{e[3]:>8.4f}")
    # the separation alone, against the FFT of the record: the 30-minute, 3-probe case
    t = np.arange(int(30 * 60 * FS)) / FS
    x = np.array(layouts[3])
    eta = _probes(irregular_wave_field(t, x, hm0=hm0, peak_period=tp, depth=DEPTH,
                                       reflection=kr, rng=3), np.random.default_rng(3))
    v = eta.values
    fft = _time(lambda: np.fft.rfft(v, axis=1), 20)[1]
    band = _time(lambda: separate(eta, DEPTH, method="zelt_skjelbreia", regular=False,
                                  band=(0.5 / tp, 4.0 / tp)), 10)[1]
    whole = _time(lambda: separate(eta, DEPTH, method="zelt_skjelbreia", regular=False), 10)[1]
    head = (f"{'irregular':<8}{'probes':>7}{'bins':>7}{'best':>9}{'dHm0':>8}{'dTe':>8}{'dTp':>8}"
            f"{'|dKr|':>8}\n{'[min]':<8}{'':>7}{'':>7}{'[ms]':>9}{'[%]':>8}{'[%]':>8}{'[%]':>8}"
            f"{'[-]':>8}")
    note = (f"RMS errors over {len(seeds)} seed(s) of analyse_irregular_run (span from the start,"
            " the record being periodic; bins: periodogram bins per band of the smoothed "
            "spectrum, auto = fp/16; Tp from the smoothed spectrum, its error the band's width). "
            f"Separating the 30-min, 3-probe, 25 Hz record: {band * 1e3:.2f} ms over the "
            f"analysis band 0.5-4 fp ({band / fft:.1f} FFTs of the 3-probe record, one FFT "
            f"{fft * 1e3:.2f} ms), {whole * 1e3:.2f} ms over every bin to the Nyquist frequency "
            f"({whole / fft:.1f} FFTs).")
    return "\n".join([head, *rows, note])


def _toolbox_table(repeats: int) -> str:
    """Time ``separate`` against the Deltares wave toolbox's Zelt & Skjelbreia separation.

    ``separate`` with its defaults against ``decompose_linear_ZS`` (the Mansard-Funke least
    squares with three probes) on the same 10-minute, 3-probe, 25 Hz regular record, timed in
    the same run.

    The toolbox is not a dependency of flumekit: install it for the bench only
    (``pip install deltares-wave-toolbox``); without it the row says so.
    """
    period = 3.5
    x12, x23 = probe_spacing(period, DEPTH)
    x = np.array([-6.0, -6.0 + x12, -6.0 + x12 + x23])
    t = np.arange(int(10 * 60 * FS)) / FS
    d = _probes(regular_wave_field(t, x, period=period, height=0.2, depth=DEPTH,
                                   reflection=0.1, theory="stokes2"), np.random.default_rng(0))
    fns = {"ours": lambda: separate(d, DEPTH),
           "irregular": lambda: separate(d, DEPTH, regular=False)}
    try:
        from deltares_wave_toolbox.cores.core_wave_decomposition import decompose_linear_ZS
    except ImportError:
        decompose_linear_ZS = None
    else:
        series = np.ascontiguousarray(d.values.T)
        fns["theirs"] = lambda: decompose_linear_ZS(d.time.values, series, DEPTH, x, np.ones(3))
    # interleaved, so that a ratio compares the codes under one load of a shared machine
    times = _time_interleaved(fns, max(11, repeats))
    ours, irregular = times["ours"], times["irregular"]
    rows = [f"{'10-min regular record, 3 probes, 25 Hz':<44}{'median':>9}{'best':>8}",
            f"{'':<44}{'[ms]':>9}{'[ms]':>8}",
            f"{'flumekit separate (defaults: regular)':<44}{ours[0] * 1e3:>9.2f}"
            f"{ours[1] * 1e3:>8.2f}",
            f"{'flumekit separate (regular=False)':<44}{irregular[0] * 1e3:>9.2f}"
            f"{irregular[1] * 1e3:>8.2f}"]
    if decompose_linear_ZS is None:
        rows.append("Deltares wave toolbox: not installed (pip install deltares-wave-toolbox "
                    "for this comparison)")
        return "\n".join(rows)
    theirs = times["theirs"]
    rows.append(f"{'Deltares wave toolbox decompose_linear_ZS':<44}{theirs[0] * 1e3:>9.2f}"
                f"{theirs[1] * 1e3:>8.2f}")
    rows.append(f"separate is {theirs[0] / ours[0]:.1f} times faster than the toolbox (medians; "
                f"{theirs[1] / ours[1]:.1f} on the best times; regular=False "
                f"{theirs[0] / irregular[0]:.1f}); the toolbox returns the time series only. "
                f"Timed in {max(11, repeats)} interleaved rounds.")
    return "\n".join(rows)


def _time_interleaved(fns: dict, rounds: int) -> dict:
    """Median and best wall time [s] of each function, timed in interleaved rounds.

    Each round calls every function once, in an order that rotates from round to round, so
    that the load of a shared machine weighs on each alike and their ratios compare the codes.
    """
    for fn in fns.values():
        fn()  # warm-up
    names = list(fns)
    out = {name: [] for name in names}
    for r in range(rounds):
        for name in names[r % len(names):] + names[:r % len(names)]:
            t0 = time.perf_counter()
            fns[name]()
            out[name].append(time.perf_counter() - t0)
    return {name: (float(np.median(v)), float(np.min(v))) for name, v in out.items()}


def _stream_function_table(repeats: int) -> str:
    """Return the run time of the stream-function solve against the number of modes N.

    Errors against N = 40, for the flume's most nonlinear wave (T = 4 s, H = 0.3 m, Ursell 72).
    """
    from flumekit.waves.stream_function import stream_function_wave

    ref = stream_function_wave(4.0, 0.3, DEPTH, n_modes=40)
    rows = [f"{'stream fn N':<14}{'median':>9}{'best':>8}{'|dE1|':>10}{'|dcrest|':>10}"
            f"{'|dk|/k':>10}\n{'':<14}{'[ms]':>9}{'[ms]':>8}{'[m]':>10}{'[m]':>10}{'[-]':>10}"]
    for n in (8, 12, 16, 20, 28):
        w = stream_function_wave(4.0, 0.3, DEPTH, n_modes=n)
        med, best = _time(lambda n=n: stream_function_wave(4.0, 0.3, DEPTH, n_modes=n), repeats)
        rows.append(f"{n:<14}{med * 1e3:>9.2f}{best * 1e3:>8.2f}"
                    f"{abs(w.elevation_coefficients[0] - ref.elevation_coefficients[0]):>10.1e}"
                    f"{abs(w.elevation(0.0) - ref.elevation(0.0)):>10.1e}"
                    f"{abs(w.wavenumber / ref.wavenumber - 1):>10.1e}")
    rows.append("one solve per run (the virtual flume uses N = 20, cached); evaluating η, u, w is "
                "vectorised over (x, z, t).")
    return "\n".join(rows)


if __name__ == "__main__":
    print(run())
