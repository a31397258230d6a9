"""The virtual flume: write a complete raw campaign from known physics, with its truth.

The campaign reproduces the design of Brito et al. (2020): water depth 0.825 m, the flap and PTO
of §2.2, the periods and heights of Table 1 with probes at x12 = L/10 and x23 = L/4 of the local
wavelength, regular waves ramped up from the wavemaker, reflection from the flap, second-order
bound harmonics, probe gains/offsets and noise, encoder quantisation, pressure sensor noise and,
for the UVP runs (T = 3.5 s, H = 0.25 m), Met-Flow profile files of three beams.

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
from flumekit.io.netcdf import write_dataset
from flumekit.io.tables import write_table
from flumekit.synth.flume import RepeatScatter
from flumekit.waves.theory import group_velocity, wavelength

PERIODS = (2.0, 2.25, 2.5, 2.75, 3.0, 3.25, 3.5, 3.75, 4.0)  # Table 1 [s]
HEIGHTS = (0.15, 0.175, 0.2, 0.225, 0.25, 0.275, 0.3)  # Table 1 [m]
UVP_CONDITION = (3.5, 0.25)  # §2.4 [s], [m]
UVP_ELEVATIONS = tuple(np.round(np.arange(0.20, 0.7201, 0.02), 3))  # §2.3 [m]
CALIBRATION_LEVELS = (-0.10, -0.05, 0.0, 0.05, 0.10)  # static submersions [m]


@dataclass(frozen=True)
class Size:
    wave_runs: tuple[tuple[float, float], ...]
    uvp_elevations: tuple[float, ...]  # one UVP run per entry (repeats allowed)
    n_steady_waves: int = 55  # steady waves after the ramp (>= 50 are averaged)


def _size(name: str) -> Size:
    if name == "small":
        return Size(wave_runs=((2.0, 0.15), (3.5, 0.25)), uvp_elevations=(0.30, 0.50))
    if name == "default":
        return Size(wave_runs=tuple((t, h) for t in PERIODS for h in (0.15, 0.2, 0.25)),
                    uvp_elevations=UVP_ELEVATIONS[::2])
    if name == "paper":
        # 78 repeats cycling through the 27 elevations of §2.3 (most elevations 3 times)
        return Size(wave_runs=tuple((t, h) for t in PERIODS for h in HEIGHTS),
                    uvp_elevations=tuple(UVP_ELEVATIONS[k % len(UVP_ELEVATIONS)]
                                         for k in range(78)))
    raise ValueError(f"unknown campaign size '{name}': small, default or paper")


@dataclass(frozen=True)
class Truth:
    """Known physics of the virtual flume not written in the raw metadata."""

    reflection: float = 0.20  # flap reflection coefficient (Brito et al. 2020, §2.4)
    reflection_phase: float = 0.6  # [rad]
    probe_noise: float = 0.5e-3  # probe noise, as elevation [m]
    static_seconds: float = 30.0  # record length at each static level [s]
    ramp_waves: float = 10.0  # wavemaker ramp (quasi-steady after ~35 waves at the flap)
    x_wavemaker: float = -32.7  # [m]
    x_wp3: float = -2.0  # WP3 position [m]; WP1, WP2 follow Table 1 spacings
    x_wp4: float = -0.6  # [m]
    scatter: RepeatScatter = RepeatScatter()  # run-to-run variability (synth/flume.py)


def probe_positions(period: float, depth: float, truth: Truth) -> dict[str, float]:
    """Table 1 layout: x12 = L/10 and x23 = L/4 of the local wavelength, upstream of WP3."""
    L = float(wavelength(period, depth))
    x3 = truth.x_wp3
    return {"WP1": round(x3 - L / 4 - L / 10, 4), "WP2": round(x3 - L / 4, 4), "WP3": x3,
            "WP4": truth.x_wp4}


def _probe_gains(names, rng) -> tuple[np.ndarray, np.ndarray]:
    """True sensor law V = a + b eta per probe: b ~ 10 V/m, a ~ 2.5 V, each a few % apart."""
    b = 10.0 * (1 + 0.05 * rng.standard_normal(len(names)))
    a = 2.5 + 0.3 * rng.standard_normal(len(names))
    return a, b


def write_campaign(root: str | Path, size: str = "small", seed: int = 2020,
                   truth: Truth = Truth(), progress=None) -> Campaign:
    """Write a virtual-flume campaign to ``root`` and return it.

    ``root`` must be absent or an empty folder: synthesis never deletes or overwrites anything
    it did not write (raw data is sacred). The campaign is written to a fresh temporary sibling
    folder and renamed into place at the end, so an interrupted synthesis leaves no half
    campaign at ``root``. ``progress(i, n, run_id)`` is called before each run.
    """
    root = Path(root)
    _check_empty(root)
    spec = _size(size)
    rng = np.random.default_rng(seed)
    root.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{root.name}.", suffix=".partial", dir=root.parent))
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(tmp, 0o777 & ~umask)  # mkdtemp makes 0700; the campaign folder follows the umask
    try:
        _write_all(tmp, root.name, spec, seed, size, truth, rng, progress)
        # os.rename onto an empty directory replaces it atomically; onto a non-empty one it
        # fails (ENOTEMPTY), so a folder filled meanwhile by someone else is never clobbered
        _check_empty(root)
        os.rename(tmp, root)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)  # only the folder this call created
        raise
    return load_campaign(root)


def _check_empty(root: Path) -> None:
    if root.exists() and (not root.is_dir() or any(root.iterdir())):
        raise InputError(root, "the virtual flume writes only into an absent or empty folder; "
                         "this one has files (nothing was changed). Point the pipeline's "
                         "'raw' at the campaign folder, or choose a new folder")


def _write_all(tmp: Path, name: str, spec: Size, seed: int, size: str, truth: Truth, rng,
               progress) -> None:
    (tmp / "calibration").mkdir(parents=True)
    (tmp / "truth").mkdir()
    template = resources.files("flumekit.data").joinpath("default_campaign.toml").read_text()
    template = template.replace('name = "default"', f'name = "{name}"', 1)
    (tmp / "campaign.toml").write_text(template)
    campaign = load_campaign(tmp)
    names = campaign.probes.names
    a, b = _probe_gains(names, rng)
    _write_calibration(tmp, names, a, b, campaign.probes.sampling_rate, truth, rng)

    runs = [("waves", t, h, None) for t, h in spec.wave_runs]
    runs += [("uvp", *UVP_CONDITION, z) for z in spec.uvp_elevations]
    from flumekit.synth.flap import flume_hydrodynamics

    # the flap simulator's coefficients and radiation model: the same for every run (~1.5 s)
    flap_hydro = flume_hydrodynamics(campaign)
    seen: dict[str, int] = {}
    for i, (kind, period, height, z) in enumerate(runs):
        base = f"T{period:.2f}_H{height:.3f}" if kind == "waves" else f"uvp_z{z:.3f}"
        repeat = seen.get(base, 0)
        seen[base] = repeat + 1
        run_id = f"{base}_r{repeat}"
        if progress is not None:
            progress(i, len(runs), run_id)
        _write_run(tmp, campaign, run_id, kind, period, height, repeat, z, a, b, truth,
                   np.random.default_rng([seed, len(seen), repeat]), spec.n_steady_waves,
                   flap_hydro=flap_hydro)
    if spec.uvp_elevations:
        from flumekit.synth.uvp import true_field

        field = true_field(campaign, period=UVP_CONDITION[0], height=UVP_CONDITION[1],
                           reflection=truth.reflection, reflection_phase=truth.reflection_phase,
                           x_wavemaker=truth.x_wavemaker)
        _finish(field, "Virtual flume truth: phase-averaged velocity field", size, seed)
        write_dataset(field, tmp / "truth" / "uvp_field.nc")


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
    lines = ["[run]", f'kind = "{kind}"', f"period = {period}", f"height = {height}",
             f"repeat = {repeat}"]
    if z is not None:
        lines.append(f"uvp_elevation = {z}")
    lines += ["", "[probes]  # x [m]"] + [f"{p} = {x}" for p, x in xp.items()]
    (run_dir / "run.toml").write_text("\n".join(lines) + "\n")

    wave_kw = dict(period=generated_period, height=generated_height, depth=depth,
                   reflection=truth.reflection,
                   reflection_phase=truth.reflection_phase, x_reflector=0.0,
                   ramp_waves=truth.ramp_waves, second_order=True, x_wavemaker=truth.x_wavemaker)
    names = campaign.probes.names
    t25 = np.arange(int(duration * campaign.probes.sampling_rate)) / campaign.probes.sampling_rate
    field = regular_wave_field(t25, np.array([xp[p] for p in names] + [0.0]), **wave_kw)
    eta = (field["eta_incident"] + field["eta_reflected"]).values  # (x, time)
    noisy = eta[:-1] + truth.probe_noise * rng.standard_normal(eta[:-1].shape)
    volts = a[:, None] + b[:, None] * noisy
    write_table(run_dir / "probes.csv", [("time", "s")] + [(p, "V") for p in names],
                np.column_stack([t25, volts.T]), fmt=["%.2f"] + ["%.6f"] * len(names))

    enc = campaign.encoder
    t100 = np.arange(int(duration * enc.sampling_rate)) / enc.sampling_rate
    n100 = t100.size
    # the flap is driven 20 s past the record's end, so that its last seconds see the wave
    # that goes on (flumekit.synth.flap.flap_record, eta_lead_out)
    t_lead = t100[-1] + np.arange(1, int(20.0 * enc.sampling_rate) + 1) / enc.sampling_rate
    at_flap = regular_wave_field(np.concatenate([t100, t_lead]), np.array([0.0]), **wave_kw)
    at_flap = {k: at_flap[k].values[0] for k in ("eta_incident", "eta_reflected")}
    flap = flap_record(t100, at_flap["eta_incident"][:n100], period=generated_period,
                       campaign=campaign, rng=rng, height=generated_height, hydro=flap_hydro,
                       truth=flap_truth,
                       eta_lead_out=at_flap["eta_incident"][n100:],
                       eta_front=at_flap["eta_incident"] + at_flap["eta_reflected"])
    write_table(run_dir / "flap.csv", [("time", "s"), ("encoder", "counts"), ("pressure", "bar")],
                np.column_stack([t100, flap["encoder_counts"].values,
                                 flap["chamber_pressure"].values / 1e5]),
                fmt=["%.2f", "%d", "%.6f"])

    truth_dir = root / "truth" / run_id
    waves_truth = xr.Dataset(
        {"eta_incident": (("probe", "time"), field["eta_incident"].values[:-1]),
         "eta_reflected": (("probe", "time"), field["eta_reflected"].values[:-1])},
        coords={"probe": list(names), "time": t25, "x": ("probe", [xp[p] for p in names])},
        attrs={k: v for k, v in field.attrs.items() if np.isscalar(v)})
    write_dataset(_finish(waves_truth, f"Virtual flume truth: waves of run {run_id}", "", 0),
                  truth_dir / "waves.nc")
    flap_truth = flap.assign(eta_incident=("time", at_flap["eta_incident"][:n100]),
                             eta_reflected=("time", at_flap["eta_reflected"][:n100]))
    write_dataset(_finish(flap_truth, f"Virtual flume truth: flap of run {run_id}", "", 0),
                  truth_dir / "flap.nc")

    if kind == "uvp":
        from flumekit.synth.uvp import uvp_beams, write_uvp_run

        u = campaign.uvp
        tu = np.arange(int(duration * u.sampling_rate)) / u.sampling_rate
        beams = uvp_beams(tu, u, z, period=generated_period, height=generated_height,
                          depth=depth,
                          hinge_height=campaign.flap.hinge_height, reflection=truth.reflection,
                          reflection_phase=truth.reflection_phase,
                          x_wavemaker=truth.x_wavemaker, ramp_waves=truth.ramp_waves,
                          theta=np.interp(tu, t100, flap["theta"].values),
                          flap_thickness=campaign.flap.thickness, rng=rng)
        write_uvp_run(run_dir, beams)
