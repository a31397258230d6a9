"""The figure test on every figure function: no empty or hidden axes, every shown axis labelled
with units, text >= 8 pt at the saved size, one- or two-column width, legends outside the data,
a title naming the run(s) and condition. And the test itself catches each fault."""

from __future__ import annotations

import numpy as np
import pytest
from matplotlib.figure import Figure

from flumekit.figures import ballscrew as bs
from flumekit.figures import flap as figs
from flumekit.figures import uvp
from flumekit.figures import waves as wave_figs
from flumekit.figures.check import problems
from flumekit.figures.style import new_figure, title

from .conftest import comparison_run


def _passes(fig):
    assert isinstance(fig, Figure)
    assert problems(fig) == []
    return fig


def test_wave_figures(waves):
    fig = _passes(wave_figs.figure_5a(waves))
    assert "T2.00_H0.150_r0" in fig._suptitle.get_text()
    fig6 = _passes(wave_figs.figure_6a(waves, start=40))
    # the normalising scale, the amplitude scale of the probe shown (nearest x_ref = 0: WP4)
    a_s = float(waves.amplitude_scale.sel(probe="WP4"))
    for f in (fig, fig6):
        assert f"$A_s$ = {a_s:.3f} m" in f._suptitle.get_text().replace("\xa0", " ")


def test_separation_figure(waves):
    fig = _passes(wave_figs.separation(waves))
    text = fig._suptitle.get_text().replace("\xa0", " ")  # no-break spaces in the title
    assert f"{float(waves.reflection_coefficient):.3f}" in text  # Kr in the title
    assert f"{float(waves.incident_height):.3f} m" in text  # H_I in the title
    (ax_t, ax_f) = fig.axes
    # (a) the separated series at x_ref over five periods of the steady window
    inc = ax_t.lines[0]
    assert np.ptp(inc.get_xdata()) == pytest.approx(5 * float(waves.measured_period), abs=0.05)
    # masked bins are shaded: mask two bins and one span appears
    masked = waves.copy()
    m = np.zeros(masked.frequency.size, np.int8)
    m[10:12] = 1
    masked["masked"] = ("frequency", m)
    fig = _passes(wave_figs.separation(masked))
    assert len(fig.axes[1].patches) == 1


def test_separation_spectra_are_band_averaged_with_their_degrees_of_freedom(waves):
    fig = _passes(wave_figs.separation(waves, n_bins=4))
    ax_f = fig.axes[1]
    assert "8 degrees of freedom" in ax_f.get_title(loc="left")
    # the drawn incident spectrum: means of consecutive groups of 4 periodogram bins
    f = waves.frequency.values
    s = waves.spectrum_incident.values
    n = f.size // 4 * 4
    fb, sb = f[:n].reshape(-1, 4).mean(axis=1), s[:n].reshape(-1, 4).mean(axis=1)
    line = ax_f.lines[0]
    keep = sb > 0
    np.testing.assert_allclose(line.get_xdata(), fb[keep], rtol=1e-12)
    np.testing.assert_allclose(line.get_ydata(), sb[keep], rtol=1e-12)
    # the variance is kept: the bands hold what the bins hold (to round-off)
    assert np.sum(sb) * 4 == pytest.approx(np.sum(s[:n]), rel=1e-12)


def test_separation_figure_of_separate_output(waves):
    from flumekit.waves import separate

    steady = waves["eta"].sel(time=slice(float(waves.steady_start), float(waves.steady_end)))
    result = separate(steady.sel(probe=["WP1", "WP2", "WP3"]), 0.825)
    fig = _passes(wave_figs.separation(result))
    # five periods of the detected fundamental, not the whole record
    period = 1.0 / result.attrs["fundamental_frequency"]
    assert np.ptp(fig.axes[0].lines[0].get_xdata()) == pytest.approx(5 * period, abs=0.05)


def test_flap_time_series_figures(flaps):
    ds = flaps[-1]
    fig = _passes(figs.figure_5b(ds))
    # the dash-dotted lines meet the steady crest and trough, whatever the mean lean
    lines = [ln for ln in fig.axes[0].lines if ln.get_linestyle() == "-."]
    levels = sorted(float(ln.get_ydata()[0]) for ln in lines)
    scale = float(ds.theta_amplitude)
    assert levels == pytest.approx([float(ds.theta_phase_mean.min()) / scale,
                                    float(ds.theta_phase_mean.max()) / scale])
    fig = _passes(figs.figure_6bcd(ds, start=30))
    titles = [ax.get_title(loc="left").replace("\xa0", " ") for ax in fig.axes]
    assert [t[:3] for t in titles] == ["(a)", "(b)", "(c)"]  # lettered in this file from (a)
    # each panel states its scale, computed here from the phase averages
    theta_s = 0.5 * float(np.ptp(ds.theta_phase_mean.values))
    p_s = float(ds.chamber_pressure_phase_mean.max())
    dot_s = 0.5 * float(np.ptp(ds.theta_dot_phase_mean.values))
    assert titles[0].endswith(rf"$\theta_s$ = {np.degrees(theta_s):.1f}°")
    assert titles[1].endswith(f"$P_s$ = {p_s / 1e3:.0f} kPa")
    assert titles[2].endswith(rf"$\dot\theta_s$ = {dot_s:.2f} rad/s")


def test_figure_7_one_panel_per_run_named(flaps):
    fig = _passes(figs.figure_7(flaps[:2]))
    titles = [ax.get_title(loc="left") for ax in fig.axes]
    assert len(titles) == 2 and len(set(titles)) == 2  # no empty axes, distinct titles
    assert all(str(ds.run.values) in t for ds, t in zip(flaps, titles))
    fig = _passes(figs.figure_7(flaps[:5]))  # two columns, the sixth slot removed
    assert len(fig.axes) == 5


def test_campaign_figures_with_models(flaps):
    comps = [comparison_run(f) for f in flaps]
    exp = [c.sel(source="experiment") for c in comps]
    models = {s: [c.sel(source=s) for c in comps] for s in ("analytical", "simulator")}
    fig = _passes(figs.figure_8(exp, models=models))
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    assert "time-domain simulator" in labels and "simulator" not in labels  # human labels
    _passes(figs.figure_9(exp, models=models))


def test_figures_8_9_drawn_from_the_comparison_files_stacked(flaps, tmp_path):
    """The figures stage reads the comparison files of Figs. 8-9 stacked along ``run``: the
    points and lines drawn are those drawn from the runs' datasets one by one."""
    from flumekit.figures.registry import figure
    from flumekit.io.netcdf import write_product
    from flumekit.io.processed import stack_files

    comps = {str(f.run.values): comparison_run(f) for f in flaps}
    for run, c in comps.items():
        write_product(c, tmp_path / f"{run}.nc", "comparison", "test")
    stacked = stack_files([tmp_path / f"{run}.nc" for run in sorted(comps)])
    one_by_one = [comps[run] for run in sorted(comps)]
    for name, draw in (("fig08", figs.figure_8), ("fig09", figs.figure_9)):
        entry = figure(name)
        assert entry.stacked
        got = entry.draw({"runs": stacked})
        want = draw([c.sel(source="experiment") for c in one_by_one],
                    models={s: [c.sel(source=s) for c in one_by_one]
                            for s in ("analytical", "simulator")})
        assert len(got.axes) == len(want.axes)
        for ax_got, ax_want in zip(got.axes, want.axes, strict=True):
            assert len(ax_got.lines) == len(ax_want.lines) > 0
            for a, b in zip(ax_got.lines, ax_want.lines, strict=True):
                np.testing.assert_array_equal(a.get_xydata(), b.get_xydata())
        assert got._suptitle.get_text() == want._suptitle.get_text()


def test_uncertainty_budget_bars_stack_each_conditions_shares():
    """Each condition's bar stacks its components' shares of the variance, the components
    below 1 % of every result as "other", one legend entry per component."""
    import xarray as xr

    from flumekit.figures.uncertainty import figure_budget

    rng = np.random.default_rng(5)
    comps = ["probe_noise", "calibration", "tiny", "water_depth"]
    share = rng.uniform(0, 1, (4, 3, len(comps)))  # (result, condition, component)
    share[..., 2] = 0.001
    share *= 100 / share.sum(axis=-1, keepdims=True)
    names = ("incident_height", "reflection_coefficient", "theta_amplitude", "capture_factor")
    budget = xr.Dataset({f"{q}_contribution": (("condition", "uncertainty_component"), s)
                         for q, s in zip(names, share, strict=True)},
                        coords={"uncertainty_component": comps,
                                "wave_period": ("condition", [2.0, 3.0, 3.5]),
                                "wave_height": ("condition", [0.15, 0.2, 0.25])})
    fig = _passes(figure_budget(budget))
    for ax, s in zip(fig.axes, share, strict=True):
        major = s[:, [0, 1, 3]]
        parts = np.column_stack([major, s[:, 2]])  # the minor component as "other", last
        tops = [np.max(c.get_paths()[k].vertices[:, 1]) for c in ax.collections
                for k in range(3)]
        np.testing.assert_allclose(tops, np.cumsum(parts, axis=1).T.ravel(), rtol=1e-12)
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    assert labels == ["probe noise", "calibration", "water depth", "other"]


def test_figure_10_experiment_visible_and_in_the_legend(flaps):
    ds = flaps[-1]
    comp = comparison_run(ds)
    models = {s: comp.sel(source=s) for s in ("analytical", "simulator")}
    fig = _passes(figs.figure_10(ds, models=models))
    assert len(fig.axes) == 3  # no elevation given: no empty panel
    titles = [ax.get_title(loc="left").replace("\xa0", " ") for ax in fig.axes]
    assert [t[:3] for t in titles] == ["(a)", "(b)", "(c)"]
    assert f"$W_I$ = {float(ds.incident_power):.3g} W" in titles[1]
    assert rf"$\omega$ = {2 * np.pi / float(ds.measured_period):.2f} rad/s" in titles[2]
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    assert len(labels) == 3 and labels[0].startswith("experiment")
    exp_line = fig.axes[0].lines[0]
    sim_line = [ln for ln in fig.axes[0].lines if ln.get_color() == "tab:red"][0]
    # the experiment stays visible under a coinciding simulator: thicker, and the model dashed
    assert exp_line.get_linewidth() > sim_line.get_linewidth()
    assert sim_line.get_linestyle() == "--"


def test_uvp_figures(field):
    fig = _passes(uvp.fig11(field))
    u0 = float(field.velocity_scale)
    assert f"= {u0:.3f} m/s" in fig._suptitle.get_text().replace("\xa0", " ")  # U0 stated
    # no arrow reaches its neighbour: the longest is shorter than the lattice spacing
    q = [c for c in fig.axes[0].collections if type(c).__name__ == "Quiver"][0]
    xy = q.get_offsets()
    xs, zs = np.unique(xy[:, 0]), np.unique(xy[:, 1])
    spacing = min(np.min(np.diff(xs)), np.min(np.diff(zs)))
    shown = [uvp._at_phase(field, p) for p in uvp.PHASES]
    longest = max(float(np.nanmax(np.hypot(f.u_normalised.values, f.w_normalised.values)))
                  for f in shown)  # over every grid point, so at least the drawn ones
    assert longest / q.scale <= spacing  # drawn length [x/h] of the longest arrow
    assert 3 <= xs.size <= 12 and 3 <= zs.size <= 12  # a few arrows, not a hatching
    # the colour bar covers every value drawn: no saturated colour, no extension triangle
    cs = [c for c in fig.axes[0].collections if hasattr(c, "levels")][0]
    umax = max(float(np.nanmax(np.abs(f.u_normalised.values))) for f in shown)
    assert cs.levels[0] <= -umax and cs.levels[-1] >= umax and cs.extend == "neither"
    cbar = [ax for ax in fig.axes if getattr(ax, "_colorbar", None)][0]
    ticks = cbar.get_yticks()
    # readable colour-bar ticks: round numbers (multiples of 0.05)
    assert np.allclose(ticks * 20, np.round(ticks * 20))
    assert any(type(a).__name__ == "QuiverKey" for a in fig.axes[0].texts + fig.axes[0].artists
               + fig.axes[0].get_children())
    fig = _passes(uvp.fig12(field))
    assert f"= {u0:.3f} m/s" in fig._suptitle.get_text().replace("\xa0", " ")


def test_fig12_drops_phases_without_data(field):
    f = field.copy(deep=True)
    for name in ("u_normalised", "w_normalised"):
        f[name][:50] = np.nan  # no data at all in the first half cycle
    fig = _passes(uvp.fig12(f, phases=(0.1, 0.3, 0.6, 0.8)))
    assert [ax.get_title(loc="left")[4:] for ax in fig.axes] == ["t/T = 0.60", "t/T = 0.80"]


def test_ballscrew_figures(ballscrew):
    from flumekit.stages.ballscrew import FIGURE_SOURCES

    for n, step in FIGURE_SOURCES.items():
        assert problems(bs.FIGURES[n](ballscrew[step])) == [], n
    fig = bs.figure_18(ballscrew["thermal_fem"])
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    assert any(lab.startswith("stator end (") for lab in labels)
    assert not any("_" in lab for lab in labels)
    fig = bs.figure_10(ballscrew["thermal_fem"])
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    assert "screw under the nut" in labels and not any("_" in lab for lab in labels)


# --- the figure test catches each fault --------------------------------------------------


def _good(width=7.0):
    fig, axes = new_figure(1, 2, width=width, height=2.5)
    for ax in axes[0]:
        ax.plot([0, 1], [0, 1], label="line")
        ax.set_xlabel("Time [s]")
        ax.set_ylabel("Elevation [m]")
    title(fig, "Run X (T = 1 s, H = 0.1 m)")
    return fig, axes[0]


def test_check_passes_a_good_figure():
    fig, _ = _good()
    assert problems(fig) == []


@pytest.mark.parametrize("fault, expect", [
    (lambda fig, ax: ax[1].lines[0].remove(), "empty axes"),
    (lambda fig, ax: ax[1].set_visible(False), "hidden axes"),
    (lambda fig, ax: ax[0].set_ylabel("Elevation"), "no units"),
    (lambda fig, ax: ax[0].set_xlabel(""), "x axis has no label"),
    (lambda fig, ax: ax[0].tick_params(labelsize=6), "below 8 pt"),
    (lambda fig, ax: ax[0].legend(loc="center"), "legend overlaps the data area"),
    (lambda fig, ax: fig.suptitle(""), "no figure title"),
    (lambda fig, ax: fig.set_size_inches(6.5, 2.5), "neither one column"),
    (lambda fig, ax: fig.text(0.98, 0.5, "a long note running off the page"), "cut at the"),
    (lambda fig, ax: [a.set_title(f"({t}) panel", loc="left") for a, t in zip(ax, "bc")],
     "not from (a)"),
    (lambda fig, ax: [a.set_title(f"({t}) panel", loc="left") for a, t in zip(ax, "ac")],
     "not from (a)"),
])
def test_check_catches(fault, expect):
    fig, ax = _good()
    assert problems(fig) == []
    fault(fig, ax)
    found = problems(fig)
    assert any(expect in p for p in found), found


# --- deterministic saving ------------------------------------------------------------------


def _figure():
    fig, axes = new_figure(1, 1, width=3.5, height=2.5)
    axes[0, 0].plot(np.arange(10), np.arange(10) ** 2)
    axes[0, 0].set_xlabel("Time [s]")
    axes[0, 0].set_ylabel("Elevation [m]")
    title(fig, "Run X")
    return fig


def test_same_figure_same_bytes_in_every_format(tmp_path):
    from flumekit.figures.style import FORMATS, save

    paths = {}
    for folder in ("one", "two/deeper"):
        out = [tmp_path / folder / f"fig.{fmt}" for fmt in FORMATS]
        assert save(_figure(), *out) == out
        paths[folder] = out
    for a, b in zip(paths["one"], paths["two/deeper"]):
        data = a.read_bytes()
        assert data == b.read_bytes(), a.suffix
        # no software version, date or absolute path in the file
        for marker in (b"Matplotlib", b"CreationDate", str(tmp_path).encode()):
            assert marker not in data, (a.suffix, marker)
    assert not list(tmp_path.rglob(".*tmp*"))  # no temporary file left


def test_a_layout_off_in_its_last_digits_gives_the_same_bytes(tmp_path, monkeypatch):
    """The constrained layout's solver can place a box a few ulps apart in two processes (it
    orders its variables by address); the laid-out boxes are rounded to a 1e-9 grid of the
    figure, so such noise never reaches the PDF's ten-decimal coordinates."""
    from matplotlib.layout_engine import ConstrainedLayoutEngine
    from matplotlib.transforms import Bbox

    from flumekit.figures import style

    (clean,) = style.save(_figure(), tmp_path / "clean.pdf")
    solve = ConstrainedLayoutEngine.execute

    def noisy(self, fig):  # the solver's answer, 1e-11 of the figure off
        out = solve(self, fig)
        for ax in fig.get_axes():
            x0, y0, w, h = ax.get_position(original=True).bounds
            ax._set_position(Bbox.from_bounds(x0 + 1e-11, y0 - 1e-11, w, h))
        return out

    monkeypatch.setattr(ConstrainedLayoutEngine, "execute", noisy)
    fig = _figure()
    (off,) = style.save(fig, tmp_path / "off.pdf")
    assert off.read_bytes() == clean.read_bytes()
    for ax in fig.get_axes():  # every box on the grid
        bounds = np.array(ax.get_position().bounds)
        assert np.array_equal(bounds, np.round(bounds, style.LAYOUT_DECIMALS))


def test_png_at_300_dpi_and_print_size(tmp_path):
    import struct

    from flumekit.figures.style import save

    (path,) = save(_figure(), tmp_path / "f.png")
    data = path.read_bytes()
    width, height = struct.unpack(">II", data[16:24])  # the IHDR chunk
    assert (width, height) == (3.5 * 300, 2.5 * 300)
    with pytest.raises(ValueError, match="format 'jpg'"):
        save(_figure(), tmp_path / "f.jpg")


def test_figure_rules_write_every_format(campaign, tmp_path):
    from flumekit.errors import FlumekitError
    from flumekit.stages import figures as stage
    from flumekit.stages.context import Context

    # the campaign has no run: the figures are the ball-screw study's, which a scene asks for
    asks = {"ballscrew": ["figure/bs_fig*"]}
    assert stage.rules(Context(campaign=campaign, processed=tmp_path), dict(stage.DEFAULTS)) == []
    rules = stage.rules(Context(campaign=campaign, processed=tmp_path, scenes=asks),
                        dict(stage.DEFAULTS))
    assert rules and all(sorted(r.outputs) == ["pdf", "png"] for r in rules)
    assert all(r.outputs["png"] == tmp_path / "figures" / (r.target[len("figure/"):] + ".png")
               for r in rules)
    ctx = Context(campaign=campaign, processed=tmp_path, scenes=asks,
                  params={"figures": {"formats": ["svg"]}})
    svg = stage.rules(ctx, ctx.stage_params("figures", stage.DEFAULTS))
    assert svg and all(list(r.outputs) == ["svg"] for r in svg)
    ctx = Context(campaign=campaign, processed=tmp_path, scenes=asks,
                  params={"figures": {"formats": ["jpg"]}})
    with pytest.raises(FlumekitError, match="formats"):
        stage.rules(ctx, ctx.stage_params("figures", stage.DEFAULTS))


def test_captions_read_as_what_the_figure_shows():
    """A figure's caption (its files' Description, the report's caption) is its docstring's
    summary without the imperative verb, and the prose paragraph after it."""
    from flumekit.figures.registry import every_figure, figure

    for name, entry in every_figure().items():
        caption = entry.description
        assert caption and not caption.startswith("Draw "), (name, caption)
        assert "Parameters" not in caption and "----" not in caption, (name, caption)
    qc = figure("qc").description
    assert qc.startswith("The QC'd records (black) of every probe and flap channel")
    assert "suspect, failed and missing samples" in qc  # the paragraph after the summary


def test_thin_keeps_each_columns_extremes_and_gaps():
    """The thinned line keeps, per pixel column, the first lowest and highest finite sample
    (ties: the first), and the samples around each gap."""
    from flumekit.figures.style import thin

    rng = np.random.default_rng(3)
    n = 30000
    x = np.arange(n) / 50.0
    y = np.round(rng.normal(size=n), 1)  # many ties
    y[1000:1500] = np.nan
    xs, ys = thin(x, y, width=3.5)
    kept = set(np.searchsorted(x, xs))
    col = np.minimum((x * (1050 / x[-1])).astype(int), 1049)
    for c in (0, 17, 300, 1049):
        idx = np.flatnonzero((col == c) & np.isfinite(y))
        assert idx[np.argmin(y[idx])] in kept and idx[np.argmax(y[idx])] in kept
    assert {999, 1000, 1500} <= kept  # the samples around the gap: it stays a gap


def test_a_figure_drawn_without_the_collector_is_freed_at_the_end():
    """Inside without_collector the cyclic collector does not run; the reference cycles the
    block made (a figure and its artists) are freed when it ends, and the collector is on."""
    import gc
    import weakref

    from flumekit.figures.style import without_collector

    with without_collector():
        fig, axes = new_figure()
        axes[0, 0].plot([0, 1], [0, 1])
        gone = weakref.ref(fig)
        del fig, axes
        assert not gc.isenabled() and gone() is not None  # a cycle: only the collector frees it
    assert gc.isenabled() and gone() is None


def test_a_figure_is_looked_up_without_the_figure_modules_after_its_own():
    """A QC figure's worker does not import the ball-screw figures (and their models)."""
    import subprocess
    import sys

    code = ("import sys; from flumekit.figures.registry import figure; figure('qc'); "
            "print('flumekit.figures.ballscrew' in sys.modules, "
            "'flumekit.figures.qc' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.split()
    assert out == ["False", "True"]


def test_png_bytes_decode_to_the_pixels_texts_and_resolution(tmp_path):
    """The PNG encoder: every row filtered from the one above, decoded (Pillow) to the same
    pixels, grey, RGB and RGBA (views of a canvas' bands); Latin-1 and other texts and the
    resolution read back, by the report's reader too."""
    from PIL import Image

    from flumekit.figures.style import png_bytes
    from flumekit.report import _png_text

    rng = np.random.default_rng(7)
    for bands in (1, 3, 4):
        image4 = rng.integers(0, 256, (37, 23, 4), dtype=np.uint8)
        image4[10:20] = image4[9]  # rows that repeat the row above, as blank space does
        pixels = image4[..., :bands]  # a view of the canvas' bands, as the figures pass
        texts = {"Title": "Wave separation: run T3.50 (T = 3.5 s)", "Description": "θ ≈ 0.1 π"}
        path = tmp_path / f"image{bands}.png"
        path.write_bytes(png_bytes(pixels, 300, texts))
        with Image.open(path) as image:
            assert image.mode == {1: "L", 3: "RGB", 4: "RGBA"}[bands]
            np.testing.assert_array_equal(np.asarray(image), pixels[..., 0] if bands == 1
                                          else pixels)
            assert image.text == texts
            assert image.info["dpi"] == pytest.approx((300, 300), abs=1e-3)
        assert _png_text(path) == texts


def test_ticks_updated_once_per_state_give_the_same_pixels(tmp_path, monkeypatch):
    """Each axis's ticks updated, and their labels measured, once per state during
    :func:`save`: the PNG (and PDF) of a figure of shared rows (offset texts, labels of
    different widths) has the pixels (bytes) it has when every request updates and measures
    them again, as matplotlib does, and each axis has its own methods back."""
    from PIL import Image

    from flumekit.figures import style as st

    def drawing():
        fig, axes = new_figure(3, 1)
        t = np.linspace(0.0, 600.0, 2000)
        for i, ax in enumerate(axes[:, 0]):
            ax.plot(t, 1e5 + 10.0 ** (2 * i) * np.sin(t / 7.0), lw=0.5)
            ax.set_ylabel("[Pa]")
            ax.set_title(f"panel {i}", loc="left")
        for ax in axes[1:, 0]:
            ax.sharex(axes[0, 0])
        axes[-1, 0].set_xlabel("Time [s]")
        title(fig, "Three shared rows")
        return fig

    updates, measures = [], []
    axis_class = type(Figure().add_subplot().xaxis)
    update, measure = axis_class._update_ticks, axis_class._get_ticklabel_bboxes
    monkeypatch.setattr(axis_class, "_update_ticks",
                        lambda axis: updates.append(axis) or update(axis))
    monkeypatch.setattr(axis_class, "_get_ticklabel_bboxes",
                        lambda axis, *a: measures.append(axis) or measure(axis, *a))
    fig = drawing()
    path, _ = st.save(fig, tmp_path / "a.png", tmp_path / "a.pdf")
    remembered, n_remembered = np.asarray(Image.open(path)), (len(updates), len(measures))
    assert not any({"_update_ticks", "_get_ticklabel_bboxes"} & set(vars(axis))
                   for ax in fig.axes for axis in (ax.xaxis, ax.yaxis))
    monkeypatch.setattr(st, "_ticks_remembered", lambda fig: lambda: None)
    updates.clear()
    measures.clear()
    path, _ = st.save(drawing(), tmp_path / "b.png", tmp_path / "b.pdf")
    every_time = np.asarray(Image.open(path))
    assert (remembered == every_time).all()
    assert (tmp_path / "a.pdf").read_bytes() == (tmp_path / "b.pdf").read_bytes()
    assert 3 * n_remembered[0] < len(updates), (n_remembered, len(updates))
    assert 2 * n_remembered[1] <= len(measures), (n_remembered, len(measures))


def test_pdf_fonts_are_subset_without_layout_tables_and_say_nothing(tmp_path, caplog,
                                                                    monkeypatch):
    """The embedded subset keeps the glyphs asked for and drops the tables a PDF never
    reads; saving a PDF warns of nothing (the subsetter's warnings would reach the make's
    output)."""
    import io
    import logging

    from fontTools.ttLib import TTFont
    from matplotlib import font_manager

    from flumekit.figures import style
    from flumekit.figures.style import _font_subset, save

    monkeypatch.setattr(style, "_SUBSETS", {})  # subset here, not remembered from before
    path = font_manager.findfont("DejaVu Sans")
    glyphs = frozenset(range(3, 40))
    data, index = _font_subset(path, 0, glyphs)
    font = TTFont(io.BytesIO(data))
    assert not {"GSUB", "GPOS", "GDEF", "kern", "FFTM"} & set(font.keys())
    assert {"glyf", "hmtx", "loca", "head"} <= set(font.keys())
    assert glyphs <= set(index) and len(font.getGlyphOrder()) < 100
    with caplog.at_level(logging.WARNING, logger="fontTools"):
        (pdf,) = save(_figure(), tmp_path / "f.pdf")
    assert not caplog.records, caplog.records
    assert b"FontFile2" in pdf.read_bytes()


def test_figure_6a_title_counts_the_waves_shown(waves):
    # the paper's five waves by default; another count is named as such, not as "Five waves"
    assert wave_figs.figure_6a(waves, start=40).get_suptitle().startswith("Five waves,")
    fig = wave_figs.figure_6a(waves, start=40, n_waves=3)
    assert fig.get_suptitle().startswith("Three waves,")
    assert wave_figs.figure_6a(waves, start=40, n_waves=12).get_suptitle().startswith("12 waves,")
