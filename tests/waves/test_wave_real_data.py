"""Separation on a real flume record (WaveLabX, vendored in examples/wavelabx/ with its source).

Source: GitHub sandslamsal/WaveLabX, wavedata.csv (MIT): three capacitance gauges at
x = 0, 0.6, 0.9 m, 100 Hz, 200 s of regular waves (T ≈ 1.33 s) in h = 0.25 m. No published
analysis result is used: the truth is the measurement itself. Linear theory with the right depth
must explain the first harmonic at all three gauges with one incident and one reflected wave;
a wrong depth (wrong wavenumber) must not.
"""

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from flumekit.waves import separate

DATA = Path(__file__).resolve().parents[2] / "examples" / "wavelabx" / "wavedata.csv"


@pytest.fixture(scope="module")
def eta():
    d = np.loadtxt(DATA, delimiter=",", skiprows=1)
    t = np.arange(d.shape[0]) / 100.0
    return xr.DataArray((d - d.mean(axis=0)).T, dims=("probe", "time"),
                        coords={"probe": ["G1", "G2", "G3"], "x": ("probe", [0.0, 0.6, 0.9]),
                                "time": t})


def _residual(eta, depth):
    """Relative RMS misfit of incident + reflected to each gauge's first-harmonic band."""
    band = (0.375, 1.125)  # f1 = 0.75 Hz ± f1/2
    f = np.fft.rfftfreq(eta.time.size, 0.01)
    c = np.fft.rfft(eta.values, axis=-1)
    c[:, (f < band[0]) | (f > band[1])] = 0
    measured = np.fft.irfft(c, eta.time.size, axis=-1)
    out = []
    for p, xp in enumerate(eta.x.values):
        r = separate(eta, depth, regular=True, band=band, x_ref=float(xp))
        model = (r.eta_incident + r.eta_reflected).values
        out.append(np.sqrt(np.mean((model - measured[p]) ** 2) / np.mean(measured[p] ** 2)))
    return np.array(out), r


def test_linear_theory_explains_the_first_harmonic_at_every_gauge(eta):
    res, r = _residual(eta, 0.25)
    assert r.attrs["fundamental_frequency"] == pytest.approx(0.75, abs=0.005)  # T ≈ 1.33 s
    assert np.all(res < 0.06)  # measured: 0.04, 0.007, 0.045
    assert 0 <= float(r.reflection_coefficient) < 0.2
    for wrong in (0.15, 0.5):  # wrong wavenumbers do not fit
        assert np.max(_residual(eta, wrong)[0]) > 0.12
