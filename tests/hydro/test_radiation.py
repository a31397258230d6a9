"""Radiation impulse response, Filon transforms and the state-space realisation."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import integrate, linalg

from flumekit.hydro import coefficients as H
from flumekit.hydro import radiation as R

KERNEL = {"amplitude": [400.0, 300.0], "decay_rate": [1.0, 3.0], "frequency": [2.5, 6.0]}
A_INF = 25.0


def true_kernel(t):
    return sum(a * np.exp(-al * t) * np.cos(be * t) for a, al, be in zip(*KERNEL.values()))


def analytic(w_max=25.0, n=400):
    w = np.linspace(0.05, w_max, n)
    return H.from_kernel(w, **KERNEL, added_inertia_infinite=A_INF,
                         excitation_torque=np.ones_like(w), hydrostatic_stiffness=605.0)


@settings(max_examples=30, deadline=None)
@given(nodes=st.lists(st.floats(0.0, 10.0), min_size=2, max_size=6, unique=True),
       values=st.lists(st.floats(-5.0, 5.0), min_size=6, max_size=6),
       y=st.floats(0.0, 40.0), kind=st.sampled_from(["cos", "sin"]))
def test_filon_is_exact_for_piecewise_linear_data(nodes, values, y, kind):
    x = np.sort(nodes)
    if np.min(np.diff(x)) < 1e-3:
        return
    f = np.asarray(values[: x.size])
    got = R.filon(x, f, y, kind)
    trig = np.cos if kind == "cos" else np.sin
    want = sum(integrate.quad(lambda u, j=j: np.interp(u, x, f) * trig(y * u), x[j], x[j + 1],
                              epsabs=1e-12, epsrel=1e-12, limit=200)[0] for j in range(x.size - 1))
    assert got == pytest.approx(want, abs=1e-9 * (1 + np.abs(f).max() * (x[-1] - x[0])))


def test_impulse_response_matches_the_analytic_kernel():
    k = R.impulse_response(analytic(), duration=20.0, dt=0.01)
    truth = true_kernel(k["lag"].values)
    err = np.sqrt(np.sum((k.values - truth) ** 2) / np.sum(truth**2))
    # B is known to 25 rad/s; the fitted power tail (exponent ~2.5 against the true local
    # slope) carries the rest: 0.3 % of the L2 norm, 1 % at t = 0
    assert err < 3e-3
    assert k.values[0] == pytest.approx(truth[0], rel=0.01)
    assert 2.0 < k.attrs["tail_exponent"] < 3.5
    # the reported fraction of ∫B beyond the tail's end against the true one (B ~ Σaα/ω²)
    w_end = 25.0 * 20
    true_beyond = np.dot(KERNEL["amplitude"], KERNEL["decay_rate"]) / w_end
    true_total = np.pi / 2 * true_kernel(0.0)
    assert k.attrs["tail_truncation"] == pytest.approx(true_beyond / true_total, rel=0.7)


def test_memory_response_reproduces_the_coefficients():
    hy = analytic()
    k = R.impulse_response(hy, duration=30.0, dt=0.01)
    w = hy["angular_frequency"].values[10:300:10]
    got = R.memory_response(k, w)
    # K̂ = B + iω(A∞ − A) (Ogilvie 1964), e^{-iωt} convention
    want = (hy["radiation_damping"].values[10:300:10]
            + 1j * w * (A_INF - hy["added_inertia"].values[10:300:10]))
    assert np.max(np.abs(got - want)) < 5e-3 * np.max(np.abs(want))


def test_state_space_recovers_the_kernel_poles():
    k = R.impulse_response(analytic(), duration=20.0, dt=0.01)
    ss = R.fit_state_space(k)
    # the kernel is exactly of order 4: two damped cosines
    assert ss.order == 4
    assert ss.fit_error_time < 0.01 and ss.fit_error_frequency < 0.01
    poles = np.sort_complex(ss.poles)
    truth = np.sort_complex(np.array([-3 + 6j, -1 + 2.5j]))
    np.testing.assert_allclose(poles, truth, rtol=0.05)
    assert np.all(ss.poles.real < 0)
    # a higher order fits better
    assert R.fit_state_space(k, order=8).fit_error_time < ss.fit_error_time


def test_state_space_forms_agree():
    ss = R.fit_state_space(R.impulse_response(analytic(), duration=20.0, dt=0.01), order=6)
    a, b, c = ss.matrices()
    t = np.linspace(0, 5, 11)
    direct = [c @ linalg.expm(a * ti) @ b for ti in t]
    np.testing.assert_allclose(ss.impulse(t), direct, rtol=1e-9, atol=1e-9)
    # frequency response of the real form: C (-iω - A)^-1 B, e^{-iωt} convention
    w = np.array([0.5, 2.0, 7.0])
    fr = [c @ np.linalg.solve(-1j * wi * np.eye(a.shape[0]) - a, b) for wi in w]
    np.testing.assert_allclose(ss.frequency_response(w), fr, rtol=1e-9)


def test_frequency_error_is_measured_against_the_coefficients():
    hy = analytic()
    k = R.impulse_response(hy, duration=20.0, dt=0.01)
    ss = R.fit_state_space(k, order=6)
    w = np.linspace(0.1, 20, 100)
    kh = H.kernel_response(w, **KERNEL)
    assert np.max(np.abs(ss.frequency_response(w) - kh)) < 0.01 * np.max(np.abs(kh))


def test_state_space_survives_netcdf_and_complex_merge(tmp_path):
    """One fit per campaign: the model written by the models/hydro stage reads back exactly."""
    from flumekit.hydro.coefficients import merge_complex
    from flumekit.io.netcdf import read_dataset, write_dataset

    w = np.linspace(0.05, 25.0, 300)
    hy = H.from_kernel(w, [400.0, 300.0], [1.0, 3.0], [2.5, 6.0], added_inertia_infinite=25.0,
                       excitation_torque=np.ones_like(w) + 0j, hydrostatic_stiffness=605.0)
    ss = R.fit_state_space(R.impulse_response(hy, 20.0, 0.01), order=6)
    from flumekit import conventions

    out = R.state_space_dataset(ss)
    out.attrs.update(conventions.global_attrs("radiation model", "test", {}))
    write_dataset(out, tmp_path / "ss.nc")
    ds = read_dataset(tmp_path / "ss.nc")
    for back in (R.state_space_from_dataset(ds), R.state_space_from_dataset(merge_complex(ds))):
        np.testing.assert_array_equal(back.poles, ss.poles)
        np.testing.assert_array_equal(back.residues, ss.residues)
        assert back.fit_error_time == ss.fit_error_time and back.order == ss.order
