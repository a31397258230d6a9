"""Run time against error of the flap simulator: time step, IRF length, state-space order.

Setting: the flume of Brito et al. (2020) (default campaign: h = 0.825 m, flap 1.31 m wide,
I = 14.74 kg m2, C = 605 N m/rad, hydraulic PTO with the campaign's LuGre friction,
K_p = 2e6 Pa s2/rad2, I_p = 2.4e4 Pa s2/rad, the virtual flume's values), Renzi-Dias channel
coefficients over 0.4-25 rad/s (A∞ by the Ogilvie relation), a regular wave T = 3.5 s,
H = 0.25 m ramped over 5 periods, 600 s (``quick``: 120 s and fewer frequencies).

Errors are RMS differences of θ over the run divided by the RMS of the reference θ, and the
relative error of the mean PTO power; run times are the best of a few repetitions on one core.
Section 4 gives the CPU time (``time.process_time``, best of 5) of the 600 s hydraulic + LuGre
run at the pipeline's step (0.04 s) as a multiple of real time, and the peak memory
(``tracemalloc``) of a 1e5 s run (``quick``: 1e4 s) with output every second.

    python -m flumekit.bench.simulator
"""

from __future__ import annotations

import tempfile
import time
from importlib import resources
from pathlib import Path

import numpy as np
import xarray as xr

from flumekit.bench import best_time
from flumekit.campaign import load_campaign
from flumekit.flap import simulator as S
from flumekit.hydro import coefficients as H
from flumekit.hydro import radiation as R
from flumekit.hydro.excitation import excitation_torque

KP, IP = 2.0e6, 2.4e4
PERIOD, HEIGHT = 3.5, 0.25


def _campaign():
    with tempfile.TemporaryDirectory() as d:
        text = resources.files("flumekit.data").joinpath("default_campaign.toml").read_text()
        (Path(d) / "campaign.toml").write_text(text)
        return load_campaign(d)


def _coefficients(campaign, n: int):
    w = np.linspace(0.4, 25.0, n)
    try:
        from flumekit.flap.renzi_dias import model as renzi_dias

        c = renzi_dias.coefficients(2 * np.pi / w, campaign.flume.water_depth,
                                    campaign.flap.width, campaign.flap.hinge_height,
                                    channel_width=campaign.flume.width)
        hy, source = H.from_renzi_dias(c, campaign.flap.buoyancy_stiffness), "Renzi-Dias channel"
    except ImportError:  # pragma: no cover - the analytic kernel stands in
        f = 3000 * np.exp(-((w / 6) ** 2)) * np.exp(-0.3j * w)
        hy = H.from_kernel(w, [400.0, 300.0], [1.0, 3.0], [2.5, 6.0], added_inertia_infinite=25.0,
                           excitation_torque=f,
                           hydrostatic_stiffness=campaign.flap.buoyancy_stiffness)
        source = "analytic kernel"
    return H.with_infinite_frequency_inertia(hy, max_spread=None), source



def _err(ds: xr.Dataset, ref: xr.Dataset) -> tuple[float, float]:
    r = ref["theta"].interp(time=ds["time"]).values
    e = float(np.sqrt(np.mean((ds["theta"].values - r) ** 2) / np.mean(r**2)))
    p = float(ds["power"].mean() / ref["power"].mean() - 1)
    return e, p


def _table(title: str, header: list[str], rows: list[list[str]]) -> str:
    widths = [max(len(h), *(len(r[i]) for r in rows)) for i, h in enumerate(header)]
    line = "  ".join(h.rjust(w) for h, w in zip(header, widths))
    out = [title, line, "-" * len(line)]
    out += ["  ".join(c.rjust(w) for c, w in zip(r, widths)) for r in rows]
    return "\n".join(out)


def run(quick: bool = False) -> str:
    """Run the benchmark and return the printed tables.

    Parameters
    ----------
    quick : bool, default False
        A 120 s run with fewer frequencies and one repetition instead of 600 s and three.

    Returns
    -------
    str
        The tables of run time against error (module notes).
    """
    campaign = _campaign()
    duration = 120.0 if quick else 600.0
    repeat = 1 if quick else 3
    hy, source = _coefficients(campaign, 120 if quick else 400)
    a_inf = float(hy["added_inertia_infinite"])
    w = 2 * np.pi / PERIOD
    t = np.arange(0.0, duration + 5.0, 0.01)
    eta = xr.DataArray(HEIGHT / 2 * np.clip(t / (5 * PERIOD), 0, 1) * np.cos(w * t),
                       dims="time", coords={"time": t})
    exc = excitation_torque(eta, hy)
    flap = S.FlapDynamics(campaign.flap.inertia, a_inf, float(hy["hydrostatic_stiffness"]))
    cyl = S.HydraulicCylinder.from_campaign(campaign.pto, KP, IP, friction=True)
    t0 = time.perf_counter()
    irf40 = R.impulse_response(hy, 40.0, 0.005)
    t_irf = time.perf_counter() - t0
    t0 = time.perf_counter()
    ss = R.fit_state_space(irf40)
    t_fit = time.perf_counter() - t0
    out = [(f"flumekit.bench.simulator  ({source} coefficients, A_inf = {a_inf:.2f} kg m2 "
           f"(Ogilvie spread {hy.attrs['added_inertia_infinite_spread']:.1%}), T = {PERIOD} s, "
           f"H = {HEIGHT} m, {duration:g} s runs; IRF 40 s in {t_irf:.2f} s, state-space fit "
           f"order {ss.order} in {t_fit:.2f} s, fit error {ss.fit_error_time:.2%} (K(t)), "
           f"{ss.fit_error_frequency:.2%} (K^(w)))")]

    # 1. time step: hydraulic PTO + LuGre, state-space radiation
    steps = [0.1, 0.05, 0.04, 0.02, 0.01] if not quick else [0.1, 0.04, 0.02]
    runs = {}
    for dt in sorted({*steps, *(d / 10 for d in steps)}):
        rep = repeat if dt in steps else 1
        runs[dt] = best_time(lambda dt=dt: S.simulate(exc, flap, ss, cyl, dt=dt, duration=duration),
                         rep)
    finest = runs[min(runs)][1]
    rows = []
    for dt in steps:
        sec, ds = runs[dt]
        e10, p10 = _err(ds, runs[dt / 10][1])
        ef, _ = _err(ds, finest)
        rows.append([f"{dt:g}", f"{sec:.3f}", f"{duration / sec:.0f}",
                     f"{(duration / dt) / sec:.0f}", f"{e10:.2e}", f"{p10:+.2e}", f"{ef:.2e}",
                     f"{float(ds['cavitating'].mean()):.2f}"])
    out.append(_table(
        "\n1. Time step (hydraulic cylinder Eq. 13 + LuGre friction, state-space radiation)",
        ["dt [s]", "run [s]", "x real time", "steps/s", "theta err vs dt/10",
         "power err vs dt/10", f"theta err vs dt={min(runs):g}", "cavitating"], rows))

    # 2. IRF length: convolution, linear PTO (so that radiation dominates the error)
    lin = S.LinearDamper(500.0)
    ref_sec, ref = best_time(
        lambda: S.simulate(exc, flap, irf40, lin, dt=0.02, duration=duration), 1)
    rows = []
    for length in ([2.5, 5.0, 10.0, 20.0] if not quick else [5.0, 20.0]):
        k = irf40.sel(lag=slice(0, length))
        sec, ds = best_time(lambda k=k: S.simulate(exc, flap, k, lin, dt=0.02, duration=duration),
                        repeat)
        e, p = _err(ds, ref)
        rows.append([f"{length:g}", f"{sec:.3f}", f"{(duration / 0.02) / sec:.0f}", f"{e:.2e}",
                     f"{p:+.2e}"])
    rows.append(["40 (ref)", f"{ref_sec:.3f}", f"{(duration / 0.02) / ref_sec:.0f}", "0", "0"])
    out.append(_table("\n2. IRF length (convolution, linear PTO 500 N m s, dt = 0.02 s)",
                      ["IRF [s]", "run [s]", "steps/s", "theta err vs 40 s",
                       "power err vs 40 s"], rows))

    # 3. state-space order against the convolution with the 40 s IRF
    rows = []
    for order in ([2, 4, 6, 8, 10, 14] if not quick else [4, 8]):
        model = R.fit_state_space(irf40, order=order)
        sec, ds = best_time(lambda m=model: S.simulate(exc, flap, m, lin, dt=0.02,
                                                   duration=duration), repeat)
        e, p = _err(ds, ref)
        rows.append([f"{model.order}", f"{model.fit_error_time:.2%}",
                     f"{model.fit_error_frequency:.2%}", f"{sec:.3f}",
                     f"{(duration / 0.02) / sec:.0f}", f"{e:.2e}", f"{p:+.2e}"])
    sec, ds = best_time(lambda: S.simulate(exc, flap, ss, lin, dt=0.02, duration=duration), repeat)
    e, p = _err(ds, ref)
    rows.append([f"auto {ss.order}", f"{ss.fit_error_time:.2%}", f"{ss.fit_error_frequency:.2%}",
                 f"{sec:.3f}", f"{(duration / 0.02) / sec:.0f}", f"{e:.2e}", f"{p:+.2e}"])
    out.append(_table("\n3. State-space order (linear PTO, dt = 0.02 s) against the 40 s "
                      "convolution", ["order", "K(t) fit err", "K^(w) fit err", "run [s]",
                                      "steps/s", "theta err vs conv", "power err vs conv"],
                      rows))
    out.append(_long_runs(hy, exc, flap, ss, cyl, duration, quick))
    return "\n".join(out)


def _long_runs(hy, exc, flap, ss, cyl, duration, quick) -> str:
    """Measure the CPU time of the hydraulic run and the peak memory of a long decimated run."""
    import tracemalloc

    from flumekit.hydro.simulation import RegularWave, simulate

    cpu = np.inf
    for _ in range(1 if quick else 5):
        t0 = time.process_time()
        S.simulate(exc, flap, ss, cyl, dt=0.04, duration=duration)
        cpu = min(cpu, time.process_time() - t0)
    long = 1e4 if quick else 1e5
    tracemalloc.start()
    t0 = time.process_time()
    ds = simulate(hy, flap.inertia, cyl, RegularWave(HEIGHT, PERIOD, ramp=5 * PERIOD), dt=0.1,
                  duration=long, radiation=ss, output_step=1.0)
    sec = time.process_time() - t0
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    rows = [["600 s, dt = 0.04 s, every step", f"{cpu:.3f}", f"{duration / cpu:.0f}", "-"],
            [f"{long:.0e} s, dt = 0.1 s, output 1 s ({ds.sizes['time']} samples)",
             f"{sec:.1f} (traced)", f"{long / sec:.0f} (traced)", f"{peak / 1e6:.1f}"]]
    return _table("\n4. CPU time and memory (hydraulic cylinder + LuGre, state-space radiation)",
                  ["run", "CPU [s]", "x real time", "peak memory [MB]"], rows)


if __name__ == "__main__":
    print(run())
