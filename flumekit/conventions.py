"""The one registry of variable names, units and CF attributes used by every flumekit dataset.

Every variable or coordinate that flumekit writes has an entry here; :func:`annotate` applies the
entries to a dataset and :func:`check` refuses a dataset with a variable lacking units or a long
name. Units follow UDUNITS spelling. ``time`` is seconds since the start of a record (see
:mod:`flumekit.io.netcdf`).
"""

from __future__ import annotations

import contextvars
import functools
import hashlib
import json
from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # imported where a dataset is made: the names alone need no xarray
    import xarray as xr

CONVENTIONS = "CF-1.8"
#: attribute of a ``time`` coordinate: the instant of time 0, ISO 8601 (ending in ``Z`` when in
#: UTC; without a zone, the recording computer's clock), from the raw file or the run's
#: ``start`` in run.toml; written as the origin of the time units (``seconds since ...``)
RECORD_START = "record_start"
#: its value in a file when neither the raw file nor the run says when the record started
UNKNOWN_START = "unknown"
#: global attribute: newline-separated warnings of the analysis that wrote a dataset, kept by
#: every stage that reads it and by the campaign summaries (each line naming its run)
WARNINGS = "flumekit_warnings"
#: global attribute: the raw file a dataset was read or quality-controlled from
SOURCE_FILE = "source_file"
#: global attribute of a quality-controlled product: the longest run of failed samples that
#: is interpolated [s] (masked spans longer than this stay NaN)
MAX_GAP = "max_gap"


def run_warnings(run: str | None, text: str) -> list[str]:
    r"""Return the lines of a :data:`WARNINGS` attribute, each naming its run.

    A line starts with ``run <run>: `` when ``run`` is given and the line does not name it
    already.

    Parameters
    ----------
    run : str or None
        The run the warnings are of; None leaves the lines as they are.
    text : str
        The attribute's value (newline-separated warnings).

    Returns
    -------
    list of str
        The non-blank lines.

    Examples
    --------
    >>> run_warnings("r1", "probe WP2 flat\nrun r1: gap")
    ['run r1: probe WP2 flat', 'run r1: gap']
    """
    lines = [w for w in text.splitlines() if w.strip()]
    if not run:
        return lines
    return [w if run in w else f"run {run}: {w}" for w in lines]


def record_start(ds: xr.Dataset | xr.DataArray, axis: str = "time") -> str | None:
    """Return the start of the record a time axis counts from.

    Parameters
    ----------
    ds : xarray.Dataset or xarray.DataArray
        The dataset.
    axis : str, default "time"
        The time coordinate.

    Returns
    -------
    str or None
        The ISO 8601 :data:`RECORD_START` of the axis (ending in ``Z`` when in UTC); None
        when the axis is absent or its start is not known.

    Examples
    --------
    >>> import xarray as xr
    >>> ds = xr.Dataset(coords={"time": ("time", [0.0, 0.1],
    ...                                  {"record_start": "2024-03-05T10:12:00Z"})})
    >>> record_start(ds), record_start(ds, "x")
    ('2024-03-05T10:12:00Z', None)
    """
    if axis not in ds.coords:
        return None
    v = ds[axis].attrs.get(RECORD_START)
    return None if v in (None, "", UNKNOWN_START) else str(v)


@dataclass(frozen=True)
class Variable:
    """The registered attributes of a variable name.

    Parameters
    ----------
    units : str
        UDUNITS spelling (``"1"`` for dimensionless and labels).
    long_name : str
        CF long name.
    standard_name : str, optional
        CF standard name, where one exists.
    """

    units: str
    long_name: str
    standard_name: str | None = None

    def attrs(self) -> dict[str, str]:
        """Return the CF attributes: ``units``, ``long_name`` and ``standard_name`` if any."""
        out = {"units": self.units, "long_name": self.long_name}
        if self.standard_name:
            out["standard_name"] = self.standard_name
        return out


_V = Variable

#: name -> attributes. Sections are per domain; add new names to the section of their domain.
VARIABLES: dict[str, Variable] = {
    # --- coordinates and run parameters ---
    "time": _V("s", "time since start of record", "time"),
    "probe": _V("1", "wave probe name"),
    "channel": _V("1", "UVP channel index along the beam"),
    "beam": _V("1", "UVP transducer name"),
    "run": _V("1", "run identifier"),
    "source": _V("1", "origin of the values: experiment, analytical (linear) model or simulator"),
    "x": _V("m", "longitudinal position (x = 0 at the flap hinge, positive towards the beach)"),
    "y": _V("m", "lateral position (y = 0 on the flume centre plane)"),
    "z": _V("m", "elevation above the hinge axis (z = 0 at the hinge, 0.1 m above the bed)"),
    "frequency": _V("Hz", "frequency"),
    "angular_frequency": _V("rad s-1", "angular frequency"),
    "phase": _V("1", "wave phase as a fraction of the period, t/T"),
    "level": _V("m", "static calibration water level relative to the still-water level"),
    "wave_period": _V("s", "target wave period"),
    "wave_height": _V("m", "target wave height"),
    "wave_hm0": _V("m", "target significant wave height Hm0 of an irregular run"),
    "wave_tp": _V("s", "target peak period of an irregular run"),
    "wave_te": _V("s", "target energy period Tm-1,0 of an irregular run"),
    "repeat": _V("1", "repeat number of the test condition"),
    "uvp_elevation": _V("m", "elevation of the horizontal UVP transducer (UP2)"),
    "sampling_rate": _V("Hz", "sampling rate"),
    "polynomial_order": _V("1", "power of the calibration polynomial term"),
    # --- raw instruments ---
    "probe_voltage": _V("V", "wave probe output voltage"),
    "probe_elevation": _V("m", "water surface elevation recorded by a calibrated wave probe, "
                          "still-water level not removed"),
    "still_water_level": _V("m", "still-water level removed from the probe's record"),
    "encoder_counts": _V("1", "wire encoder count"),
    "wire_shortening": _V("m", "shortening of the encoder measuring wire, Delta L7"),
    "chamber_pressure": _V("Pa", "gauge pressure in the PTO cylinder chamber",
                           "sea_water_pressure"),
    "calibration_voltage": _V("V", "probe voltage at a static calibration level"),
    # --- calibration ---
    # c_n has the unit m V-n, which differs per order: UDUNITS has no such unit, so the
    # variable is declared dimensionless and its long name says the unit of each c_n
    "calibration_coefficients": _V("1", "calibration polynomial coefficients, eta = sum c_n V^n "
                                   "with c_n in m V-n"),
    "calibration_r2": _V("1", "coefficient of determination of the calibration fit"),
    "calibration_residual": _V("m", "calibration fit residual"),
    "calibration_rms_residual": _V("m", "root-mean-square calibration residual"),
    "calibration_monotonic": _V("1",
                                "1 if the calibration is monotonic over the recorded voltages"),
    "gain": _V("m V-1", "probe gain"),
    "offset": _V("m", "probe offset (elevation at zero volt)"),
    "eta": _V("m", "water surface elevation above still water level",
              "water_surface_height_above_reference_datum"),
    "probe_x": _V("m", "wave probe position along the flume"),
    # --- waves ---
    "eta_incident": _V("m", "incident water surface elevation"),
    "eta_reflected": _V("m", "reflected water surface elevation"),
    "eta_beach": _V("m", "water surface elevation of the wave returning from the beach"),
    "spectrum_incident": _V("m2 s", "variance density of the incident wave"),
    "spectrum_reflected": _V("m2 s", "variance density of the reflected wave"),
    "reflection_coefficient": _V("1", "reflection coefficient Kr"),
    "incident_height": _V("m", "incident wave height"),
    "reflected_height": _V("m", "reflected wave height"),
    "masked": _V("1", "1 where the separation was ill-conditioned and masked"),
    "masked_energy_fraction": _V("1", "fraction of the energy in the band held by masked bins"),
    "condition_number": _V("1", "condition number of the least-squares system"),
    "wave_number": _V("rad m-1", "wave number"),
    "steady_start": _V("s", "start of the quasi-steady window"),
    "steady_end": _V("s", "end of the quasi-steady window"),
    "crest_steady_start": _V("s", "start of the window where every probe's crests are "
                                  "quasi-steady (Brito et al. 2020, 2.5)"),
    "reflection_drift": _V("1", "largest change of the first-harmonic complex reflection "
                                "coefficient outside the quasi-steady window"),
    "measured_period": _V("s", "mean wave period of the quasi-steady window"),
    "measured_height": _V("m", "mean wave height of the quasi-steady window"),
    "amplitude_scale": _V("m", "amplitude scale of the quasi-steady window"),
    "steady_tolerance": _V("1", "relative crest tolerance of the quasi-steady window"),
    "energy_flux": _V("W m-1", "period-averaged incident energy flux per unit crest width"),
    "probe_spacing": _V("m", "distance between the probes of a pair"),
    "pair": _V("1", "wave probe pair"),
    "harmonic": _V("1", "harmonic order n of the fundamental wave frequency"),
    "incident_harmonic_amplitude": _V("m", "amplitude of the incident wave at harmonic n"),
    "reflected_harmonic_amplitude": _V("m", "amplitude of the reflected wave at harmonic n"),
    "harmonic_reflection_coefficient": _V("1", "reflection coefficient at harmonic n"),
    "incident_amplitude": _V("m", "first-harmonic amplitude of the incident wave"),
    "incident_phase": _V("rad",
                         "phase of the first-harmonic incident wave, eta = a cos(omega t + phase)"),
    "steady_cycles": _V("1", "number of wave cycles in the quasi-steady window"),
    "analysis_start": _V("s", "start of the analysed span of an irregular run"),
    "analysis_end": _V("s", "end of the analysed span of an irregular run"),
    "reflection_coefficient_spectrum": _V("1", "reflection coefficient per frequency Kr(f): "
                                          "the returning wave over the incident one "
                                          "(sqrt(S_R / S_I) over a band)"),
    "low_frequency_energy_fraction": _V("1", "share of the records' variance below half the "
                                        "peak frequency"),
    "reflected_hm0": _V("m", "spectral significant height Hm0 of the reflected wave"),
    # --- flap ---
    "theta": _V("rad", "flap rotation angle, positive towards the beach"),
    "theta_dot": _V("rad s-1", "flap angular velocity"),
    "theta_ddot": _V("rad s-2", "flap angular acceleration"),
    "rod_length": _V("m", "PTO rod length between anchors"),
    "rod_velocity": _V("m s-1", "PTO rod extension rate"),
    "beta": _V("rad", "angle between the PTO rod and the flap"),
    "lever_arm": _V("m", "lever arm of the PTO rod force about the hinge"),
    "torque_hydrodynamic": _V("N m", "hydrodynamic torque on the flap about the hinge"),
    "torque_gravity": _V("N m", "gravity and buoyancy torque about the hinge"),
    "torque_pto": _V("N m", "torque of the PTO on the flap"),
    "torque_pressure": _V("N m", "torque of the cylinder pressure force"),
    "torque_friction": _V("N m", "torque of the cylinder friction force"),
    "torque_inertia": _V("N m", "inertia torque I theta_ddot"),
    "force_pressure": _V("N", "cylinder pressure force"),
    "force_friction": _V("N", "cylinder friction force"),
    "flow_rate": _V("m3 s-1", "flow rate through the PTO cylinder"),
    "power": _V("W", "instantaneous PTO power P_int Q"),
    "mean_power": _V("W", "mean PTO power over the quasi-steady window"),
    "incident_power": _V("W", "incident energy flux times flap width, W_I"),
    "capture_factor": _V("1", "power capture factor C_f"),
    "pressure_loss_coefficient": _V("Pa s2 rad-2", "pressure loss coefficient K_p"),
    "fluid_inertia": _V("Pa s2 rad-1", "fluid inertia coefficient I_p"),
    "pressure_fit_r2": _V("1", "coefficient of determination of the pressure model fit"),
    "theta_amplitude": _V("rad", "amplitude of the flap rotation"),
    "torque_amplitude": _V("N m", "amplitude of the hydrodynamic torque"),
    "domain_flag": _V("1", "1 where the encoder sample lies outside the domain of Eq. (1)"),
    "chamber_pressure_true": _V("Pa", "noise-free gauge pressure in the PTO cylinder chamber "
                                "(virtual flume truth)", "sea_water_pressure"),
    "chamber_pressure_fitted": _V("Pa", "chamber gauge pressure of the fitted model, Eq. (13)"),
    "torque_pressure_fitted": _V("N m", "torque of the fitted cylinder pressure force"),
    "cavitating": _V("1", "1 where the chamber is on the cavitation branch of the pressure model"),
    "bristle_deflection": _V("m", "mean bristle deflection z of the LuGre friction model"),
    "film_thickness_parameter": _V("1", "dimensionless lubricant film thickness h_l of the "
                                   "friction model"),
    "torque_excitation": _V("N m", "wave excitation torque on the flap about the hinge"),
    "theta_phase_mean": _V("rad", "phase-averaged flap rotation angle"),
    "theta_phase_ci95": _V("rad", "half-width of the 95 % confidence interval of the "
                           "phase-averaged flap angle"),
    "theta_dot_phase_mean": _V("rad s-1", "phase-averaged flap angular velocity"),
    "power_phase_mean": _V("W", "phase-averaged PTO power"),
    "chamber_pressure_phase_mean": _V("Pa", "phase-averaged chamber gauge pressure"),
    "torque_hydrodynamic_phase_mean": _V("N m", "phase-averaged hydrodynamic torque"),
    "torque_hydrodynamic_phase_ci95": _V("N m", "half-width of the 95 % confidence interval of the "
                                         "phase-averaged hydrodynamic torque"),
    "domain_flagged_fraction": _V("1", "fraction of encoder samples outside the domain of Eq. (1)"),
    # statistics of the flap's motion and torque in irregular seas (performance/statistics.py)
    "theta_mean": _V("rad", "mean flap rotation angle over the analysed span"),
    "theta_rms": _V("rad", "standard deviation of the flap rotation angle about its mean"),
    "theta_significant_amplitude": _V("rad", "significant amplitude of the flap rotation "
                                      "2 sqrt(m0)"),
    "theta_significant_amplitude_zero_crossing": _V(
        "rad", "half the mean zero-crossing height of the highest third of the flap rotation"),
    "theta_maximum_amplitude": _V("rad", "half the largest zero-crossing height of the flap "
                                  "rotation"),
    "theta_cycles": _V("1", "number of zero up-crossing cycles of the flap rotation"),
    "torque_mean": _V("N m", "mean hydrodynamic torque over the analysed span"),
    "torque_rms": _V("N m", "standard deviation of the hydrodynamic torque about its mean"),
    "torque_significant_amplitude": _V("N m", "significant amplitude of the hydrodynamic "
                                       "torque 2 sqrt(m0)"),
    "torque_significant_amplitude_zero_crossing": _V(
        "N m", "half the mean zero-crossing height of the highest third of the hydrodynamic "
        "torque"),
    "torque_maximum_amplitude": _V("N m", "half the largest zero-crossing height of the "
                                   "hydrodynamic torque"),
    "torque_cycles": _V("1", "number of zero up-crossing cycles of the hydrodynamic torque"),
    # --- uvp ---
    "distance": _V("m", "distance from the transducer face along the beam"),
    "beam_velocity": _V("m s-1", "velocity along the beam"),
    "amplitude": _V("1", "echo amplitude (raw counts)"),
    "u": _V("m s-1", "longitudinal velocity", "sea_water_x_velocity"),
    "w": _V("m s-1", "vertical velocity", "upward_sea_water_velocity"),
    "u_rms": _V("m s-1", "RMS of the longitudinal velocity fluctuation"),
    "w_rms": _V("m s-1", "RMS of the vertical velocity fluctuation"),
    "tke": _V("m2 s-2", "turbulent kinetic energy from the available components"),
    "u_ci": _V("m s-1", "half-width of the 95 % confidence interval of <u>"),
    "w_ci": _V("m s-1", "half-width of the 95 % confidence interval of <w>"),
    "u_normalised": _V("1", "<u>/U0 with U0 = pi H/T"),
    "w_normalised": _V("1", "<w>/U0 with U0 = pi H/T"),
    "record": _V("1", "index of the profile record in the instrument file"),
    "beam_angle": _V("rad", "UVP beam angle above the horizontal, towards +x"),
    "beam_x": _V("m", "x of the UVP transducer face"),
    "beam_dz": _V("m", "elevation of the UVP transducer face relative to the run's UVP elevation"),
    "beam_velocity_std": _V("m s-1",
                            "RMS of the along-beam velocity fluctuation about its phase average"),
    "beam_velocity_ci": _V("m s-1", "half-width of the 95 % confidence interval of the "
                           "phase-averaged beam velocity"),
    "n_cycles": _V("1", "number of wave cycles phase-averaged"),
    "n_repeats": _V("1", "number of repeated runs averaged"),
    "n_beams": _V("1", "number of UVP beams that see the point"),
    "uu": _V("m2 s-2",
             "variance of the longitudinal velocity fluctuation <u'u'> (unclipped estimate)"),
    "ww": _V("m2 s-2", "variance of the vertical velocity fluctuation <w'w'> (unclipped estimate)"),
    "uw": _V("m2 s-2", "covariance of the longitudinal and vertical velocity fluctuations <u'w'>"),
    "velocity_scale": _V("m s-1", "velocity scale U0 = pi H/T"),
    "inside_flap": _V("1", "1 where the point lies inside the flap (masked)"),
    "phase_reference": _V("s", "time of the zero up-crossing of the incident wave at x = 0 that "
                          "starts the phase average"),
    # --- models ---
    "added_inertia": _V("kg m2", "added moment of inertia about the hinge"),
    "radiation_damping": _V("N m s", "radiation damping about the hinge"),
    "excitation_torque": _V("N m m-1", "excitation torque per unit wave amplitude"),
    "hydrostatic_stiffness": _V("N m rad-1",
                                "net buoyancy (hydrostatic) stiffness about the hinge"),
    "theta_relative_rms_difference": _V(
        "1", "RMS of simulated minus measured theta over the steady window, over its amplitude"),
    "pto_damping": _V("N m s", "linear PTO damping"),
    "theta_complex_amplitude": _V("rad m-1",
                                  "complex flap rotation amplitude per unit wave amplitude"),
    "efficiency": _V("1", "efficiency"),
    "temperature": _V("K", "temperature"),
    "film_thickness": _V("m", "lubricant film thickness"),
    "film_parameter": _V("1", "film parameter lambda = h_min / sigma"),
    "friction_coefficient": _V("1", "friction coefficient"),
    # time-domain hydrodynamics and simulator (models/hydro.py, radiation.py, simulator.py)
    "added_inertia_infinite": _V("kg m2",
                                 "infinite-frequency added moment of inertia about the hinge"),
    "added_inertia_infinite_estimate": _V("kg m2", "Ogilvie (1964) estimate of the "
                                          "infinite-frequency added inertia at each frequency"),
    "lag": _V("s", "time lag of the radiation impulse response"),
    "radiation_irf": _V("N m", "radiation impulse response K(t): memory torque per unit angular "
                        "velocity per unit time"),
    "torque_radiation": _V("N m", "radiation torque acting on the flap, "
                           "-A_inf theta_ddot - int K theta_dot"),
    "torque_drag": _V("N m", "quadratic viscous drag torque acting on the flap"),
    # the virtual flume's extra losses (synth/flume.py), acting on the flap
    "torque_vortex_drag": _V("N m", "vortex drag torque of the oscillating flap, C_d(KC)"),
    "torque_wetted_length": _V("N m", "waterline torque of the flap's changing wetted length"),
    "torque_overtopping": _V("N m", "excitation lost to overtopping of the flap's top"),
    "torque_bearing": _V("N m", "friction torque of the hinge bearings"),
    "torque_valve": _V("N m", "torque of the PTO check valve's pressure"),
    "chamber_pressure_valve": _V("Pa", "pressure drop of the PTO check valve in the chamber"),
    # performance in irregular seas and the power matrix (performance/, flap/analysis.py)
    "capture_width": _V("m", "capture width (capture length) P / J"),
    "capture_width_ratio": _V("1", "capture width ratio P / (J w)"),
    "hm0_bin": _V("m", "centre of the significant wave height bin of the power matrix"),
    "te_bin": _V("s", "centre of the energy period bin of the power matrix"),
    "hm0_bin_bounds": _V("m", "edges of the significant wave height bin of the power matrix"),
    "te_bin_bounds": _V("s", "edges of the energy period bin of the power matrix"),
    "run_count": _V("1", "number of runs in the cell of the power matrix"),
    "runs_outside": _V("1", "number of runs outside the bins of the power matrix"),
    "mean_power_std": _V("W", "standard deviation (ddof = 0) of the mean power over the runs "
                         "of the cell"),
    "capture_width_std": _V("m", "standard deviation (ddof = 0) of the capture width over the "
                            "runs of the cell"),
    "capture_width_ratio_std": _V("1", "standard deviation (ddof = 0) of the capture width "
                                  "ratio over the runs of the cell"),
    "run_hm0": _V("m", "incident significant wave height Hm0 of the run at the flap"),
    "run_te": _V("s", "incident energy period Te of the run at the flap"),
    "run_mean_power": _V("W", "mean PTO power of the run over its analysed span"),
    "run_capture_width": _V("m", "capture width P / J of the run"),
    "run_capture_width_ratio": _V("1", "capture width ratio P / (J w) of the run"),
    "torque_compliance": _V("N m", "torque of the PTO chamber's compliance pressure"),
    "chamber_pressure_compliance": _V("Pa", "pressure lag of the PTO chamber's compliance"),
    "torque_cavity": _V("N m", "torque of the PTO chamber's vapour cavity pressure"),
    "chamber_pressure_cavity": _V("Pa", "PTO chamber pressure change while a vapour cavity "
                                        "persists"),
    # Renzi-Dias linear model and frequency-domain response (models/renzi_dias.py, response.py)
    "period": _V("s", "wave period"),
    "excitation_torque_real": _V("N m m-1", "real part of the complex excitation torque per unit "
                                 "wave amplitude at the hinge line"),
    "excitation_torque_imag": _V("N m m-1", "imaginary part of the complex excitation torque per "
                                 "unit wave amplitude at the hinge line"),
    "reflection_coefficient_real": _V("1", "real part of the complex plane-wave reflection "
                                      "coefficient R0 of the fixed flap"),
    "reflection_coefficient_imag": _V("1", "imaginary part of the complex plane-wave reflection "
                                      "coefficient R0 of the fixed flap"),
    "transmission_coefficient_real": _V("1", "real part of the complex plane-wave transmission "
                                        "coefficient T0 of the fixed flap"),
    "transmission_coefficient_imag": _V("1", "imaginary part of the complex plane-wave "
                                        "transmission coefficient T0 of the fixed flap"),
    "propagating_transverse_modes": _V("1", "number of symmetric transverse channel modes above "
                                       "cut-off (k b > 2 pi q)"),
    "theta_real": _V("rad", "real part of the complex flap rotation amplitude, "
                     "theta = Re(Theta exp(-i omega t))"),
    "theta_imag": _V("rad", "imaginary part of the complex flap rotation amplitude"),
    "theta_phase": _V("rad", "phase of the flap rotation, arg Theta, relative to the incident "
                      "crest at the hinge line"),
    "optimal_pto_damping": _V("N m s", "PTO damping maximising the mean power, RD12 Eq. (2.40)"),
    "capture_factor_channel": _V("1", "mean power over the incident energy flux across the "
                                 "channel width"),
    # ball-screw WEC (Senatore & De Simone 2022): buoy kinematics
    "buoy_heave": _V("m",
                     "vertical displacement of the buoy centre of gravity from static equilibrium"),
    "buoy_heave_velocity": _V("m s-1", "vertical velocity of the buoy centre of gravity"),
    "buoy_heave_acceleration": _V("m s-2", "vertical acceleration of the buoy centre of gravity"),
    "arm_angle": _V("rad", "holding-arm angle above the horizontal"),
    "arm_angular_velocity": _V("rad s-1", "holding-arm angular velocity"),
    "arm_angular_acceleration": _V("rad s-2", "holding-arm angular acceleration"),
    "nut_travel": _V("m", "ball-screw nut travel from the rest position"),
    "nut_velocity": _V("m s-1", "ball-screw nut velocity v_nut"),
    "nut_acceleration": _V("m s-2", "ball-screw nut acceleration a_PTO"),
    "screw_speed": _V("rad s-1", "screw shaft angular speed omega = 2 pi v / lead"),
    "linkage_ratio": _V("1", "nut velocity per unit buoy heave velocity ds/dz"),
    "buoy_draft": _V("m", "draft of the float"),
    "displaced_volume": _V("m3", "volume of water displaced by the float"),
    "waterplane_area": _V("m2", "waterplane area of the float"),
    "buoyancy_force": _V("N", "buoyancy force on the float F_hs"),
    "wave_force": _V("N", "vertical hydrodynamic force on the float F_hd (inverse dynamics)"),
    "net_vertical_force": _V("N", "net vertical force on the float F_z = F_hs + F_hd - m g"),
    # ball-screw PTO and EHL
    "pto_force": _V("N", "axial PTO force on the nut F_PTO, Eq. (3)"),
    "friction_force": _V("N", "ball-screw friction force magnitude"),
    "ball_load": _V("N", "normal load per loaded ball Q"),
    "entrainment_speed": _V("m s-1", "mean entrainment speed of the ball-groove contacts"),
    "min_film_thickness_screw": _V("m",
                                   "Hamrock-Dowson minimum film thickness, ball-screw contact"),
    "min_film_thickness_nut": _V("m", "Hamrock-Dowson minimum film thickness, ball-nut contact"),
    "film_parameter_screw": _V("1", "film parameter lambda_screw = h_min / sigma"),
    "film_parameter_nut": _V("1", "film parameter lambda_nut = h_min / sigma"),
    "lubrication_regime_screw": _V("1", "lubrication regime, ball-screw: "
                                   "0 boundary, 1 mixed, 2 full film"),
    "lubrication_regime_nut": _V("1",
                                 "lubrication regime, ball-nut: 0 boundary, 1 mixed, 2 full film"),
    "friction_coefficient_screw": _V("1", "friction coefficient f_ball-screw"),
    "friction_coefficient_nut": _V("1", "friction coefficient f_ball-nut"),
    "ballscrew_efficiency": _V("1", "indirect efficiency of the ball screw eta = P_out / P_in"),
    "direct_efficiency": _V("1", "direct efficiency of the ball screw (screw drives nut)"),
    "power_flow_direction": _V("1", "+1 nut drives screw (indirect), -1 screw drives nut"),
    "screw_torque": _V("N m", "torque transmitted to the screw shaft M_scr"),
    "input_power": _V("W", "power delivered by the nut P_in = F_nut v_nut"),
    "output_power": _V("W", "power delivered to the screw shaft P_out = M_scr omega"),
    "generator_power": _V("W", "power absorbed by the generator damping"),
    "mechanical_power_loss": _V("W", "mechanical power loss of the PTO Q_mecc"),
    "electrical_power_loss": _V("W", "electrical power loss of the generator Q_el"),
    # PTO thermal models
    "component": _V("1", "lumped thermal component"),
    "heat_source": _V("W", "heat generated in the component"),
    "bearing_heat_loss": _V("W", "mechanical loss heating the support bearing "
                            "(leaves the lumped model)"),
    "temperature_rise_fit": _V("K", "temperature rise Delta T of the fit "
                               "T0 + Delta T (1 - exp(-t/tau))"),
    "time_constant_fit": _V("s", "time constant tau of the exponential fit"),
    "radial_coordinate": _V("m", "radial coordinate r of the axisymmetric model"),
    "axial_coordinate": _V("m", "axial coordinate of the axisymmetric model"),
    "cell_nodes": _V("1", "node indices of each finite-element cell"),
    "cell_region": _V("1", "region index of each finite-element cell"),
    "region": _V("1", "material region of the axisymmetric PTO model"),
    "snapshot_time": _V("s", "time of a temperature-field snapshot"),
    "temperature_field": _V("K", "temperature at the finite-element nodes"),
    "control_point": _V("1", "temperature control point"),
    "control_temperature": _V("K", "temperature at a control point"),
    "control_radius": _V("m", "radial coordinate of the control point"),
    "control_axial": _V("m", "axial coordinate of the control point"),
    "control_region": _V("1", "material region holding the control point"),
    # sea state: spectrum, spectral parameters, zero-crossing statistics (waves/spectra.py,
    # waves/statistics.py); CF standard names where the CF table has one
    "variance_density": _V("m2 s", "one-sided variance density of the surface elevation",
                           "sea_surface_wave_variance_spectral_density"),
    "variance_density_lower": _V("m2 s", "lower bound of the confidence interval of the "
                                 "variance density"),
    "variance_density_upper": _V("m2 s", "upper bound of the confidence interval of the "
                                 "variance density"),
    "degrees_of_freedom": _V("1", "equivalent degrees of freedom of the spectral estimate"),
    "m_minus1": _V("m2 s", "spectral moment of order -1, m_-1"),
    "m0": _V("m2", "spectral moment of order 0, m0 (variance)"),
    "m1": _V("m2 s-1", "spectral moment of order 1, m1"),
    "m2": _V("m2 s-2", "spectral moment of order 2, m2"),
    "m4": _V("m2 s-4", "spectral moment of order 4, m4"),
    "hm0": _V("m", "spectral significant wave height Hm0 = 4 sqrt(m0)",
              "sea_surface_wave_significant_height"),
    "tp": _V("s", "peak period of the discrete spectrum",
             "sea_surface_wave_period_at_variance_spectral_density_maximum"),
    "tp_smoothed": _V("s", "smoothed peak period"),
    "tm01": _V("s", "mean period m0/m1", "sea_surface_wave_mean_period_from_variance_spectral_"
               "density_first_frequency_moment"),
    "tm02": _V("s", "mean period sqrt(m0/m2)", "sea_surface_wave_mean_period_from_variance_"
               "spectral_density_second_frequency_moment"),
    "tm_10": _V("s", "energy period Te = m_-1/m0", "sea_surface_wave_mean_period_from_variance_"
                "spectral_density_inverse_frequency_moment"),
    "te": _V("s", "energy period Te = Tm-1,0 = m_-1/m0 of the incident wave",
             "sea_surface_wave_mean_period_from_variance_spectral_density_inverse_frequency_"
             "moment"),
    "spectral_width": _V("1", "spectral width epsilon = sqrt(1 - m2^2/(m0 m4))"),
    "spectral_narrowness": _V("1", "spectral narrowness nu = sqrt(m0 m2/m1^2 - 1)"),
    "peakedness": _V("1", "Goda's spectral peakedness Qp = 2/m0^2 int f S^2 df"),
    "spectral_energy_flux": _V("W m-1", "energy flux per unit crest width of the wave spectrum, "
                               "rho g int S(f) c_g(f) df", "sea_surface_wave_energy_flux"),
    "wave": _V("1", "index of the individual zero-crossing wave in the record"),
    "individual_wave_height": _V("m", "trough-to-crest height of the individual zero-crossing "
                                 "wave"),
    "individual_wave_period": _V("s", "period of the individual zero-crossing wave"),
    "individual_wave_start": _V("s", "time of the zero crossing that starts the individual wave"),
    "number_of_waves": _V("1", "number of zero-crossing waves in the record"),
    "hrms": _V("m", "root-mean-square height of the zero-crossing waves"),
    "h1_3": _V("m", "mean height of the highest third of the zero-crossing waves, H1/3",
               "sea_surface_wave_significant_height"),
    "t1_3": _V("s", "mean period of the highest third of the zero-crossing waves, T1/3",
               "sea_surface_wave_significant_period"),
    "h1_10": _V("m", "mean height of the highest tenth of the zero-crossing waves, H1/10",
                "sea_surface_wave_mean_height_of_highest_tenth"),
    "hmax": _V("m", "height of the highest zero-crossing wave",
               "sea_surface_wave_maximum_height"),
    "tz": _V("s", "mean zero-crossing period", "sea_surface_wave_mean_period"),
    # --- truth of the virtual flume ---
    "spectrum_target": _V("m2 s", "target JONSWAP variance density of the incident wave"),
    "incident_spectral_amplitude": _V("m", "amplitude of the incident wave's Fourier component "
                                      "at the flap"),
    "incident_spectral_phase": _V("rad", "phase of the incident wave's Fourier component at "
                                  "the flap, eta = a cos(2 pi f (t - start) + phase)"),
    "reflection_phase_spectrum": _V("rad", "phase of the returning wave over the incident wave "
                                    "at the flap"),
    "flap_reflection_coefficient_spectrum": _V("1", "reflection coefficient of the flap alone"),
    "flap_transmission_coefficient_spectrum": _V("1", "transmission coefficient of the flap"),
    "beach_reflection_coefficient_spectrum": _V("1", "reflection coefficient of the beach"),
}


# --- uncertainty (flumekit.uncertainty): repeat statistics and uncertainties of the per-run
# summary quantities, each in the unit of its quantity ---
#: the summary quantities that carry repeat statistics and uncertainties
UNCERTAIN_QUANTITIES = ("incident_height", "measured_period", "reflection_coefficient",
                        "energy_flux", "theta_amplitude", "torque_amplitude", "mean_power",
                        "capture_factor", "hm0", "tp", "te", "capture_width_ratio")
#: suffix -> long name prefix of the statistics of quantity X (X_<suffix>)
UNCERTAINTY_SUFFIXES = {
    "std": "sample standard deviation over the repeats (ddof = 1) of the",
    "standard_error": "standard error of the mean over the repeats of the",
    "uncertainty_type_a": "Type A standard uncertainty (repeats) of the",
    "uncertainty_type_b": "Type B standard uncertainty (instruments, propagated) of the",
    "uncertainty": "combined standard uncertainty of the",
    "expanded_uncertainty": "expanded uncertainty (95 % coverage) of the",
    "uncertainty_linear": "standard uncertainty by linear GUM propagation of the",
    "budget": "standard uncertainty contributed by each component to the",
    "contribution": "share of the combined variance contributed by each component to the",
    "sensitivity": "sensitivity coefficient (per unit of the component's input) of the",
    "dof": "degrees of freedom of the Type A uncertainty of the",
    "coverage_low": "lower end of the probabilistically symmetric 95 % Monte Carlo coverage "
                    "interval of the",
    "coverage_high": "upper end of the probabilistically symmetric 95 % Monte Carlo coverage "
                     "interval of the",
}
VARIABLES.update({
    f"{q}_{suffix}": _V({"dof": "1", "contribution": "percent", "sensitivity": "1"}.get(
        suffix, VARIABLES[q].units), f"{prefix} {VARIABLES[q].long_name}")
    for q in UNCERTAIN_QUANTITIES if q in VARIABLES
    for suffix, prefix in UNCERTAINTY_SUFFIXES.items()})
VARIABLES.update({
    "condition": _V("1", "test condition index (runs with the same target wave)"),
    "uncertainty_component": _V("1", "Type B uncertainty component (campaign [uncertainty])"),
    "input_standard_uncertainty": _V("1", "standard uncertainty of the component's input, in "
                                     "the unit named by input_units"),
    "input_units": _V("1", "unit of the component's input"),
    "component_type": _V("1", "GUM evaluation type of the component (A or B)"),
    "draws": _V("1", "number of Monte Carlo draws"),
})

def attrs(name: str) -> dict[str, str]:
    """Return the CF attributes of a registered variable name.

    Parameters
    ----------
    name : str
        A variable's name in :data:`VARIABLES`, e.g. ``"hm0"``.

    Returns
    -------
    dict of str to str
        ``units`` (UDUNITS), ``long_name`` and, where the CF table has one, ``standard_name``.

    Raises
    ------
    KeyError
        For a ``name`` that :data:`VARIABLES` does not hold.

    Examples
    --------
    >>> a = attrs("hm0")
    >>> a["units"], a["standard_name"]
    ('m', 'sea_surface_wave_significant_height')
    """
    try:
        return VARIABLES[name].attrs()
    except KeyError:
        raise KeyError(f"'{name}' is not in flumekit.conventions.VARIABLES; register it") from None


def annotate(obj: xr.Dataset | xr.DataArray) -> xr.Dataset | xr.DataArray:
    """Attach registry attributes to every variable and coordinate whose name is registered.

    Attributes already present are kept (a caller may refine a long name), but ``units`` always
    comes from the registry so that one name means one unit everywhere.

    Parameters
    ----------
    obj : xarray.Dataset or xarray.DataArray
        The object to annotate (not modified).

    Returns
    -------
    xarray.Dataset or xarray.DataArray
        A copy with the registry's attributes.

    Examples
    --------
    >>> import xarray as xr
    >>> ds = annotate(xr.Dataset(coords={"time": [0.0, 0.1]}))
    >>> ds.time.attrs["units"], ds.time.attrs["standard_name"]
    ('s', 'time')
    """
    import xarray as xr

    obj = obj.copy()  # shallow: new variables with copies of their attrs, the data shared
    # the variables themselves (a DataArray per name would cost more than the annotation)
    variables = obj.variables if isinstance(obj, xr.Dataset) else obj.coords.variables
    for name, target in variables.items():
        if str(name) not in VARIABLES:
            continue
        new = _registry_attrs(name, target.attrs)
        target.attrs.clear()
        target.attrs.update(new)
    if isinstance(obj, xr.DataArray) and obj.name in VARIABLES:
        obj.attrs = {**VARIABLES[obj.name].attrs(), **obj.attrs}
    return obj


def _registry_attrs(name, attrs: dict) -> dict:
    """Return ``attrs`` completed by the registry's, with the registry's units (see annotate)."""
    var = VARIABLES.get(str(name))
    if var is None:
        return dict(attrs)
    return {**var.attrs(), **{k: v for k, v in attrs.items() if k != "units"},
            "units": var.units}


def annotated_dataset(data: dict, coords: dict, attrs: dict | None = None) -> xr.Dataset:
    """Build a dataset whose registered variables carry the registry's attributes.

    The dataset :func:`annotate` would return for ``xarray.Dataset(data, coords, attrs)``,
    built once: each variable is made with its attributes, and each dimension coordinate's
    index from its values, instead of a dataset being built, then copied and annotated.

    Parameters
    ----------
    data : dict
        Data variable name -> ``(dims, values)`` or ``(dims, values, attrs)``.
    coords : dict
        Dimension coordinate name -> its values (1-D), or ``(dims, values[, attrs])`` for
        another coordinate.
    attrs : dict, optional
        The dataset's attributes.

    Returns
    -------
    xarray.Dataset
        The dataset, annotated.

    Examples
    --------
    >>> import numpy as np
    >>> ds = annotated_dataset({"eta_incident": ("time", np.zeros(2))}, {"time": [0.0, 0.1]})
    >>> ds.time.attrs["units"], ds.eta_incident.attrs["units"], list(ds.indexes)
    ('s', 'm', ['time'])
    """
    import xarray as xr

    def variable(name, v, coordinate=False):
        dims, values, *more = v if isinstance(v, tuple) else ((name,), v)
        kind = xr.IndexVariable if coordinate and dims == (name,) else xr.Variable
        return kind(dims, values, _registry_attrs(name, more[0] if more else {}))

    data_vars = {k: variable(k, v) for k, v in data.items()}
    coord_vars = {k: variable(k, v, coordinate=True) for k, v in coords.items()}
    return dataset_of_variables(data_vars, coord_vars, attrs)


def dataset_of_variables(data_vars: dict, coord_vars: dict, attrs: dict | None = None,
                         dims_from_data: bool = False) -> xr.Dataset:
    """Return ``xarray.Dataset(data_vars, coords, attrs)`` of ready variables, made directly.

    When every dimension has one size, the names are distinct and each dimension coordinate
    is one-dimensional, the dataset is made from the variables as they are, each dimension
    coordinate with its default index: the merge and alignment of the constructor, which
    check all of that for any input, are most of the cost of a small dataset (the
    separation's, built once per record and per Monte Carlo draw; a product read). Otherwise,
    or where this xarray has no ``Dataset._construct_direct``, the constructor builds it (and
    raises what is wrong).

    Parameters
    ----------
    data_vars, coord_vars : dict of str to xarray.Variable
        The data variables, and the coordinates (dimension coordinates as
        ``xarray.IndexVariable``), in the order the dataset lists them: data first.
    attrs : dict, optional
        The dataset's attributes.
    dims_from_data : bool
        Order the dimensions as the data variables first use them (as a dataset read from a
        file has them), not the coordinates.

    Returns
    -------
    xarray.Dataset
        The dataset; its variables are those given (not copies).

    Examples
    --------
    >>> import numpy as np
    >>> import xarray as xr
    >>> ds = dataset_of_variables({"theta": xr.Variable("time", np.zeros(2))},
    ...                           {"time": xr.IndexVariable("time", [0.0, 0.1])})
    >>> list(ds.data_vars), list(ds.indexes)
    (['theta'], ['time'])
    """
    import pandas as pd
    import xarray as xr
    from xarray.indexes import PandasIndex

    construct = getattr(xr.Dataset, "_construct_direct", None)
    sizes: dict | None = {}
    order = (*data_vars.values(), *coord_vars.values()) if dims_from_data else (
        *coord_vars.values(), *data_vars.values())
    for var in order:
        for dim, n in zip(var.dims, var.shape, strict=True):
            if sizes.setdefault(dim, n) != n:
                sizes = None
                break
        if sizes is None:
            break
    if construct is None or set(data_vars) & set(coord_vars) or sizes is None:
        return xr.Dataset(data_vars, coords=xr.Coordinates(coord_vars), attrs=attrs)
    indexes = {k: PandasIndex(pd.Index(v.values), k) for k, v in coord_vars.items()
               if v.dims == (k,)}
    return construct({**data_vars, **coord_vars}, set(coord_vars), sizes, attrs, indexes)


def check(ds: xr.Dataset) -> None:
    """Raise ``ValueError`` naming every variable that lacks ``units`` or ``long_name``.

    Label variables (strings) need a ``long_name`` only.

    Parameters
    ----------
    ds : xarray.Dataset
        The dataset to check.

    Raises
    ------
    ValueError
        Listing every variable and the attribute it lacks.
    """
    missing = []
    for name in [*ds.coords, *ds.data_vars]:  # Variables: no DataArray built for each
        var = ds.variables[name]
        if var.dtype.kind in "OSU":  # labels
            if "long_name" not in var.attrs:
                missing.append(f"{name} (long_name)")
            continue
        missing += [f"{name} ({a})" for a in ("units", "long_name") if a not in var.attrs]
    if missing:
        raise ValueError("dataset variables lack CF attributes: " + ", ".join(missing))


def global_attrs(title: str, source: str, parameters: dict | None = None) -> dict[str, str]:
    """Return the global attributes of a written dataset.

    No clock time: identical inputs give identical bytes (the time of a build is in the
    engine's state, ``.flumekit-state.json``).

    Parameters
    ----------
    title : str
        What the dataset holds.
    source : str
        What it was made from.
    parameters : dict, optional
        The parameters it was made with (JSON-encoded, keys sorted).

    Returns
    -------
    dict of str to str
        ``Conventions``, ``title``, ``source``, ``history`` (the flumekit version) and
        ``flumekit_parameters``.

    References
    ----------
    CF Conventions 1.8, §2.6.2 (description of file contents).
    """
    from flumekit import __version__

    params = json.dumps(parameters or {}, sort_keys=True, default=str)
    return {
        "Conventions": CONVENTIONS,
        "title": title,
        "source": source,
        "history": f"flumekit {__version__}: {title}",
        "flumekit_parameters": params,
    }


#: the rule being built in this process (set by :func:`flumekit.pipeline.rules.execute`):
#: its target, version, parameters, inputs with their content hashes and relative paths
_PROVENANCE: contextvars.ContextVar[dict | None] = contextvars.ContextVar("flumekit_provenance",
                                                                           default=None)
#: global attributes that describe how a file was made rather than what it holds; left out of
#: :func:`content_digest` so that a rebuild with other settings but identical data is identical
PROVENANCE_ATTRS = ("history", "flumekit_parameters", "flumekit_rule", "flumekit_version",
                    "flumekit_rule_version", "flumekit_inputs", "flumekit_dependencies")


def set_provenance(prov: dict | None):
    """Declare the rule being built in this context.

    Parameters
    ----------
    prov : dict or None
        The rule's target, version, parameters, inputs and paths
        (:func:`flumekit.pipeline.rules.execute`); None: no rule.

    Returns
    -------
    contextvars.Token
        For :func:`reset_provenance`.
    """
    return _PROVENANCE.set(prov)


def reset_provenance(token) -> None:
    """Restore the provenance that :func:`set_provenance` replaced (``token``: its result)."""
    _PROVENANCE.reset(token)


@functools.cache
def _dependency_versions() -> str:
    """Return the versions of the numerical libraries, looked up once per process.

    They cannot change within a process, and importlib.metadata parses each package's
    metadata file, which is too slow to repeat for every written product.
    """
    from importlib.metadata import PackageNotFoundError, version

    out = []
    for name in ("numpy", "scipy", "xarray", "netCDF4", "pandas", "matplotlib"):
        try:
            out.append(f"{name} {version(name)}")
        except PackageNotFoundError:
            pass
    return "; ".join(out)


def provenance(attrs: dict) -> dict:
    """Return global attributes with the provenance of the rule being built.

    Absolute input paths in string attributes (a stage's ``source``) become paths relative to
    the pipeline file, so that the same campaign built in two folders gives the same bytes.

    Parameters
    ----------
    attrs : dict
        The dataset's global attributes (not modified).

    Returns
    -------
    dict
        ``attrs`` with the flumekit version and the versions of the numerical libraries, and,
        inside a rule (:func:`set_provenance`), the rule, its version and parameters, and every
        input with its relative path and content hash.
    """
    from flumekit import __version__

    prov = _PROVENANCE.get()
    out = dict(attrs)
    out["flumekit_version"] = __version__
    out["flumekit_dependencies"] = _dependency_versions()
    if prov is None:
        return out
    for k, v in out.items():
        if isinstance(v, str):
            for absolute, rel in prov["paths"].items():
                v = v.replace(absolute, rel)
            out[k] = v
    out["flumekit_rule"] = prov["target"]
    out["flumekit_rule_version"] = prov["version"]
    out["flumekit_parameters"] = json.dumps(prov["params"], sort_keys=True, default=str)
    out["flumekit_inputs"] = json.dumps(prov["inputs"], sort_keys=True)
    return out


def content_digest(ds: xr.Dataset) -> str:
    """Return the SHA-256 of what a dataset holds, without how it was made.

    Values, dimensions, dtypes and attributes count; the attributes of
    :data:`PROVENANCE_ATTRS` do not. Two datasets with the same digest are the same data: the
    engine stops a rebuild's cascade there.

    Parameters
    ----------
    ds : xarray.Dataset
        The dataset (loaded values).

    Returns
    -------
    str
        Hex digest.

    Examples
    --------
    >>> import xarray as xr
    >>> a = xr.Dataset({"h": ("t", [1.0, 2.0])}, attrs={"history": "run 1"})
    >>> content_digest(a) == content_digest(a.assign_attrs(history="run 2"))
    True
    """
    import numpy as np

    h = hashlib.sha256()
    for name in sorted(map(str, ds.variables)):
        var = ds.variables[name]
        h.update(json.dumps([name, list(map(str, var.dims)), str(var.dtype),
                             {str(k): str(v) for k, v in sorted(var.attrs.items())}]).encode())
        values = np.asarray(var.values)
        h.update(values.tobytes() if values.dtype.kind not in "OUS"
                 else "\x00".join(map(str, values.ravel())).encode())
    h.update(json.dumps({str(k): str(v) for k, v in sorted(ds.attrs.items())
                         if k not in PROVENANCE_ATTRS}).encode())
    return h.hexdigest()
