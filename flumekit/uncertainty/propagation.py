"""Propagation of the declared Type B components through the real analysis of a run.

Monte Carlo after JCGM 101:2008: each draw perturbs the run's records and set-up by one sample of
every declared component (probe noise and resolution, calibration gains, probe positions, water
depth; encoder resolution, pressure sensor accuracy, flap inertia, clock offset) and reruns the
analyses the pipeline runs (:func:`flumekit.waves.analyse_run`, then
:func:`flumekit.flap.analyse_run` with the draw's incident height, so that H_I's uncertainty
reaches C_f). The standard uncertainty of a result is the spread of its draws about the
unperturbed result (their standard deviation and the shift of their mean, in quadrature: a
nonlinear analysis shifts it) and the quantiles of the draws give the probabilistically
symmetric 95 % interval (JCGM 101 §7.7). The draws are analysed together, through the
results-only paths of those analyses (:func:`flumekit.waves.analysis.variant_results`,
:func:`flumekit.flap.analysis.run_results`): the same computations, without the datasets and
the pressure fit that no propagated result reads.

The linear propagation of GUM §5.1 is the cross-check and the budget: sensitivity coefficients
by central differences, ±u of one input at a time; an input with one value per sample (noise,
resolution) is a vector, and its contribution E[(∇f·z)²] u² is estimated from
``directions`` random unit-variance directions z.

A draw applies a perturbation to the record as it was measured: the spread of the results over
the draws is the spread that errors of the declared size cause (the recorded noise is one draw
of it), which is what a Type B evaluation of a single run states.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np
import xarray as xr

from flumekit.docstrings import filler

#: docstring text that several functions of this module share
_doc = filler(
    inputs=("inputs : list of Input\n"
            "    Resolved components (:func:`resolve_inputs`)."),
    model=("model : RunModel\n"
           "    The run's analysis."))

#: results of the waves analysis and of the flap analysis that are propagated
WAVES_RESULTS = ("incident_height", "reflection_coefficient", "measured_period", "energy_flux")
FLAP_RESULTS = ("theta_amplitude", "torque_amplitude", "mean_power", "capture_factor")

#: component -> (what it perturbs, how): "probe_time" one value per probe and sample,
#: "probe" one per probe, "scalar" one, "flap_time" one per flap sample
SHAPES = {"probe_noise": "probe_time", "probe_resolution": "probe_time",
          "calibration": "probe", "probe_position": "probe", "water_depth": "scalar",
          "encoder_resolution": "flap_time", "pressure_accuracy": "flap_time",
          "flap_inertia": "scalar", "clock_offset": "scalar"}
FLAP_ONLY = ("encoder_resolution", "pressure_accuracy", "flap_inertia", "clock_offset")
#: the flap analysis' keywords that its encoder kinematics take
KINEMATICS_KW = ("pto", "encoder", "cutoff", "zero_count", "max_flagged_fraction")


@dataclass(frozen=True)
class Input:
    """A Type B component resolved for a run.

    ``u`` is the standard uncertainty in ``units`` (a scalar, or one value per probe for
    ``calibration``); ``distribution`` "normal" or "rectangular" (then the draws are uniform
    over ±sqrt(3) u); ``source`` says where the value comes from.

    Parameters
    ----------
    name : str
        Component name (a key of ``SHAPES``).
    u : float or numpy.ndarray
        Standard uncertainty [``units``]; one per probe for ``calibration``.
    units : str
        Units of ``u``.
    distribution : str
        "normal" or "rectangular".
    source : str
        Where the value comes from ("declared" or the default's origin).

    References
    ----------
    JCGM 100:2008 (GUM), §4.3 (Type B evaluation of standard uncertainty).

    Examples
    --------
    A probe read in steps of 1 mm: the rounding is rectangular over ±0.5 mm, of standard
    uncertainty 0.5/√3 mm, and one draw of it perturbs every sample of every probe:

    >>> import math
    >>> from flumekit.uncertainty.propagation import Input
    >>> step = Input("probe_resolution", 0.5e-3 / math.sqrt(3.0), "m", "rectangular",
    ...              "declared")
    >>> round(step.u * 1e3, 4), step.shape  # [mm]
    (0.2887, 'probe_time')
    """

    name: str
    u: float | np.ndarray
    units: str
    distribution: str
    source: str

    @property
    def shape(self) -> str:
        """Return what one draw of the component perturbs (its value in ``SHAPES``).

        Returns
        -------
        str
            "probe_time", "probe", "scalar" or "flap_time".
        """
        return SHAPES[self.name]


def resolve_inputs(components, *, calibration: xr.Dataset | None = None,
                   counts_per_metre: float | None = None, flap: bool = True) -> list[Input]:
    """Resolve the uncertainty components of a campaign (``Campaign.uncertainty``) for its runs.

    Parameters
    ----------
    components : sequence of flumekit.campaign.Component
        The declared (or default) components.
    calibration : xarray.Dataset, optional
        ``calibration.nc`` of the campaign (probes in volts): the default probe noise is its
        RMS residual (the static records hold the probes' noise) and the default calibration
        uncertainty the standard error of each fitted gain, s / sqrt(sum (V - V̄)²) over the
        gain (GUM H.3).
    counts_per_metre : float, optional
        The encoder's counts per metre of wire [m-1]: the default encoder resolution is half a
        count, as a rectangular distribution (standard uncertainty 0.5 / sqrt(3) counts).
    flap : bool
        Whether the campaign has the flap instruments (else their components are left out).

    Returns
    -------
    list of Input
        Components with a non-zero standard uncertainty that a result depends on (the UVP's
        velocity resolution reaches none of the propagated results and is left out).

    Warns
    -----
    UserWarning
        A component whose default needs data the campaign lacks (the noise and calibration of
        probes recorded in metres, without calibration.nc): it is left out, and the warning
        says so (declare ``[uncertainty.probe_noise] value``).

    References
    ----------
    JCGM 100:2008 (GUM), §4.3 (Type B evaluation; 4.3.7 rectangular distribution) and H.3
    (calibration of a linear fit).

    Examples
    --------
    Probe noise and gain uncertainty declared (no calibration.nc at hand to derive them),
    the rest at the defaults, and an encoder of 12 000 counts per metre: half a count is a
    rectangular half-width, u = 0.5 / 12000 / √3 m; the pressure sensor's 0.2 % of its 1 MPa
    rated output is 2 kPa.

    >>> from flumekit.campaign import uncertainty_components
    >>> declared = uncertainty_components({"probe_noise": {"value": 0.5e-3},
    ...                                    "calibration": {"value": 0.01}})
    >>> inputs = {i.name: i for i in resolve_inputs(declared, counts_per_metre=12000.0)}
    >>> inputs["probe_noise"].source, round(inputs["encoder_resolution"].u * 1e6, 2)  # [μm]
    ('declared', 24.06)
    >>> inputs["pressure_accuracy"].u, inputs["pressure_accuracy"].units
    (2000.0, 'Pa')

    A campaign of probes alone leaves out the flap's components:

    >>> [i.name for i in resolve_inputs(declared, flap=False)]
    ['probe_noise', 'probe_resolution', 'calibration', 'probe_position', 'water_depth']
    """
    from flumekit.campaign import UNCERTAINTY_COMPONENTS

    out = []
    for c in components:
        if c.name not in SHAPES or (c.name in FLAP_ONLY and not flap):
            continue
        unit = UNCERTAINTY_COMPONENTS[c.name][0]
        src = "declared" if c.declared else "default: " + UNCERTAINTY_COMPONENTS[c.name][4]
        u = c.standard_uncertainty
        if c.name == "pressure_accuracy" and u is not None:
            u, unit = u * c.rated_output, "Pa"
        if u is None and c.name in ("probe_noise", "calibration"):
            if calibration is None:
                warnings.warn(f"[uncertainty.{c.name}] is left out of the uncertainty: the "
                              "probes are recorded in length units (no calibration.nc to "
                              "derive its default from); declare its value in campaign.toml",
                              UserWarning, stacklevel=2)
                continue
            res = calibration["calibration_residual"].transpose("sample", "probe").values
            if c.name == "probe_noise":
                u = float(np.sqrt(np.nanmean(res ** 2)))
            else:
                volts = calibration["calibration_voltage"].transpose("sample", "probe").values
                n = np.sum(np.isfinite(res), axis=0)
                s = np.sqrt(np.nansum(res ** 2, axis=0) / np.maximum(n - 2, 1))
                sxx = np.nansum((volts - np.nanmean(volts, axis=0)) ** 2, axis=0)
                u = s / np.sqrt(sxx) / np.abs(calibration["gain"].values)
        if u is None and c.name == "encoder_resolution":
            if counts_per_metre is None:
                continue
            u = 0.5 / counts_per_metre / math.sqrt(3.0)
        if u is None or not np.any(np.asarray(u) > 0):
            continue
        out.append(Input(c.name, u, unit, c.distribution, src))
    return out


def _sample(rng: np.random.Generator, distribution: str, shape) -> np.ndarray:
    """Unit-variance draws of a normal or rectangular distribution."""
    if distribution == "rectangular":
        return rng.uniform(-math.sqrt(3.0), math.sqrt(3.0), shape)
    return rng.standard_normal(shape)


@_doc
class RunModel:
    """The analysis of one run as a function of the perturbations of its inputs.

    Parameters
    ----------
    eta : xarray.DataArray
        Calibrated elevation (probe, time) [m] with ``x`` on ``probe``.
    %(depth)s
    %(target_period)s
    waves_kw : dict
        Keyword arguments of :func:`flumekit.waves.analyse_run` (x_ref, method, ...).
    flap_record : dict, optional
        ``time`` [s], ``encoder_counts`` [-], ``chamber_pressure`` [Pa] of the run.
    flap_kw : dict, optional
        Keyword arguments of :func:`flumekit.flap.analyse_run` (flap, pto, encoder, cutoff...).

    Examples
    --------
    A 2 s, 0.08 m wave in 0.825 m on three probes (as in :func:`flumekit.waves.analyse_run`),
    unperturbed, then with every probe's gain 1 % high: the incident height reads 1 % high
    and the energy flux, ∝ H², 2 %:

    >>> import numpy as np
    >>> from flumekit.uncertainty.propagation import RunModel
    >>> from flumekit.waves import probe_record, probe_spacing, wavenumber
    >>> x = -4.0 + np.cumsum([0.0, *probe_spacing(2.0, 0.825)])  # [m]
    >>> k, t = float(wavenumber(np.pi, 0.825)), np.arange(1200) / 20.0
    >>> eta = probe_record(0.04 * np.cos(np.pi * t - k * x[:, None]), x=x, sampling_rate=20.0)
    >>> model = RunModel(eta, 0.825, 2.0, {})
    >>> model.results
    ('incident_height', 'reflection_coefficient', 'measured_period', 'energy_flux')
    >>> base, high = model({}), model({"calibration": np.full(3, 0.01)})
    >>> round(float(base[0]), 4), (high / base)[[0, 3]].round(4).tolist()
    (0.08, [1.01, 1.0201])
    """

    def __init__(self, eta: xr.DataArray, depth: float, period: float, waves_kw: dict,
                 flap_record: dict | None = None, flap_kw: dict | None = None):
        self.eta = eta.transpose("probe", "time")
        self.depth, self.period = float(depth), float(period)
        self.waves_kw = dict(waves_kw)
        self.flap_record, self.flap_kw = flap_record, dict(flap_kw or {})
        self.results = WAVES_RESULTS + (FLAP_RESULTS if flap_record is not None else ())
        self.n_probes, self.n_samples = self.eta.shape
        self.n_flap = 0 if flap_record is None else len(flap_record["time"])
        self._base_waves = None
        self._base = None  # the unperturbed run's results
        self._chains: dict = {}  # the unperturbed flap record's chain and window per period
        self._chain = None  # that chain, which is the same whatever the period
        self._kinematics = None  # the unperturbed encoder's part of that chain
        self._arrays = None  # the records' arrays (flumekit.waves.analysis.ProbeArrays)

    def size(self, inp: Input) -> tuple[int, ...]:
        """Return the shape of one draw of ``inp``.

        Parameters
        ----------
        inp : Input
            A resolved component.

        Returns
        -------
        tuple of int
            (probe, time), (probe,), () or (flap sample,).
        """
        return {"probe_time": (self.n_probes, self.n_samples), "probe": (self.n_probes,),
                "scalar": (), "flap_time": (self.n_flap,)}[inp.shape]

    def _eta(self, d: dict):
        """Return the records and probe positions perturbed by ``d`` (a ProbeArrays)."""
        from flumekit.waves.analysis import ProbeArrays
        from flumekit.waves.separation import unpack_probe_time

        if self._arrays is None:
            self._arrays = ProbeArrays(*unpack_probe_time(self.eta))
        v, t, x, probes = self._arrays
        if "probe_noise" in d:
            v = v + d["probe_noise"]
        if "probe_resolution" in d:
            v = v + d["probe_resolution"]
        if "calibration" in d:
            v = v * (1.0 + d["calibration"])[:, None]
        if "probe_position" in d:
            x = x + d["probe_position"]
        # time and labels are shared, not copied: nothing downstream writes into them
        return ProbeArrays(v, t, x, probes)

    def _waves(self, ds: list[dict]) -> np.ndarray:
        """Return the waves results (len(ds), len(WAVES_RESULTS)), NaN where refused."""
        from flumekit.waves.analysis import variant_results

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the warnings of the unperturbed run are recorded
            r = variant_results([self._eta(d) for d in ds],
                                [self.depth + float(d.get("water_depth", 0.0)) for d in ds],
                                self.period, **self.waves_kw)
        return np.stack([r[k] for k in WAVES_RESULTS], axis=-1)

    def waves(self, d: dict) -> dict[str, float]:
        """Return the waves results with the perturbations ``d``.

        Parameters
        ----------
        d : dict
            Component name -> its perturbation, in the component's input units, of the shape of
            :meth:`size`.

        Returns
        -------
        dict of str to float
            ``WAVES_RESULTS`` of :func:`flumekit.waves.analyse_run` on the perturbed run.

        Raises
        ------
        ValueError
            When the analysis refuses the perturbed run.
        """
        w = self._waves([d])[0]
        if not np.all(np.isfinite(w)):
            raise ValueError("the waves analysis refused the perturbed run")
        return dict(zip(WAVES_RESULTS, w.tolist(), strict=True))

    def flap(self, d: dict, incident_height: float, period: float) -> dict[str, float]:
        """Return the flap results with the perturbations ``d`` and the draw's incident wave.

        Parameters
        ----------
        d : dict
            Component name -> its perturbation, in the component's input units.
        incident_height : float
            The draw's incident wave height [m] (so that its uncertainty reaches C_f).
        period : float
            The draw's measured wave period [s] (W_I's group velocity, as the flap stage).

        Returns
        -------
        dict of str to float
            ``FLAP_RESULTS`` of :func:`flumekit.flap.analyse_run` on the perturbed run
            (:func:`flumekit.flap.analysis.run_results`).
        """
        import dataclasses

        from flumekit.flap.analysis import run_results, steady_measured

        r = self.flap_record
        kw = dict(self.flap_kw)
        if "flap_inertia" in d:
            kw["flap"] = dataclasses.replace(kw["flap"], inertia=kw["flap"].inertia
                                             * (1.0 + float(d["flap_inertia"])))
        counts = r["encoder_counts"]
        if "encoder_resolution" in d:
            counts = counts + d["encoder_resolution"] * kw["encoder"].counts_per_metre
        pressure = r["chamber_pressure"] + d.get("pressure_accuracy", 0.0)
        time = r["time"] + float(d.get("clock_offset", 0.0))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            steady_kw = {k: v for k, v in kw.items() if k != "n_phase"}
            if not any(k in FLAP_ONLY for k in d):  # the flap's records and set-up unperturbed
                if period not in self._chains:  # the window depends on the period alone
                    try:
                        self._chains[period] = steady_measured(
                            time, counts, pressure, **steady_kw, period=period,
                            kinematics=self._encoder_kinematics(time, counts, kw),
                            chain=self._chain)
                    except ValueError as e:
                        self._chains[period] = e
                if isinstance(self._chains[period], ValueError):
                    raise self._chains[period]
                self._chain = self._chains[period][0]
                kw["measured"] = self._chains[period]
            elif not any(k in d for k in ("encoder_resolution", "clock_offset")):
                # the encoder's counts and times unperturbed: its part of the chain is the run's
                kw["measured"] = steady_measured(
                    time, counts, pressure, **steady_kw, period=period,
                    kinematics=self._encoder_kinematics(time, counts, kw))
            res = run_results(time, counts, pressure, depth=self.depth
                              + float(d.get("water_depth", 0.0)), period=period,
                              incident_height=incident_height, **kw)
        return {k: float(res[k]) for k in FLAP_RESULTS}

    def _encoder_kinematics(self, time, counts, kw: dict):
        """Return the unperturbed encoder's part of the flap chain (computed once)."""
        from flumekit.flap.analysis import encoder_kinematics

        if self._kinematics is None:
            self._kinematics = encoder_kinematics(time, counts, **{
                k: v for k, v in kw.items() if k in KINEMATICS_KW})
        return self._kinematics

    def evaluate(self, ds: list[dict]) -> np.ndarray:
        """Return all results for many sets of perturbations at once.

        The waves analyses of all sets run together (:func:`flumekit.waves.analysis.
        variant_results`); a set that perturbs flap inputs only reuses the unperturbed run's
        waves results once they are known.

        Parameters
        ----------
        ds : list of dict
            Each a component name -> its perturbation (see :meth:`__call__`).

        Returns
        -------
        numpy.ndarray
            (len(ds), len(self.results)); a row of NaN where the analysis refuses the set.
        """
        out = np.full((len(ds), len(self.results)), np.nan)
        reuse = self._base_waves is not None
        need = [i for i, d in enumerate(ds) if not (reuse and all(k in FLAP_ONLY for k in d))]
        waves = np.empty((len(ds), len(WAVES_RESULTS)))
        if reuse:
            waves[:] = [self._base_waves[k] for k in WAVES_RESULTS]
        if need:
            waves[need] = self._waves([ds[i] for i in need])
        nw = len(WAVES_RESULTS)
        for i, d in enumerate(ds):  # one flap analysis per set
            if not np.all(np.isfinite(waves[i])):
                continue
            out[i, :nw] = waves[i]
            if self.flap_record is not None:
                try:
                    w = dict(zip(WAVES_RESULTS, waves[i].tolist(), strict=True))
                    f = self.flap(d, w["incident_height"], w["measured_period"])
                except ValueError:
                    out[i] = np.nan
                    continue
                out[i, nw:] = [f[k] for k in FLAP_RESULTS]
            if not d and self._base_waves is None:
                self._base_waves = dict(zip(WAVES_RESULTS, waves[i].tolist(), strict=True))
        return out

    def __call__(self, d: dict) -> np.ndarray:
        """Return all results with the perturbations ``d``.

        Parameters
        ----------
        d : dict
            Component name -> its perturbation; empty: the unperturbed run (its waves results are
            kept for the draws that perturb the flap only).

        Returns
        -------
        numpy.ndarray
            The results in the order of ``self.results``; NaN where the analysis refuses the
            perturbed run.
        """
        if d:
            return self.evaluate([d])[0]
        if self._base is None:  # the unperturbed run, analysed once
            self._base = self.evaluate([d])[0]
        return self._base.copy()


#: sets of perturbations analysed together: bounds the memory of the perturbed records
BLOCK = 32


@_doc
def monte_carlo(model: RunModel, inputs: list[Input], draws: int, seed) -> np.ndarray:
    """Return the results of ``draws`` seeded Monte Carlo draws.

    Each draw perturbs every input by one sample of its distribution (normal, or rectangular
    over ±sqrt(3) u) times its standard uncertainty. Draw i uses its own generator
    (``SeedSequence(seed).spawn``), so the first n draws of a larger sample are the n draws of
    a smaller one, and the same seed gives the same numbers.

    Parameters
    ----------
    %(model)s
    %(inputs)s
    draws : int
        Number of draws.
    seed : int or sequence of int
        Seed of the draws.

    Returns
    -------
    numpy.ndarray
        Results (draws, results) [units of each result]; a row of NaN for a draw the analysis
        refused.

    References
    ----------
    JCGM 101:2008, Propagation of distributions using a Monte Carlo method, §6-7.
    """
    model({})  # the unperturbed run, kept for the flap-only components
    children = np.random.SeedSequence(seed).spawn(draws)
    out = np.empty((draws, len(model.results)))
    for start in range(0, draws, BLOCK):  # the draws of a block analysed together
        ds = []
        for child in children[start:start + BLOCK]:
            rng = np.random.default_rng(child)
            ds.append({inp.name: np.asarray(inp.u) * _sample(rng, inp.distribution,
                                                             model.size(inp))
                       for inp in inputs})
        out[start:start + len(ds)] = model.evaluate(ds)
    return out


@_doc
def linear(model: RunModel, inputs: list[Input], directions: int, seed
           ) -> tuple[np.ndarray, np.ndarray]:
    """Propagate the inputs linearly (GUM §5.1): sensitivities and contributions.

    Per input, the sensitivity coefficient by central differences of ±u (results per unit of the
    input; for an input with one value per probe the root-sum-square over probes, for one per
    sample the RMS over ``directions`` random unit-variance directions) and the contribution c u.

    Parameters
    ----------
    %(model)s
    %(inputs)s
    directions : int
        Random directions of each per-sample input.
    seed : int or sequence of int
        Seed of the directions.

    Returns
    -------
    sensitivity : numpy.ndarray
        (inputs, results) [unit of the result per unit of the input].
    contribution : numpy.ndarray
        (inputs, results), c u [unit of the result].

    References
    ----------
    JCGM 100:2008 (GUM), §5.1.2-5.1.4 (law of propagation of uncertainty, sensitivity
    coefficients).
    """
    base = model({})
    rng = np.random.default_rng(np.random.SeedSequence(seed).spawn(1)[0])
    sens = np.zeros((len(inputs), base.size))
    contrib = np.zeros((len(inputs), base.size))
    steps, sets = [], []
    for inp in inputs:  # the ±u steps of every input, analysed together
        shape = model.size(inp)
        u = np.broadcast_to(np.asarray(inp.u, float), shape if inp.shape == "probe" else ())
        if inp.shape in ("probe", "scalar"):
            st = [np.eye(shape[0])[j] * u for j in range(shape[0])] if shape else [u]
        else:  # a random direction of unit variance per element, scaled by u
            st = [rng.standard_normal(shape) * u for _ in range(max(1, directions))]
        steps.append((u, len(st)))
        sets += [d for s in st for d in ({inp.name: s}, {inp.name: -s})]
    results = np.concatenate([model.evaluate(sets[i:i + BLOCK])
                              for i in range(0, len(sets), BLOCK)]) if sets else np.empty(0)
    first = 0
    for i, (inp, (u, n_steps)) in enumerate(zip(inputs, steps, strict=True)):
        r = results[first:first + 2 * n_steps]
        first += 2 * n_steps
        d = (r[0::2] - r[1::2]) / 2.0
        c_u_sq = np.sum(d ** 2, axis=0) if inp.shape in ("probe", "scalar") \
            else np.mean(d ** 2, axis=0)
        contrib[i] = np.sqrt(c_u_sq)
        scale = float(np.sqrt(np.mean(np.square(u)))) if np.size(u) else 0.0
        sens[i] = contrib[i] / scale if scale > 0 else np.nan
    return sens, contrib


def draws_uncertainty(draws: np.ndarray, base: np.ndarray) -> np.ndarray:
    """Return the standard uncertainty of each result from its Monte Carlo draws.

    The draws' spread about the unperturbed result, not only about their own mean: where the
    analysis is nonlinear in the errors (a per-cycle maximum of a quantised angle), perturbing
    the record moves the draws' mean off it by about as much as the record's own errors moved
    the result off the truth (θ amplitude on the virtual flume: +1.9e-6 and +1.7e-6 rad
    against a spread of 2.1e-6). The shift adds in quadrature, less the noise of the mean, so
    that a result linear in the errors keeps its standard deviation.

    Parameters
    ----------
    draws : numpy.ndarray
        Results of the draws, shape (n, results) [units of each result], all finite.
    base : numpy.ndarray
        The unperturbed results, shape (results,).

    Returns
    -------
    numpy.ndarray
        sqrt(s² + max(0, (ȳ - y₀)² - s²/n)) per result, s the draws' standard deviation
        (ddof 1); NaN with fewer than two draws.

    References
    ----------
    JCGM 101:2008, §7.6 (the standard uncertainty from the draws).

    Examples
    --------
    >>> import numpy as np
    >>> draws = np.array([[1.0], [3.0]])
    >>> float(draws_uncertainty(draws, np.array([2.0]))[0])  # mean on the base: s = sqrt(2)
    1.4142135623730951
    """
    n = draws.shape[0]
    if n < 2:
        return np.full(base.shape, np.nan)
    s2 = draws.var(axis=0, ddof=1)
    shift2 = np.square(draws.mean(axis=0) - base) - s2 / n
    return np.sqrt(s2 + np.maximum(shift2, 0.0))


@_doc
def propagate(model: RunModel, inputs: list[Input], draws: int = 50, seed=0,
              directions: int = 4, linear_check: bool = True) -> xr.Dataset:
    """Propagate ``inputs`` through the analysis of one run, by Monte Carlo and linearly.

    Parameters
    ----------
    %(model)s
    %(inputs)s
    draws : int
        Monte Carlo draws [-]: the speed/accuracy knob (the relative standard deviation of an
        estimated standard uncertainty is about 1/sqrt(2 (draws - 1))).
    seed : int or sequence of int
        Seed of the draws (same seed and inputs: same result).
    directions : int
        Random directions of each per-sample input in the linear propagation [-].
    linear_check : bool
        Whether to run the linear propagation (the budget).

    Returns
    -------
    xarray.Dataset
        For each result X: ``X`` (the unperturbed analysis), ``X_uncertainty`` (the run's
        combined standard uncertainty, its Type B), ``X_uncertainty_type_b`` (the draws'
        spread about X: their standard deviation s and, in quadrature, the shift of their mean
        from X less its noise, sqrt(s² + max(0, (ȳ - X)² - s²/n)); attributes ``method``,
        ``draws``, ``degrees_of_freedom``),
        ``X_expanded_uncertainty`` (coverage factor from the t distribution with draws - 1
        degrees of freedom, attribute ``coverage_factor``), ``X_coverage_low``/``_high``
        (2.5 and 97.5 % quantiles of the draws), ``X_uncertainty_linear`` and, along
        ``uncertainty_component``, ``X_sensitivity``, ``X_budget`` (c u) and
        ``X_contribution`` [%]; ``input_standard_uncertainty`` with ``input_units``.

    References
    ----------
    JCGM 101:2008, Propagation of distributions using a Monte Carlo method, §5-7.
    JCGM 100:2008 (GUM), §5.1 and G.4. ITTC 7.5-02-07-03.12 (2021), Uncertainty analysis for
    a wave energy converter.

    Examples
    --------
    See :func:`flumekit.stages.uncertainty_run.run_uncertainty` for a run of the pipeline.
    """
    from scipy import stats

    from flumekit import conventions

    base = model({})
    mc = monte_carlo(model, inputs, draws, seed)
    ok = np.isfinite(mc).all(axis=1)
    failed = int((~ok).sum())
    mc = mc[ok]
    n = mc.shape[0]
    u_mc = draws_uncertainty(mc, base)
    k = float(stats.t.ppf(0.975, n - 1)) if n > 1 else np.nan
    lo, hi = (np.quantile(mc, [0.025, 0.975], axis=0) if n > 1
              else (np.full(base.size, np.nan),) * 2)
    names = [i.name for i in inputs]
    data = {}
    if linear_check:
        sens, contrib = linear(model, inputs, directions, seed)
        u_lin = np.sqrt(np.sum(contrib ** 2, axis=0))
    method = (f"Monte Carlo (JCGM 101), {n} draws of the declared Type B components through "
              "flumekit.waves.analyse_run and flumekit.flap.analyse_run; the draws' spread "
              "about the unperturbed result")
    for j, q in enumerate(model.results):
        anc = [f"{q}_uncertainty", f"{q}_uncertainty_type_b", f"{q}_expanded_uncertainty"]
        data[f"{q}_uncertainty"] = ((), u_mc[j], {
            "method": "combined standard uncertainty of the run: its Type B (a single run has "
                      "no Type A evaluation; conditions.nc combines the repeats)"})
        data[f"{q}_uncertainty_type_b"] = ((), u_mc[j], {
            "method": method, "draws": n, "failed_draws": failed,
            "degrees_of_freedom": n - 1})
        data[f"{q}_expanded_uncertainty"] = ((), k * u_mc[j], {
            "coverage_factor": k, "coverage_probability": 0.95,
            "method": "t distribution with draws - 1 degrees of freedom times the Monte Carlo "
                      "standard uncertainty"})
        data[f"{q}_coverage_low"] = ((), lo[j])
        data[f"{q}_coverage_high"] = ((), hi[j])
        if linear_check:
            anc.append(f"{q}_uncertainty_linear")
            total = u_lin[j] ** 2
            data[f"{q}_uncertainty_linear"] = ((), u_lin[j], {
                "method": f"linear GUM propagation, central differences of +-u (vector inputs: "
                          f"{directions} random directions)"})
            data[f"{q}_sensitivity"] = ("uncertainty_component", sens[:, j], {
                "comment": "result per unit of the component's input (input_units); vector "
                           "inputs: root-sum-square over probes or RMS over random directions"})
            data[f"{q}_budget"] = ("uncertainty_component", contrib[:, j])
            data[f"{q}_contribution"] = ("uncertainty_component",
                                         100.0 * contrib[:, j] ** 2 / total if total > 0
                                         else np.zeros(len(inputs)))
        data[q] = ((), base[j], {"ancillary_variables": " ".join(anc)})
    coords = {"uncertainty_component": names}
    if linear_check:
        data["input_standard_uncertainty"] = ("uncertainty_component", [
            float(np.sqrt(np.mean(np.square(i.u)))) for i in inputs], {
            "comment": "RMS over probes for a component with one value per probe"})
        data["input_units"] = ("uncertainty_component", [i.units for i in inputs])
        data["component_type"] = ("uncertainty_component", ["B"] * len(inputs))
        data["component_distribution"] = ("uncertainty_component",
                                          [i.distribution for i in inputs],
                                          {"long_name": "probability distribution of the "
                                           "component"})
        data["component_source"] = ("uncertainty_component", [i.source for i in inputs],
                                    {"long_name": "where the component's value comes from"})
    ds = xr.Dataset(data, coords=coords if linear_check else {})
    if failed:
        warnings.warn(f"{failed} of {draws} Monte Carlo draws were refused by the analysis and "
                      "left out", UserWarning, stacklevel=2)
    return conventions.annotate(ds)
