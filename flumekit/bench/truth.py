"""A built virtual campaign against the virtual flume's truth: errors and tolerances.

Shared by tests/test_virtual_flume_truth.py and the benchmarks (``flumekit bench qc``).

Tolerances (:data:`TOLERANCE`) are the acceptance points of the virtual-flume truth test:
probe gains and offsets 0.1 %; Kr ±0.005 and H_I 0.5 %; theta 0.05° RMS over the
quasi-steady window, C_f 2 %; UVP <u>, <w> within 2 % of U0 RMS over the field, with more
than 30 % of it not masked. Irregular runs (:func:`irregular_errors`): incident Hm0 and Te
within 2 %, Tp 5 %, bulk Kr ±0.02, Kr(f) ±0.05 over the band of 90 % of the incident energy,
mean absorbed power and capture width ratio 5 %, against the truth of the span the pipeline
analysed.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from flumekit.docstrings import filler

#: error: tolerance (each error is below its tolerance, or at most it where marked in
#: :data:`INCLUSIVE`: the relative checks, pytest.approx and assert_allclose's own)
TOLERANCE = {"gain": 1e-3, "offset": 1e-3, "reflection": 5e-3, "incident_height": 5e-3,
             "theta_rms_deg": 0.05, "capture_factor": 0.02, "uvp_rms": 0.02,
             "uvp_coverage": 0.3,
             # irregular runs
             "hm0": 0.02, "energy_period": 0.02, "peak_period": 0.05, "bulk_reflection": 0.02,
             "reflection_spectrum": 0.05, "mean_power": 0.05, "capture_width_ratio": 0.05}
INCLUSIVE = {"gain", "offset", "incident_height", "capture_factor", "hm0", "energy_period",
             "peak_period", "bulk_reflection", "reflection_spectrum", "mean_power",
             "capture_width_ratio"}

#: parameters several checks share
_TRUTH = "truth : pathlib.Path\n    The truth folder."
_doc = filler(truth=_TRUTH, run="run : str\n    Run id.",
              parameters_folders=("Parameters\n----------\nprocessed : pathlib.Path\n"
                                  "    The processed folder of the build.\n" + _TRUTH))


def within(name: str, error: float) -> bool:
    """Return whether ``error`` is within the tolerance of check ``name``.

    Parameters
    ----------
    name : str
        A key of :data:`TOLERANCE`.
    error : float
        The error [unit of the check].

    Returns
    -------
    bool
        ``error`` below the tolerance (or at most it, for the checks in :data:`INCLUSIVE`).

    Examples
    --------
    >>> from flumekit.bench.truth import within
    >>> within("gain", 1e-3), within("reflection", 5e-3)
    (True, False)
    """
    tol = TOLERANCE[name]
    return error <= tol if name in INCLUSIVE else error < tol


def runs(truth: Path) -> list[str]:
    """Return the runs the truth folder describes.

    Parameters
    ----------
    truth : pathlib.Path
        The truth folder of a virtual campaign.

    Returns
    -------
    list of str
        Run ids, sorted.
    """
    return sorted(p.name for p in Path(truth).iterdir() if p.is_dir())


@_doc
def irregular(truth: Path, run: str) -> bool:
    """Return whether a run of the truth folder is an irregular sea state.

    Parameters
    ----------
    %(truth)s
    %(run)s

    Returns
    -------
    bool
        True for an irregular run.
    """
    with _open(Path(truth) / run / "waves.nc") as t:
        return t.attrs.get("kind") == "irregular"


def _open(path: Path):
    import xarray as xr

    return xr.open_dataset(path, decode_times=False)


@_doc
def calibration_errors(processed: Path, truth: Path) -> dict[str, float]:
    """Return the largest relative error of the probes' calibration gains and offsets.

    %(parameters_folders)s

    Returns
    -------
    dict of str to float
        ``gain`` and ``offset`` [-].
    """
    with _open(Path(processed) / "calibration.nc") as cal, \
            _open(Path(truth) / "calibration.nc") as true:
        return {k: float(np.max(np.abs(cal[k].values - true[k].values)
                                / np.abs(true[k].values))) for k in ("gain", "offset")}


@_doc
def waves_errors(processed: Path, truth: Path, run: str) -> dict[str, float]:
    """Return the errors of the reflection coefficient and the incident height of one run.

    %(parameters_folders)s
    %(run)s

    Returns
    -------
    dict of str to float
        ``reflection``: absolute error of Kr [-]; ``incident_height``: relative error of H_I [-].
    """
    with _open(Path(processed) / "waves" / f"{run}.nc") as w, \
            _open(Path(truth) / run / "waves.nc") as t:
        return {"reflection": abs(float(w.reflection_coefficient)
                                  - t.attrs["reflection_coefficient"]),
                "incident_height": abs(float(w.incident_height) / t.attrs["wave_height"] - 1)}


def steady_window(flap) -> np.ndarray:
    """Return the quasi-steady samples of a flap dataset (its ``steady_start``-``steady_end``).

    Parameters
    ----------
    flap : xarray.Dataset
        A flap product (``time`` [s], ``steady_start`` and ``steady_end`` [s]).

    Returns
    -------
    numpy.ndarray
        Boolean mask over ``time``.
    """
    t = flap.time.values
    return (t >= float(flap.steady_start)) & (t <= float(flap.steady_end))


@_doc
def flap_errors(processed: Path, truth: Path, run: str) -> dict[str, float]:
    """Return the errors of theta and the capture factor of one run.

    C_f is compared with the true mean power over the same quasi-steady window over W_I from
    the true height (Eq. A2 of Brito et al. 2020).

    %(parameters_folders)s
    %(run)s

    Returns
    -------
    dict of str to float
        ``theta_rms_deg``: RMS error of theta over the quasi-steady window [deg];
        ``capture_factor``: relative error of C_f [-].
    """
    from flumekit.flap.power import incident_power

    with _open(Path(processed) / "flap" / f"{run}.nc") as f, \
            _open(Path(truth) / run / "flap.nc") as t:
        win = steady_window(f)
        theta = np.degrees(np.sqrt(np.mean((f.theta.values[win] - t.theta.values[win]) ** 2)))
        w_i = incident_power(t.attrs["wave_height_target"], float(f.measured_period), 0.825,
                             1.31)
        c_true = float(np.mean(t.power.values[win])) / float(w_i)
        return {"theta_rms_deg": float(theta),
                "capture_factor": abs(float(f.capture_factor) / c_true - 1)}


@_doc
def uvp_field_errors(processed: Path, truth: Path) -> dict[str, dict[str, float]]:
    """Return the coverage and RMS error of each velocity component of the UVP field.

    %(parameters_folders)s

    Returns
    -------
    dict
        Component (``u``, ``w``) -> {``uvp_coverage``: share of the field not masked [-],
        ``uvp_rms``: RMS error over it relative to U0 [-]}.
    """
    with _open(Path(processed) / "uvp_field.nc") as f, _open(Path(truth) / "uvp_field.nc") as t:
        true = t.interp(z=f.z, x=f.x)
        u0 = float(t.velocity_scale)
        out = {}
        for name in ("u", "w"):
            err = (f[name] - true[name]).values
            ok = np.isfinite(err)
            rms = np.sqrt(np.mean(err[ok] ** 2)) / u0 if ok.any() else np.inf
            out[name] = {"uvp_coverage": float(ok.mean()), "uvp_rms": float(rms)}
        return out


@_doc
def failures(processed: Path, truth: Path, skip_flap=()) -> list[str]:
    """Return every check of this module that the campaign built in ``processed`` fails.

    Calibration gains, Kr and H_I of every regular run, theta and C_f of every regular run not
    in ``skip_flap``, the sea state, Kr, power and capture width ratio of every irregular run,
    the UVP field.

    %(parameters_folders)s
    skip_flap : collection of str
        Runs whose flap is not checked (e.g. one with an injected clock offset).

    Returns
    -------
    list of str
        One message per failed check; empty when all pass.
    """
    fails = []
    gain = calibration_errors(processed, truth)["gain"]
    if not within("gain", gain):
        fails.append(f"calibration gain off by {gain:.2%}")
    for run in runs(truth):
        if irregular(truth, run):
            fails += [f"{run}: {name} off by {error:.4f}" for name, error
                      in irregular_errors(processed, truth, run).items()
                      if not within(name, error)]
            continue
        checks = [(waves_errors, "Kr off by {reflection:.4f}, H_I by {incident_height:.2%}")]
        if run not in skip_flap:
            checks.append((flap_errors, "theta RMS {theta_rms_deg:.3f} deg, C_f off by "
                                        "{capture_factor:.2%}"))
        for errors, message in checks:
            e = errors(processed, truth, run)
            if not all(within(name, error) for name, error in e.items()):
                fails.append(f"{run}: " + message.format(**e))
    for name, e in uvp_field_errors(processed, truth).items():
        if e["uvp_coverage"] <= TOLERANCE["uvp_coverage"] or not within("uvp_rms", e["uvp_rms"]):
            fails.append(f"uvp field {name}: {e['uvp_coverage']:.0%} not masked, RMS "
                         f"{e['uvp_rms']:.2%} of U0")
    return fails


@_doc
def irregular_truth(truth: Path, run: str, span: tuple[float, float],
                    power_span: tuple[float, float] | None = None) -> dict:
    """Return the truth of an irregular run over the span a pipeline analysed.

    The realised sea state at the flap is recomputed from the truth's series at x = 0
    (``flap.nc``) over that span (:func:`flumekit.synth.irregular.sea_state_truth`): over a
    span other than the truth's own (``analysis_start`` to the record's end, one repeat period
    of the wavemaker) the realised Hm0 differs by up to a few per cent. The mean power is the
    flap's p Q over ``power_span``.

    Parameters
    ----------
    %(truth)s
    %(run)s
    span : tuple of float
        [start, end) of the analysis [s].
    power_span : tuple of float, optional
        [start, end) of the mean power [s]; default ``span``.

    Returns
    -------
    dict
        The attributes of ``sea_state_truth`` with ``frequency`` [Hz], ``spectrum_incident`` and
        ``spectrum_reflected`` [m2 s], ``mean_power`` [W] and ``capture_width_ratio`` [-].
    """
    from flumekit.synth.irregular import sea_state_truth

    with _open(Path(truth) / run / "flap.nc") as f, _open(Path(truth) / run / "waves.nc") as w:
        t = f.time.values
        state = sea_state_truth(t, f.eta_incident.values,
                                f.eta_reflected.values + f.eta_beach.values, span,
                                depth=w.attrs["depth"], f_max=float(w.frequency.values[-1]),
                                rho=w.attrs["rho"])
        lo, hi = power_span if power_span is not None else span
        inside = (t >= lo - 1e-9) & (t < hi - 1e-9)
        power = float(np.mean(f.power.values[inside]))
        width = w.attrs["flap_width"]
    return {**state.attrs, "frequency": state.frequency.values,
            "spectrum_incident": state.spectrum_incident.values,
            "spectrum_reflected": state.spectrum_reflected.values, "mean_power": power,
            "capture_width_ratio": power / (state.attrs["energy_flux"] * width)}


@_doc
def irregular_errors(processed: Path, truth: Path, run: str) -> dict[str, float]:
    """Return the errors of an irregular run against its truth over the span the pipeline analysed.

    Relative errors of the incident Hm0, Te and Tp (against the generated peak) at the flap, of
    the mean absorbed power and of the capture width ratio; absolute errors of the bulk Kr and
    the largest of Kr(f) over the band holding the central 90 % of the incident energy, each
    band of the product against sqrt(Σ S_R / Σ S_I) of the truth's periodogram over the same
    band.

    %(parameters_folders)s
    %(run)s

    Returns
    -------
    dict of str to float
        ``hm0``, ``energy_period``, ``peak_period``, ``bulk_reflection``,
        ``reflection_spectrum``, ``mean_power``, ``capture_width_ratio`` [-].
    """
    with _open(Path(processed) / "waves" / f"{run}.nc") as w, \
            _open(Path(processed) / "flap" / f"{run}.nc") as fl:
        span = (float(w.analysis_start), float(w.analysis_end))
        t = irregular_truth(truth, run, span,
                            (float(fl.analysis_start), float(fl.analysis_end)))
        with _open(Path(truth) / run / "waves.nc") as own:
            generated_peak = float(own.attrs["peak_period"])
        f = w.frequency.values
        kr = w.reflection_coefficient_spectrum.values
        half = 0.5 * float(np.median(np.diff(f)))
        ft, s_i, s_r = t["frequency"], t["spectrum_incident"], t["spectrum_reflected"]
        band = (f >= t["energy_band_low"]) & (f <= t["energy_band_high"]) & np.isfinite(kr)
        lower = np.searchsorted(ft, f[band] - half)
        upper = np.searchsorted(ft, f[band] + half)
        cum_i, cum_r = np.r_[0.0, np.cumsum(s_i)], np.r_[0.0, np.cumsum(s_r)]
        true_kr = np.sqrt((cum_r[upper] - cum_r[lower]) / (cum_i[upper] - cum_i[lower]))
        return {"hm0": abs(float(w.hm0) / t["hm0"] - 1),
                "energy_period": abs(float(w.te) / t["energy_period"] - 1),
                # the peak of the sea as generated (the truth's own span is one repeat
                # period: its periodogram is the components'); over another span the largest
                # periodogram bin of the realised sea is one random bin of the leaked spectrum
                "peak_period": abs(float(w.tp) / generated_peak - 1),
                "bulk_reflection": abs(float(w.reflection_coefficient)
                                       - t["reflection_coefficient"]),
                "reflection_spectrum": float(np.max(np.abs(kr[band] - true_kr))),
                "mean_power": abs(float(fl.mean_power) / t["mean_power"] - 1),
                "capture_width_ratio": float(abs(float(fl.capture_width_ratio)
                                                 / t["capture_width_ratio"] - 1))}
