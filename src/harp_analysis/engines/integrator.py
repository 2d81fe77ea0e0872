"""Compiled building blocks of an adaptive Runge-Kutta integration of a point mass.

The scheme is Dormand and Prince's 8(5,3) pair, with scipy's published tableau
(``scipy.integrate.DOP853``) and its error norm and step control; between steps, positions and
velocities are reconstructed by quintic Hermite interpolation from the position, velocity and
acceleration at both ends (error O(h^6), below a millimetre on the 3DOF's flights), which also
locates events and the surfaces where the equations are not smooth. The state is second order:
``y = [position (3), velocity (3)]``.

The stepping loop itself lives beside its right-hand side (:func:`harp_analysis.engines.threedof`'s
``_integrate``): numba caches a compiled function only if what it calls is a global, not an
argument. Everything here works on one trajectory and is compiled (:mod:`.compiled`).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import DOP853

from ..foundation import earth
from ..foundation.compiled import jit

__all__ = [
    "TABLEAU",
    "STAGES",
    "DENSE_TABLEAU",
    "DENSE_STAGES",
    "RADIAL_VELOCITY",
    "ALTITUDE",
    "trial_step",
    "first_step",
    "stage_state",
    "error_norm",
    "step_factor",
    "hermite",
    "event_value",
    "crossing_fraction",
    "STRADDLE",
    "MIN_CUT_S",
]

#: scipy's DOP853 tableau as contiguous arrays: A (stage weights), B (solution), C (nodes),
#: E3 and E5 (the two error estimators).
TABLEAU = tuple(
    np.ascontiguousarray(x, dtype=float)
    for x in (
        DOP853.A[: DOP853.n_stages, : DOP853.n_stages],
        DOP853.B,
        DOP853.C,
        DOP853.E3,
        DOP853.E5,
    )
)
STAGES = DOP853.n_stages
#: The tableau's extension for scipy's 7th-order dense output of a step: the three extra stages'
#: weights A_EXTRA (3, DENSE_STAGES) and nodes C_EXTRA, and the interpolant's coefficients D
#: (4, DENSE_STAGES), for a stepper that reports between its steps as ``solve_ivp``'s t_eval.
DENSE_TABLEAU = tuple(
    np.ascontiguousarray(x, dtype=float) for x in (DOP853.A_EXTRA, DOP853.C_EXTRA, DOP853.D)
)
DENSE_STAGES = DOP853.D.shape[1]
_ORDER = DOP853.order
_ERROR_EXPONENT = -1.0 / (DOP853.error_estimator_order + 1)

#: Event kinds: the radial velocity r.v (apogee where it turns negative) and the altitude above
#: the spherical Earth minus a level (impact, or an atmosphere's layer boundary).
RADIAL_VELOCITY, ALTITUDE = 0, 1

#: A trial step that crosses a breakpoint is cut to end this share of itself short of it; a
#: crossing sooner than MIN_CUT_S after the step's start is not cut (the step starts on it).
STRADDLE = 1e-6
MIN_CUT_S = 1e-7


@jit(inline=True)
def _rms(values, scale):
    total = 0.0
    for i in range(6):
        total += (values[i] / scale[i]) ** 2
    return math.sqrt(total / 6)


@jit
def trial_step(y, derivative, scale):
    """The first of Hairer, Norsett and Wanner's two trial steps toward a starting step (as
    scipy's ``select_initial_step``), from y and y' scaled by ``scale``."""
    d0, d1 = _rms(y, scale), _rms(derivative, scale)
    return 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1


@jit
def first_step(h0, derivative, trial_derivative, scale, max_step_s):
    """The starting step, from y' at the start and at the trial step ``h0`` later."""
    d1 = _rms(derivative, scale)
    change = np.empty(6)
    for i in range(6):
        change[i] = trial_derivative[i] - derivative[i]
    d2 = _rms(change, scale) / h0
    if max(d1, d2) <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1 / (_ORDER + 1))
    return min(min(100 * h0, h1), max_step_s)


@jit(inline=True)
def stage_state(stage, y, k, h, out):
    """``out = y + h sum_j A[stage, j] k[j]``, the state where stage ``stage`` is evaluated
    (``stage = STAGES`` gives the solution, weights B)."""
    a, b = TABLEAU[0], TABLEAU[1]
    for i in range(6):
        total = 0.0
        for j in range(stage):
            weight = b[j] if stage == STAGES else a[stage, j]
            total += weight * k[j, i]
        out[i] = y[i] + h * total


@jit(inline=True)
def error_norm(y, y_new, k, h, rtol, floor):
    """DOP853's error of a trial step relative to ``rtol max(|y|, |y_new|, floor)``, component
    by component: accept the step if it is at most 1."""
    e3, e5 = TABLEAU[3], TABLEAU[4]
    err5 = 0.0
    err3 = 0.0
    for i in range(6):
        scale = rtol * max(max(abs(y[i]), abs(y_new[i])), floor[i])
        five = 0.0
        three = 0.0
        for j in range(STAGES + 1):
            five += e5[j] * k[j, i]
            three += e3[j] * k[j, i]
        err5 += (five / scale) ** 2
        err3 += (three / scale) ** 2
    denominator = err5 + 0.01 * err3 if err5 + err3 > 0 else 1.0
    return h * err5 / math.sqrt(denominator * 6)


@jit(inline=True)
def step_factor(error):
    """How much the next step may grow (or must shrink) after a trial step's ``error``."""
    return min(max(0.9 * (error if error > 0 else 1e-10) ** _ERROR_EXPONENT, 0.2), 5.0)


@jit(inline=True)
def hermite(t0, t1, y0, y1, a0, a1, t, out):
    """Quintic Hermite interpolation of position and velocity at ``t`` between two steps with
    states ``y0``, ``y1`` (6,) and accelerations ``a0``, ``a1`` (3,); written to ``out`` (6,)."""
    h = t1 - t0
    s = (t - t0) / h
    s2, s3 = s * s, s * s * s
    s4, s5 = s3 * s, s3 * s * s
    b0 = 1 - 10 * s3 + 15 * s4 - 6 * s5
    b1 = s - 6 * s3 + 8 * s4 - 3 * s5
    b2 = 0.5 * s2 - 1.5 * s3 + 1.5 * s4 - 0.5 * s5
    b3 = 0.5 * s3 - s4 + 0.5 * s5
    b4 = -4 * s3 + 7 * s4 - 3 * s5
    b5 = 10 * s3 - 15 * s4 + 6 * s5
    d0 = -30 * s2 + 60 * s3 - 30 * s4
    d1 = 1 - 18 * s2 + 32 * s3 - 15 * s4
    d2 = s - 4.5 * s2 + 6 * s3 - 2.5 * s4
    d3 = 1.5 * s2 - 4 * s3 + 2.5 * s4
    d4 = -12 * s2 + 28 * s3 - 15 * s4
    d5 = 30 * s2 - 60 * s3 + 30 * s4
    for i in range(3):
        terms = (y0[i], h * y0[3 + i], h * h * a0[i], h * h * a1[i], h * y1[3 + i], y1[i])
        out[i] = (
            b0 * terms[0]
            + b1 * terms[1]
            + b2 * terms[2]
            + b3 * terms[3]
            + b4 * terms[4]
            + b5 * terms[5]
        )
        out[3 + i] = (
            d0 * terms[0]
            + d1 * terms[1]
            + d2 * terms[2]
            + d3 * terms[3]
            + d4 * terms[4]
            + d5 * terms[5]
        ) / h


@jit
def event_value(kind, level, y):
    """The event function of ``kind`` at state ``y``: r.v, or the altitude minus ``level``."""
    if kind == RADIAL_VELOCITY:
        return y[0] * y[3] + y[1] * y[4] + y[2] * y[5]
    return math.sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]) - earth.RADIUS_M - level


@jit
def crossing_fraction(kind, level, t0, t1, y0, y1, a0, a1, work):
    """Where (0 to 1) between two states the event function changes sign, on the Hermite
    interpolant: Illinois (modified regula falsi) iterations until the iterates move less than
    1e-13, at most 30. ``work`` is scratch space (6,)."""
    low, high = 0.0, 1.0
    g_low, g_high = event_value(kind, level, y0), event_value(kind, level, y1)
    side = 0
    previous = math.nan
    middle = 0.5
    for _ in range(30):
        denominator = g_high - g_low
        if denominator != 0:
            middle = (low * g_high - high * g_low) / denominator
        else:
            middle = 0.5 * (low + high)
        middle = min(max(middle, low), high)
        if abs(middle - previous) < 1e-13:
            break
        previous = middle
        hermite(t0, t1, y0, y1, a0, a1, t0 + middle * (t1 - t0), work)
        g_middle = event_value(kind, level, work)
        near = np.sign(g_middle) == np.sign(g_low)
        if near:
            low, g_low = middle, g_middle
            if side == 1:  # Illinois: halve the stale end's value when one end moves twice
                g_high *= 0.5
            side = 1
        else:
            high, g_high = middle, g_middle
            if side == -1:
                g_low *= 0.5
            side = -1
    return middle
