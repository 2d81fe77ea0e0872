"""A better MKS (Chapter 7 C: "more work on accurately predicting the asymptotic angular momentum
and decay of angular momentum during reentry"): the dissertation's closed form with a
self-consistent drag decay on the way up and a re-entry decay on the way down. A named variant;
:mod:`.mks` and :mod:`.eci` stay as the text has them.

Why h(theta) is what matters. For drag along the velocity the Binet equation u'' + u =
GM/h(theta)^2 is exact: the drag's radial part and the term -(h'/h) u' that a varying h adds
cancel. The MKS's errors on a non-rotating Earth therefore come from its model of h(theta) (and
the series' truncation): eq 3.22's beta is the loss integral ln(h0/h_inf) = int (A/2m) rho Cd ds
taken along a straight line through eq 3.11's air at the launch Cd0 (Assumptions 2-4), and
nothing decays on the way down, so the flight ends early.

Ascent, self-consistent. Along any flight, d(-ln h)/dtheta = (A/2m) rho Cd(M) |Vrel|
(1 - omega n_z r^2/h) r^2/h exactly (in-plane part): |Vrel|^2 = V^2 - 2 omega h n_z + omega^2
r^2 cos^2(latitude), since V.(omega x r) = omega.(r x V) = omega h n_z with n the flight plane's
normal, and r x Vrel = h - r x (omega x r) has the in-plane part h - omega n_z r^2. Evaluated
along the MKS's own path with its own speed, through the launch's air and drag law, it gives the
loss L = int rate dtheta and the shape of h = h_inf exp(beta e^{-tau theta}) by the first moment,
tau = 1/<theta> (the exponential's loss density beta tau e^{-tau theta} has mean 1/tau). The MKS
flown with these is evaluated again, to a fixed point: the path curves as the solution does
(Fig 4.14's straight-line error), and the air and Cd(Mach) are the launch's own. Drive and decay
take one beta (eq 3.23's h = h_inf exp(beta gamma) needs the same one in both).

On a rotating Earth the drag along Vrel also pushes across the inertial velocity. Chapter 5 gives
that push to the launch as V_tangent (eq 6.15), from eq 5.8's straight line through eq 3.11's
air; here V_tangent is its integral along the same path, int (A/2m) rho Cd |Vrel| |(omega x
r) across V| dt, in eq 6.15's direction. V_tangent raises h0 above that of the gun's Vrel +
omega x r0, which is what the loss decays: h_inf = h_gun e^{-L}, so beta = L + ln(h0/h_gun).

Re-entry. The same form mirrored about the impact, h = h_inf exp(-beta_re e^{-tau_re (theta_imp -
theta)}): GM/h^2 = c3 sum_n (2 beta_re e^{tau_re (theta - theta_imp)})^n / n!, and each term
e^{+n tau_re theta} has the particular solution B_n e^{n tau_re (theta - theta_imp)}, B_n = c3
(2 beta_re)^n / (n! (1 + n^2 tau_re^2)) (mks's A_n with tau -> -tau). A conic absorbs the
terms' (vanishing) value and slope at launch, so u(0) and u'(0) stay the launch's; at the impact
the terms are sum B_n whatever theta_imp, so u = 1/r0 is one equation in it. beta_re and tau_re
are the loss along the ascent solution's descent from the top of the air to its impact,
integrated forward with the speed it loses (h = h_inf e^{-L}), and 1 / the loss's mean distance
before the impact. h(theta) is the product of the two branches: continuous and non-increasing
from launch to impact. Time is t = int dtheta / (h u^2) with it.

The re-entry terms hardly move the path (B_n ~ c3 beta_re / tau_re^2: metres at the impact):
drag along the path bends it only by slowing it. What they change is the time of flight, and so
the position at a given time.

The one fitted number (:class:`Calibration`): ``reentry_scale`` on beta_re. The descent loss is
taken along the drag-free conic's path, shallower and faster than the real one, and spread as
an exponential only roughly; one factor absorbs both, fitted by
:func:`harp_analysis.analyses.mks_improvement.fit` on training launches only (1 is the physics
alone).

Computation. The loss rate is written once, compiled (:mod:`.compiled`), and both losses call
it: the ascent's by the trapezoid rule on points spaced geometrically from the launch, the
re-entry's by marching dL/dtheta = rate(theta, h_inf e^-L) with scipy's DOP853 for one equation,
compiled (its step control, at rtol 1e-10, and its dense output at the quadrature's points),
restarted where the descent crosses one of the air's breakpoints, where the rate jumps or kinks
unseen by a step's error estimate. :func:`warm_up` compiles the kernels ahead of use.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace
from functools import cached_property
from typing import overload

import numpy as np
from scipy.optimize import brentq

from ..foundation import earth
from ..foundation.compiled import formula, jit
from ..foundation.validation import Bounds, ModelValidityWarning, finite_array
from ..models import atmosphere, drag
from ..models.launch import Launch, Launches, baseline_chapter_4
from ..models.trajectory import launch_frame, rotate_about_axis, surface_ranges
from . import eci, mks
from .integrator import DENSE_STAGES, DENSE_TABLEAU, STAGES, TABLEAU

__all__ = [
    "Calibration",
    "UNCALIBRATED",
    "VARIANTS",
    "ImprovedSolution",
    "solve",
    "dissertation",
    "flight",
    "TOP_OF_ATMOSPHERE_M",
    "AIR_MOMENTUM_SHARE_RANGE",
    "MAX_JUDGED_BETA",
    "air_momentum_share",
    "warm_up",
]

#: Outside this band of the air's share in the launch's angular momentum
#: (:func:`air_momentum_share`) the improved MKS warns: on the error map (bearing x elevation x
#: latitude, :func:`harp_analysis.analyses.mks_improvement.error_map`) it misses the impact by more
#: than
#: the dissertation's at every point outside it. The band was drawn from that same map; on
#: launches off the map (:func:`harp_analysis.analyses.mks_improvement.broad_band_shares`) it is the
#: better at most points inside and at few outside: a band of where it is usually worse.
AIR_MOMENTUM_SHARE_RANGE = (-0.5, 1.0)
#: The largest eq 3.22 beta (the dissertation's ECI MKS's) of the launches the improved MKS was
#: fitted and first judged on (mks_improvement's TRAINING and JUDGING, up to 0.469 for HP);
#: beyond it it warns. The broad judging set (mks_improvement.broad_judgement) bears it out:
#: there its apogee falls kilometres short (at beta 0.54, HP at 1 km/s and 45 deg, 17 %).
MAX_JUDGED_BETA = 0.47
#: Where the loss integrals stop: above 100 km eqs 2.1-2.2's density is 3e-7 kg/m^3 and what
#: is left of the loss, rho H Cd A/(2m), is below 1e-8 of h.
TOP_OF_ATMOSPHERE_M = 100_000.0
#: Points of the loss quadratures, spaced geometrically from the dense end (the air's scale
#: height is a few thousandths of a flight's angular range).
_QUADRATURE_POINTS = 1500
#: The self-consistent ascent stops when beta and tau change by less than this (relative).
_FIXED_POINT_TOLERANCE = 1e-10
_FIXED_POINT_ITERATIONS = 30
#: Points of the time grid from launch to impact (3-point Gauss-Legendre on each interval).
_TIME_POINTS = 4001
#: The re-entry march's tolerances (DOP853's, as solve_ivp's rtol and atol): the loss within
#: 1e-9 of itself at 1e-13 on the fit's and the judging launches (tests). At 1e-8 it is off by
#: up to 1e-5 on some: a step's error estimate misses the kinks of the rate that it straddles
#: (the drag tables' Mach points; the march restarts on the air's breakpoints instead).
_REENTRY_RTOL, _REENTRY_ATOL = 1e-10, 1e-13

VARIANTS = ("dissertation", "improved")


@dataclass(frozen=True)
class Calibration:
    """The fitted part of the improved MKS: ``reentry_scale`` multiplies the re-entry loss
    beta_re (1: the loss along the drag-free conic as it is)."""

    reentry_scale: float = 1.0

    def __post_init__(self):
        value = Bounds(low=0.0).scalar(self.reentry_scale, "reentry_scale")
        object.__setattr__(self, "reentry_scale", value)


#: The physics alone, nothing fitted.
UNCALIBRATED = Calibration()


@dataclass(frozen=True)
class _Plane:
    """The inertial flight plane (longitude 0 at t = 0): unit vectors up (the launch point) and
    along (the launch velocity's horizontal part), and the z component of their normal."""

    up: np.ndarray
    along: np.ndarray

    @property
    def normal_z(self) -> float:
        return float(self.up[0] * self.along[1] - self.up[1] * self.along[0])

    def directions(self, theta_rad) -> np.ndarray:
        """Unit vectors (n, 3) at angular ranges ``theta_rad`` (n,)."""
        theta = np.asarray(theta_rad, dtype=float)[:, None]
        return np.cos(theta) * self.up + np.sin(theta) * self.along


def _plane(ascent: mks.ModifiedKeplerSolution, correction, latitude_rad) -> _Plane:
    """Chapter 5's plane of ``correction`` as :func:`eci.inertial_positions` places the MKS."""
    apogee = float(ascent.apogee_angle)
    points = eci.inertial_positions(ascent, correction, latitude_rad, [0.0, apogee])
    up = points[0] / np.linalg.norm(points[0])
    along = points[1] / np.linalg.norm(points[1]) - math.cos(apogee) * up
    return _Plane(up, along / np.linalg.norm(along))


# --- the losses along a path, compiled ----------------------------------------------------------
# ``air`` is what the loss rate needs of a launch (:class:`_Air`): its atmosphere's code and table
# (:func:`atmosphere.air`), its drag law's code, parameters and table
# (:func:`drag.drag_coefficient`), and an array of numbers: A / (2 m), the Earth's rotation rate,
# the flight plane's n_z and the z components of its unit vectors up and along, the day's density
# factor and gamma R dT. The models are chosen by number at run time: one compilation (10-20 s)
# serves every pair, for a solve about a fifth slower than kernels compiled for each pair would
# give (as the 3DOF's; about 10 s a pair).
_PER_DENSITY, _OMEGA, _NORMAL_Z, _UP_Z, _ALONG_Z, _DENSITY_FACTOR, _SOUND_CHANGE = range(7)
#: Points of the search for the top of the atmosphere (linear interpolation between them).
_TOP_POINTS = 2001
#: Bisections, at most, for the angles where the descent crosses one of the air's breakpoints
#: (to the last bit of a flight's angular range).
_CROSSING_BISECTIONS = 80


@jit(inline=True)
def _loss_rate(theta, u, slope, h, air):
    """d(-ln h)/dtheta (per rad) at angular range ``theta`` of a path with u = 1/r and du/dtheta
    ``slope`` flown with angular momentum ``h`` (module docstring), and the drag's acceleration
    across the inertial velocity per rad, dV_tangent/dtheta (m/s)."""
    air_code, drag_code, table, parameters, table_mach, table_cd, numbers = air
    r = 1 / u
    altitude = max(r - earth.RADIUS_M, 0.0)
    speed_squared = h * h * (u * u + slope * slope)
    omega, n_z = numbers[_OMEGA], numbers[_NORMAL_Z]
    z = math.cos(theta) * numbers[_UP_Z] + math.sin(theta) * numbers[_ALONG_Z]
    # the air's velocity omega x r: its square, and its part along the inertial velocity
    air_squared = (omega * r) ** 2 * (1 - z * z)
    along = omega * h * n_z
    air_speed = math.sqrt(max(speed_squared - 2 * along + air_squared, 0.0))
    across = math.sqrt(max(air_squared - along * along / speed_squared, 0.0))
    model_density, model_sound = atmosphere.air(air_code, altitude, table)
    density, sound = atmosphere.day_air(
        model_density, model_sound, numbers[_DENSITY_FACTOR], numbers[_SOUND_CHANGE]
    )
    cd = drag.drag_coefficient(drag_code, air_speed / sound, parameters, table_mach, table_cd)
    per_theta = numbers[_PER_DENSITY] * density * cd * (air_speed * r * r / h)  # times dt/dtheta
    return per_theta * (1 - omega * n_z * r * r / h), per_theta * across


@jit(inline=True)
def _altitude(path, tau, radius, theta):
    """Altitude (m) at ``theta`` of the single-launch MKS whose constants are ``path``."""
    return 1 / mks.point(path, 0, tau, theta)[0] - radius


@jit(inline=True)
def _top_angle(path, tau, radius, low, high, rising):
    """Angular range in [low, high] where the MKS passes TOP_OF_ATMOSPHERE_M going up
    (``rising``) or down, interpolated linearly between _TOP_POINTS points; ``high`` (the
    apogee) or ``low`` if it never gets that high."""
    step = (high - low) / (_TOP_POINTS - 1)
    angle, altitude = low, _altitude(path, tau, radius, low)
    if not rising and altitude <= TOP_OF_ATMOSPHERE_M:
        return low
    for i in range(1, _TOP_POINTS):
        previous_angle, previous = angle, altitude
        angle = high if i == _TOP_POINTS - 1 else low + i * step
        altitude = _altitude(path, tau, radius, angle)
        passed = altitude >= TOP_OF_ATMOSPHERE_M if rising else altitude <= TOP_OF_ATMOSPHERE_M
        if passed:
            share = (TOP_OF_ATMOSPHERE_M - previous) / (altitude - previous)
            return previous_angle + share * (angle - previous_angle)
    return high if rising else low


@jit(inline=True)
def _distances(span):
    """0 and _QUADRATURE_POINTS distances spaced geometrically from 1e-7 ``span`` to ``span``:
    the loss quadratures' points, measured from the dense end of the air."""
    out = np.empty(_QUADRATURE_POINTS + 1)
    out[0] = 0.0
    ratio = math.log(1e7) / (_QUADRATURE_POINTS - 1)
    for i in range(_QUADRATURE_POINTS):
        out[1 + i] = span * 1e-7 * math.exp(i * ratio)
    out[-1] = span
    return out


@jit(inline=True)
def _moments(rate, theta, origin):
    """Trapezoids on ``theta``: int rate dtheta, and 1 / the mean |theta - origin| weighted by
    |rate| (the exponential's tau; |rate|, because on a rotating Earth the air can add angular
    momentum as well as take it), infinite where there is no rate."""
    loss = weight = moment = 0.0
    for i in range(1, theta.size):
        half = 0.5 * (theta[i] - theta[i - 1])
        low, high = abs(rate[i - 1]), abs(rate[i])
        loss += half * (rate[i - 1] + rate[i])
        weight += half * (low + high)
        moment += half * (low * abs(theta[i - 1] - origin) + high * abs(theta[i] - origin))
    return loss, weight / moment if moment > 0 else math.inf


@jit
def _ascent_losses(path, tau, h_inf, decay, apogee, radius, air):
    """Along the MKS's ascent from the launch to the top of the atmosphere, with its own speed
    (h = h_inf exp(decay e^{-tau theta}), eq 3.23): the loss, its tau (:func:`_moments`,
    infinite without air) and the cross-track impulse V_tangent (m/s)."""
    theta = _distances(_top_angle(path, tau, radius, 0.0, apogee, True))
    rate, cross = np.empty(theta.size), np.empty(theta.size)
    for i in range(theta.size):
        u, slope, _ = mks.point(path, 0, tau, theta[i])
        h = h_inf * math.exp(decay * math.exp(-tau * theta[i]))
        rate[i], cross[i] = _loss_rate(theta[i], u, slope, h, air)
    loss, rate_tau = _moments(rate, theta, 0.0)
    return loss, rate_tau, _moments(cross, theta, 0.0)[0]


@jit(inline=True)
def _descent_rate(theta, loss, path, tau, h_inf, air):
    """dL/dtheta along the MKS of ``path`` flown with the speed lost so far, h = h_inf e^-L."""
    u, slope, _ = mks.point(path, 0, tau, theta)
    h = h_inf * math.exp(-loss)
    if not h > 0:  # every bit of angular momentum lost (a trial step's): no finite rate
        return math.inf
    return _loss_rate(theta, u, slope, h, air)[0]


@jit(inline=True)
def _first_step(t, y, f, stop, path, tau, h_inf, air, rtol, atol):
    """Hairer, Norsett and Wanner's starting step from L = ``y``, dL/dtheta = ``f`` at ``t``
    (scipy's select_initial_step), at most to ``stop``."""
    scale = atol + abs(y) * rtol
    d0, d1 = abs(y) / scale, abs(f) / scale
    h0 = min(1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1, stop - t)
    trial = _descent_rate(t + h0, y + h0 * f, path, tau, h_inf, air)
    d2 = abs(trial - f) / scale / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1 / 8)  # 1 / (the error estimator's order + 1)
    return min(100 * h0, h1, stop - t)


@jit(inline=True)
def _stages(k, t, y, h, path, tau, h_inf, air):
    """The stages of a trial step ``h`` from L = ``y`` at ``t`` (``k[0]`` the rate there),
    written into ``k``, the last of them the rate at the step's end; returns L there."""
    a, b, c, _, _ = TABLEAU
    for stage in range(1, STAGES + 1):  # the last is the solution's, at t + h
        change = 0.0
        for j in range(stage):
            change += (b[j] if stage == STAGES else a[stage, j]) * k[j]
        node = t + (h if stage == STAGES else c[stage] * h)
        k[stage] = _descent_rate(node, y + change * h, path, tau, h_inf, air)
    return y + change * h


@jit(inline=True)
def _error(k, h, y, y_new, rtol, atol):
    """DOP853's error of a trial step from ``y`` to ``y_new`` with stages ``k``, relative to
    ``atol + rtol max(|y|, |y_new|)``: at most 1 accepts it."""
    _, _, _, e3, e5 = TABLEAU
    scale = atol + max(abs(y), abs(y_new)) * rtol
    five = three = 0.0
    for j in range(STAGES + 1):
        five += e5[j] * k[j]
        three += e3[j] * k[j]
    five, three = (five / scale) ** 2, (three / scale) ** 2
    return 0.0 if five == 0 and three == 0 else h * five / math.sqrt(five + 0.01 * three)


@jit(inline=True)
def _step(k, t, y, f, h_abs, stop, path, tau, h_inf, air, rtol, atol):
    """One step from L = ``y``, dL/dtheta = ``f`` at ``t``, first tried at ``h_abs`` and
    shortened until its error is accepted, ``k`` its stages. Returns its end, L and the rate
    there, the next step's length, and whether it was accepted (not if it had to shrink below
    ten ulps of ``t``)."""
    min_step = 10 * (np.nextafter(t, math.inf) - t)
    h_abs, rejected = max(h_abs, min_step), False
    while True:
        t_new = min(t + h_abs, stop)
        h = t_new - t
        k[0] = f
        y_new = _stages(k, t, y, h, path, tau, h_inf, air)
        error = _error(k, h, y, y_new, rtol, atol)
        if error < 1:
            factor = 10.0 if error == 0 else min(10.0, 0.9 * error ** (-1 / 8))
            h_abs = h * (min(1.0, factor) if rejected else factor)
            return t_new, y_new, k[STAGES], h_abs, True
        # as scipy does, a step whose error is not finite (a trial stage that lost every bit
        # of h) is shortened fivefold
        shrink = 0.9 * error ** (-1 / 8) if math.isfinite(error) else 0.0
        h_abs, rejected = h * max(0.2, shrink), True
        if h_abs < min_step:
            return t_new, y_new, k[STAGES], h_abs, False


@jit(inline=True)
def _interpolate(theta, index, loss, k, terms, t, t_new, y, y_new, f, f_new, path, tau, h_inf, air):
    """L on the step from ``t`` to ``t_new`` (stages ``k``) at the points of ``theta`` from
    ``index`` on that it passed, by its dense output (the extra stages into ``k``, the
    interpolant's terms into ``terms``), written into ``loss``; returns the next index."""
    a_extra, c_extra, d = DENSE_TABLEAU
    h = t_new - t
    for stage in range(STAGES + 1, DENSE_STAGES):
        change = 0.0
        for j in range(stage):
            change += a_extra[stage - STAGES - 1, j] * k[j]
        node = t + c_extra[stage - STAGES - 1] * h
        k[stage] = _descent_rate(node, y + change * h, path, tau, h_inf, air)
    delta = y_new - y
    terms[0], terms[1], terms[2] = delta, h * f - delta, 2 * delta - h * (f_new + f)
    for row in range(4):
        change = 0.0
        for j in range(DENSE_STAGES):
            change += d[row, j] * k[j]
        terms[3 + row] = h * change
    while index < theta.size and theta[index] <= t_new:
        x = (theta[index] - t) / h
        value = 0.0
        for i in range(7):
            value = (value + terms[6 - i]) * (x if i % 2 == 0 else 1 - x)
        loss[index] = value + y
        index += 1
    return index


@jit(inline=True)
def _march(theta, index, loss, start, stop, y, path, tau, h_inf, air, rtol, atol):
    """dL/dtheta = :func:`_descent_rate` from L = ``y`` at ``start`` to ``stop``: scipy's DOP853
    for one equation as solve_ivp(method="DOP853", rtol=rtol, atol=atol, t_eval=theta) runs
    it (:func:`_first_step`, :func:`_step` and :func:`_interpolate`, its dense output), L
    written into ``loss`` at the points of ``theta`` from ``index`` on that it passes. Returns
    L at ``stop``, the next index and whether it got there (a rate that is not finite, or a
    step too small, stops it). The rate is called from four places, each compiled inline
    (the pieces too, each called once): the fewer, the shorter the compilation."""
    if stop <= start:  # a piece of no length: the descent starts on one of the air's levels
        return y, index, True
    k, terms = np.empty(DENSE_STAGES), np.empty(7)
    t = start
    f = _descent_rate(t, y, path, tau, h_inf, air)
    h_abs = _first_step(t, y, f, stop, path, tau, h_inf, air, rtol, atol)
    while t < stop:
        t_new, y_new, f_new, h_abs, accepted = _step(
            k, t, y, f, h_abs, stop, path, tau, h_inf, air, rtol, atol
        )
        if not accepted:
            return y, index, False
        if index < theta.size and theta[index] <= t_new:  # the interpolant at the points passed
            index = _interpolate(
                theta, index, loss, k, terms, t, t_new, y, y_new, f, f_new, path, tau, h_inf, air
            )
        t, y, f = t_new, y_new, f_new
    return y, index, True


@jit(inline=True)
def _crossing(path, tau, radius, level, low, high):
    """The two neighbouring angles in [low, high] between which the MKS, above ``level`` at
    ``low`` and at or below it at ``high``, passes it (bisection to the last bit)."""
    for _ in range(_CROSSING_BISECTIONS):
        middle = 0.5 * (low + high)
        if not low < middle < high:
            break
        if _altitude(path, tau, radius, middle) > level:
            low = middle
        else:
            high = middle
    return low, high


# IEEE division, as numpy's: a descent whose decay loses all of h before the impact divides by
# zero somewhere in the march, and its loss, inf or NaN, is what _reentry_decay refuses by name
@jit(zero_division="ieee")
def _reentry_losses(path, tau, h_inf, apogee, impact, radius, breakpoints, air, rtol, atol):
    """Along the MKS's descent from the top of the atmosphere to its impact, flown with the
    speed it loses: the angles (n,), the loss L on them and 1 / its mean distance before the
    impact (:func:`_moments`). The march (:func:`_march`) stops on the last angle above each of
    the air's ``breakpoints`` (m, descending) that the descent crosses and starts again on the
    first below it: there the rate may jump or kink, which the error estimate of a step across
    it does not see, and each piece's steps see the rate of its own side only."""
    top = _top_angle(path, tau, radius, apogee, impact, False)
    theta = impact - _distances(impact - top)[::-1]
    starts, stops = np.empty(breakpoints.size + 1), np.empty(breakpoints.size + 1)
    starts[0], count = theta[0], 0
    for level in breakpoints:  # descending: the first crossed first
        if 0 < level < _altitude(path, tau, radius, theta[0]):
            stops[count], starts[count + 1] = _crossing(path, tau, radius, level, theta[0], impact)
            count += 1
    stops[count] = impact
    loss = np.full(theta.size, np.nan)
    loss[0], index, y = 0.0, 1, 0.0
    for piece in range(count + 1):
        y, index, reached = _march(
            theta, index, loss, starts[piece], stops[piece], y, path, tau, h_inf, air, rtol, atol
        )
        if not reached:
            return theta, loss, math.nan
    rate = np.empty(theta.size)
    for i in range(theta.size):
        rate[i] = _descent_rate(theta[i], loss[i], path, tau, h_inf, air)
    return theta, loss, _moments(rate, theta, impact)[1]


class _Air:
    """What the loss rate needs of a launch, its air on its day, drag law, drag per density and
    Earth rotation as the compiled losses take them (``packed``), and the flight plane."""

    def __init__(self, launch: Launch, plane: _Plane):
        self.latitude_rad = launch.latitude_rad
        projectile = launch.projectile
        model = atmosphere.get_atmosphere(launch.atmosphere)
        law = projectile.drag_law.kernel_parameters()
        self.breakpoints_m = np.array(sorted(model.breakpoints_m, reverse=True), dtype=float)
        numbers = np.zeros(7)
        numbers[_PER_DENSITY] = projectile.reference_area_m2 / (2 * projectile.mass_kg)
        numbers[_OMEGA] = launch.rotation_rate_rad_s
        numbers[_DENSITY_FACTOR], numbers[_SOUND_CHANGE] = launch.day
        table, parameters, table_mach, table_cd = (
            np.ascontiguousarray(x, dtype=float) for x in (model.table(), *law[1:])
        )
        self.packed = (model.code, law[0], table, parameters, table_mach, table_cd, numbers)
        self.plane = plane

    @property
    def plane(self) -> _Plane:
        return self._plane

    @plane.setter
    def plane(self, plane: _Plane):
        self._plane = plane
        numbers = self.packed[-1]
        numbers[_NORMAL_Z], numbers[_UP_Z], numbers[_ALONG_Z] = (
            plane.normal_z,
            plane.up[2],
            plane.along[2],
        )


def _path(solution: mks.ModifiedKeplerSolution) -> tuple:
    """A single-launch MKS as the compiled losses take it: its constants (as its own kernels
    take them), tau and h_inf."""
    return solution.kernel_table, float(solution.tau[0, 0]), float(solution.h_inf[0, 0])


def _along_ascent(solution: mks.ModifiedKeplerSolution, air: _Air) -> tuple[float, float, float]:
    """The loss along ``solution``'s ascent with its own speed, its tau (infinite without air)
    and the cross-track impulse V_tangent (m/s)."""
    decay = float(solution.beta[0, 0] * solution.decay_scale[0, 0])
    apogee, radius = float(solution.apogee_angle), float(solution.radius_m[0, 0])
    return _ascent_losses(*_path(solution), decay, apogee, radius, air.packed)


def _along_descent(
    ascent: mks.ModifiedKeplerSolution,
    air: _Air,
    rtol: float = _REENTRY_RTOL,
    atol: float = _REENTRY_ATOL,
):
    """The angles from the top of the atmosphere to ``ascent``'s impact (n,), the loss on them
    along its descent flown with the speed it loses (marched to ``rtol`` and ``atol``), and
    1 / its mean distance before the impact (rad)."""
    impact, apogee = float(ascent.impact_angle), float(ascent.apogee_angle)
    radius = float(ascent.radius_m[0, 0])
    return _reentry_losses(
        *_path(ascent), apogee, impact, radius, air.breakpoints_m, air.packed, rtol, atol
    )


def _scalar(value) -> float:
    """The one number of a single launch's (1,) or () result."""
    return float(np.ravel(value)[0])


def _with_tangent(correction, tangent_speed_m_s: float, latitude_rad: float):
    """``correction`` launched with V_tangent = ``tangent_speed_m_s`` along eq 6.15's direction."""
    direction = eci.tangent_direction(
        correction.relative_m_s, correction.relative_m_s + correction.surface_m_s
    )
    velocity = correction.relative_m_s + correction.surface_m_s + tangent_speed_m_s * direction
    speed = np.linalg.norm(velocity)
    elevation, azimuth = eci.elevation_azimuth(velocity, latitude_rad)
    return replace(
        correction,
        tangent_speed_m_s=np.asarray(tangent_speed_m_s),
        velocity_m_s=velocity,
        speed_m_s=speed,
        elevation_rad=elevation,
        azimuth_rad=azimuth,
        initial_angular_momentum_m2_s=eci.initial_angular_momentum(speed, elevation),
    )


def _ascent_decay(correction, air: _Air, n_terms: int):
    """(corrected launch, MKS) whose beta and tau are the loss and first moment along the MKS's
    own ascent, and whose V_tangent is the cross-track drag's impulse along it."""
    solution = correction.solution(n_terms=n_terms, warn=False)
    beta, tau = float(solution.beta[0, 0] * solution.decay_scale[0, 0]), float(solution.tau[0, 0])
    radius = float(solution.radius_m[0, 0])
    # The loss decays the angular momentum the gun gives, that of Vrel + omega x r0.
    h_gun = float(
        eci.initial_angular_momentum(
            correction.corrected_speed_m_s, correction.corrected_elevation_rad, radius
        )
    )
    for _ in range(_FIXED_POINT_ITERATIONS):
        loss, new_tau, cross_impulse = _along_ascent(solution, air)
        if math.isinf(new_tau):  # no air: beta = 0 and the MKS is the conic, whatever tau
            break
        correction = _with_tangent(correction, cross_impulse, air.latitude_rad)
        air.plane = _plane(solution, correction, air.latitude_rad)  # V_tangent may tilt it
        h0 = float(correction.initial_angular_momentum_m2_s)
        new_beta = loss + math.log(h0 / h_gun)
        converged = (
            abs(new_beta - beta) <= _FIXED_POINT_TOLERANCE * abs(beta)
            and abs(new_tau - tau) <= _FIXED_POINT_TOLERANCE * tau
        )
        beta, tau = new_beta, new_tau
        # mks takes beta >= 0; a gain (beta < 0) is its size with both scales -1
        sign = 1.0 if beta >= 0 else -1.0
        solution = mks.ModifiedKeplerSolution(
            float(correction.speed_m_s),
            float(correction.elevation_rad),
            abs(beta),
            tau,
            n_terms=n_terms,
            radius_m=radius,
            drive_scale=sign,
            decay_scale=sign,
            warn=False,
        )
        if converged:
            break
    return correction, solution


def _reentry_decay(ascent: mks.ModifiedKeplerSolution, air: _Air) -> tuple[float, float]:
    """(beta_re, tau_re): the loss along ``ascent``'s descent from the top of the atmosphere to
    its impact, integrated forward with the speed it loses, and 1 / its mean distance before
    the impact (rad)."""
    _, loss, tau = _along_descent(ascent, air)
    if not np.all(np.isfinite(loss)):
        raise ValueError(
            "the improved MKS's re-entry decay has no finite solution for this launch: on its "
            "descent the air, turning with the Earth, drags the inertial angular momentum h "
            "toward its own omega n_z r^2 (a westward or near-vertical shot) and the "
            "exponential decay loses all of h before the impact; the dissertation's MKS "
            "(mks_improved.dissertation) or the 3DOF flies it"
        )
    total = float(loss[-1])
    return (0.0, math.inf) if total == 0.0 else (total, tau)


@formula
def _reentry_terms(rates, amplitudes, impact, theta):
    """u_re, du_re/dtheta, d2u_re/dtheta2 of the re-entry terms (``rates`` n tau_re and
    ``amplitudes`` B_n) plus the conic that keeps u(0) and u'(0) the launch's, for an impact at
    ``impact``: of arrays ``theta`` in numpy, of a number in compiled code."""
    value = slope = curvature = 0.0 * theta
    at_launch = amplitudes * np.exp(-rates * impact)
    cos_shift, sin_shift = -at_launch.sum(), -(rates * at_launch).sum()
    for rate, amplitude in zip(rates, amplitudes):
        term = amplitude * np.exp(rate * (theta - impact))
        value, slope, curvature = value + term, slope + rate * term, curvature + rate**2 * term
    sin, cos = np.sin(theta), np.cos(theta)
    return (
        value + sin_shift * sin + cos_shift * cos,
        slope + sin_shift * cos - cos_shift * sin,
        curvature - sin_shift * sin - cos_shift * cos,
    )


@jit
def _impact_excess(theta, path, tau, rates, amplitudes, inverse_radius):
    """u - 1/r0 at ``theta`` of the solution (the ascent's MKS ``path`` and the re-entry terms)
    whose impact is at ``theta``: zero at the impact (ImprovedSolution._impact_angle)."""
    ascent = mks.point(path, 0, tau, theta)[0]
    return ascent + _reentry_terms(rates, amplitudes, theta, theta)[0] - inverse_radius


def _cumulative_time(theta, integrand_of):
    """t(theta) on the sorted grid ``theta`` (starting at 0): 3-point Gauss-Legendre of
    ``integrand_of`` (vectorised) on every interval, summed."""
    nodes, weights = np.polynomial.legendre.leggauss(3)
    low, high = theta[:-1], theta[1:]
    half = 0.5 * (high - low)
    points = half[:, None] * (nodes + 1) + low[:, None]
    pieces = half * (integrand_of(points.ravel()).reshape(points.shape) @ weights)
    return np.concatenate([[0.0], np.cumsum(pieces)])


class ImprovedSolution:
    """An MKS of one launch: the closed-form ascent (a
    :class:`~harp_analysis.engines.mks.ModifiedKeplerSolution`) with, for the improved variant, the
    re-entry branch (module docstring). Angles in rad, SI otherwise; positions are inertial (x
    toward longitude 0 at t = 0, z north) as the 3DOF's table has them, Earth-fixed ones where
    said."""

    def __init__(
        self,
        launch: Launch,
        correction,
        ascent: mks.ModifiedKeplerSolution,
        beta_reentry: float = 0.0,
        tau_reentry: float = math.inf,
        variant: str = "improved",
    ):
        self.launch, self.correction, self.ascent, self.variant = (
            launch,
            correction,
            ascent,
            variant,
        )
        self.beta_reentry, self.tau_reentry = float(beta_reentry), float(tau_reentry)
        self.radius_m = float(ascent.radius_m[0, 0])
        self.plane = _plane(ascent, correction, launch.latitude_rad)
        rates = np.arange(1, ascent.n_terms) * self.tau_reentry
        powers = (2 * self.beta_reentry) ** np.arange(1, ascent.n_terms)
        factorials = np.cumprod(np.arange(1, ascent.n_terms, dtype=float))
        self._rates = rates if self.beta_reentry != 0 else np.zeros(0)
        self._amplitudes = (
            float(ascent.c3[0, 0]) * powers / (factorials * (1 + rates**2))
            if self.beta_reentry != 0
            else np.zeros(0)
        )
        self.impact_angle = self._impact_angle()

    # --- the re-entry terms and the solution ---------------------------------------------------
    def _reentry_terms(self, theta, impact):
        """:func:`_reentry_terms` of this solution at ``theta`` for an impact at ``impact``."""
        return _reentry_terms(self._rates, self._amplitudes, impact, np.asarray(theta, dtype=float))

    def _impact_angle(self) -> float:
        """Where u returns to 1/r0 descending; the re-entry terms equal sum B_n there, so
        u_ascent(theta) + sum B_n (+ the conic shift) = 1/r0 is one equation in theta."""
        low, high = float(self.ascent.apogee_angle), float(self.ascent.impact_angle)
        if self._amplitudes.size == 0:
            return high
        high += 0.05 * (high - low)  # a re-entry gain (beta_re < 0) lands a little further
        path, tau, _ = _path(self.ascent)
        constants = (path, tau, self._rates, self._amplitudes, 1 / self.radius_m)
        below_at_apogee = _impact_excess(low, *constants) > 0
        if below_at_apogee or _impact_excess(high, *constants) < 0:
            where = (
                "below the launch radius already at the ascent's apogee"
                if below_at_apogee
                else "above it beyond 1.05 times the ascent's range"
            )
            raise ValueError(
                f"the improved MKS of this launch has no impact after its apogee: its re-entry "
                f"decay (beta_re = {self.beta_reentry:.3g}; the ascent's "
                f"beta = {float(self.ascent.beta[0, 0]):.3g}) puts it {where}; the "
                "dissertation's MKS (mks_improved.dissertation) or the 3DOF flies it"
            )
        return float(
            brentq(_impact_excess, low, high, constants, xtol=1e-15, rtol=4 * np.finfo(float).eps)
        )

    # Functions of the angular range return the shape of ``theta_rad``.
    def u(self, theta_rad):
        """u = 1/r (1/m) at ``theta_rad``."""
        theta = np.asarray(theta_rad, dtype=float)
        ascent = np.reshape(self.ascent.u(theta), theta.shape)
        return ascent + self._reentry_terms(theta, self.impact_angle)[0]

    def du_dtheta(self, theta_rad):
        theta = np.asarray(theta_rad, dtype=float)
        ascent = np.reshape(self.ascent.du_dtheta(theta), theta.shape)
        return ascent + self._reentry_terms(theta, self.impact_angle)[1]

    def radius(self, theta_rad):
        return 1 / self.u(theta_rad)

    def altitude(self, theta_rad):
        return self.radius(theta_rad) - self.radius_m

    def angular_momentum(self, theta_rad):
        """h(theta) (m^2/s): the ascent's decay times the re-entry's."""
        theta = np.asarray(theta_rad, dtype=float)
        reentry = np.exp(
            -self.beta_reentry * np.exp(-self.tau_reentry * (self.impact_angle - theta))
        )
        ascent = np.reshape(self.ascent.angular_momentum(theta), theta.shape)
        return ascent * (reentry if self.beta_reentry != 0 else 1.0)

    def speed(self, theta_rad):
        """Inertial speed (m/s), V = h sqrt(u^2 + u'^2)."""
        return self.angular_momentum(theta_rad) * np.hypot(
            self.u(theta_rad), self.du_dtheta(theta_rad)
        )

    # --- apogee, impact, time ------------------------------------------------------------------
    @cached_property
    def apogee_angle(self) -> float:
        """The zero of du/dtheta: Newton's iteration from the ascent's own apogee."""
        theta = float(self.ascent.apogee_angle)
        for _ in range(5):
            extra = self._reentry_terms(theta, self.impact_angle)
            slope = _scalar(self.ascent.du_dtheta(theta) + extra[1])
            curvature = _scalar(self.ascent.d2u_dtheta2(theta) + extra[2])
            theta -= slope / curvature
        return theta

    @property
    def apogee_altitude_m(self) -> float:
        return float(self.altitude(self.apogee_angle))

    @cached_property
    def _time_grid(self):
        theta = np.union1d(np.linspace(0.0, self.impact_angle, _TIME_POINTS), [self.apogee_angle])
        times = _cumulative_time(theta, lambda x: 1 / (self.u(x) ** 2 * self.angular_momentum(x)))
        return theta, times

    def time(self, theta_rad):
        """Time of flight (s) to ``theta_rad`` (within the flight), t = int dtheta / (h u^2)."""
        theta, times = self._time_grid
        return np.interp(theta_rad, theta, times)

    @property
    def apogee_time_s(self) -> float:
        return float(self.time(self.apogee_angle))

    @property
    def impact_time_s(self) -> float:
        return float(self._time_grid[1][-1])

    @property
    def impact_flight_path_angle_rad(self) -> float:
        """The angle of the velocity below the horizontal at impact (positive)."""
        return float(np.arctan2(self.du_dtheta(self.impact_angle), self.u(self.impact_angle)))

    def angle_at(self, time_s):
        """Angular range (rad) at ``time_s`` (clipped to the flight)."""
        theta, times = self._time_grid
        return np.interp(time_s, times, theta)

    # --- positions -----------------------------------------------------------------------------
    def positions(self, time_s) -> np.ndarray:
        """Inertial positions (n, 3) at ``time_s`` (n,), in the 3DOF's frame (longitude of the
        launch included); after the impact, the impact point."""
        time = finite_array(time_s, "time_s").reshape(-1)
        theta = self.angle_at(time)
        inertial = self.radius(theta)[:, None] * self.plane.directions(theta)
        return rotate_about_axis(
            inertial.T, np.full(theta.size, math.radians(self.launch.longitude_deg))
        ).T

    @property
    def impact_point_m(self) -> np.ndarray:
        """The impact point (3,) fixed to the Earth (the inertial frame at t = 0)."""
        inertial = self.positions([self.impact_time_s])[0]
        turned = rotate_about_axis(
            inertial[:, None], np.array([-self.launch.rotation_rate_rad_s * self.impact_time_s])
        )
        return turned[:, 0]

    @property
    def impact_range_m(self) -> tuple[float, float]:
        """(ground range, cross range) of the impact point on the turning Earth (m)."""
        launch = self.launch
        up, downrange, _ = launch_frame(
            launch.latitude_rad, math.radians(launch.longitude_deg), launch.bearing_rad
        )
        ground, cross = surface_ranges(self.impact_point_m, np.ravel(up), np.ravel(downrange))
        return float(ground), float(cross)


def _correction(launch: Launch):
    if not isinstance(launch, Launch):
        raise TypeError(f"launch must be a Launch; got {type(launch).__name__}")
    if launch.elevation_deg >= 90.0:
        raise ValueError(
            f"the MKS cannot fly launch.elevation_deg = {launch.elevation_deg:g}: a vertical "
            "shot has no angular momentum"
        )
    return eci.correction_for_launch(launch)


def dissertation(launch: Launch, *, n_terms: int = 3) -> ImprovedSolution:
    """The dissertation's MKS of ``launch`` (Chapter 5's ECI MKS,
    :func:`~harp_analysis.engines.eci.correction_for_launch` with the consistent decay; on a
    non-rotating Earth it is :func:`~harp_analysis.engines.mks.for_launch`) behind the same
    interface, with no re-entry decay."""
    correction = _correction(launch)
    ascent = correction.solution(n_terms=n_terms, warn=False)
    return ImprovedSolution(launch, correction, ascent, variant="dissertation")


def air_momentum_share(launch: Launch) -> float:
    """omega n_z r0^2 / h0: the angular momentum the turning air has about the Earth's centre in
    the flight plane over the launch's (gun velocity Vrel + omega x r0). It sets the in-plane
    loss factor 1 - omega n_z r^2/h; outside :data:`AIR_MOMENTUM_SHARE_RANGE` the air adds
    or takes a large share of h and the improved MKS is worse than the text's."""
    return _air_momentum_share(launch, _correction(launch))


def _air_momentum_share(launch: Launch, correction) -> float:
    """:func:`air_momentum_share` of ``launch`` and its ``correction``."""
    velocity = np.ravel(correction.relative_m_s + correction.surface_m_s)
    up = np.ravel(launch_frame(launch.latitude_rad, 0.0, 0.0)[0]) * earth.RADIUS_M
    momentum = np.cross(up, velocity)
    return float(
        launch.rotation_rate_rad_s * momentum[2] * earth.RADIUS_M**2 / (momentum @ momentum)
    )


@overload
def solve(
    launch: Launch, calibration: Calibration = ..., *, n_terms: int = ...
) -> ImprovedSolution: ...
@overload
def solve(
    launch: Launches, calibration: Calibration = ..., *, n_terms: int = ...
) -> list[ImprovedSolution]: ...
def solve(launch, calibration=UNCALIBRATED, *, n_terms=3):
    """The improved MKS of ``launch``: the self-consistent ascent decay and the re-entry decay
    (module docstring), beta_re scaled by ``calibration``. For
    :class:`~harp_analysis.models.launch.Launches`, one solution per launch, in order (each is a
    fixed point of its own).

    Parameters
    ----------
    launch : Launch or Launches
        One launch, or many solved one by one.
    calibration : Calibration
        The scale of the re-entry loss (``mks_improvement.calibration()`` fits it on the
        simulations); uncalibrated by default.
    n_terms : int
        Terms of the series of eq 3.30.

    Returns
    -------
    ImprovedSolution or list of ImprovedSolution
        The improved MKS of the launch (apogee, impact, the state at any time), or one per
        launch of a Launches. It warns where a launch lies beyond the drag it was fitted on
        or is near-vertical in the inertial frame.
    """
    if not isinstance(calibration, Calibration):
        raise TypeError(f"calibration must be a Calibration; got {type(calibration).__name__}")
    if isinstance(launch, Launches):
        return [solve(one, calibration, n_terms=n_terms) for one in launch]
    correction = _correction(launch)
    first = correction.solution(n_terms=n_terms, warn=False)
    air = _Air(launch, _plane(first, correction, launch.latitude_rad))
    beta = float(first.beta[0, 0])
    if beta > MAX_JUDGED_BETA:
        warnings.warn(
            f"improved MKS beta = {beta:.3g} > {MAX_JUDGED_BETA:g}: beyond the drag of the "
            "launches it was fitted on (mks_improvement), where its apogee falls kilometres "
            "short of the simulations'",
            ModelValidityWarning,
            stacklevel=2,
        )
    share = _air_momentum_share(launch, correction)
    low, high = AIR_MOMENTUM_SHARE_RANGE
    if not low < share <= high:
        warnings.warn(
            f"the air carries {share:.2f} of the launch's angular momentum (omega n_z r0^2 / "
            f"h0, outside ({low:g}, {high:g}]): a near-vertical shot in the inertial frame, "
            "where the improved MKS's exponential decay does not hold (mks_improvement's maps)",
            ModelValidityWarning,
            stacklevel=2,
        )
    correction, ascent = _ascent_decay(correction, air, n_terms)
    beta_re, tau_re = _reentry_decay(ascent, air)
    return ImprovedSolution(launch, correction, ascent, calibration.reentry_scale * beta_re, tau_re)


def flight(
    launch: Launch, variant: str = "improved", calibration: Calibration = UNCALIBRATED
) -> ImprovedSolution:
    """The ``variant`` (one of :data:`VARIANTS`) MKS of ``launch``."""
    if variant == "dissertation":
        return dissertation(launch)
    if variant == "improved":
        return solve(launch, calibration)
    raise ValueError(
        f"unknown variant {variant!r}; expected one of {', '.join(map(repr, VARIANTS))}"
    )


def warm_up() -> None:
    """Compile the improved MKS's kernels now (or load them from the on-disk cache), not at
    first use; one compilation serves every atmosphere and drag law."""
    solve(baseline_chapter_4(45.0))
