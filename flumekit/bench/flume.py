"""Calibration of the virtual flume against what Brito et al. (2020) state (issue 16).

``flumekit bench flume`` synthesises the default campaign (27 wave runs of Table 1 with
H = 0.15, 0.2, 0.25 m and 14 repeats of T = 3.5 s, H = 0.25 m for the UVP), builds the
pipeline's waves, flap and comparison stages on it, and prints each number the paper states
next to the virtual flume's, as the pipeline's own analysis measures it. ``quick`` uses the
small campaign (T = 2 s and 3.5 s only; no repeat statistics or Table 1 trends).

The calibrated coefficients are the defaults of :class:`flumekit.synth.flume.FlumeLosses`,
:class:`flumekit.synth.flume.RepeatScatter` and K_p of :class:`flumekit.synth.flap.FlapTruth`.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
TARGETS = ("waves_summary", "flap_summary", "comparison_summary")


def _build(project: Path, size: str) -> Path:
    from flumekit.synth.campaign import write_campaign

    shutil.copytree(ROOT / "pipelines", project / "pipelines")
    pipeline = "small" if size == "small" else "default"
    write_campaign(project / "raw" / pipeline, size=size, seed=2020)
    r = subprocess.run([sys.executable, "-m", "flumekit.cli", "make", "--pipeline",
                        f"pipelines/{pipeline}.toml", "-j", "2", *TARGETS], cwd=project,
                       capture_output=True, text=True)
    if r.returncode:
        raise RuntimeError(r.stderr)
    return project / "processed" / pipeline


def _runs(processed: Path) -> dict:
    import xarray as xr

    out = {}
    for f in sorted((processed / "flap").glob("*.nc")):
        run = f.stem
        with xr.open_dataset(f) as fl, xr.open_dataset(processed / "waves" / f.name) as w, \
                xr.open_dataset(processed / "comparison" / f.name) as c:
            out[run] = {"flap": fl.drop_dims("time").load(), "waves": w.drop_dims(
                [d for d in w.dims if d == "time"]).load(), "cmp": c.load()}
    return out


def _condition(run: str) -> tuple[float, float] | None:
    if not run.startswith("T"):
        return None
    t, h = run.split("_")[:2]
    return float(t[1:]), float(h[1:])


def _row(rows, quantity, paper, flume, note=""):
    rows.append((quantity, paper, flume, note))


def table(runs: dict) -> list[tuple[str, str, str, str]]:
    """The paper's stated numbers against the virtual flume's (rows of text)."""
    rows: list[tuple[str, str, str, str]] = []
    main = runs.get("T3.50_H0.250_r0")
    if main is not None:
        fl, w, c = main["flap"], main["waves"], main["cmp"]
        T = float(fl.measured_period)
        th = fl.theta_phase_mean.values
        _row(rows, "max <theta>/pi (T=3.5 s, H=0.25 m)", "0.06", f"{th.max() / np.pi:.3f}",
             "§3.3, Fig. 10b")
        _row(rows, "min <theta>/pi", "-0.06", f"{th.min() / np.pi:.3f}", "almost symmetric")
        _row(rows, "<W_out>/W_I measured", "0.12", f"{float(fl.capture_factor):.3f}", "§3.3")
        cf_lin = float(c.capture_factor.sel(source="analytical"))
        _row(rows, "<W_out>/W_I linear model (Eq. A1)", "0.33", f"{cf_lin:.3f}",
             "energy-equivalent PTO damping")
        lin = c.theta_phase_mean.sel(source="analytical").values
        _row(rows, "max <theta> below linear model's", "37 %",
             f"{100 * (1 - th.max() / lin.max()):.0f} %", "(lin - exp)/lin")
        sim = c.theta_phase_mean.sel(source="simulator").values
        _row(rows, "max <theta> below simulator's", "-",
             f"{100 * (1 - th.max() / sim.max()):.0f} %", "three distinct curves")
        _row(rows, "Kr", "0.20", f"{float(w.reflection_coefficient):.3f}", "§2.4")
        _row(rows, "quasi-steady from t/T (eta, 2 %)", "35",
             f"{float(w.steady_start) / float(w.measured_period):.1f}", "§2.5")
        _row(rows, "quasi-steady from t/T (theta, 2 %)", "35",
             f"{float(fl.steady_start) / T:.1f}", "§2.5")
        _row(rows, "T_p fit R2 (T=3.5 s, H=0.25 m)", "0.95",
             f"{float(fl.pressure_fit_r2):.3f}", "Fig. 7a")
    other = runs.get("T2.50_H0.200_r0")
    if other is not None:
        _row(rows, "T_p fit R2 (T=2.5 s, H=0.2 m)", "0.95",
             f"{float(other['flap'].pressure_fit_r2):.3f}", "Fig. 7b")
    reps = [r for k, r in runs.items() if k.startswith("uvp_") or k == "T3.50_H0.250_r0"]
    if len(reps) >= 3:
        def rel_std(values):
            v = np.asarray(values, dtype=float)
            return f"{100 * v.std(ddof=1) / v.mean():.2f} %"

        n = len(reps)
        _row(rows, f"repeats: std of eta amplitude (n={n})", "< 0.5 %",
             rel_std([r["waves"].incident_height for r in reps]), "incident H, §2.5")
        _row(rows, "repeats: std of eta period", "< 0.2 %",
             rel_std([r["waves"].measured_period for r in reps]), "")
        _row(rows, "repeats: std of theta amplitude", "< 2.1 %",
             rel_std([r["flap"].theta_amplitude for r in reps]), "")
        _row(rows, "repeats: std of theta period", "< 0.4 %",
             rel_std([r["flap"].measured_period for r in reps]), "")
    grid = {_condition(k): r for k, r in runs.items() if _condition(k) and k.endswith("_r0")}
    periods = sorted({t for t, _ in grid})
    heights = sorted({h for _, h in grid})
    if len(periods) >= 3 and len(heights) >= 2:
        for name, label in (("torque_amplitude", "T_h"), ("theta_amplitude", "theta"),
                            ("capture_factor", "C_f")):
            def ratio(t, h, name=name):
                c = grid[(t, h)]["cmp"][name]
                return float(c.sel(source="analytical")) / float(c.sel(source="experiment"))

            for h in heights:
                r = [ratio(t, h) for t in periods]
                _row(rows, f"linear/measured {label}, H={h:g} m, T={periods[0]:g}..{periods[-1]:g}",
                     "grows with T", " ".join(f"{x:.2f}" for x in r),
                     f"Spearman rho = {_spearman(periods, r):+.2f}")
            r_h = [np.mean([ratio(t, h) for t in periods]) for h in heights]
            _row(rows, f"linear/measured {label}, mean over T, H={heights[0]:g}..{heights[-1]:g}",
                 "grows with H", " ".join(f"{x:.2f}" for x in r_h),
                 f"Spearman rho = {_spearman(heights, r_h):+.2f}")
    return rows


def _spearman(x, y) -> float:
    rx, ry = np.argsort(np.argsort(x)), np.argsort(np.argsort(y))
    return float(np.corrcoef(rx, ry)[0, 1])


def _format(rows, header) -> str:
    w = [max(len(str(r[i])) for r in rows + [header]) for i in range(4)]
    line = "  ".join
    out = [line(str(h).ljust(w[i]) for i, h in enumerate(header)),
           line("-" * w[i] for i in range(4))]
    out += [line(str(c).ljust(w[i]) for i, c in enumerate(r)) for r in rows]
    return "\n".join(out)


def run(quick: bool = False) -> str:
    size = "small" if quick else "default"
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        processed = _build(Path(tmp), size)
        elapsed = time.perf_counter() - t0
        rows = table(_runs(processed))
    return (f"Virtual flume vs Brito et al. (2020), '{size}' campaign, synthesis + build "
            f"{elapsed:.0f} s\n" + _format(rows, ("quantity", "paper", "virtual flume", "note")))
