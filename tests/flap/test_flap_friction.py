"""Modified LuGre friction (Appendix B): steady state, step convergence, reversals, stiffness."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from flumekit.flap import friction as fr


@pytest.fixture(scope="module")
def model(campaign):
    return fr.LuGre.from_campaign(campaign.pto.friction)


def test_steady_state_limits_check_the_corrected_equations(model):
    fc, fs = model.coulomb_force, model.static_force
    # breakaway: F_ss -> F_s as v -> 0+ (no film, full Stribeck excess)
    # (h_ss grows like v^(2/3): 3e-8 at 1e-12 m/s)
    assert float(fr.steady_friction(1e-12, model)) == pytest.approx(fs, rel=1e-6)
    # beyond v_b the film is at h_max = 1 - F_c/F_s (Eq. A9 with exponent -2/3) and the
    # static excess (1 - h) F_s - F_c vanishes: exactly Coulomb plus viscous friction
    for v in (model.minimum_friction_velocity, 0.2, 1.0):
        assert float(fr.film_steady_state(v, model)) == pytest.approx(1 - fc / fs, rel=1e-12)
        assert float(fr.steady_friction(v, model)) == pytest.approx(fc + model.sigma2 * v,
                                                                  rel=1e-12)
        assert float(fr.steady_friction(-v, model)) == pytest.approx(-(fc + model.sigma2 * v),
                                                                  rel=1e-12)


@pytest.mark.parametrize("v", [0.002, 0.01, 0.03, 0.16, -0.05])
def test_constant_velocity_converges_to_steady_friction(model, v):
    # 3 s at constant velocity (>> tau_hm, >> 1/r): the dynamic model reaches F_ss(v)
    force, z, h = fr.friction_series(np.full(3000, v), 1e-3, model)
    assert force[-1] == pytest.approx(float(fr.steady_friction(v, model)), rel=1e-6)
    assert h[-1] == pytest.approx(float(fr.film_steady_state(v, model)), rel=1e-6)


def _flap_like_velocity(t, amp):
    w = 2 * np.pi / 3.5
    return amp * (np.sin(w * t) + 0.25 * np.sin(2 * w * t + 0.7) + 0.1 * np.sin(3 * w * t))


@pytest.mark.parametrize("amp", [0.16, 0.03, 0.004])
def test_sampling_step_agrees_with_a_100_times_smaller_step(model, amp):
    # stick -> sliding -> stick at every reversal (two per cycle, plus harmonics): the 100 Hz
    # force agrees with the 10 kHz force within 1 % of its amplitude at every sample
    fs = 100.0
    t = np.arange(0, 7.0, 1 / fs)
    v = _flap_like_velocity(t, amp)
    coarse, _, _ = fr.friction_series(v, 1 / fs, model)
    fine, _, _ = fr.friction_series(v, 1 / fs, model, substeps=100)
    scale = np.max(np.abs(fine))
    assert np.max(np.abs(coarse - fine)) <= 0.01 * scale
    # and the scheme converges: the 10 kHz solution is within 1e-4 of a 100 kHz one
    finer, _, _ = fr.friction_series(v[:200], 1 / fs, model, substeps=1000)
    assert np.max(np.abs(fine[:200] - finer)) <= 1e-4 * scale


def test_presliding_is_elastic(model):
    # displacement 1e-7 m << F_c/sigma0 = 4e-5 m: the bristles stick, F = sigma0 x + (sigma1 +
    # sigma2) v to within x sigma0 / F_c ~ 0.3 % of sigma0 X0
    fs, x0, w = 100.0, 1e-7, 2 * np.pi
    t = np.arange(0, 3.0, 1 / fs)
    x, v = x0 * np.sin(w * t), x0 * w * np.cos(w * t)
    force, _, _ = fr.friction_series(v, 1 / fs, model, substeps=10)
    expected = model.sigma0 * x + (model.sigma1 + model.sigma2) * v
    assert np.max(np.abs(force - expected)) < 0.005 * model.sigma0 * x0


def test_dwell_and_film_build_up_are_exact(model):
    # frozen-velocity steps are exact: dwell (v = 0) decays h with tau_h0 and holds z;
    # from rest at v < v_b the film builds with tau_hp
    st0 = fr.FrictionState(2e-5, 0.3)
    st1 = fr.friction_step(st0, 0.0, 0.7, model)
    assert st1.z == st0.z
    assert st1.h == pytest.approx(0.3 * math.exp(-0.7 / model.tau_h0), rel=1e-14)
    v, dt = 0.01, 0.005
    hss = float(fr.film_steady_state(v, model))
    state = fr.FrictionState()
    for k in range(1, 11):
        state = fr.friction_step(state, v, dt, model)
        assert state.h == pytest.approx(hss * (1 - math.exp(-k * dt / model.tau_hp)), rel=1e-12)


def test_stepping_api_reproduces_the_series(model):
    # the simulator's interface (advance + force) gives the series function's numbers
    fs = 100.0
    v = _flap_like_velocity(np.arange(0, 4.0, 1 / fs), 0.1)
    force, z, h = fr.friction_series(v, 1 / fs, model)
    state = fr.FrictionState()
    for k in range(1, v.size):
        state = fr.friction_advance(state, v[k - 1], v[k], 1 / fs, model)
        assert float(fr.friction_force(state, v[k], model)) == pytest.approx(force[k], rel=1e-12,
                                                                          abs=1e-12)
    assert state.z == z[-1] and state.h == h[-1]


@settings(max_examples=40, deadline=None)
@given(v=st.lists(st.one_of(st.just(0.0), st.floats(-5.0, 5.0)), min_size=2, max_size=60),
       dt=st.floats(1e-6, 1.0))
def test_stable_for_any_velocity_and_step(model, v, dt):
    # exact exponential steps: |z| never exceeds F_s/sigma0 (from rest), 0 <= h <= h_max,
    # forces finite, whatever the step (up to 1 s, i.e. r dt up to ~1e5) and the reversals
    force, z, h = fr.friction_series(np.array(v), dt, model)
    assert np.all(np.isfinite(force))
    assert np.all(np.abs(z) <= model.static_force / model.sigma0 * (1 + 1e-12))
    assert np.all((h >= 0) & (h <= model.film_max * (1 + 1e-12)))
    v_max = np.max(np.abs(v))
    bound = model.static_force + model.sigma1 * 2 * v_max + model.sigma2 * v_max
    assert np.all(np.abs(force) <= bound * (1 + 1e-9))


def test_reversal_every_step_stays_bounded(model):
    # a velocity that reverses at every 100 Hz sample (chatter): the force stays within the
    # static band and the bristles never overshoot
    v = 0.05 * (-1.0) ** np.arange(2000)
    force, z, _ = fr.friction_series(v, 0.01, model)
    assert np.all(np.abs(z) <= model.static_force / model.sigma0)
    assert np.all(np.abs(force) <= model.static_force + (model.sigma1 * 2 + model.sigma2) * 0.05)


def test_bad_parameters_and_input(model, campaign):
    kw = {k: getattr(model, k) for k in model.__dataclass_fields__}
    with pytest.raises(ValueError, match="static force"):
        fr.LuGre(**{**kw, "static_force": kw["coulomb_force"] / 2})
    with pytest.raises(ValueError, match="sigma0"):
        fr.LuGre(**{**kw, "sigma0": 0.0})
    with pytest.raises(ValueError, match="coulomb_force"):
        fr.LuGre(**{**kw, "coulomb_force": 0.0})
    with pytest.raises(ValueError, match="non-finite"):
        fr.friction_series(np.array([0.0, np.nan]), 0.01, model)
    with pytest.raises(ValueError, match="dt"):
        fr.friction_series(np.zeros(3), 0.0, model)
    with pytest.raises(ValueError, match="step"):
        fr.friction_step(fr.FrictionState(), 0.1, -1.0, model)
