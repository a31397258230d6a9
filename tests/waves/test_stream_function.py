"""Stream-function (Fourier approximation) waves against linear/Stokes theory, Fenton's program
and their own governing equations."""

import numpy as np
import pytest

from flumekit.waves import stokes2_coefficient, wavenumber
from flumekit.waves.stream_function import (
    highest_wave,
    nonlinear_wavenumber,
    stream_function_wave,
)

H = 0.825  # the flume's depth [m]


@pytest.mark.parametrize("period", [1.0, 2.0, 4.0])
def test_small_amplitude_limit_is_linear_dispersion_and_stokes_second_harmonic(period):
    # Stokes expansion in ε = kH: k, E1 = H/2 and E2 = B k E1² carry relative corrections of
    # O(ε²), so halving H must divide each relative error by 4 (second order), and at
    # H = 1e-3 m they are below 1e-5.
    k0 = float(wavenumber(2 * np.pi / period, H))
    b = float(stokes2_coefficient(k0, H))
    errors = []
    for height in (1e-3, 5e-4):
        w = stream_function_wave(period, height, H)
        e = w.elevation_coefficients
        err = np.array([w.wavenumber / k0 - 1, e[0] / (height / 2) - 1,
                        e[1] / (b * k0 * e[0] ** 2) - 1])
        assert np.all(np.abs(err) < 1e-5)
        errors.append(err)
    np.testing.assert_allclose(errors[0] / errors[1], 4.0, rtol=0.01)
    # first harmonic of u and w: the linear a ω cosh(k(z+h))/sinh(kh), a ω sinh(k(z+h))/sinh(kh)
    # at mid-depth and at the still water level
    w = stream_function_wave(period, 1e-3, H)
    theta = np.linspace(0, 2 * np.pi, 64, endpoint=False)
    for z in (-H / 2, 0.0):
        u, v = w.velocity(theta, np.full(theta.size, z))
        lin = 0.5e-3 * w.omega / np.sinh(k0 * H)
        assert 2 * np.mean(u * np.cos(theta)) == pytest.approx(
            lin * np.cosh(k0 * (z + H)), rel=1e-5)
        assert 2 * np.mean(v * np.sin(theta)) == pytest.approx(
            lin * np.sinh(k0 * (z + H)), rel=1e-5)


# Output of J. D. Fenton's program FOURIER (Fenton 1988), Stokes' first definition (Euler
# current 0), dimensionless with g and the mean depth; coefficients k E_j and B_j with g and k.
# (a) 20 modes, H/d = 0.300, T sqrt(g/d) = 10.00 (Solution.res of github.com/jasper-aurora/
#     Fourier); (b) 8 modes, H/d = 0.375, T sqrt(g/d) = 9.9045 (nonlinearWaves/Solution.res of
#     github.com/erdc/proteus). Values as printed there.
FENTON = {
    "a": dict(n=20, height=0.300, period=10.0, length=9.6897, c=0.9690, u2=0.0111, r=1.4730,
              q=0.9579, kE=[8.8912241e-02, 2.7443980e-02, 7.5955668e-03, 2.1863966e-03,
                            6.7265439e-04],
              B=[1.1499699e-01, 1.7651940e-02, 2.4828287e-03, 2.5065983e-04]),
    "b": dict(n=8, height=0.375, period=9.9045, length=9.7556, c=0.9850, u2=0.0165, r=1.4901,
              q=0.9684, kE=[1.0563897e-01, 3.8999027e-02, 1.3066154e-02, 4.5740107e-03,
                            1.7217481e-03],
              B=[1.3540388e-01, 2.4808040e-02, 4.2638109e-03, 5.5394551e-04]),
}


@pytest.mark.parametrize("case", sorted(FENTON))
def test_against_fentons_program(case):
    ref = FENTON[case]
    w = stream_function_wave(ref["period"], ref["height"], 1.0, n_modes=ref["n"],
                             current="euler", g=1.0)
    # integral quantities printed to 4 decimals: half a unit of the last digit; case b's
    # period is itself rounded to 4 decimals, which moves L by up to another 5e-5
    tol = 5e-5 if case == "a" else 1e-4
    for value, key in ((w.wavelength, "length"), (w.celerity, "c"), (w.mass_transport, "u2"),
                       (w.bernoulli, "r"), (w.volume_flux, "q")):
        assert value == pytest.approx(ref[key], abs=tol), key
    assert w.eulerian_current == pytest.approx(0.0, abs=1e-12)
    k = w.wavenumber
    # coefficients printed to 8 digits: 1e-6 relative for (a); for (b) the period's rounding
    # (5e-6 relative) moves them by up to 2e-5
    rtol = 1e-6 if case == "a" else 5e-5
    np.testing.assert_allclose(k * w.elevation_coefficients[:5], ref["kE"], rtol=rtol)
    np.testing.assert_allclose(w.stream_coefficients[:4] / np.sqrt(1.0 / k**3), ref["B"],
                               rtol=rtol)
    # and Fenton's program's highest wave for this length ("43 % of the maximum of H/d = 0.706")
    assert float(highest_wave(w.wavelength, 1.0)) == pytest.approx(
        0.706 if case == "a" else 0.707, abs=5e-4)


def test_converges_geometrically_with_the_number_of_modes():
    # the flume's most nonlinear wave (T = 4 s, H = 0.3 m, Ursell 72): the first-harmonic
    # amplitude and the crest against 40 modes; each 4 more modes gain at least a factor 10
    ref = stream_function_wave(4.0, 0.3, H, n_modes=40)
    errs = []
    for n in (8, 12, 16, 20):
        w = stream_function_wave(4.0, 0.3, H, n_modes=n)
        errs.append(max(abs(w.elevation_coefficients[0] - ref.elevation_coefficients[0]),
                        abs(w.elevation(0.0) - ref.elevation(0.0))))
    errs = np.array(errs)
    assert np.all(errs[1:] < errs[:-1] / 10)
    assert errs[-1] < 1e-9 * 0.3  # the default 20 modes


@pytest.mark.parametrize("current", ["stokes", "euler"])
@pytest.mark.parametrize("period, height", [(2.0, 0.15), (3.5, 0.25), (4.0, 0.3)])
def test_solution_satisfies_the_free_surface_conditions_between_the_collocation_points(
        current, period, height):
    w = stream_function_wave(period, height, H, current=current)
    theta = np.linspace(0, np.pi, 1001)  # 50 points between collocation points
    eta = w.elevation(theta)
    assert eta[0] - eta[-1] == pytest.approx(height, rel=1e-10)  # Eq. (6)
    assert np.mean(w.elevation(np.linspace(0, 2 * np.pi, 4096, endpoint=False))) == \
        pytest.approx(0.0, abs=1e-12)  # Eq. (5): the mean level is the still water level
    u, ww = w.velocity(theta, eta)
    c = w.celerity
    # Eq. (4) in the moving frame: Bernoulli constant along the surface, to 1e-5 of g H (an
    # elevation error of 1e-5 H between the points; 0 at them)
    bern = 0.5 * ((u - c) ** 2 + ww**2) + w.g * (eta + H)
    assert np.ptp(bern) < 1e-5 * w.g * height
    # Eq. (3): the surface is a streamline, W/(U - c) = dη/dX, to 1e-4 of the
    # slope scale kH between the points (the derivative weighs the last modes by j)
    j = np.arange(1, w.n_modes + 1)
    slope = -w.wavenumber * np.sin(np.outer(theta, j)) @ (j * w.elevation_coefficients)
    np.testing.assert_allclose(ww / (u - c), slope, atol=1e-4 * w.wavenumber * height)
    if current == "stokes":  # zero mean mass transport: a closed flume, with a return current
        assert w.mass_transport == pytest.approx(0.0, abs=1e-12)
        assert w.eulerian_current < 0
    else:
        assert w.eulerian_current == pytest.approx(0.0, abs=1e-12)


def test_velocity_field_is_divergence_free_and_irrotational():
    w = stream_function_wave(3.5, 0.25, H)
    th, z, d = 0.7, -0.4, 1e-5
    k = w.wavenumber
    u = lambda a, b: w.velocity(np.array(a), np.array(b))[0]  # noqa: E731
    v = lambda a, b: w.velocity(np.array(a), np.array(b))[1]  # noqa: E731
    dudx = (u(th + k * d, z) - u(th - k * d, z)) / (2 * d)
    dwdz = (v(th, z + d) - v(th, z - d)) / (2 * d)
    dudz = (u(th, z + d) - u(th, z - d)) / (2 * d)
    dwdx = (v(th + k * d, z) - v(th - k * d, z)) / (2 * d)
    scale = w.omega * 0.125
    assert abs(dudx + dwdz) < 1e-6 * scale
    assert abs(dudz - dwdx) < 1e-6 * scale


def test_amplitude_dispersion_and_nonlinear_shape_in_the_flume():
    # T = 3.5 s, H = 0.25 m (Ursell 43): crest higher than trough is deep, wave longer than
    # linear theory says, first harmonic below H/2
    w = stream_function_wave(3.5, 0.25, H)
    k0 = float(wavenumber(2 * np.pi / 3.5, H))
    assert 0.95 < w.wavenumber / k0 < 0.99
    crest, trough = w.elevation(0.0), w.elevation(np.pi)
    assert crest > 1.5 * -trough and crest - trough == pytest.approx(0.25, rel=1e-12)
    assert w.elevation_coefficients[0] < 0.125
    assert 40 < w.ursell_number < 46


def test_bad_input_is_refused():
    with pytest.raises(ValueError, match="highest wave"):
        stream_function_wave(4.0, 0.7, H)
    with pytest.raises(ValueError, match="current"):
        stream_function_wave(4.0, 0.1, H, current="lagrange")
    with pytest.raises(ValueError, match="finite period"):
        stream_function_wave(-1.0, 0.1, H)
    with pytest.raises(ValueError, match="n_modes"):
        stream_function_wave(2.0, 0.1, H, n_modes=1)


def test_nonlinear_wavenumber():
    k0 = float(wavenumber(2 * np.pi / 3.5, H))
    assert nonlinear_wavenumber(3.5, 1e-5, H) == k0  # below 1e-4 h: the linear one
    assert nonlinear_wavenumber(3.5, 0.25, H) == stream_function_wave(3.5, 0.25, H).wavenumber
    with pytest.raises(ValueError, match="highest wave"):
        nonlinear_wavenumber(3.5, 0.7, H)


@pytest.mark.parametrize("period", [1.2, 2.0, 3.5])
def test_the_chord_iteration_from_a_grid_wave_finds_newtons_root(period):
    # the default start (a grid wave, the chord method with its Jacobian fixed) against Newton's
    # method raised from linear theory in height steps: the same wave to the round-off of the
    # equations (steep short waves are the worst conditioned)
    for height in (0.02, 0.1, 0.2, 0.25):
        fast = stream_function_wave(period, height, H)
        slow = stream_function_wave(period, height, H, height_steps=4)
        assert fast.wavenumber == pytest.approx(slow.wavenumber, rel=1e-13, abs=0)
        assert np.allclose(fast.elevation_coefficients, slow.elevation_coefficients,
                           rtol=0, atol=1e-13 * height)
