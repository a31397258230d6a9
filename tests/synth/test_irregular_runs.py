"""The virtual flume's irregular runs against their truth (flumekit.synth.irregular).

The small campaign's irregular run (Hm0 0.10 m, Tp 2 s, γ 3.3, 400 s) is written alone with
write_virtual_run, which writes the same bytes as the whole campaign. Tolerances:

* the realised incident Hm0 at the flap within 1 % of the target (the wavemaker's gain scatter
  is 0.3 %, clipped at 3 standard deviations; the random-phase components hold the target's
  variance exactly), Te and Tp of the realised spectrum within 0.5 % of the target's (period
  scatter 0.05 %);
* the probes equal the truth's incident + reflected + beach waves to the probes' 0.5 mm noise
  (RMS within 10 % of it), and so does a reconstruction from the truth's spectra alone;
* the separation of the probes (flumekit.waves.separate, regular=False) meets the acceptance of
  the irregular-sea analysis: incident Hm0 and Te within 2 %, Tp within 5 %, bulk Kr within
  0.02, Kr(f) within 0.05 over the band holding 90 % of the incident energy.
"""

import hashlib

import numpy as np
import pandas as pd
import pytest
import xarray as xr

from flumekit.campaign import load_campaign
from flumekit.synth.campaign import Truth, plan_runs, write_virtual_base, write_virtual_run
from flumekit.synth.flap import flap_scattering, radiation_damping
from flumekit.synth.irregular import sea_state_truth
from flumekit.synth.waves import jonswap
from flumekit.waves import separate
from flumekit.waves.layout import check_layout
from flumekit.waves.theory import group_velocity, wavenumber

RUN = "JS_Hm0.100_Tp2.00_r0"
NOISE = Truth().probe_noise


def _write(root):
    write_virtual_base(root, "small", 11)
    write_virtual_run(root, RUN)
    return root


@pytest.fixture(scope="module")
def campaign(tmp_path_factory):
    return _write(tmp_path_factory.mktemp("a") / "small")


def _open(path):
    return xr.open_dataset(path, decode_times=False)


def _probes(root):
    """Calibrated probe records [m] with the truth's gains, their times and the campaign."""
    c = load_campaign(root)
    run = c.run(RUN)
    table = pd.read_csv(run.file("probes"))
    with _open(root / "truth" / "calibration.nc") as cal:
        eta = np.array([cal.gain.sel(probe=p).item() * table[f"{p} [V]"].values
                        + cal.offset.sel(probe=p).item() for p in c.probes.names])
    return c, run, table["time [s]"].values, eta


def test_irregular_run_is_written_as_the_schema_says(campaign):
    c, run, t, eta = _probes(campaign)
    assert run.irregular and run.period is None
    s = run.sea_state
    assert (s.hm0, s.tp, s.te, s.gamma, s.seed, s.duration) == (0.10, 2.0, None, 3.3, 11, 400.0)
    assert sorted(p.name for p in run.path.iterdir()) == ["flap.csv", "probes.csv", "run.toml"]
    assert t.size == 400 * c.probes.sampling_rate
    flap = pd.read_csv(run.file("flap"))
    assert len(flap) == 400 * c.encoder.sampling_rate
    # the flap moves and the chamber holds pressure in the developed sea
    assert np.ptp(flap["encoder [counts]"].values) > 50
    with _open(campaign / "truth" / RUN / "waves.nc") as w:
        assert w.attrs["analysis_end"] == 400.0
        assert 60 < w.attrs["analysis_start"] < 150


def test_same_seed_same_bytes(campaign, tmp_path):
    other = _write(tmp_path / "small")

    def digest(root):
        files = sorted(p for d in (root / "runs" / RUN, root / "truth" / RUN)
                       for p in d.iterdir())
        return {p.relative_to(root).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
                for p in files}

    assert digest(campaign) == digest(other)


def test_realised_incident_sea_state_matches_the_target(campaign):
    with _open(campaign / "truth" / RUN / "waves.nc") as w, \
            _open(campaign / "truth" / RUN / "flap.nc") as fl:
        f = w.frequency.values
        df = f[1] - f[0]
        assert df == pytest.approx(1.0 / (w.attrs["analysis_end"] - w.attrs["analysis_start"]))
        target = w.spectrum_target.values
        # the target recomputed here: the JONSWAP of the run.toml's sea state over its band
        assert np.allclose(target, jonswap(f, 0.10, 2.0, 3.3, band=(0.3, 1.5)), rtol=1e-12)
        hm0_target = 4 * np.sqrt(target.sum() * df)
        assert hm0_target == pytest.approx(0.10, rel=1e-9)
        # the realised incident wave at the flap over the span, from its time series
        t = fl.time.values
        span = (t >= w.attrs["analysis_start"]) & (t < w.attrs["analysis_end"])
        hm0 = 4 * np.std(fl.eta_incident.values[span])
        assert hm0 == pytest.approx(w.attrs["hm0"], rel=1e-6)
        assert hm0 == pytest.approx(0.10, rel=0.01)
        s = w.spectrum_incident.values
        assert 4 * np.sqrt(s.sum() * df) == pytest.approx(hm0, rel=1e-6)
        # the truth of waves.nc is that of flap.nc's series at x = 0 over the span
        again = sea_state_truth(t, fl.eta_incident.values,
                                fl.eta_reflected.values + fl.eta_beach.values,
                                (w.attrs["analysis_start"], w.attrs["analysis_end"]),
                                depth=0.825, f_max=f[-1])
        assert np.array_equal(again.spectrum_incident.values, s)
        assert np.array_equal(again.spectrum_reflected.values, w.spectrum_reflected.values)
        assert again.attrs["reflection_coefficient"] == w.attrs["reflection_coefficient"]
        te_target = (target / f).sum() / target.sum()
        assert w.attrs["energy_period"] == pytest.approx(te_target, rel=0.005)
        assert w.attrs["energy_period"] == pytest.approx((s / f).sum() / s.sum(), rel=1e-9)
        assert w.attrs["peak_period"] == pytest.approx(2.0, rel=0.005)
        # energy flux and capture width ratio from their definitions
        j = 1000.0 * 9.81 * (s * group_velocity(1 / f, 0.825)).sum() * df
        assert w.attrs["energy_flux"] == pytest.approx(j, rel=1e-9)
        power = float(np.mean(fl.power.values[span]))
        assert w.attrs["mean_power"] == pytest.approx(power, rel=1e-12)
        assert w.attrs["capture_width_ratio"] == pytest.approx(power / (j * 1.31), rel=1e-9)
        assert 0.05 < w.attrs["capture_width_ratio"] < 0.6


def test_probes_are_the_truths_waves_plus_noise(campaign):
    c, run, t, eta = _probes(campaign)
    with _open(campaign / "truth" / RUN / "waves.nc") as w:
        true = (w.eta_incident + w.eta_reflected + w.eta_beach).values
        d = eta - true
        assert np.all(np.abs(d.mean(axis=1)) < 0.1 * NOISE)
        assert np.allclose(d.std(axis=1), NOISE, rtol=0.1)
        # independently, from the truth's spectra at the flap: the incident components and
        # R_eff(f), each travelling to the probe with its linear wavenumber
        start, end = w.attrs["analysis_start"], w.attrs["analysis_end"]
        span = (t >= start) & (t < end)
        n = int(span.sum())
        f = w.frequency.values
        k = wavenumber(2 * np.pi * f, 0.825)
        a = w.incident_spectral_amplitude.values * np.exp(1j * w.incident_spectral_phase.values)
        r = w.reflection_coefficient_spectrum.values * np.exp(
            1j * w.reflection_phase_spectrum.values)
        x = np.array([run.probe_x[p] for p in c.probes.names])[:, None]
        coef = np.zeros((x.size, n // 2 + 1), complex)
        bins = np.rint(f * (end - start)).astype(int)
        coef[:, bins] = a * (np.exp(-1j * k * x) + r * np.exp(1j * k * x)) * (n / 2.0)
        rebuilt = np.fft.irfft(coef, n)
        d = eta[:, span] - rebuilt
        assert np.allclose(d.std(axis=1), NOISE, rtol=0.1), d.std(axis=1)
        assert np.all(d.std(axis=1) < 0.02 * eta[:, span].std(axis=1))


def test_separation_recovers_the_truth(campaign):
    c, run, t, eta = _probes(campaign)
    with _open(campaign / "truth" / RUN / "waves.nc") as w:
        truth = dict(w.attrs)
        ft, st_i, st_r = (w.frequency.values, w.spectrum_incident.values,
                          w.spectrum_reflected.values)
    sep = [c.probes.names.index(p) for p in c.probes.separation]
    span = (t >= truth["analysis_start"]) & (t < truth["analysis_end"])
    res = separate(eta[sep][:, span], 0.825, x=[run.probe_x[p] for p in c.probes.separation],
                   sampling_rate=c.probes.sampling_rate, regular=False, x_ref=0.0)
    f = res.frequency.values
    s_i, s_r = res.spectrum_incident.values, res.spectrum_reflected.values
    m0 = s_i.sum()
    assert 4 * np.sqrt(m0 * (f[1] - f[0])) == pytest.approx(truth["hm0"], rel=0.02)
    assert (s_i / f).sum() / m0 == pytest.approx(truth["energy_period"], rel=0.02)
    assert 1 / f[np.argmax(s_i)] == pytest.approx(truth["peak_period"], rel=0.05)
    assert float(res.reflection_coefficient) == pytest.approx(truth["reflection_coefficient"],
                                                              abs=0.02)
    # Kr(f) in 0.05 Hz bands over the band of 90 % of the incident energy, the truth's own
    # spectra smoothed the same way
    edges = np.arange(truth["energy_band_low"], truth["energy_band_high"], 0.05)
    for lo, hi in zip(edges[:-1], edges[1:]):
        m, mt = (f >= lo) & (f < hi), (ft >= lo) & (ft < hi)
        kr = np.sqrt(s_r[m].sum() / s_i[m].sum())
        assert kr == pytest.approx(np.sqrt(st_r[mt].sum() / st_i[mt].sum()), abs=0.05), lo


def test_irregular_probe_layout_resolves_every_sea_state():
    truth = Truth()
    x = [dict(truth.sea.probe_x)[p] for p in ("WP1", "WP2", "WP3")]
    for size in ("small", "default", "paper"):
        for r in plan_runs(size):
            if r.sea is None:
                continue
            band = (truth.sea.band[0] / r.sea["tp"], truth.sea.band[1] / r.sea["tp"])
            assert check_layout(x, 0.825, band).attrs["ill_conditioned_fraction"] == 0, r.id


def test_regular_runs_keep_their_random_streams():
    """The irregular runs come after the regular and UVP runs, so every regular run keeps its
    id and its random stream (key): a regular run of small is written to the same bytes as
    before the irregular runs existed (checked once on every file of the campaign)."""
    small = [(r.id, r.key) for r in plan_runs("small")]
    assert small == [("T2.00_H0.150_r0", (1, 0)), ("T3.50_H0.250_r0", (2, 0)),
                     ("uvp_z0.300_r0", (3, 0)), ("uvp_z0.500_r0", (4, 0)),
                     (RUN, (5, 0))]
    default = [r for r in plan_runs("default") if r.sea is not None]
    assert [r.id for r in default] == ["JS_Hm0.080_Tp2.00_r0", "JS_Hm0.080_Tp2.80_r0",
                                       "JS_Hm0.120_Tp2.00_r0", "JS_Hm0.120_Tp2.80_r0"]
    assert len([r for r in plan_runs("paper") if r.sea is not None]) == 12


def test_flap_scattering_conserves_energy(tmp_path):
    """|R|² + |T|² + 2 ν ν_L / |Z|² = 1 (the share absorbed by the loss damping), a free flap is
    lossless, transparent at resonance and a wall at high frequency."""
    root = tmp_path / "c"
    write_virtual_base(root, "small", 11)
    c = load_campaign(root)
    f = np.linspace(0.2, 3.0, 50)
    w = 2 * np.pi * f
    flap = c.flap
    nu = radiation_damping(w, 0.825, flap.hinge_height, flap.width)
    for loss in (0.0, 110.0, 500.0):
        r, t = flap_scattering(f, c, loss)
        z2 = (nu + loss) ** 2 + (w * (flap.inertia + 120.0) - flap.buoyancy_stiffness / w) ** 2
        assert np.allclose(np.abs(r) ** 2 + np.abs(t) ** 2 + 2 * nu * loss / z2, 1.0)
    r, t = flap_scattering(np.array([np.sqrt(flap.buoyancy_stiffness
                                             / (flap.inertia + 120.0)) / (2 * np.pi)]), c, 0.0)
    assert abs(t[0]) == pytest.approx(1.0) and abs(r[0]) < 1e-12
    r, _ = flap_scattering(np.array([5.0]), c, 110.0)
    assert abs(r[0]) > 0.99


def test_the_plan_reads_the_irregular_run(tmp_path):
    """virtual_campaign (what a pipeline plans with before synthesis) reads the irregular
    run's run.toml as load_campaign reads the written one."""
    from flumekit.synth.campaign import virtual_campaign

    run = virtual_campaign(tmp_path / "small", "small", 11).run(RUN)
    assert run.irregular and run.sea_state.seed == 11 and run.sea_state.duration == 400.0
    assert run.probe_x == dict(Truth().sea.probe_x)


def test_the_sea_arrives_from_the_wavemaker_and_nothing_wraps_round():
    """Before the fastest (shallow-water) wave could reach a position the field is calm (below
    1e-4 Hm0 until 80 % of that time; the dispersive front rises just before it): the FFT
    is long enough that the end of the record does not wrap round into its start."""
    from flumekit.synth.irregular import SeaTruth, irregular_sea
    from flumekit.synth.waves import Beach

    def wall(f):
        return np.ones(f.size, complex), np.zeros(f.size, complex)

    x = np.array([-3.2, 0.0])
    sea = irregular_sea(25.0, 300, x, hm0=0.1, peak_period=2.0, gamma=3.3, seed=3,
                        depth=0.825, flap=wall, beach=Beach(), x_wavemaker=-32.7,
                        sea=SeaTruth())
    t = sea.field.time.values
    c0 = np.sqrt(9.81 * 0.825)
    for i, xi in enumerate(x):
        calm = t < 0.8 * (xi + 32.7) / c0
        assert np.abs(sea.field.eta_incident.values[i, calm]).max() < 1e-4 * 0.1
        calm = t < 0.8 * (32.7 - xi) / c0
        assert np.abs(sea.field.eta_reflected.values[i, calm]).max() < 1e-4 * 0.1
    # a fixed wall reflects every component in phase at x = 0 once the sea has developed
    late = t >= sea.analysis_start
    assert np.allclose(sea.field.eta_reflected.values[1, late],
                       sea.field.eta_incident.values[1, late], atol=2e-4 * 0.1)
