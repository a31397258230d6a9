"""Renzi–Dias model: run time against error over the truncation orders.

The flume of Brito et al. (2020): h = 0.825 m, flap w = 1.31 m hinged at c = 0.10 m, channel
b = 1.5 m, the 9 periods of Table 1 (T = 2–4 s). Errors are the largest relative deviation of
μ, ν and ``|F|`` over the periods from a reference with every order raised; "next" is the change to
the next order in the table. Run times are the best of several calls of
:func:`flumekit.flap.renzi_dias.model.coefficients` (dataset construction included).
"""

from __future__ import annotations

import numpy as np

from flumekit.bench import best_time
from flumekit.docstrings import doc
from flumekit.flap.renzi_dias import model as rd

H, W, C, B = 0.825, 1.31, 0.10, 1.5
PERIODS = np.arange(2.0, 4.001, 0.25)


def _timed(repeat: int, **kw):
    best, ds = best_time(lambda: rd.coefficients(PERIODS, H, W, C, **kw), repeat)
    return ds, best


def _err(ds, ref) -> float:
    f, fr = np.abs(rd.excitation(ds).values), np.abs(rd.excitation(ref).values)
    return float(max(np.max(np.abs(ds.added_inertia.values / ref.added_inertia.values - 1)),
                     np.max(np.abs(ds.radiation_damping.values / ref.radiation_damping.values
                                   - 1)),
                     np.max(np.abs(f / fr - 1))))


def _knob_table(title, channel, ref_opts, knob, values, repeat) -> list[str]:
    ref = rd.coefficients(PERIODS, H, W, C, channel, **ref_opts)
    rows = [f"  {title}: {knob} (others at the reference {ref_opts})",
            f"    {knob:>18} {'error':>9} {'next':>9} {'time ms':>8}"]
    results = [_timed(repeat, channel_width=channel, **{**ref_opts, knob: v}) for v in values]
    for i, (v, (ds, t)) in enumerate(zip(values, results, strict=True)):
        nxt = f"{_err(ds, results[i + 1][0]):9.1e}" if i + 1 < len(values) else " " * 9
        rows.append(f"    {v:>18} {_err(ds, ref):9.1e} {nxt} {t * 1e3:8.2f}")
    return rows


@doc
def run(quick: bool = False) -> str:
    """Run the benchmark and return its tables: default accuracy and speed, then per order.

    Parameters
    ----------
    quick : bool
        Fewer truncation orders and repeats.

    Returns
    -------
    str
        The printed tables: error and time of the defaults in the channel and in open water, then
        error, change to the next order and time per truncation order.

    %(references_renzi_dias2012)s.
    """
    repeat = 3 if quick else 10
    out = ["Renzi-Dias thin-flap model, flume of Brito et al. 2020, Table 1 periods (9)"]
    ds, t_def = _timed(repeat, channel_width=B)
    ref_c = dict(chebyshev_terms=40, evanescent_modes=48, lattice_modes=800)
    ref = rd.coefficients(PERIODS, H, W, C, B, **ref_c)
    trunc = {k[len("truncation_"):]: v for k, v in ds.attrs.items() if k.startswith("truncation")}
    out.append(f"channel, defaults {trunc}: {t_def * 1e3:.2f} ms "
               f"(target < 50 ms), error {_err(ds, ref):.1e} (target 1e-4)")
    ocean, t_oc = _timed(repeat)
    ref_o = rd.coefficients(PERIODS, H, W, C, chebyshev_terms=30, evanescent_modes=48,
                            quadrature_nodes=64)
    out.append(f"open water, defaults: {t_oc * 1e3:.2f} ms, error {_err(ocean, ref_o):.1e}")
    out.append("")
    out.append("  T [s]   mu [kg m2]  nu [N m s]  |F| [N m/m]  arg F [deg]  |R0|   (channel)")
    f = rd.excitation(ds).values
    r = np.abs(rd.reflection(ds).values)
    for i, period in enumerate(PERIODS):
        out.append(f"  {period:5.2f} {ds.added_inertia.values[i]:11.2f} "
                   f"{ds.radiation_damping.values[i]:11.2f} {abs(f[i]):12.1f} "
                   f"{np.degrees(np.angle(f[i])):12.2f} {r[i]:6.3f}")
    out.append("")
    out.append("run time against error over the truncation orders")
    cheb = [4, 6, 8, 12, 16] if quick else [4, 6, 8, 10, 12, 16, 24]
    evan = [1, 2, 4, 8, 16] if quick else [0, 1, 2, 4, 8, 16, 32]
    lat = [2, 4, 16, 64] if quick else [2, 4, 8, 16, 32, 64, 128]
    out += _knob_table("channel", B, ref_c, "chebyshev_terms", cheb, repeat)
    out += _knob_table("channel", B, ref_c, "evanescent_modes", evan, repeat)
    out += _knob_table("channel", B, ref_c, "lattice_modes", lat, repeat)
    ref_o_opts = dict(chebyshev_terms=30, evanescent_modes=48, quadrature_nodes=64)
    out += _knob_table("open water", None, ref_o_opts, "chebyshev_terms", cheb, repeat)
    out += _knob_table("open water", None, ref_o_opts, "quadrature_nodes",
                       [6, 8, 12, 16, 24] if quick else [6, 8, 12, 16, 24, 32, 48], repeat)
    out.append("")
    out.append("  channel lattice: RD12 direct image sum against the Kummer-accelerated modal sum")
    out.append(f"    {'images':>8} {'error':>9} {'energy':>9} {'time ms':>8}")
    for m in ([25, 100, 400] if quick else [25, 100, 400, 1600]):
        d, t = _timed(1, channel_width=B, lattice="direct", images=m)
        rr = rd.reflection(d).values
        energy = float(np.max(np.abs(np.abs(rr) ** 2 + np.abs(1 - rr) ** 2 - 1)))
        out.append(f"    {m:>8} {_err(d, ref):9.1e} {energy:9.1e} {t * 1e3:8.1f}")
    rr = rd.reflection(ds).values
    energy = float(np.max(np.abs(np.abs(rr) ** 2 + np.abs(1 - rr) ** 2 - 1)))
    out.append(f"    {'spectral':>8} {_err(ds, ref):9.1e} {energy:9.1e} {t_def * 1e3:8.1f}")
    return "\n".join(out)


if __name__ == "__main__":
    print(run())
