"""The virtual flume's extra torque on the flap, compiled: one call per simulator step.

The terms and their physics are :class:`flumekit.synth.flume.ExtraTorque`'s (module notes of
:mod:`flumekit.synth.flume`); this is their scalar kernel with the signature of an extra torque
of :mod:`flumekit.hydro.stepping`, its constants in one float array (layout below), its state
(the compliance's lag and the vapour cavity) in another, and the ten terms of each call
recorded in one row of the record. The UVP's regular wave field
(:func:`flumekit.synth.uvp.wave_kinematics`) is summed here too, one point at a time.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from flumekit.hydro.stepping import EXTRA

__all__ = ["N_PARAMS", "N_STATE", "N_TERMS", "flume_torque"]

# constants: depth below the still water level to the hinge h − c, flap length above the hinge,
# 1/ω, the drag, KC, waterline, overtopping and bearing coefficients, the valve, the bore area,
# the compression sign, the lever-arm table's origin, inverse spacing and last index, K_p, the
# compliance time, the half step, the cavity share, the refill rate and the cavitating suction;
# then the local elevation at the half steps, the lever arms at the nodes and their differences
(_D, _LF, _INV_W, _K_DRAG, _FOUR_PI2, _KC2_MIN, _K_WET, _K_OVER, _T_BEAR, _INV_WB, _P_VALVE,
 _INV_VC, _AREA, _SIGN, _TH0, _INV_DTH, _N_TAB, _K_P, _TAU_C, _HALF_STEP, _PHI, _W_REFILL,
 _P_CAV, _N_ETA, N_PARAMS) = range(25)
# state: the compliance's last call (half step) and lagged pressure [Pa]; the cavity's last
# call, its volume over the bore area [m] and rate [m s-1]; whether the last call had a cavity
_LAG_J, _LAG_P, _CAV_J, _CAV_X, _CAV_R, _CAV_OPEN, N_STATE = range(7)
#: terms recorded per call (flumekit.synth.flume.ExtraTorque.record)
N_TERMS = 10


@njit(EXTRA, cache=True)
def flume_torque(j, th, om, p, st, rec):
    """Compute the flume's extra torque [N m] at half step ``j``, angle θ [rad], rate θ̇ [rad s-1].

    ``p`` holds the constants (module layout), ``st`` the state (advanced), and row ``j // 2``
    of ``rec`` receives the terms: vortex drag, wetted length, overtopping and bearing torques,
    then the valve's, the compliance's and the cavity's chamber pressure [Pa] and torque.
    """
    n_eta = int(p[_N_ETA])
    ef = p[N_PARAMS + j]
    c = math.cos(th)
    d, lf = p[_D], p[_LF]
    dw = (d + ef) / c
    dw = lf if dw > lf else (0.0 if dw < 0 else dw)
    kc2 = p[_FOUR_PI2] * (th * th + (om * p[_INV_W]) ** 2)
    kc2_min = p[_KC2_MIN]
    dw2 = dw * dw
    t_d = -p[_K_DRAG] * (kc2 if kc2 > kc2_min else kc2_min) ** (-1.0 / 6.0) \
        * dw2 * dw2 * om * abs(om)
    t_w = p[_K_WET] * ef * ef
    over = ef - (lf * c - d)
    t_o = -p[_K_OVER] * over if over > 0 else 0.0
    t_b = -p[_T_BEAR] * math.tanh(om * p[_INV_WB])
    n_tab = int(p[_N_TAB])
    u = (th - p[_TH0]) * p[_INV_DTH]
    i = int(u)
    i = 0 if i < 0 else (n_tab if i > n_tab else i)
    o_m = N_PARAMS + n_eta
    m = p[o_m + i] + (u - i) * p[o_m + n_tab + 2 + i]
    so = p[_SIGN] * om  # compression rate [rad s-1]
    k_p, p_cav, phi, half_step = p[_K_P], p[_P_CAV], p[_PHI], p[_HALF_STEP]
    p_k = p_c = p_v = 0.0
    p13u = k_p * so * abs(om)  # Eq. (13)'s K_p pressure [Pa]
    # clamped at P_v as the simulator clamps it, there with I_p θ̈ added, which this term does
    # not see (at H = 0.3 m the two clamps part for a sample or two)
    p13 = p13u if p13u > -p_cav else -p_cav
    dd = -so - p[_W_REFILL]  # > 0: the suction outruns the refill
    # the chamber holds the compression stroke's resistances (K_p θ̇² and the valve) through
    # the compliance's first-order lag; a cavity holds nothing
    x = st[_CAV_X] + st[_CAV_R] * (j - st[_CAV_J]) * half_step if phi > 0 else 0.0
    x = x if x > 0 else 0.0
    st[_CAV_J], st[_CAV_X] = j, x
    if x > 0:
        # discrete vapour cavity: the chamber stays at P_v while it lasts (ΔP = P_v - Eq. (13)'s
        # K_p pressure); it grows by φ times the suction's excess over the refill, shrinks at
        # the refill plus the compression rate (explicit over the time to the next call)
        p_k = -p_cav - p13
        st[_CAV_R] = (m if m > 0 else -m) * (phi * dd if dd > 0 else dd)
        p_q = 0.0
    else:
        if so > 0 and p[_P_VALVE] > 0:
            p_v = -p[_P_VALVE] * math.expm1(-abs(m * om) * p[_INV_VC])
        p_q = k_p * om * om + p_v if so > 0 else 0.0
    tau_c = p[_TAU_C]
    if x <= 0 and st[_CAV_OPEN] != 0.0:
        st[_LAG_P] = -p_cav - p13u - p_v + p_q  # collapse: the chamber goes on from P_v
    elif tau_c > 0:
        st[_LAG_P] = p_q + (st[_LAG_P] - p_q) * math.exp(-(j - st[_LAG_J]) * half_step / tau_c)
    else:
        st[_LAG_P] = p_q
    st[_LAG_J] = j
    st[_CAV_OPEN] = 1.0 if x > 0 else 0.0
    if x <= 0:
        # the chamber's pressure, at P_v at least: the suction cavitates it once the lag's
        # stored pressure has returned, and only then can a cavity open
        pr = p13u + p_v + st[_LAG_P] - p_q
        st[_CAV_R] = 0.0
        if pr <= -p_cav:
            pr = -p_cav
            if phi > 0 and dd > 0:
                st[_CAV_R] = (m if m > 0 else -m) * phi * dd
        p_c = pr - p13 - p_v
    r = rec[j // 2]
    r[0], r[1], r[2], r[3] = t_d, t_w, t_o, t_b
    if p_v == 0.0 and p_c == 0.0 and p_k == 0.0:
        r[4] = r[5] = r[6] = r[7] = r[8] = r[9] = 0.0
        return t_d + t_w + t_o + t_b + 0.0 + 0.0 + 0.0
    ma = m * p[_AREA]
    r[4], r[5], r[6], r[7], r[8], r[9] = p_v, ma * p_v, p_c, ma * p_c, p_k, ma * p_k
    return t_d + t_w + t_o + t_b + ma * p_v + ma * p_c + ma * p_k


@njit(cache=True)
def wave_field(t, cwt, swt, lag, cos_p, sin_p, amps, vel, n_harm, ch, sh, current, ramp_time,
               paired, u, w, eta):
    """Sum the velocity and elevation of a regular wave and its returning waves, in place.

    For wave m (the incident one first, then those travelling back), with the envelope
    e = clip((t - lag_m) / ramp_time, 0, 1) (1 without a ramp) and p = e e^{iθ},
    cos θ = cos ωt cos φ_m + sin ωt sin φ_m, sin θ = sin ωt cos φ_m - cos ωt sin φ_m:
    η_m = Σ_n a_n Re pⁿ, u_m = Σ_n V_n C_n Re pⁿ, w_m = Σ_n V_n S_n Im pⁿ
    (:func:`flumekit.synth.uvp.wave_kinematics`), the powers by repeated multiplication. Then
    u = u_0 + c_0 e_0² - Σ_m>0 (u_m + c_m e_m²), w = -w_0 - Σ_m>0 w_m, η = Σ_m η_m, each added
    in that order. One point at a time: no array per harmonic, wave or term.

    Parameters
    ----------
    t, cwt, swt : ndarray
        Time [s] and cos ωt, sin ωt [-], shape (T,).
    lag, cos_p, sin_p : ndarray
        Per wave and position: the ramp's arrival time [s] and cos φ, sin φ [-], shape (M, P).
    amps, vel : ndarray
        a_n [m] and V_n [m s-1] of each wave, shape (M, N) (the first ``n_harm[m]`` used).
    n_harm : ndarray
        Harmonics of each wave, shape (M,).
    ch, sh : ndarray
        C_n and S_n [-] at each position, shape (M, P, N).
    current : ndarray
        Mean current c_m of each wave at full amplitude [m s-1], shape (M,).
    ramp_time : float
        Ramp duration [s]; 0 for the steady state (e = 1).
    paired : bool
        False: every time with every position (outputs (T, P)); True: time k with position k
        only (T == P, outputs (1, P)).
    u, w, eta : ndarray
        Outputs [m s-1], [m s-1], [m].
    """
    nw, npos = lag.shape
    rows = 1 if paired else t.size
    for i in range(rows):
        for j in range(npos):
            k = j if paired else i
            tk, ct, st = t[k], cwt[k], swt[k]
            us = ws = es = 0.0
            for m in range(nw):
                if ramp_time > 0:
                    s = (tk - lag[m, j]) / ramp_time
                    e = 0.0 if s < 0.0 else (1.0 if s > 1.0 else s)
                else:
                    e = 1.0
                cp, sp = cos_p[m, j], sin_p[m, j]
                p1 = complex(e * (ct * cp + st * sp), e * (st * cp - ct * sp))
                pn = p1
                ev = amps[m, 0] * pn.real
                uv = (vel[m, 0] * ch[m, j, 0]) * pn.real
                wv = (vel[m, 0] * sh[m, j, 0]) * pn.imag
                for n in range(1, n_harm[m]):
                    pn = pn * p1
                    ev += amps[m, n] * pn.real
                    uv += (vel[m, n] * ch[m, j, n]) * pn.real
                    wv += (vel[m, n] * sh[m, j, n]) * pn.imag
                if m == 0:
                    us, ws, es = uv + current[0] * (e * e), -wv, ev
                else:
                    us, ws, es = (us - uv) - current[m] * (e * e), ws - wv, es + ev
            u[i, j], w[i, j], eta[i, j] = us, ws, es


@njit(cache=True)
def beam_echo(u, w, eta, j0, jf, x, z, zf, swl, ca, sa, tan_theta, half_width, theta_dot,
              noise, draws, v, state):
    """Project one beam's velocities, mark its channels' echo and add the Doppler noise.

    Channel j of profile i sees the water (state 0) while the transducer (at ``zf``) and every
    channel up to j are under the free surface and in front of the flap; the flap (state 1)
    once a channel up to j is behind the flap's seaward face x = z tan θ - t / (2 cos θ); no
    echo (state 2, before the flap) once one is above the surface. The velocity along the beam
    is u cos α + w sin α in the water, the flap's θ̇ (z cos α - x sin α) on it, plus
    ``noise`` times the standard normal ``draws``.

    Parameters
    ----------
    u, w, eta : ndarray
        Velocity [m s-1] and elevation [m] of the wave field, shape (T, ≥ P): the beam's
        channels in columns ``j0`` on, the transducer's elevation in column ``jf`` of ``eta``.
    j0, jf : int
        The columns of the beam's first channel and of its transducer.
    x, z : ndarray
        The channels' position [m], shape (P,).
    zf, swl : float
        The transducer's elevation and the still water level above the hinge [m].
    ca, sa : float
        cos α and sin α of the beam's angle [-].
    tan_theta, half_width, theta_dot : ndarray
        tan θ [-], t / (2 cos θ) [m] and θ̇ [rad s-1] per profile, shape (T,).
    noise : float
        Standard deviation of the Doppler noise [m s-1].
    draws : ndarray
        Standard normal draws, shape (T, P).
    v : ndarray
        Output: velocity along the beam [m s-1], shape (T, P).
    state : ndarray
        Output: 0 water, 1 flap, 2 no echo, shape (T, P).
    """
    nt, npos = v.shape
    for i in range(nt):
        wet = zf < swl + eta[i, jf]
        behind = False
        for j in range(npos):
            wet = wet and z[j] < swl + eta[i, j0 + j]
            behind = behind or x[j] > z[j] * tan_theta[i] - half_width[i]
            if behind:
                vj = theta_dot[i] * (z[j] * ca - x[j] * sa)
            else:
                vj = u[i, j0 + j] * ca + w[i, j0 + j] * sa
            v[i, j] = vj + noise * draws[i, j]
            state[i, j] = 1 if behind else 0
            if not wet:
                state[i, j] = 2


@njit(cache=True)
def beam_counts(v, state, no_echo, draws, dv, lo, n_counts, velocity, amplitude):
    """Quantise one beam's velocities to raw counts and draw its echo amplitude.

    Velocity counts round v / ΔV (the channels without echo take the next of ``no_echo``,
    in row order) and wrap into [lo, lo + n_counts); the amplitude [counts] is 400 ± 40 in
    the water, 2000 ± 100 on the flap and 8 ± 3 without echo, from the standard normal
    ``draws``, rounded.

    Parameters
    ----------
    v : ndarray
        Velocity along the beam [m s-1], shape (T, P).
    state : ndarray
        0 water, 1 flap, 2 no echo (:func:`beam_echo`).
    no_echo : ndarray
        Random counts of the channels without echo, in row order.
    draws : ndarray
        Standard normal draws, shape (T, P).
    dv : float
        Velocity resolution ΔV [m s-1].
    lo, n_counts : int
        Lowest raw count and the number of counts.
    velocity : ndarray
        Output: the quantised velocity [m s-1], shape (T, P).
    amplitude : ndarray
        Output: the echo amplitude [counts] (int16), shape (T, P).
    """
    nt, npos = v.shape
    k = 0
    for i in range(nt):
        for j in range(npos):
            s = state[i, j]
            if s == 2:
                c = float(no_echo[k])
                k += 1
                level, spread = 8.0, 3.0
            else:
                c = np.rint(v[i, j] / dv)
                level = 2000.0 if s == 1 else 400.0
                spread = 0.1 * level
            # wrap into the raw range: (c - lo) mod n_counts + lo, which inside the range is
            # c itself (+ 0.0: a count -0.0 wraps to +0.0)
            c = c + 0.0 if lo <= c < lo + n_counts else (c - lo) % n_counts + lo
            velocity[i, j] = c * dv
            amplitude[i, j] = np.int16(np.rint(level + spread * draws[i, j]))
