"""The virtual flume: write a complete raw campaign from known physics, with its truth.

The campaign reproduces the design of Brito et al. (2020): water depth 0.825 m, the flap and PTO
of §2.2, the periods and heights of Table 1 with probes at x12 = L/10 and x23 = L/4 of the local
wavelength, regular waves ramped up from the wavemaker, reflection from the flap, second-order
bound harmonics, probe gains/offsets and noise, encoder quantisation, pressure sensor noise and,
for the UVP runs (T = 3.5 s, H = 0.25 m), Met-Flow profile files of three beams. Irregular
runs (JONSWAP sea states, :mod:`flumekit.synth.irregular`) follow the regular and UVP runs,
so that every regular run keeps its random stream.

Layout written (raw/README.md): ``campaign.toml``, ``calibration/probes.csv``,
``runs/<run>/{run.toml, probes.csv, flap.csv, UP1.mfprof, ...}`` and the truth in ``truth/``
(``calibration.nc``, ``<run>/waves.nc``, ``<run>/flap.nc``, ``uvp_field.nc``). The same seed
gives the same files.
"""

from __future__ import annotations

import dataclasses
import os
import shutil
import tempfile
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.campaign import Campaign, load_campaign
from flumekit.errors import InputError
from flumekit.io.atomic import umask
from flumekit.io.netcdf import write_dataset
from flumekit.io.tables import write_table
from flumekit.synth import DEFAULT_SEED, MARKER
from flumekit.synth.flume import RepeatScatter
from flumekit.synth.irregular import SeaTruth
from flumekit.synth.marker import record_written, start_record
from flumekit.synth.waves import RAMP_WAVES, Beach
from flumekit.waves.theory import group_velocity, wavelength

PERIODS = (2.0, 2.25, 2.5, 2.75, 3.0, 3.25, 3.5, 3.75, 4.0)  # Table 1 [s]
HEIGHTS = (0.15, 0.175, 0.2, 0.225, 0.25, 0.275, 0.3)  # Table 1 [m]
UVP_CONDITION = (3.5, 0.25)  # §2.4 [s], [m]
UVP_ELEVATIONS = tuple(np.round(np.arange(0.20, 0.7201, 0.02), 3))  # §2.3 [m]
CALIBRATION_LEVELS = (-0.10, -0.05, 0.0, 0.05, 0.10)  # static submersions [m]
#: irregular runs: the JONSWAP peak enhancement of every sea state [-] and the seed of the
#: first sea state's phases (the next ones count on from it)
SEA_GAMMA = 3.3
SEA_SEED = 11
#: a run's truth (waves.nc, flap.nc) is stored uncompressed: its dense float series deflate to
#: 60-80 % of their size only, and deflating them cost more than the rest of a run's synthesis
_RUN_TRUTH_COMPRESSED = False


@dataclass(frozen=True)
class Size:
    """What a campaign size holds: its regular, UVP and irregular runs.

    Attributes
    ----------
    wave_runs : tuple of (float, float)
        (period [s], height [m]) of each regular wave run.
    uvp_elevations : tuple of float
        Elevation of the UVP above the bed [m], one UVP run per entry (repeats allowed).
    n_steady_waves : int
        Steady waves after the ramp (>= 50 are averaged) [-].
    sea_states : tuple of (float, float)
        (Hm0 [m], Tp [s]) of each irregular run.
    sea_duration : float
        Record length of the irregular runs [s].
    """

    wave_runs: tuple[tuple[float, float], ...]
    uvp_elevations: tuple[float, ...]  # one UVP run per entry (repeats allowed)
    n_steady_waves: int = 55  # steady waves after the ramp (>= 50 are averaged)
    sea_states: tuple[tuple[float, float], ...] = ()  # irregular runs: (Hm0 [m], Tp [s])
    sea_duration: float = 600.0  # record length of the irregular runs [s]


def _size(name: str) -> Size:
    # sea states: steepness Hm0/Lp 0.013-0.029 (moderate), Hm0/h at most 0.15; the 400 s of
    # the small run leave 294 s (147 peak periods) after the sea has developed
    if name == "small":
        return Size(wave_runs=((2.0, 0.15), (3.5, 0.25)), uvp_elevations=(0.30, 0.50),
                    sea_states=((0.10, 2.0),), sea_duration=400.0)
    if name == "default":
        # a 2 x 2 power matrix (Hm0 x Te)
        return Size(wave_runs=tuple((t, h) for t in PERIODS for h in (0.15, 0.2, 0.25)),
                    uvp_elevations=UVP_ELEVATIONS[::2],
                    sea_states=tuple((h, t) for h in (0.08, 0.12) for t in (2.0, 2.8)))
    if name == "paper":
        # 78 repeats cycling through the 27 elevations of §2.3 (most elevations 3 times);
        # a 3 x 4 power matrix
        return Size(wave_runs=tuple((t, h) for t in PERIODS for h in HEIGHTS),
                    uvp_elevations=tuple(UVP_ELEVATIONS[k % len(UVP_ELEVATIONS)]
                                         for k in range(78)),
                    sea_states=tuple((h, t) for h in (0.06, 0.09, 0.12)
                                     for t in (1.8, 2.2, 2.6, 3.0)),
                    sea_duration=900.0)
    raise ValueError(f"unknown campaign size '{name}': small, default or paper")


@dataclass(frozen=True)
class Truth:
    """Known physics of the virtual flume not written in the raw metadata."""

    # the flap's own reflection coefficient: with the beach's wave returning through the flap
    # the separation measures 0.20 at T = 3.5 s, H = 0.25 m, as Brito et al. (2020, §2.4)
    reflection: float = 0.14
    reflection_phase: float = 0.6  # [rad]
    probe_noise: float = 0.5e-3  # probe noise, as elevation [m]
    static_seconds: float = 30.0  # record length at each static level [s]
    ramp_waves: float = RAMP_WAVES  # linear wavemaker ramp [periods] (steady from ~35 waves)
    x_wavemaker: float = -32.7  # [m]
    x_wp3: float = -2.0  # WP3 position [m]; WP1, WP2 follow Table 1 spacings
    x_wp4: float = -0.6  # [m]
    scatter: RepeatScatter = RepeatScatter()  # run-to-run variability (synth/flume.py)
    # the beach's reflection (8 % without the flap, Brito et al. 2020, §2.3), reaching the
    # probes through the flap twice: K_t = 0.9 from the energy the flap lets pass, K_t² ≈
    # 1 - Kr² - C_f b/B = 1 - 0.04 - 0.12 · 1.31/1.5 less its viscous losses; None: no beach
    beach: Beach | None = Beach(transmission=0.9)
    # the irregular runs' flume: ramp, band, the flap's and the beach's reflection per
    # frequency (their transmission replaces the beach's constant one), probe layout
    sea: SeaTruth = SeaTruth()


def probe_positions(period: float, depth: float, truth: Truth) -> dict[str, float]:
    """Table 1 layout: x12 = L/10 and x23 = L/4 of the local wavelength, upstream of WP3."""
    L = float(wavelength(period, depth))
    x3 = truth.x_wp3
    return {"WP1": round(x3 - L / 4 - L / 10, 4), "WP2": round(x3 - L / 4, 4), "WP3": x3,
            "WP4": truth.x_wp4}


def _probe_gains(names, rng) -> tuple[np.ndarray, np.ndarray]:
    """Draw the true sensor law V = a + b eta per probe: b ~ 10 V/m, a ~ 2.5 V, a few % apart."""
    b = 10.0 * (1 + 0.05 * rng.standard_normal(len(names)))
    a = 2.5 + 0.3 * rng.standard_normal(len(names))
    return a, b




@dataclass(frozen=True)
class RunSpec:
    """One planned run of a virtual campaign.

    Attributes
    ----------
    id : str
        Run identifier, the name of its folder under ``runs/``.
    kind : str
        ``"waves"``, ``"uvp"`` or ``"irregular"``.
    period : float
        Wave period [s] (an irregular run: the peak period Tp).
    height : float
        Wave height [m] (an irregular run: Hm0).
    repeat : int
        Repeat index of the condition [-].
    uvp_elevation : float or None
        UVP elevation above the bed [m] of a UVP run, else None.
    key : tuple of int
        With the campaign's seed, the run's random stream: (condition index, repeat).
    sea : dict or None
        An irregular run's hm0, tp, gamma, seed and duration (as in ``run.toml``), else None.
    """

    id: str
    kind: str
    period: float
    height: float
    repeat: int
    uvp_elevation: float | None
    key: tuple[int, int]  # with the seed, the run's random stream: (condition index, repeat)
    sea: dict | None = None  # irregular runs: hm0, tp, gamma, seed, duration of run.toml


def plan_runs(size: str) -> list[RunSpec]:
    """Plan the runs of a campaign size, each with its own random stream.

    Each run's random stream depends only on the seed and the run's key, so any subset of runs
    can be synthesised, in any order, to the same bytes as the whole campaign.

    Parameters
    ----------
    size : str
        Campaign size: ``"small"``, ``"default"`` or ``"paper"``.

    Returns
    -------
    list of RunSpec
        The regular runs, then the UVP runs, then the irregular runs.

    Raises
    ------
    ValueError
        If ``size`` is not one of the three sizes.

    Examples
    --------
    >>> [r.id for r in plan_runs("small")][:3]
    ['T2.00_H0.150_r0', 'T3.50_H0.250_r0', 'uvp_z0.300_r0']
    """
    spec = _size(size)
    runs = [("waves", t, h, None) for t, h in spec.wave_runs]
    runs += [("uvp", *UVP_CONDITION, z) for z in spec.uvp_elevations]
    runs += [("irregular", tp, hm0, None) for hm0, tp in spec.sea_states]
    seen: dict[str, int] = {}
    out = []
    for kind, period, height, z in runs:
        base = (f"T{period:.2f}_H{height:.3f}" if kind == "waves" else
                f"uvp_z{z:.3f}" if kind == "uvp" else f"JS_Hm{height:.3f}_Tp{period:.2f}")
        repeat = seen.get(base, 0)
        seen[base] = repeat + 1
        if kind == "irregular":
            # a repeat plays the same wavemaker signal (the same seed)
            sea = {"hm0": height, "tp": period, "gamma": SEA_GAMMA,
                   "seed": SEA_SEED + spec.sea_states.index((height, period)),
                   "duration": spec.sea_duration}
            out.append(RunSpec(f"{base}_r{repeat}", kind, period, height, repeat, None,
                               (len(seen), repeat), sea))
            continue
        out.append(RunSpec(f"{base}_r{repeat}", kind, period, height, repeat, z,
                           (len(seen), repeat)))
    return out


def write_campaign(root: str | Path, size: str = "small", seed: int = DEFAULT_SEED,
                   truth: Truth = Truth(), progress=None) -> Campaign:
    """Write a virtual-flume campaign to ``root`` and return it.

    ``root`` must be absent or an empty folder: synthesis never deletes or overwrites anything
    it did not write (raw data is sacred). The campaign is written to a fresh temporary sibling
    folder and renamed into place at the end, so an interrupted synthesis leaves no half
    campaign at ``root``. The layout is that of raw/README.md, with the truth in ``truth/``
    (module notes).

    Parameters
    ----------
    root : str or pathlib.Path
        Campaign folder to create; absent or empty.
    size : str, default "small"
        Campaign size: ``"small"`` (2 regular, 2 UVP and 1 irregular run), ``"default"``
        (27 regular runs of Table 1, 14 UVP repeats, 4 sea states) or ``"paper"`` (the 63
        conditions of Table 1, 78 UVP repeats, 12 sea states).
    seed : int, default :data:`flumekit.synth.DEFAULT_SEED`
        Seed of every random stream: the same seed gives the same files.
    truth : Truth, optional
        Physics of the virtual flume not written in the raw metadata.
    progress : callable, optional
        ``progress(i, n, run_id)``, called before each of the ``n`` runs.

    Returns
    -------
    flumekit.campaign.Campaign
        The written campaign, as :func:`flumekit.load_campaign` reads it.

    Raises
    ------
    flumekit.errors.InputError
        If ``root`` exists and is not an empty folder (nothing is changed).
    ValueError
        If ``size`` is unknown.

    See Also
    --------
    virtual_campaign : The same campaign's plan, without writing it.

    References
    ----------
    Brito, M. et al. (2020). Experimental investigation on the power capture of an oscillating
    wave surge converter in unidirectional waves. Energies 13, 5417 (§2, Table 1).

    Examples
    --------
    The small campaign takes several seconds to synthesise, so it is not run here; what it
    writes:

    >>> campaign = write_campaign("raw/small", "small")  # doctest: +SKIP
    >>> len(campaign.runs), campaign.runs[1].id  # doctest: +SKIP
    (5, 'T2.00_H0.150_r0')
    >>> sorted(p.name for p in campaign.root.iterdir())  # doctest: +SKIP
    ['.flumekit-virtual.json', 'calibration', 'campaign.toml', 'runs', 'truth']
    >>> sorted(p.name for p in (campaign.root / "runs" / "T2.00_H0.150_r0").iterdir())
    ... # doctest: +SKIP
    ['flap.csv', 'probes.csv', 'run.toml']
    >>> sorted(p.name for p in (campaign.root / "truth" / "T2.00_H0.150_r0").iterdir())
    ... # doctest: +SKIP
    ['flap.nc', 'waves.nc']

    A folder that holds anything is refused before a file is written:

    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     _ = (Path(folder) / "notes.txt").write_text("tank 2, May")
    ...     try:
    ...         write_campaign(folder, "small")
    ...     except InputError as e:
    ...         refused = "nothing was changed" in str(e)
    ...     left = sorted(p.name for p in Path(folder).iterdir())
    >>> refused, left
    (True, ['notes.txt'])
    """
    root = Path(root)

    def fill(tmp: Path) -> None:
        campaign, a, b = _write_base(tmp, root.name, size, seed, truth)
        runs = plan_runs(size)
        from flumekit.synth.flap import flume_hydrodynamics

        # the flap simulator's coefficients and radiation model: the same for every run
        flap_hydro = flume_hydrodynamics(campaign)
        for i, r in enumerate(runs):
            if progress is not None:
                progress(i, len(runs), r.id)
            if r.sea is not None:
                _write_irregular_run(tmp, campaign, r.id, r.repeat, r.sea, a, b, truth,
                                     np.random.default_rng([seed, *r.key]), flap_hydro)
                continue
            _write_run(tmp, campaign, r.id, r.kind, r.period, r.height, r.repeat,
                       r.uvp_elevation, a, b, truth, np.random.default_rng([seed, *r.key]),
                       _size(size).n_steady_waves, flap_hydro=flap_hydro)
        if any(r.kind == "uvp" for r in runs):
            _write_uvp_truth(tmp, campaign, truth, size, seed)

    _into_new_folder(root, fill)
    return load_campaign(root)


def write_virtual_base(root: str | Path, size: str, seed: int, truth: Truth = Truth()) -> None:
    """Write the campaign-wide files of a virtual campaign into ``root``, without any run.

    The files are ``campaign.toml``, the probe calibration, its truth and :data:`MARKER`;
    :func:`write_virtual_run` then adds the runs one by one.

    Parameters
    ----------
    root : str or pathlib.Path
        Campaign folder to create; absent or empty.
    size : str
        Campaign size (:func:`plan_runs`).
    seed : int
        Seed of the campaign's random streams.
    truth : Truth, optional
        Physics of the virtual flume not written in the raw metadata.

    Raises
    ------
    flumekit.errors.InputError
        If ``root`` exists and is not an empty folder.
    """
    root = Path(root)

    def fill(tmp: Path) -> None:
        _write_base(tmp, root.name, size, seed, truth)
        start_record(tmp)

    _into_new_folder(root, fill)


def write_virtual_run(root: str | Path, run_id: str, truth: Truth = Truth()) -> None:
    """Add one planned run and its truth to a virtual campaign of :func:`write_virtual_base`.

    The run's files are the same bytes as in the whole campaign of :func:`write_campaign`.
    The run folder appears only complete (its truth first, then the run folder by a rename).

    Parameters
    ----------
    root : str or pathlib.Path
        Folder of a campaign the virtual flume wrote (it holds :data:`MARKER`).
    run_id : str
        Identifier of a run of the campaign's plan (:func:`plan_runs`).
    truth : Truth, optional
        Physics of the virtual flume not written in the raw metadata.

    Raises
    ------
    flumekit.errors.InputError
        If ``root`` is not a virtual-flume campaign, the plan has no run ``run_id`` or the
        run's folder exists (nothing there is touched).
    """
    import json

    root = Path(root)
    marker = root / MARKER
    if not marker.is_file():
        raise InputError(root, f"not a virtual-flume campaign ({MARKER} missing); runs are "
                         "synthesised only into a campaign the virtual flume wrote")
    info = json.loads(marker.read_text())
    size, seed = info["size"], int(info["seed"])
    spec = {r.id: r for r in plan_runs(size)}.get(run_id)
    if spec is None:
        raise InputError(marker, f"the '{size}' campaign has no run '{run_id}'")
    if (root / "runs" / run_id).exists():
        raise InputError(root / "runs" / run_id, "exists; the virtual flume never writes over it")
    campaign = load_campaign(root)
    rng = np.random.default_rng(seed)
    a, b = _probe_gains(campaign.probes.names, rng)
    (root / "runs").mkdir(exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{run_id}.", suffix=".partial", dir=root / "runs"))
    try:
        os.chmod(tmp, 0o777 & ~umask())
        rng = np.random.default_rng([seed, *spec.key])
        if spec.sea is not None:
            _write_irregular_run(tmp, campaign, run_id, spec.repeat, spec.sea, a, b, truth,
                                 rng, _hydro(campaign))
        else:
            _write_run(tmp, campaign, run_id, spec.kind, spec.period, spec.height,
                       spec.repeat, spec.uvp_elevation, a, b, truth, rng,
                       _size(size).n_steady_waves, flap_hydro=_hydro(campaign))
        # truth first, the run folder last: a run appears only complete
        (root / "truth").mkdir(exist_ok=True)
        os.rename(tmp / "truth" / run_id, root / "truth" / run_id)
        if spec.kind == "uvp" and not (root / "truth" / "uvp_field.nc").exists():
            _write_uvp_truth(root, campaign, truth, size, seed)
        os.rename(tmp / "runs" / run_id, root / "runs" / run_id)
        record_written(root, run_id)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)  # only the folder this call created


_HYDRO: dict = {}


def _hydro(campaign: Campaign):
    """Return the flap simulator's hydrodynamics, computed once per process and campaign."""
    from flumekit.synth.flap import flume_hydrodynamics

    key = campaign.root
    if key not in _HYDRO:
        _HYDRO[key] = flume_hydrodynamics(campaign)
    return _HYDRO[key]


def virtual_campaign(root: str | Path, size: str, seed: int) -> Campaign:
    """Return the campaign :func:`write_campaign` would write at ``root``, writing nothing.

    This is what a pipeline plans with before the virtual flume has run. The campaign and run
    files are written to a temporary folder and read by :func:`flumekit.load_campaign`
    itself, so the plan is what the campaign reader makes of the files the virtual flume will
    write; the paths point into ``root``.

    Parameters
    ----------
    root : str or pathlib.Path
        Folder the campaign would be written to (not touched; need not exist).
    size : str
        Campaign size: ``"small"``, ``"default"`` or ``"paper"`` (:func:`write_campaign`).
    seed : int
        Seed of the campaign (the plan does not depend on it).

    Returns
    -------
    flumekit.campaign.Campaign
        The planned campaign, its runs without data files.

    Raises
    ------
    ValueError
        If ``size`` is unknown.

    Examples
    --------
    >>> c = virtual_campaign("raw/small", "small", 2020)
    >>> c.name, len(c.runs), c.runs[0].id
    ('small', 5, 'JS_Hm0.100_Tp2.00_r0')
    """
    import dataclasses

    root = Path(root)
    truth = Truth()
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        (tmp / "campaign.toml").write_text(campaign_toml(root.name))
        depth = load_campaign(tmp).flume.water_depth
        for r in plan_runs(size):
            (tmp / "runs" / r.id).mkdir(parents=True)
            xp = (dict(truth.sea.probe_x) if r.sea is not None
                  else probe_positions(r.period, depth, truth))
            sea = None if r.sea is None else {**r.sea, "transient": transient(r.sea, depth,
                                                                              xp, truth)}
            (tmp / "runs" / r.id / "run.toml").write_text(run_toml(
                r.kind, r.period, r.height, r.repeat, r.uvp_elevation, xp, sea=sea))
        planned = load_campaign(tmp)

        def moved(p: Path) -> Path:
            return root / os.path.relpath(p, tmp)

        runs = tuple(dataclasses.replace(r, path=moved(r.path),
                                         files={k: moved(v) for k, v in r.files.items()})
                     for r in planned.runs)
    return dataclasses.replace(planned, root=root, runs=runs)


def campaign_toml(name: str) -> str:
    """Return the text of the virtual campaign's ``campaign.toml`` under the name ``name``.

    Parameters
    ----------
    name : str
        Campaign name (the folder's name).

    Returns
    -------
    str
        The packaged default campaign (``flumekit/data/default_campaign.toml``) renamed.
    """
    template = resources.files("flumekit.data").joinpath("default_campaign.toml").read_text()
    return template.replace('name = "default"', f'name = "{name}"', 1)


def _into_new_folder(root: Path, fill) -> None:
    _check_empty(root)
    root.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{root.name}.", suffix=".partial", dir=root.parent))
    os.chmod(tmp, 0o777 & ~umask())  # mkdtemp makes 0700; the campaign folder follows the umask
    try:
        fill(tmp)
        # os.rename onto an empty directory replaces it atomically; onto a non-empty one it
        # fails (ENOTEMPTY), so a folder filled meanwhile by someone else is never clobbered
        _check_empty(root)
        os.rename(tmp, root)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)  # only the folder this call created
        raise


def _check_empty(root: Path) -> None:
    if root.exists() and (not root.is_dir() or any(root.iterdir())):
        raise InputError(root, "the virtual flume writes only into an absent or empty folder; "
                         "this one has files (nothing was changed). Point the pipeline's "
                         "'raw' at the campaign folder, or choose a new folder")


def _write_base(tmp: Path, name: str, size: str, seed: int, truth: Truth):
    import json

    (tmp / "calibration").mkdir(parents=True)
    (tmp / "truth").mkdir()
    (tmp / "campaign.toml").write_text(campaign_toml(name))
    campaign = load_campaign(tmp)
    names = campaign.probes.names
    rng = np.random.default_rng(seed)
    a, b = _probe_gains(names, rng)
    _write_calibration(tmp, names, a, b, campaign.probes.sampling_rate, truth, rng)
    (tmp / MARKER).write_text(json.dumps({"size": size, "seed": seed,
                                          "runs": [r.id for r in plan_runs(size)]}) + "\n")
    return campaign, a, b


def _write_uvp_truth(root: Path, campaign: Campaign, truth: Truth, size: str, seed: int) -> None:
    from flumekit.synth.uvp import true_field

    field = true_field(campaign, period=UVP_CONDITION[0], height=UVP_CONDITION[1],
                       reflection=truth.reflection, reflection_phase=truth.reflection_phase,
                       x_wavemaker=truth.x_wavemaker, beach=truth.beach)
    _finish(field, "Virtual flume truth: phase-averaged velocity field", size, seed)
    write_dataset(field, root / "truth" / "uvp_field.nc")


def _finish(ds: xr.Dataset, title: str, size: str, seed: int) -> xr.Dataset:
    ds.attrs.update(conventions.global_attrs(title, "flumekit virtual flume (flumekit.synth)",
                                             {"size": size, "seed": seed}))
    return ds


def _write_calibration(root, names, a, b, rate, truth: Truth, rng) -> None:
    n = int(truth.static_seconds * rate)
    levels = np.repeat(CALIBRATION_LEVELS, n)
    noise = truth.probe_noise * rng.standard_normal((levels.size, len(names)))
    volts = a + b * (levels[:, None] + noise)
    write_table(root / "calibration" / "probes.csv", [("level", "m")] + [(p, "V") for p in names],
                np.column_stack([levels, volts]), fmt="%.6f")
    ds = xr.Dataset({"gain": ("probe", 1.0 / b), "offset": ("probe", -a / b)},
                    coords={"probe": list(names)})
    write_dataset(_finish(ds, "Virtual flume truth: probe calibration", "", 0),
                  root / "truth" / "calibration.nc")


def transient(sea: dict, depth: float, probe_x: dict[str, float], truth: Truth) -> float:
    """Return the start of an irregular run's analysed span [s], as a laboratory declares it.

    The span starts after the wavemaker's ramp and the time the incident wave, the flap's
    reflection and the beach's wave take to reach the flap and the farthest probe
    (:func:`flumekit.synth.irregular.analysis_start`; the flap's reflection weighted as the
    incident spectrum, the beach's by its measured roll-off), in whole seconds.

    Parameters
    ----------
    sea : dict
        The run's target sea state: ``hm0`` [m], ``tp`` [s], ``gamma`` [-], ``seed``,
        ``duration`` [s].
    depth : float
        Water depth [m].
    probe_x : dict of str to float
        Probe positions [m] (x = 0 at the flap hinge).
    truth : Truth
        The virtual flume's physics (ramp, band, beach).

    Returns
    -------
    float
        Start of the analysed span [s], a whole second, written as ``transient`` in
        ``run.toml``.
    """
    from flumekit.synth.irregular import analysis_start, beach_reflection
    from flumekit.synth.waves import random_phase_components

    sea_cfg = truth.sea
    fp = 1.0 / sea["tp"]
    f, a, _ = random_phase_components(sea["duration"], sea["hm0"], sea["tp"], sea["gamma"],
                                      sea["seed"], (sea_cfg.band[0] * fp, sea_cfg.band[1] * fp))
    beach = truth.beach if truth.beach is not None else Beach(reflection=0.0)

    def returning(f):  # the flap's reflection unknown (1), the beach's as the lab measured it
        return np.ones(f.size), beach_reflection(f, beach, sea_cfg.beach_roll_off)

    return analysis_start(f, a, depth=depth, x_min=min(probe_x.values()),
                          x_wavemaker=truth.x_wavemaker, x_beach=beach.x,
                          ramp_time=sea_cfg.ramp_peak_periods * sea["tp"],
                          returning=returning, developed=sea_cfg.developed)


def regular_waves_at_flap(duration: float, rate: float, wave_kw: dict
                          ) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """Return the flap's time axis and the regular waves at x = 0 that drive it.

    The waves are computed 20 s past the record's end, so that the flap's last seconds see the
    wave that goes on (:func:`flumekit.synth.flap.flap_record`, ``eta_lead_out``).

    Parameters
    ----------
    duration : float
        Record length [s].
    rate : float
        The flap instruments' sampling rate [Hz].
    wave_kw : dict
        Keyword arguments of :func:`flumekit.synth.waves.regular_wave_field`.

    Returns
    -------
    time : numpy.ndarray
        The record's sample times [s].
    waves : dict of str to numpy.ndarray
        ``eta_incident``, ``eta_reflected``, ``eta_beach`` at x = 0 [m], over ``time`` and the
        20 s after it.
    """
    from flumekit.synth.waves import regular_wave_field

    t = np.arange(int(duration * rate)) / rate
    t_lead = t[-1] + np.arange(1, int(20.0 * rate) + 1) / rate
    field = regular_wave_field(np.concatenate([t, t_lead]), np.array([0.0]), **wave_kw)
    return t, {k: field[k].values[0] for k in ("eta_incident", "eta_reflected", "eta_beach")}


def run_toml(kind: str, period: float, height: float, repeat: int, z: float | None,
             probe_x: dict[str, float], sea: dict | None = None) -> str:
    """Return the text of a virtual run's ``run.toml``.

    Parameters
    ----------
    kind : str
        Run kind: ``"waves"``, ``"uvp"`` or ``"irregular"``.
    period : float
        Wave period [s] (ignored where ``sea`` is given).
    height : float
        Wave height [m] (ignored where ``sea`` is given).
    repeat : int
        Repeat index [-].
    z : float or None
        UVP elevation above the bed [m], or None.
    probe_x : dict of str to float
        Probe positions [m].
    sea : dict, optional
        An irregular run's target sea state (``hm0``, ``tp``, ``gamma``, ``seed``,
        ``duration`` and, if known, ``transient``); it replaces the period and height.

    Returns
    -------
    str
        The TOML text (raw/README.md), ending with a newline.
    """
    if sea is not None:
        lines = ["[run]", f'kind = "{kind}"', f"hm0 = {sea['hm0']}  # [m]",
                 f"tp = {sea['tp']}  # [s]", f"gamma = {sea['gamma']}",
                 f"seed = {sea['seed']}", f"duration = {sea['duration']}  # [s]",
                 *([f"transient = {sea['transient']:g}  # [s], the analysed span's start"]
                   if sea.get("transient") is not None else []),
                 f"repeat = {repeat}"]
    else:
        lines = ["[run]", f'kind = "{kind}"', f"period = {period}", f"height = {height}",
                 f"repeat = {repeat}"]
    if z is not None:
        lines.append(f"uvp_elevation = {z}")
    lines += ["", "[probes]  # x [m]"] + [f"{p} = {x}" for p, x in probe_x.items()]
    return "\n".join(lines) + "\n"


def _write_run(root, campaign: Campaign, run_id, kind, period, height, repeat, z, a, b,
               truth: Truth, rng, n_steady: int, flap_hydro=None) -> None:
    from flumekit.synth.flap import FlapTruth, flap_record
    from flumekit.synth.flume import repeat_conditions
    from flumekit.synth.waves import regular_wave_field

    depth = campaign.flume.water_depth
    # what the wavemaker generated and the flap's losses in this run (run.toml keeps the
    # nominal condition, the truth the generated one)
    flap_truth = FlapTruth()
    generated_period, generated_height, losses = repeat_conditions(
        rng, period, height, truth.scatter, flap_truth.losses)
    flap_truth = dataclasses.replace(flap_truth, losses=losses)
    run_dir = root / "runs" / run_id
    run_dir.mkdir(parents=True)
    xp = probe_positions(period, depth, truth)
    # record: travel time from the wavemaker + ramp + steady waves, rounded to whole seconds
    travel = abs(truth.x_wavemaker) / float(group_velocity(period, depth))
    duration = float(np.ceil(travel + (35 + n_steady + 10) * period))
    (run_dir / "run.toml").write_text(run_toml(kind, period, height, repeat, z, xp))

    wave_kw = dict(period=generated_period, height=generated_height, depth=depth,
                   reflection=truth.reflection,
                   reflection_phase=truth.reflection_phase, x_reflector=0.0,
                   ramp_waves=truth.ramp_waves, second_order=True, x_wavemaker=truth.x_wavemaker,
                   beach=truth.beach)
    names = campaign.probes.names
    t25 = np.arange(int(duration * campaign.probes.sampling_rate)) / campaign.probes.sampling_rate
    field = regular_wave_field(t25, np.array([xp[p] for p in names] + [0.0]), **wave_kw)
    eta = field["eta"].values  # (x, time): incident, reflected and from the beach
    noisy = eta[:-1] + truth.probe_noise * rng.standard_normal(eta[:-1].shape)
    volts = a[:, None] + b[:, None] * noisy
    write_table(run_dir / "probes.csv", [("time", "s")] + [(p, "V") for p in names],
                np.column_stack([t25, volts.T]), fmt=["%.2f"] + ["%.6f"] * len(names))

    t100, at_flap = regular_waves_at_flap(duration, campaign.encoder.sampling_rate, wave_kw)
    n100 = t100.size
    flap = flap_record(t100, at_flap["eta_incident"][:n100], period=generated_period,
                       campaign=campaign, rng=rng, height=generated_height, hydro=flap_hydro,
                       truth=flap_truth,
                       eta_lead_out=at_flap["eta_incident"][n100:],
                       eta_front=(at_flap["eta_incident"] + at_flap["eta_reflected"]
                                  + at_flap["eta_beach"]))
    write_table(run_dir / "flap.csv", [("time", "s"), ("encoder", "counts"), ("pressure", "bar")],
                np.column_stack([t100, flap["encoder_counts"].values,
                                 flap["chamber_pressure"].values / 1e5]),
                fmt=["%.2f", "%d", "%.6f"])

    truth_dir = root / "truth" / run_id
    waves_truth = xr.Dataset(
        {"eta_incident": (("probe", "time"), field["eta_incident"].values[:-1]),
         "eta_reflected": (("probe", "time"), field["eta_reflected"].values[:-1]),
         "eta_beach": (("probe", "time"), field["eta_beach"].values[:-1])},
        coords={"probe": list(names), "time": t25, "x": ("probe", [xp[p] for p in names])},
        attrs={k: v for k, v in field.attrs.items() if np.isscalar(v)})
    write_dataset(_finish(waves_truth, f"Virtual flume truth: waves of run {run_id}", "", 0),
                  truth_dir / "waves.nc", compress=_RUN_TRUTH_COMPRESSED)
    flap_truth = flap.assign(eta_incident=("time", at_flap["eta_incident"][:n100]),
                             eta_reflected=("time", at_flap["eta_reflected"][:n100]),
                             eta_beach=("time", at_flap["eta_beach"][:n100]))
    write_dataset(_finish(flap_truth, f"Virtual flume truth: flap of run {run_id}", "", 0),
                  truth_dir / "flap.nc", compress=_RUN_TRUTH_COMPRESSED)

    if kind == "uvp":
        from flumekit.synth.uvp import uvp_beams, write_uvp_run

        u = campaign.uvp
        tu = np.arange(int(duration * u.sampling_rate)) / u.sampling_rate
        beams = uvp_beams(tu, u, z, period=generated_period, height=generated_height,
                          depth=depth,
                          hinge_height=campaign.flap.hinge_height, reflection=truth.reflection,
                          reflection_phase=truth.reflection_phase,
                          x_wavemaker=truth.x_wavemaker, ramp_waves=truth.ramp_waves,
                          beach=truth.beach,
                          theta=np.interp(tu, t100, flap["theta"].values),
                          flap_thickness=campaign.flap.thickness, rng=rng)
        write_uvp_run(run_dir, beams)


def _write_irregular_run(root, campaign: Campaign, run_id: str, repeat: int, sea: dict, a, b,
                         truth: Truth, rng, flap_hydro=None) -> None:
    """Write an irregular run (:mod:`flumekit.synth.irregular`): probes, flap and their truth."""
    from flumekit.synth.flap import FlapTruth, flap_record, flap_scattering
    from flumekit.synth.flume import repeat_conditions
    from flumekit.synth.irregular import irregular_sea, sea_state_truth
    from flumekit.synth.waves import jonswap

    depth = campaign.flume.water_depth
    flap_truth = FlapTruth()
    # what the wavemaker generated (its gain and time base scatter as in the regular runs)
    peak_period, hm0, losses = repeat_conditions(rng, sea["tp"], sea["hm0"], truth.scatter,
                                                 flap_truth.losses)
    flap_truth = dataclasses.replace(flap_truth, losses=losses)
    run_dir = root / "runs" / run_id
    run_dir.mkdir(parents=True)
    xp = dict(truth.sea.probe_x)
    names = campaign.probes.names
    missing = [p for p in names if p not in xp]
    if missing:
        raise ValueError(f"the irregular runs' probe layout has no position for {missing}")
    declared = {**sea, "transient": transient(sea, depth, xp, truth)}
    (run_dir / "run.toml").write_text(run_toml("irregular", sea["tp"], sea["hm0"], repeat, None,
                                               {p: xp[p] for p in names}, sea=declared))

    enc = campaign.encoder
    rate_p, rate_f = campaign.probes.sampling_rate, enc.sampling_rate
    step = int(round(rate_f / rate_p))
    if abs(step * rate_p - rate_f) > 1e-9 * rate_f:
        raise ValueError(f"the flap's rate {rate_f} Hz must be a multiple of the probes' "
                         f"{rate_p} Hz")
    duration = float(sea["duration"])
    beach = truth.beach if truth.beach is not None else Beach(reflection=0.0)

    def scattering(f):
        return flap_scattering(f, campaign, truth.sea.loss_damping, flap_truth)

    res = irregular_sea(rate_f, duration, [xp[p] for p in names] + [0.0], hm0=hm0,
                        peak_period=peak_period, gamma=sea["gamma"], seed=sea["seed"],
                        depth=depth, flap=scattering, beach=beach,
                        x_wavemaker=truth.x_wavemaker, sea=truth.sea)
    field = res.field
    n_p, n_f = int(round(duration * rate_p)), int(round(duration * rate_f))
    parts = [field[k].values for k in ("eta_incident", "eta_reflected", "eta_beach")]
    at_probes = [p[:-1, : n_p * step : step] for p in parts]
    t_p = np.arange(n_p) / rate_p
    noisy = sum(at_probes) + truth.probe_noise * rng.standard_normal(at_probes[0].shape)
    volts = a[:, None] + b[:, None] * noisy
    write_table(run_dir / "probes.csv", [("time", "s")] + [(p, "V") for p in names],
                np.column_stack([t_p, volts.T]), fmt=["%.2f"] + ["%.6f"] * len(names))

    inc, ref, bea = (p[-1] for p in parts)  # at the flap, record and lead-out
    t_f = np.arange(n_f) / rate_f
    span = (res.analysis_start, duration)
    flap = flap_record(t_f, inc[:n_f], period=peak_period, campaign=campaign, rng=rng,
                       hydro=flap_hydro, truth=flap_truth, eta_lead_out=inc[n_f:],
                       eta_front=inc + ref + bea, span=span)
    write_table(run_dir / "flap.csv", [("time", "s"), ("encoder", "counts"), ("pressure", "bar")],
                np.column_stack([t_f, flap["encoder_counts"].values,
                                 flap["chamber_pressure"].values / 1e5]),
                fmt=["%.2f", "%d", "%.6f"])

    # the truth: the realised sea state at the flap over the analysed span, the target, the
    # reflection per frequency, and the flap's mean absorbed power over the same span
    fp = 1.0 / peak_period
    state = sea_state_truth(t_f, inc[:n_f], ref[:n_f] + bea[:n_f], span, depth=depth,
                            reflection=res.reflection,
                            f_max=truth.sea.cut[1] * truth.sea.band[1] * fp,
                            rho=campaign.flume.density)
    f = state.frequency.values
    r_flap, t_flap = scattering(f)
    nominal_band = (truth.sea.band[0] / sea["tp"], truth.sea.band[1] / sea["tp"])
    inside = t_f >= span[0]
    power = float(np.mean(flap["power"].values[inside]))
    width = campaign.flap.width
    state = state.assign(
        spectrum_target=("frequency", jonswap(f, sea["hm0"], sea["tp"], sea["gamma"],
                                              band=nominal_band)),
        flap_reflection_coefficient_spectrum=("frequency", np.abs(r_flap)),
        flap_transmission_coefficient_spectrum=("frequency", np.abs(t_flap)),
        beach_reflection_coefficient_spectrum=("frequency", res.beach(f)))
    run_attrs = {
        "kind": "irregular", "hm0_target": sea["hm0"], "peak_period_target": sea["tp"],
        "gamma": sea["gamma"], "seed": sea["seed"], "duration": duration,
        "hm0_generated": hm0, "peak_period_generated": peak_period,
        "repeat_period": res.repeat_period, "n_components": int(res.frequency.size),
        "band_low": float(res.frequency[0]), "band_high": float(res.frequency[-1]),
        "ramp_time": truth.sea.ramp_peak_periods * peak_period,
        "x_wavemaker": truth.x_wavemaker, "x_beach": beach.x, "depth": depth,
        "flap_loss_damping": truth.sea.loss_damping,
        "beach_reflection_long_waves": beach.reflection,
        "beach_roll_off": truth.sea.beach_roll_off, "beach_phase": beach.phase,
        "mean_power": power, "flap_width": width,
        "capture_width": power / state.attrs["energy_flux"],
        "capture_width_ratio": power / (state.attrs["energy_flux"] * width),
        "reflection_definition": (
            "returning wave at x = 0 (flap reflection + beach wave through the flap) over "
            "the incident wave at x = 0: R_eff(f) = R(f) + T(f)^2 K_b(f) exp(i(psi_b - 2 k "
            "x_b)); bulk Kr = sqrt(m0R/m0I) of the analysed span")}
    truth_dir = root / "truth" / run_id
    waves_truth = xr.Dataset(
        {"eta_incident": (("probe", "time"), at_probes[0]),
         "eta_reflected": (("probe", "time"), at_probes[1]),
         "eta_beach": (("probe", "time"), at_probes[2]), **state.data_vars},
        coords={"probe": list(names), "time": t_p, "x": ("probe", [xp[p] for p in names]),
                "frequency": f},
        attrs={**state.attrs, **run_attrs})
    write_dataset(_finish(waves_truth, f"Virtual flume truth: waves of run {run_id}", "", 0),
                  truth_dir / "waves.nc", compress=_RUN_TRUTH_COMPRESSED)
    flap_ds = flap.assign(eta_incident=("time", inc[:n_f]), eta_reflected=("time", ref[:n_f]),
                          eta_beach=("time", bea[:n_f]))
    flap_ds.attrs.update({k: run_attrs[k] for k in ("mean_power", "capture_width",
                                                    "capture_width_ratio", "flap_width")})
    flap_ds.attrs.update({"analysis_start": span[0], "analysis_end": span[1],
                          "energy_flux": state.attrs["energy_flux"],
                          "hm0_target": sea["hm0"], "peak_period_target": sea["tp"]})
    write_dataset(_finish(flap_ds, f"Virtual flume truth: flap of run {run_id}", "", 0),
                  truth_dir / "flap.nc", compress=_RUN_TRUTH_COMPRESSED)
