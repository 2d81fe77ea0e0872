"""A vectorised adaptive Runge-Kutta integrator: many trajectories, each with its own step.

scipy's ``solve_ivp`` integrates one system at a time; a sweep of a thousand launches through
it costs a thousand Python-level integrations. Here every trajectory advances with its own
step size and error control, but all of them share each stage's numpy evaluation, so the cost
per launch falls with the batch size. A single trajectory is a batch of one.

The scheme is Dormand and Prince's 8(5,3) pair, with scipy's published tableau
(``scipy.integrate.DOP853``) and its error norm; between steps, positions and velocities are
reconstructed by quintic Hermite interpolation from the position, velocity and acceleration at
both ends (error O(h^6), below a millimetre on this problem), which also locates the events.
The state is second order: ``y = [position (3), velocity (3)]`` per trajectory, shape (6, n).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.integrate import DOP853

__all__ = ["Event", "Breakpoint", "Solution", "integrate_batch", "hermite"]

_A, _B, _C, _E3, _E5 = DOP853.A, DOP853.B, DOP853.C, DOP853.E3, DOP853.E5
_STAGES = DOP853.n_stages
_ERROR_EXPONENT = -1.0 / (DOP853.error_estimator_order + 1)


@dataclass(frozen=True)
class Event:
    """A zero crossing of ``function(t, y) -> (n,)`` from positive to non-positive.

    ``terminal`` events end the trajectory; ``after_s`` ignores crossings before that time
    (the impact event must not fire at launch, where the altitude is zero).
    """

    name: str
    function: Callable[[np.ndarray, np.ndarray], np.ndarray]
    terminal: bool = False
    after_s: float = 0.0


@dataclass(frozen=True)
class Breakpoint:
    """A surface ``function(t, y) = 0`` where the equations are not smooth (an atmosphere's
    layer boundary). The error estimate of a step across a kink or jump can pass a badly wrong
    step (metres, on these flights), so a trial step that crosses one is cut to end just short
    of it; the next step starts at the boundary, where the error control sees the jump at once
    and takes the small steps it needs to cross."""

    function: Callable[[np.ndarray, np.ndarray], np.ndarray]


@dataclass
class Solution:
    """Accepted steps of every trajectory and the time of each event (NaN if not reached)."""

    times: list[np.ndarray]  # per trajectory: (k,) step times
    states: list[np.ndarray]  # per trajectory: (6, k)
    accelerations: list[np.ndarray]  # per trajectory: (3, k)
    event_times: dict[str, np.ndarray]
    rhs_evaluations: int
    steps: np.ndarray  # accepted steps per trajectory

    def sample(self, index: int, times_s: np.ndarray) -> np.ndarray:
        """State (6, m) of trajectory ``index`` at ``times_s`` within its integrated span."""
        t = self.times[index]
        k = np.clip(np.searchsorted(t, times_s, side="right") - 1, 0, len(t) - 2)
        y, a = self.states[index], self.accelerations[index]
        return hermite(t[k], t[k + 1], y[:, k], y[:, k + 1], a[:, k], a[:, k + 1], times_s)


def hermite(t0, t1, y0, y1, a0, a1, t):
    """Quintic Hermite interpolation of position and velocity between two steps.

    ``y`` holds positions and velocities (6, m), ``a`` accelerations (3, m); returns (6, m).
    """
    h = t1 - t0
    s = (t - t0) / h
    s2, s3 = s * s, s * s * s
    s4, s5 = s3 * s, s3 * s * s
    basis = (
        1 - 10 * s3 + 15 * s4 - 6 * s5,
        s - 6 * s3 + 8 * s4 - 3 * s5,
        0.5 * s2 - 1.5 * s3 + 1.5 * s4 - 0.5 * s5,
        0.5 * s3 - s4 + 0.5 * s5,
        -4 * s3 + 7 * s4 - 3 * s5,
        10 * s3 - 15 * s4 + 6 * s5,
    )
    slopes = (
        -30 * s2 + 60 * s3 - 30 * s4,
        1 - 18 * s2 + 32 * s3 - 15 * s4,
        s - 4.5 * s2 + 6 * s3 - 2.5 * s4,
        1.5 * s2 - 4 * s3 + 2.5 * s4,
        -12 * s2 + 28 * s3 - 15 * s4,
        30 * s2 - 60 * s3 + 30 * s4,
    )
    terms = (y0[:3], h * y0[3:], h * h * a0, h * h * a1, h * y1[3:], y1[:3])
    position = sum(b * term for b, term in zip(basis, terms))
    velocity = sum(d * term for d, term in zip(slopes, terms)) / h
    return np.concatenate([position, velocity])


_STRADDLE = 1e-6  # a cut step ends this share of itself short of the breakpoint
_MIN_CUT_S = 1e-7  # a step crossing a breakpoint sooner than this after its start is not cut


def _root(function, g0, g1, iterations=30, tolerance=1e-13):
    """Vectorised Illinois (modified regula falsi) root of ``function(s)`` on s in [0, 1],
    given its values ``g0``, ``g1`` of opposite signs at the ends; returns the last iterate,
    once the iterates move less than ``tolerance``."""
    low, high = np.zeros_like(g0), np.ones_like(g0)
    g_low, g_high = g0.astype(float), g1.astype(float)
    side = np.zeros(g0.shape, int)
    previous = np.full(g0.shape, np.nan)
    for _ in range(iterations):
        denominator = g_high - g_low
        middle = np.where(
            denominator != 0,
            (low * g_high - high * g_low) / np.where(denominator != 0, denominator, 1.0),
            0.5 * (low + high),
        )
        middle = np.clip(middle, low, high)
        if np.all(np.abs(middle - previous) < tolerance):
            break
        previous = middle
        g_middle = function(middle)
        near = np.sign(g_middle) == np.sign(g_low)
        low, g_low = np.where(near, middle, low), np.where(near, g_middle, g_low)
        high, g_high = np.where(near, high, middle), np.where(near, g_high, g_middle)
        # Illinois: halve the stale end's value when the same end moves twice running.
        g_high = np.where(near & (side == 1), 0.5 * g_high, g_high)
        g_low = np.where(~near & (side == -1), 0.5 * g_low, g_low)
        side = np.where(near, 1, -1)
    return middle


def _crossing_fraction(breakpoint, t0, h, y0, y1, a0, a1):
    """Where in each trial step (0 to 1) ``breakpoint`` is crossed (Hermite interpolant)."""

    def along(fraction):
        t = t0 + fraction * h
        return breakpoint.function(t, hermite(t0, t0 + h, y0, y1, a0, a1, t))

    return _root(along, breakpoint.function(t0, y0), breakpoint.function(t0 + h, y1))


def _first_step(acceleration, y, a, scale, max_step_s):
    """Hairer, Norsett and Wanner's starting step (as scipy's ``select_initial_step``)."""
    f = np.concatenate([y[3:], a])
    d0 = np.sqrt(np.mean((y / scale) ** 2, axis=0))
    d1 = np.sqrt(np.mean((f / scale) ** 2, axis=0))
    h0 = np.where((d0 < 1e-5) | (d1 < 1e-5), 1e-6, 0.01 * d0 / d1)
    y1 = y + h0 * f
    f1 = np.concatenate([y1[3:], acceleration(h0, y1, np.arange(y.shape[1]))])
    d2 = np.sqrt(np.mean(((f1 - f) / scale) ** 2, axis=0)) / h0
    order = DOP853.order
    h1 = np.where(
        np.maximum(d1, d2) <= 1e-15,
        np.maximum(1e-6, h0 * 1e-3),
        (0.01 / np.maximum(d1, d2)) ** (1 / (order + 1)),
    )
    return np.minimum(np.minimum(100 * h0, h1), max_step_s)


def _locate(event, t0, t1, y0, y1, a0, a1):
    """Time of ``event`` between t0 and t1 on the Hermite interpolant (vectorised)."""

    def along(fraction):
        t = t0 + fraction * (t1 - t0)
        return event.function(t, hermite(t0, t1, y0, y1, a0, a1, t))

    fraction = _root(along, event.function(t0, y0), event.function(t1, y1))
    return t0 + fraction * (t1 - t0)


def integrate_batch(
    acceleration: Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray],
    y0: np.ndarray,
    *,
    t_max_s: float,
    rtol: float,
    state_scale: np.ndarray,
    events: tuple[Event, ...] = (),
    breakpoints: tuple[Breakpoint, ...] = (),
    max_step_s: float = 20.0,
) -> Solution:
    """Integrate ``y' = [velocity, acceleration(t, y, index)]`` for every column of ``y0``.

    ``acceleration(t, y, index)`` returns (3, m) for the states ``y`` (6, m) of the trajectories
    numbered ``index`` (m,), so parameters can differ per trajectory. The local error of each
    trajectory is held below ``rtol * max(|y|, state_scale)`` component by component. A
    trajectory stops at its first terminal event or at ``t_max_s``. Steps are capped at
    ``max_step_s`` so that the interpolated velocities between steps stay within ~1e-6 m/s.
    """
    n = y0.shape[1]
    t = np.zeros(n)
    y = np.array(y0, dtype=float)
    active = np.ones(n, bool)
    floor = np.asarray(state_scale, dtype=float)[:, None]
    a = acceleration(t, y, np.arange(n))
    h = _first_step(acceleration, y, a, rtol * np.maximum(np.abs(y), floor), max_step_s)
    records = [(np.arange(n), t.copy(), y.copy(), a.copy())]  # (trajectories, t, y, a) per step
    event_times = {event.name: np.full(n, np.nan) for event in events}
    evaluations = 2
    while active.any():
        index = np.flatnonzero(active)
        ti, yi, hi = t[index], y[:, index], np.minimum(h[index], t_max_s - t[index])
        m = index.size
        k = np.empty((_STAGES + 1, 6, m))  # stage derivatives [velocity, acceleration]
        k[0, :3], k[0, 3:] = yi[3:], a[:, index]
        flat = k.reshape(_STAGES + 1, 6 * m)
        for stage in range(1, _STAGES):
            ys = yi + hi * (_A[stage, :stage] @ flat[:stage]).reshape(6, m)
            k[stage, :3] = ys[3:]
            k[stage, 3:] = acceleration(ti + _C[stage] * hi, ys, index)
        y_new = yi + hi * (_B @ flat[:_STAGES]).reshape(6, m)
        a_new = acceleration(ti + hi, y_new, index)
        k[_STAGES, :3], k[_STAGES, 3:] = y_new[3:], a_new
        evaluations += _STAGES
        scale = rtol * np.maximum(np.maximum(np.abs(yi), np.abs(y_new)), floor)
        err5 = np.sum(((_E5 @ flat).reshape(6, m) / scale) ** 2, axis=0)
        err3 = np.sum(((_E3 @ flat).reshape(6, m) / scale) ** 2, axis=0)
        denominator = np.where(err5 + err3 > 0, err5 + 0.01 * err3, 1.0)
        error = hi * err5 / np.sqrt(denominator * 6)
        accept = error <= 1.0
        factor = np.clip(0.9 * np.where(error > 0, error, 1e-10) ** _ERROR_EXPONENT, 0.2, 5.0)
        h[index] = np.minimum(hi * np.where(accept, factor, np.minimum(factor, 1.0)), max_step_s)
        for breakpoint in breakpoints:
            before = breakpoint.function(ti, yi)
            crossed = np.sign(before) != np.sign(breakpoint.function(ti + hi, y_new))
            if crossed.any():
                fraction = _crossing_fraction(breakpoint, ti, hi, yi, y_new, a[:, index], a_new)
                cut = crossed & (fraction * hi > _MIN_CUT_S) & (fraction < 1 - _STRADDLE)
                accept &= ~cut
                h[index[cut]] = hi[cut] * fraction[cut] * (1 - 2 * _STRADDLE)
        done = index[accept]
        t_old, y_old, a_old = ti[accept], yi[:, accept], a[:, done]
        t[done] += hi[accept]
        y[:, done] = y_new[:, accept]
        a[:, done] = a_new[:, accept]
        stopped = np.zeros(done.size, bool)
        for event in events:
            before = event.function(t_old, y_old) > 0
            crossed = (
                before & (event.function(t[done], y[:, done]) <= 0) & (t[done] > event.after_s)
            )
            crossed &= np.isnan(event_times[event.name][done])
            if crossed.any():
                j = done[crossed]
                event_times[event.name][j] = _locate(
                    event,
                    t_old[crossed],
                    t[j],
                    y_old[:, crossed],
                    y[:, j],
                    a_old[:, crossed],
                    a[:, j],
                )
                if event.terminal:
                    stopped |= crossed
        records.append((done, t[done], y[:, done], a[:, done]))
        active[done[stopped | (t[done] >= t_max_s)]] = False
    # Regroup the accepted steps by trajectory; a stable sort keeps each one in time order.
    owner = np.concatenate([r[0] for r in records])
    order = np.argsort(owner, kind="stable")
    bounds = np.cumsum(np.bincount(owner, minlength=n))[:-1]
    times = np.split(np.concatenate([r[1] for r in records])[order], bounds)
    states = np.split(np.concatenate([r[2] for r in records], axis=1)[:, order], bounds, axis=1)
    accelerations = np.split(
        np.concatenate([r[3] for r in records], axis=1)[:, order], bounds, axis=1
    )
    return Solution(
        times,
        states,
        accelerations,
        event_times,
        evaluations,
        np.array([len(ti) - 1 for ti in times]),
    )
