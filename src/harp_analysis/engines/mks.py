"""The Modified Kepler Solution (Chapter 3): Kepler's orbit equation driven by the decay of the
angular momentum in the atmosphere, solved in closed form.

With u = 1/r and theta the angular range, the linearised Modified Kepler equation (eq 3.30) is

    u'' + u = c3 sum_{n=0}^{N-1} (-2 beta e^{-tau theta})^n / n!,     c3 = GM / h_inf^2,

where h is the specific angular momentum, h = h_inf exp(beta gamma) with gamma = e^{-tau theta}
(eqs 3.20-3.23), beta = Cd0 rho0 A / (2 k m sin phi0) (eq 3.22) and tau = k r0 tan phi0
(eq 3.27). Each term of the series is an exponential, so the particular solution is term by
term, and the constants follow from the launch conditions u(0) = 1/r0 and
u'(0) = -tan(phi0)/r0 (eq 3.28):

    u(theta) = c1 sin(theta) + c2 cos(theta) + sum_n A_n e^{-n tau theta},
    A_n = c3 (-2 beta)^n / (n! (1 + n^2 tau^2)),
    c2 = 1/r0 - sum_n A_n,      c1 = -tan(phi0)/r0 + tau sum_n n A_n,

which for N = 3 are eqs 6.6-6.10 (c4 = A_1, c5 = A_2) without the rotating-Earth factors. Those
factors of Chapter 5 enter as two scales: the driving function's beta is multiplied by
``drive_scale`` (cos mu (Vrel/V)^2, eqs 6.9-6.10) and the decay h_inf = h0 exp(-beta
``decay_scale``) by ``decay_scale`` (cos mu, eq 6.14); both are 1 on a non-rotating Earth.

The per-launch work runs compiled (:mod:`.compiled`; :func:`warm_up` compiles it ahead of use):
the constants, the checks of the launch conditions and of escape and eq 6.4's apogee in one
pass at construction, Newton's iterations for the first zero of du/dtheta and for the impact
in another when first asked for; a single launch of plain numbers takes them all in one call.
The conic part is evaluated about eq 6.4's angle theta_6.4 = atan2(-c1, -c2), as
c1 sin(theta) + c2 cos(theta) = -rho cos(theta - theta_6.4) with rho = sqrt(c1^2 + c2^2): at
eq 6.4's apogee it takes no sine or cosine, and near it only those of a small angle.

SI units: r in m, u in 1/m, h in m^2/s, k in 1/m (the text's 0.117 /km is 1.17e-4 /m; beta
and tau are dimensionless only if k and r0, m and A share units).

The compiled building blocks, for other compiled code that solves many MKS trajectories in its
own loops (the firing solver, :mod:`harp_analysis.analyses.fire_control.solver`; the improved MKS,
:mod:`.mks_improved`): a solution's constants live in a table, one column per launch
(:attr:`ModifiedKeplerSolution.kernel_table`; :data:`AMPLITUDES_ROW` + N rows for N terms), which
:func:`solve_constants` fills from the launch's numbers (holding each to its argument's
domain); :func:`point` evaluates u and its two derivatives at an angle and :func:`u_at` u alone,
:func:`find_apogees` and :func:`find_impacts` find the first zero of du/dtheta and the return
to the launch radius, :func:`crossing_angle` where a branch crosses a
radius, and :func:`time_to` eq 3.32's time of flight to an angle. They are unchecked, like every
kernel: :class:`ModifiedKeplerSolution` and :func:`for_launch` are the checked door.
"""

from __future__ import annotations

import math
import warnings
from functools import cache, cached_property

import numpy as np
import pandas as pd

from ..foundation import earth
from ..foundation.compiled import formula, jit
from ..foundation.validation import (
    Bounds,
    ModelValidityWarning,
    finite_array,
    inside,
    positive_scalar,
    whole_number,
)
from ..models.atmosphere import SEA_LEVEL_DENSITY_KG_M3, TEXT_DECAY_CONSTANT_PER_M, get_atmosphere
from ..models.launch import Launch, Launches
from ..models.trajectory import MAX_ROWS, describe, launch_frame

__all__ = [
    "ModifiedKeplerSolution",
    "decay_factor_beta",
    "decay_rate_tau",
    "check_n_terms",
    "for_launch",
    "gun_density_kg_m3",
    "simulate_mks",
    "BETA_VALIDITY_LIMIT",
    "HighDragWarning",
    "SENSIBLE_ATMOSPHERE_M",
    "warm_up",
]

#: Chapter 4 B: "a beta value of less than 0.25 is required for a reasonably accurate MKS".
BETA_VALIDITY_LIMIT = 0.25


class HighDragWarning(ModelValidityWarning):
    """An MKS launch's beta (eq 3.22) exceeds :data:`BETA_VALIDITY_LIMIT`: the text finds the
    solution inaccurate for such high-drag projectiles (Ch. 4 B)."""


#: Chapter 3: the Kepler solution "is reasonably valid above 30 km".
SENSIBLE_ATMOSPHERE_M = 30_000.0
#: The radius of the Earth's sphere of influence against the Sun, a (m_earth/m_sun)^(2/5)
#: = 9.25e5 km: beyond it the Sun's pull dominates and no Kepler orbit about the Earth holds.
EARTH_SPHERE_OF_INFLUENCE_M = 9.25e8
#: How closely the closed form's constants must reproduce the launch conditions u(0) = 1/r0 and
#: u'(0) = -tan(phi0)/r0 (relative to 1/r0): at a very low elevation beta (eq 3.22) is so large
#: that the constants cancel to no significant digit, or overflow.
_LAUNCH_CONDITION_TOLERANCE = 1e-6


#: Series terms at most: Fig 4.6's error stops falling after five, and each term is a column of
#: every solution's table.
MAX_TERMS = 100


def check_n_terms(n_terms) -> int:
    """``n_terms``, a count of series terms, as an int in [1, :data:`MAX_TERMS`]; an error naming
    it otherwise (2.5 and "3" are refused, not read as numbers)."""
    return whole_number(n_terms, "n_terms", low=1, high=MAX_TERMS)


@cache
def _gauss_legendre(order: int):
    return np.polynomial.legendre.leggauss(order)


def decay_factor_beta(
    drag_coefficient,
    surface_density_kg_m3,
    area_m2,
    mass_kg,
    elevation_rad,
    decay_constant_per_m=TEXT_DECAY_CONSTANT_PER_M,
):
    """Eq 3.22: beta = Cd0 rho0 A / (2 k m sin phi0), the MKS ballistic coefficient."""
    return beta_formula(
        np.asarray(drag_coefficient),
        surface_density_kg_m3,
        area_m2,
        mass_kg,
        elevation_rad,
        decay_constant_per_m,
    )


@formula
def beta_formula(
    drag_coefficient, surface_density_kg_m3, area_m2, mass_kg, elevation_rad, decay_constant_per_m
):
    """:func:`decay_factor_beta` of numbers (compiled code) or arrays."""
    return (
        drag_coefficient
        * surface_density_kg_m3
        * area_m2
        / (2 * decay_constant_per_m * mass_kg * np.sin(elevation_rad))
    )


@formula
def decay_rate_tau(
    elevation_rad, decay_constant_per_m=TEXT_DECAY_CONSTANT_PER_M, radius_m=earth.RADIUS_M
):
    """Eq 3.27: tau = k r0 tan phi0, the decay rate of the density along the angular range."""
    return decay_constant_per_m * radius_m * np.tan(elevation_rad)


#: Each argument's domain. Plain numbers and float arrays pass the class's door unchecked: the
#: constants' kernel holds every launch to these domains as it reads it (``_in_domain()``, a
#: pass over the arrays saved), and where one lies outside, :func:`_checked` names the argument.
_DOMAINS: dict[str, Bounds] = {
    "speed_m_s": Bounds(low=0.0, low_inclusive=False, unit="m/s"),
    "elevation_rad": Bounds(
        low=0.0, high=math.pi / 2, low_inclusive=False, high_inclusive=False, unit="rad"
    ),
    "beta": Bounds(low=0.0),
    "tau": Bounds(low=0.0),
    "radius_m": Bounds(low=0.0, low_inclusive=False, unit="m"),
    "drive_scale": Bounds(),
    "decay_scale": Bounds(),
}
# the domains' limits as constants of the kernel
_SPEED, _ELEVATION, _BETA, _TAU, _RADIUS, _DRIVE, _DECAY = (
    bounds.limits for bounds in _DOMAINS.values()
)


def _checked(value, name: str):
    """``value`` as a finite float array inside ``name``'s domain, or a ValueError naming it."""
    return _DOMAINS[name].finite(value, name)


def _argument(value, name: str):
    """``value`` itself if it is a float or a non-empty 1-D contiguous float array (the kernel
    checks each launch's value, :data:`_DOMAINS`); else :func:`_checked`."""
    if type(value) in (float, np.float64) or (
        type(value) is np.ndarray
        and value.dtype == np.float64
        and value.ndim == 1
        and value.size
        and value.flags.c_contiguous
    ):
        return value
    return _checked(value, name)


# --- compiled kernels -------------------------------------------------------------------------
# A solution keeps its constants in a table with one row per quantity and one column per launch
# (rows are contiguous arrays): h0, h_inf, c1, c2, rho = sqrt(c1^2 + c2^2), eq 6.4's apse angle,
# the asymptotic conic's eccentricity, eq 6.4's apogee altitude, then the amplitudes A_n.
_H0, _H_INF, _C1, _C2, _RHO, _APSE, _ECCENTRICITY, _APOGEE_6_4 = range(8)
#: The table's row of the first amplitude A_0: a table of N terms has AMPLITUDES_ROW + N rows
#: (the kernels' building blocks, module docstring).
AMPLITUDES_ROW = 8
#: The escape check looks at the angle where the driving terms have died: e^{-tau theta} = e^-20.
_LATE_DECAY_EXPONENT = 20.0
#: Newton's iterations stop once a step is below _NEWTON_STEP_RAD, or below _NEWTON_NOISE_RAD
#: (6 um of range) and no smaller than the step before, or after _NEWTON_ITERATIONS.
_NEWTON_STEP_RAD = 1e-15
_NEWTON_NOISE_RAD = 1e-12
_NEWTON_ITERATIONS = 50
#: The crossing of a radius: at most this many Newton (or bisection) steps, stopping once a step
#: is below _CROSSING_TOLERANCE_RAD (64 nm of range: the rounding of u allows no better).
_CROSSING_ITERATIONS = 100
_CROSSING_TOLERANCE_RAD = 1e-14


@jit
def _at(values, i):
    """Launch ``i``'s value of an argument given once for all launches or once for each."""
    return values[min(i, values.size - 1)]


def _read_only(view: np.ndarray) -> np.ndarray:
    """``view`` marked read-only: the table behind it feeds the kernels."""
    view.flags.writeable = False
    return view


@jit
def _sin_cos(angle):
    """sin and cos of ``angle``. Below 1/32 rad (the offsets from the apse where Newton's
    iterations for the apogee look), Taylor polynomials to x^7 and x^8, within an ulp: libm
    takes 8 ns for the pair at any argument, which costs the apogees 4 ns a launch."""
    if abs(angle) >= 1 / 32:
        return math.sin(angle), math.cos(angle)
    x2 = angle * angle
    sin = angle + angle * x2 * (-1 / 6 + x2 * (1 / 120 + x2 * (-1 / 5040)))
    cos = 1.0 + x2 * (-1 / 2 + x2 * (1 / 24 + x2 * (-1 / 720 + x2 * (1 / 40320))))
    return sin, cos


@jit
def point(table, i, tau, theta):
    """u, du/dtheta and d2u/dtheta2 of launch ``i`` (column ``i`` of ``table``) at ``theta``.

    The conic part c1 sin(theta) + c2 cos(theta) is written about eq 6.4's angle, the apse:
    -rho cos(theta - apse), with rho = sqrt(c1^2 + c2^2). The series sum_n A_n e^{-n tau theta}
    raises one exponential to each power by products."""
    rho = table[_RHO, i]
    sin, cos = _sin_cos(theta - table[_APSE, i])
    decay = math.exp(-tau * theta)
    terms = slope = curvature = 0.0
    factor = 1.0  # e^{-n tau theta}
    for n in range(table.shape[0] - AMPLITUDES_ROW):
        rate = n * tau
        term = table[AMPLITUDES_ROW + n, i] * factor
        terms += term
        slope -= rate * term
        curvature += rate * rate * term
        factor *= decay
    return -rho * cos + terms, rho * sin + slope, rho * cos + curvature


@jit
def u_at(table, i, tau, theta):
    """u alone of launch ``i`` at ``theta``: :func:`point`'s first value, the same sums in the
    same order, without the two derivatives (a seventh of the constants' time a launch)."""
    cos = _sin_cos(theta - table[_APSE, i])[1]
    decay = math.exp(-tau * theta)
    terms = 0.0
    factor = 1.0
    for n in range(table.shape[0] - AMPLITUDES_ROW):
        terms += table[AMPLITUDES_ROW + n, i] * factor
        factor *= decay
    return -table[_RHO, i] * cos + terms


@jit
def _in_domain(speed, elevation, beta, tau, radius, drive_scale, decay_scale):
    """Whether one launch's arguments lie in their domains, :data:`_DOMAINS` (NaN in none)."""
    return (  # as the kernel reads each launch: 4 ns of its 52, where a pass over each array took 8
        inside(speed, *_SPEED)
        & inside(elevation, *_ELEVATION)
        & inside(beta, *_BETA)
        & inside(tau, *_TAU)
        & inside(radius, *_RADIUS)
        & inside(drive_scale, *_DRIVE)
        & inside(decay_scale, *_DECAY)
    )


@jit(zero_division="ieee")  # its checks of u(0) and u'(0) catch the inf and NaN
def solve_constants(speed, elevation, beta, tau, radius, drive_scale, decay_scale, table, escapes):
    """The constants of every launch into its column of ``table``, and whether it escapes
    (its apogee is then NaN) into ``escapes``; arguments have one value, or one per launch.
    Returns the index of the first launch whose arguments lie outside their domains
    (``_in_domain()``) or whose constants do not reproduce the launch conditions
    u(0) = 1/r0 and u'(0) = -tan(phi0)/r0 to _LAUNCH_CONDITION_TOLERANCE, or -1."""
    for i in range(escapes.size):
        phi, r, t = _at(elevation, i), _at(radius, i), _at(tau, i)
        if not _in_domain(
            _at(speed, i), phi, _at(beta, i), t, r, _at(drive_scale, i), _at(decay_scale, i)
        ):
            return i
        sin_phi, cos_phi = math.sin(phi), math.cos(phi)
        tan_phi = sin_phi / cos_phi
        h0 = _at(speed, i) * r * cos_phi  # eq 6.13
        h_inf = h0 * math.exp(-_at(beta, i) * _at(decay_scale, i))  # eq 3.23
        c3 = earth.GM_M3_S2 / (h_inf * h_inf)  # eq 6.8; inf if h_inf underflows
        ratio = -2 * _at(beta, i) * _at(drive_scale, i)
        total, moment, constant = _amplitudes(table, i, c3, ratio, t)
        inverse_radius = 1 / r  # u(0)
        c2 = inverse_radius - total
        c1 = -tan_phi * inverse_radius + moment
        # At a grazing elevation beta (eq 3.22) makes h_inf underflow, or the constants so
        # large that they cancel to no significant digit: u(0) and u'(0) say so (NaN fails).
        tolerance = _LAUNCH_CONDITION_TOLERANCE * inverse_radius
        if not (
            abs(c2 + total - inverse_radius) <= tolerance
            and abs(c1 - moment + tan_phi * inverse_radius) <= tolerance
        ):
            return i
        table[_H0, i], table[_H_INF, i], table[_C1, i], table[_C2, i] = h0, h_inf, c1, c2
        _conic(table, i, t, r, constant, escapes)
    return -1


@jit(inline=True)
def _amplitudes(table, i, c3, ratio, tau):
    """A_n = c3 ratio^n / (n! (1 + n^2 tau^2)) into launch ``i``'s column of ``table``, ratio =
    -2 beta (eqs 6.8-6.10 for n = 0, 1, 2). Returns sum_n A_n, sum_n n tau A_n and the sum of
    the terms that do not decay."""
    power = factorial = 1.0
    total = moment = constant = 0.0
    for n in range(table.shape[0] - AMPLITUDES_ROW):
        rate = n * tau
        amplitude = c3 * power / (factorial * (1 + rate * rate))
        table[AMPLITUDES_ROW + n, i] = amplitude
        total += amplitude
        moment += rate * amplitude
        if rate == 0:
            constant += amplitude
        power *= ratio
        factorial *= n + 1
    return total, moment, constant


@jit(inline=True)
def _conic(table, i, tau, radius, constant, escapes):
    """From launch ``i``'s c1 and c2 in ``table`` (``constant`` the sum of the terms that do not
    decay): rho, eq 6.4's apse, the eccentricity of the conic it ends on, whether it escapes
    on it (into ``escapes``) and eq 6.5's apogee altitude (NaN if it escapes)."""
    c1, c2 = table[_C1, i], table[_C2, i]
    # sqrt, not hypot (3 ns more): c1 and c2 are far from overflowing once they pass
    table[_RHO, i] = rho = math.sqrt(c1 * c1 + c2 * c2)
    # eq 6.4, where the conic is least. atan(c1/c2) would save 5 ns but moves the angle by
    # an ulp, and the improved MKS's re-entry march of an HP round at 40 deg by 2e-9 of its
    # loss (from 4e-11 against scipy's DOP853 at rtol 1e-12)
    table[_APSE, i] = apse = math.atan2(-c1, -c2)
    table[_ECCENTRICITY, i] = eccentricity = rho / constant
    escapes[i] = False
    if eccentricity >= 1.0:  # an open conic: escapes if aloft and climbing once the drive died
        late = _LATE_DECAY_EXPONENT / tau if tau > 0 else 0.0
        u, slope, _ = point(table, i, tau, late)
        escapes[i] = u <= 1 / radius and slope < 0
    table[_APOGEE_6_4, i] = (
        math.nan if escapes[i] else 1.0 / u_at(table, i, tau, apse) - radius
    )  # eq 6.5


@jit
def _converged(step, previous):
    """Whether Newton's iteration has converged, given its last two steps (rad). It converges
    quadratically until rounding dominates the function it zeroes; from there the steps
    stop shrinking (the impact's u - 1/r0 cancels to a few 1e-15 rad) and go on no further."""
    return abs(step) < _NEWTON_STEP_RAD or _NEWTON_NOISE_RAD > abs(step) >= abs(previous)


@jit
def find_apogees(table, tau, radius, escapes, angle, altitude):
    """Every launch's first zero of du/dtheta into ``angle``, by Newton's iteration from eq
    6.4's angle, and the altitude there into ``altitude`` (NaN for a launch that escapes);
    the index of the first launch whose iteration leaves the finite numbers, or -1."""
    for i in range(escapes.size):
        angle[i] = altitude[i] = math.nan
        if escapes[i]:
            continue
        rate, theta, step = _at(tau, i), table[_APSE, i], math.inf
        for _ in range(_NEWTON_ITERATIONS):
            u, slope, curvature = point(table, i, rate, theta)
            previous, step = step, np.divide(slope, curvature)
            theta -= step
            if not math.isfinite(theta):
                return i
            if _converged(step, previous):
                break  # where u' = 0 a step this small moves u less than its rounding
        if not _converged(step, previous):
            u = u_at(table, i, rate, theta)
        angle[i], altitude[i] = theta, np.divide(1.0, u) - _at(radius, i)
    return -1


@jit
def find_impacts(table, tau, radius, escapes, apogee_angle, angle):
    """Every launch's return to its launch radius into ``angle``, by Newton's iteration from
    twice its apogee angle (a symmetric conic's return; NaN for a launch that escapes); the
    index of the first launch whose iteration leaves the finite numbers, or -1."""
    for i in range(escapes.size):
        angle[i] = math.nan
        if escapes[i]:
            continue
        rate, inverse_radius = _at(tau, i), 1 / _at(radius, i)
        theta, step = 2 * apogee_angle[i], math.inf
        for _ in range(_NEWTON_ITERATIONS):
            u, slope, _ = point(table, i, rate, theta)
            previous, step = step, np.divide(u - inverse_radius, slope)
            theta -= step
            if not math.isfinite(theta):
                return i
            if _converged(step, previous):
                break
        angle[i] = theta
    return -1


@jit
def crossing_angle(table, i, tau, low, high, target_u, sign):
    """The angle in [low, high] where launch ``i``'s u = 1/r equals ``target_u``: u rises
    through it on the descending branch (``sign`` +1: from the apogee to the impact) and
    falls through it on the ascending one (-1: from the muzzle to the apogee). Newton's
    iteration from the branch's far end, kept inside the bracket by bisection."""
    theta = high if sign > 0 else low
    for _ in range(_CROSSING_ITERATIONS):
        u, slope, _ = point(table, i, tau, theta)
        excess = u - target_u
        if sign * excess > 0:  # past the crossing
            high = theta
        else:
            low = theta
        step = theta if excess == 0 else theta - excess / slope
        new = step if low < step < high else 0.5 * (low + high)
        done = abs(new - theta) <= _CROSSING_TOLERANCE_RAD
        theta = new
        if done:
            break
    return theta


@jit
def _interval_time(table, i, tau, growth, low, high, nodes, weights):
    """Eq 3.32's time (s) of launch ``i`` from angle ``low`` to ``high``: Gauss-Legendre on the
    ``nodes`` and ``weights`` of dtheta / (u^2 h), h = h_inf exp(growth e^{-tau theta}) (eq 3.23,
    ``growth`` = beta x decay scale)."""
    half = 0.5 * (high - low)
    total = 0.0
    for j in range(nodes.size):
        theta = low + half * (nodes[j] + 1.0)
        u = u_at(table, i, tau, theta)
        momentum = table[_H_INF, i] * math.exp(growth * math.exp(-tau * theta))
        total += weights[j] / (u * u * momentum)
    return half * total


#: Where :func:`time_to` breaks its intervals, in units of 1/tau: the driving terms' decay
#: e^{-tau theta} sets the integrand's fastest variation (within 20/tau it has died to e^-20;
#: past it u is a conic and h constant to 2e-9). With 8 points each, the time of flight to
#: the impact agrees with 4,000 equal intervals to 1 ns over 1-89.8 deg for HP, LP and the
#: baseline from Barbados (16 equal intervals: 0.2 ns, for 128 evaluations against 40); with
#: 6 points, to 0.12 us.
_TIME_BREAKS = (1.0, 3.0, 8.0, 20.0)


@jit
def time_to(table, i, tau, growth, theta, nodes, weights):
    """Eq 3.32's time of flight (s) of launch ``i`` from launch to the angle ``theta``: one
    ``_interval_time()`` per interval between the breaks of ``_TIME_BREAKS`` below it."""
    total = low = 0.0
    for mark in _TIME_BREAKS:
        high = mark / tau
        if high >= theta:
            break
        total += _interval_time(table, i, tau, growth, low, high, nodes, weights)
        low = high
    return total + _interval_time(table, i, tau, growth, low, theta, nodes, weights)


@jit
def _times(table, tau, growth, theta, nodes, weights, out):
    """Time of flight (s) into ``out`` (m, k) to every angle of ``theta`` (rows or 1, k; sorted
    and non-negative), one ``_interval_time()`` per interval from the angle before (from 0 to
    the first), for launch i on row i (or the single launch on every row)."""
    for i in range(out.shape[0]):
        launch, row = min(i, table.shape[1] - 1), min(i, theta.shape[0] - 1)
        rate, rise = _at(tau, launch), _at(growth, launch)
        previous = total = 0.0
        for j in range(out.shape[1]):
            total += _interval_time(
                table, launch, rate, rise, previous, theta[row, j], nodes, weights
            )
            out[i, j], previous = total, theta[row, j]


@jit
def _solve_through_impact(
    speed, elevation, beta, tau, radius, drive_scale, decay_scale, table, escapes, apogee, impact
):
    """:func:`solve_constants`, then :func:`find_apogees` into ``apogee`` (angle, altitude) and
    :func:`find_impacts` into ``impact``, in one call. Returns how far it got: 0 if the constants
    fail, 1 if the apogee's iteration does, 2 if the impact's does, 3 if none fails."""
    if (
        solve_constants(
            speed, elevation, beta, tau, radius, drive_scale, decay_scale, table, escapes
        )
        >= 0
    ):
        return 0
    if find_apogees(table, tau, radius, escapes, apogee[0], apogee[1]) >= 0:
        return 1
    if find_impacts(table, tau, radius, escapes, apogee[0], impact) >= 0:
        return 2
    return 3


@jit
def _evaluate(table, tau, theta, out):
    """u, du/dtheta and d2u/dtheta2 into ``out`` (3, rows, k) at ``theta`` (rows or 1, k), for
    launch i on row i (or for the single launch on every row)."""
    for i in range(out.shape[1]):
        launch, row = min(i, table.shape[1] - 1), min(i, theta.shape[0] - 1)
        rate = _at(tau, launch)
        for j in range(out.shape[2]):
            out[0, i, j], out[1, i, j], out[2, i, j] = point(table, launch, rate, theta[row, j])


@jit
def _outside_validity(beta, radius, escapes, apogee):
    """Whether any launch escapes, has beta above BETA_VALIDITY_LIMIT, an apogee (NaN if it
    escapes) beyond the Earth's sphere of influence, or one inside the sensible atmosphere."""
    escaping = high_drag = beyond = low = False
    for i in range(escapes.size):
        escaping |= escapes[i]
        high_drag |= _at(beta, i) > BETA_VALIDITY_LIMIT
        beyond |= apogee[i] + _at(radius, i) > EARTH_SPHERE_OF_INFLUENCE_M
        low |= apogee[i] <= SENSIBLE_ATMOSPHERE_M
    return escaping, high_drag, beyond, low


def _columns(values: list) -> tuple:
    """The kernels' arguments and the attributes' columns of the launches' ``values``, whether
    they are one launch, and how many. The kernels take each argument once (a number) or once
    per launch, shape (1,) or (m,); the attributes are (m, 1). A single launch's are rows of one
    array."""
    if np.ndarray in map(type, values):
        return _array_columns(values)
    columns = np.array(values, dtype=float).reshape(len(values), 1, 1)  # one launch of numbers
    return columns[:, 0], columns, True, 1


def _count(arguments: tuple, values: list) -> int:
    """How many launches ``arguments`` (``values`` as arrays of at least one dimension) hold:
    the length of those not of shape (1,), which must share it and be 1-D."""
    lengths = {value.shape for value in arguments} - {(1,)}
    if len(lengths) > 1 or any(len(length) > 1 for length in lengths):
        raise ValueError(
            "the launches' arguments must be numbers or 1-D arrays of one length; got "
            f"shapes {[np.shape(value) for value in values]}"
        )
    return lengths.pop()[0] if lengths else 1


def _array_columns(values: list) -> tuple:
    """:func:`_columns` of ``values`` of which some are arrays."""
    arguments = tuple(np.array(value, dtype=float, ndmin=1) for value in values)
    count = _count(arguments, values)
    single = all(np.ndim(value) == 0 for value in values)
    columns = tuple(
        (value if value.size == count else np.broadcast_to(value, (count,)))[:, None]
        for value in arguments
    )
    return arguments, columns, single, count


class ModifiedKeplerSolution:
    """The MKS of one or many launches (arguments broadcast to shape (m,)).

    Functions of the angular range take ``theta_rad`` of shape (k,) and return (k,) for a
    single launch or (m, k) for many; ``theta_rad`` may also be (m, k), one row per launch.
    ``asymptotic_eccentricity`` (m,) is that of the conic the solution ends on, and
    ``escapes`` (m,) marks launches that leave on an open one: their apogee and impact are NaN.
    Constants that cannot reproduce the launch conditions (a grazing elevation) raise.

    The per-launch work (constants, checks, apogee, impact) runs compiled (:func:`warm_up`
    compiles it ahead of use). The constants' attributes are read-only views.
    """

    def __init__(
        self,
        speed_m_s,
        elevation_rad,
        beta,
        tau,
        *,
        n_terms: int = 3,
        radius_m=earth.RADIUS_M,
        drive_scale=1.0,
        decay_scale=1.0,
        warn: bool = True,
    ):
        arguments = {
            "speed_m_s": speed_m_s,
            "elevation_rad": elevation_rad,
            "beta": beta,
            "tau": tau,
            "radius_m": radius_m,
            "drive_scale": drive_scale,
            "decay_scale": decay_scale,
        }
        values = [_argument(value, name) for name, value in arguments.items()]
        valid = type(n_terms) is int and 1 <= n_terms <= MAX_TERMS  # a batch's fast path
        self.n_terms = n_terms if valid else check_n_terms(n_terms)
        self._arguments, columns, self.single, count = _columns(values)
        (
            self.speed_m_s,
            self.elevation_rad,
            self.beta,
            self.tau,
            self.radius_m,
            self.drive_scale,
            self.decay_scale,
        ) = columns
        self._table = np.empty((AMPLITUDES_ROW + self.n_terms, count))
        self.escapes = np.empty(count, dtype=bool)
        if self.single:  # a kernel's call costs more than the apogee's and impact's iterations
            failed = self._solve_single()
        else:
            failed = solve_constants(*self._arguments, self._table, self.escapes)
        if failed >= 0:
            self._unusable(failed, arguments)
        if warn:
            self._warn_outside_validity()

    def _solve_single(self) -> int:
        """The constants, apogee and impact of a single launch in one kernel's call; the apogee
        and impact go to their cached properties (a failed iteration raises when one is asked
        for). Returns :func:`solve_constants`'s index of a failed launch, or -1."""
        apogee, impact = np.empty((2, 1)), np.empty(1)
        reached = _solve_through_impact(*self._arguments, self._table, self.escapes, apogee, impact)
        failed = 0 if reached == 0 else -1
        # cached_property's own storage
        if reached >= 2:
            self.__dict__["_first_zero_apogee"] = apogee
            if apogee[0, 0] < 0.0:
                raise ValueError(
                    f"the MKS has no ascent at elevation_rad = "
                    f"{self.elevation_rad[0, 0]:.6g} "
                    f"({math.degrees(self.elevation_rad[0, 0]):.6g} deg): beta = "
                    f"{self.beta[0, 0]:.3g} (eq 3.22) is so large that its solution "
                    "descends from the muzzle (its apogee lies behind the gun); the text "
                    "keeps beta below 0.25: raise the elevation or the speed"
                )
        if reached == 3:
            self.__dict__["impact_angle"] = impact[0]
        return failed

    def _unusable(self, failed: int, arguments: dict) -> None:
        """Raise for launch ``failed``: an argument outside its domain, named, or constants that
        cannot reproduce its launch conditions."""
        for name, value in arguments.items():  # an argument outside its domain, named
            _checked(value, name)
        elevation = self.elevation_rad[failed, 0]
        cause = (
            "h0 = V r0 cos(elevation) (eq 6.13) all but vanishes, so its constants cancel "
            "to no significant digit; lower the elevation"
            if elevation > math.pi / 4
            else f"beta = {self.beta[failed, 0]:.4g} (eq 3.22, which grows as 1/sin of the "
            "elevation) makes h_inf = h0 exp(-beta) underflow or its constants cancel to no "
            "significant digit; raise the elevation"
        )
        raise ValueError(
            f"the MKS has no usable closed form at elevation_rad = {elevation:.6g} "
            f"({math.degrees(elevation):.6g} deg): {cause}"
        )

    # --- the constants, shapes (m, 1) unless said ------------------------------------------
    @property
    def h0(self):
        """Launch angular momentum h0 = V r0 cos(phi0) (m^2/s), eq 6.13."""
        return _read_only(self._table[_H0, :, None])

    @property
    def h_inf(self):
        """Asymptotic angular momentum h_inf = h0 exp(-beta decay_scale) (m^2/s), eq 3.23."""
        return _read_only(self._table[_H_INF, :, None])

    @property
    def c3(self):
        """c3 = GM / h_inf^2 (1/m), eq 6.8: the amplitude of the series' first term."""
        return _read_only(self._table[AMPLITUDES_ROW, :, None])

    @property
    def amplitudes(self):
        """A_n, shape (m, N): the amplitudes of the series' terms e^{-n tau theta}."""
        return _read_only(self._table[AMPLITUDES_ROW:].T)

    @property
    def rates(self):
        """n tau, shape (m, N): the decay rates of the series' terms."""
        return np.arange(self.n_terms) * self.tau

    @property
    def c1(self):
        """c1 (1/m) of u = c1 sin(theta) + c2 cos(theta) + ..., set by u'(0) = -tan(phi0)/r0."""
        return _read_only(self._table[_C1, :, None])

    @property
    def c2(self):
        """c2 (1/m), set by u(0) = 1/r0."""
        return _read_only(self._table[_C2, :, None])

    @property
    def kernel_table(self):
        """The constants of every launch as the compiled kernels take them (module docstring):
        one column per launch, rows h0, h_inf, c1, c2, rho, eq 6.4's angle, the asymptotic
        eccentricity, eq 6.4's apogee, then the amplitudes from :data:`AMPLITUDES_ROW`."""
        return _read_only(self._table[:])

    @property
    def asymptotic_eccentricity(self):
        """Eccentricity (m,) of the conic the solution ends on."""
        return _read_only(self._table[_ECCENTRICITY])

    # --- the solution and its derivatives ----------------------------------------------------
    def _out(self, value):
        return value[0] if self.single else value

    def _theta(self, theta_rad):
        theta = finite_array(theta_rad, "theta_rad")
        return theta if theta.ndim == 2 else np.atleast_1d(theta)[None, :]

    def _solution(self, theta_rad):
        """u, du/dtheta and d2u/dtheta2 at ``theta_rad``, shapes (m, k), from one evaluation."""
        theta = np.ascontiguousarray(self._theta(theta_rad))
        launches = self._table.shape[1]
        rows = max(launches, theta.shape[0])
        if {launches, theta.shape[0]} - {1, rows}:
            raise ValueError(
                f"theta_rad has {theta.shape[0]} rows for {launches} launches; "
                "expected one row, or one per launch"
            )
        out = np.empty((3, rows, theta.shape[1]))
        _evaluate(self._table, self._arguments[3], theta, out)
        return out

    def u(self, theta_rad):
        """u = 1/r (1/m) at angular range ``theta_rad`` (eq 3.30's solution)."""
        return self._out(self._solution(theta_rad)[0])

    def du_dtheta(self, theta_rad):
        """du/dtheta (1/m per rad), eq 6.1 for three terms."""
        return self._out(self._solution(theta_rad)[1])

    def d2u_dtheta2(self, theta_rad):
        return self._out(self._solution(theta_rad)[2])

    def radius(self, theta_rad):
        """Distance from the Earth's centre (m)."""
        return 1.0 / self.u(theta_rad)

    def altitude(self, theta_rad):
        """Height above the spherical Earth (m)."""
        return self.radius(theta_rad) - self._out(self.radius_m)

    def angular_momentum(self, theta_rad):
        """Specific angular momentum h = h_inf exp(beta gamma), gamma = e^{-tau theta} (eq 3.23)."""
        theta = self._theta(theta_rad)
        return self._out(
            self.h_inf * np.exp(self.beta * self.decay_scale * np.exp(-self.tau * theta))
        )

    def speed(self, theta_rad):
        """Speed (m/s) from eq 4.2: V = h sqrt(u^2 + (du/dtheta)^2)."""
        u, slope, _ = self._solution(theta_rad)
        return self.angular_momentum(theta_rad) * self._out(np.hypot(u, slope))

    def flight_path_angle(self, theta_rad):
        """Angle of the velocity above the horizontal, tan(phi) = -u'/u (eq 3.28)."""
        u, slope, _ = self._solution(theta_rad)
        return self._out(np.arctan2(-slope, u))

    # --- apogee, impact, time ----------------------------------------------------------------
    @cached_property
    def apogee_angle_eq_6_4(self):
        """Eq 6.4: theta_apogee = atan(c1/c2), the apogee with the driving terms dropped.

        Taken on the branch where c1 sin(theta) + c2 cos(theta) is least, atan2(-c1, -c2):
        on a suborbital flight c2 < 0 (c3 = GM/h^2 exceeds 1/r0) and this is the printed
        principal branch; a launch whose horizontal speed exceeds the circular speed has
        c2 > 0 and its apogee beyond a quarter of the way round, where the principal branch
        would give the perigee's direction instead."""
        return self._out(self._table[_APSE].copy())

    @cached_property
    def _first_zero_apogee(self):
        """(angle, altitude) of every launch's first zero of du/dtheta, shapes (m,)."""
        angle, altitude = np.empty((2, self._table.shape[1]))
        failed = find_apogees(
            self._table, self._arguments[3], self._arguments[4], self.escapes, angle, altitude
        )
        self._newton_failed("apogee", failed)
        return angle, altitude

    @property
    def apogee_angle(self):
        """The first zero of du/dtheta (rad), by Newton iteration from eq 6.4; NaN for a launch
        that escapes (``escapes``)."""
        return self._out(self._first_zero_apogee[0].copy())

    def _newton_failed(self, what, index):
        """ValueError naming the elevation if Newton's iteration for ``what`` has left the
        finite numbers at launch ``index`` (-1: it has not)."""
        if index >= 0:
            raise ValueError(
                f"the MKS {what} could not be found at elevation_rad = "
                f"{self.elevation_rad[index, 0]:.6g}, beta = {self.beta[index, 0]:.4g}"
            )

    def _rows(self, function, theta_column):
        value = function(theta_column)
        return np.atleast_2d(value).reshape(theta_column.shape)

    def apogee_altitude(self, method: str = "first_zero"):
        """Apogee height (m): at the first zero of du/dtheta, or at eq 6.4's angle (eq 6.5);
        NaN for a launch that escapes (``escapes``).

        Parameters
        ----------
        method : str
            "first_zero" (the apogee of the series itself) or "eq_6_4" (the text's closed-form
            angle, as Chapter 6 predicts the HARP apogees).

        Returns
        -------
        float or numpy.ndarray
            Height above the launch site's sphere (m): a number for a single launch, an array
            (m,) for many.
        """
        if method == "first_zero":
            altitude = self._first_zero_apogee[1]
        elif method == "eq_6_4":
            altitude = self._table[_APOGEE_6_4]
        else:
            raise ValueError(f"unknown method {method!r}; expected 'first_zero' or 'eq_6_4'")
        return altitude[0] if self.single else altitude.copy()

    @cached_property
    def impact_angle(self):
        """Angular range (rad) where the descending solution returns to the launch radius; NaN
        for a launch that escapes (``escapes``)."""
        angle = np.empty(self._table.shape[1])
        failed = find_impacts(
            self._table,
            self._arguments[3],
            self._arguments[4],
            self.escapes,
            self._first_zero_apogee[0],
            angle,
        )
        self._newton_failed("impact", failed)
        angle.flags.writeable = False  # cached: a caller's edit would corrupt it
        return self._out(angle)

    def sample(self, theta_rad, order: int = 3) -> dict:
        """A whole trajectory at the (sorted) angles ``theta_rad`` in one pass: arrays of
        ``theta_rad``, ``ground_range_m``, ``altitude_m``, ``speed_m_s``,
        ``flight_path_angle_rad`` and ``time_s`` (named as in :mod:`.trajectory`)."""
        u, slope, _ = self._solution(theta_rad)
        h = self.angular_momentum(theta_rad)
        theta = self._out(self._theta(theta_rad))
        return {
            "theta_rad": theta,
            "ground_range_m": theta * self._out(self.radius_m),
            "altitude_m": self._out(1 / u - self.radius_m),
            "speed_m_s": h * self._out(np.hypot(u, slope)),
            "flight_path_angle_rad": self._out(np.arctan2(-slope, u)),
            "time_s": self.time(theta_rad, order),
        }

    def time(self, theta_rad, order: int = 3):
        """Time of flight (s) from launch to each ``theta_rad`` (sorted, starting anywhere >= 0),
        eq 3.32: t = integral of dtheta / (u^2 h), by ``order``-point Gauss-Legendre on every
        interval between consecutive angles (and from 0 to the first). On a grid of a few
        hundred angles three points per interval are converged to nanoseconds (tests); ask for
        the time at a single far angle and one three-point interval spans the whole flight:
        pass the grid and read its last value instead."""
        theta = np.ascontiguousarray(self._theta(theta_rad), dtype=float)
        count = self._table.shape[1]
        if theta.shape[0] not in (1, count):
            raise ValueError(
                f"theta_rad must have one row, or one per launch ({count}); got {theta.shape[0]}"
            )
        if theta.size and (np.any(theta[:, 0] < 0) or np.any(np.diff(theta, axis=1) < 0)):
            raise ValueError("theta_rad must be sorted and non-negative")
        nodes, weights = _gauss_legendre(int(order))
        growth = np.ascontiguousarray(np.ravel(self.beta * self.decay_scale))
        out = np.empty((count, theta.shape[1]))
        _times(self._table, self._arguments[3], growth, theta, nodes, weights, out)
        return self._out(out)

    # --- validity ------------------------------------------------------------------------------
    def _warn_outside_validity(self):
        apogee = self._first_zero_apogee[1]  # NaN, failing every comparison, if it escapes
        escaping, high_drag, beyond, low = _outside_validity(
            self._arguments[2], self._arguments[4], self.escapes, apogee
        )
        if escaping:
            i = int(np.argmax(self.escapes))
            warnings.warn(
                f"MKS launch at {self.speed_m_s[i, 0]:.6g} m/s escapes: the asymptotic angular "
                f"momentum h_inf = {self.h_inf[i, 0]:.4g} m^2/s gives an escape orbit "
                f"(eccentricity {self.asymptotic_eccentricity[i]:.4g} >= 1), with no apogee "
                "or impact (apogee and impact are NaN)",
                ModelValidityWarning,
                stacklevel=3,
            )
        if high_drag:
            warnings.warn(
                f"MKS beta = {self.beta.max():.3g} > {BETA_VALIDITY_LIMIT}: the text finds "
                "the solution inaccurate for such high-drag projectiles (Ch. 4 B)",
                HighDragWarning,
                stacklevel=3,
            )
        if beyond:
            far = apogee + self.radius_m[:, 0] > EARTH_SPHERE_OF_INFLUENCE_M
            warnings.warn(
                f"MKS apogee {apogee[far].max() / 1e3:.4g} km lies beyond the Earth's sphere "
                f"of influence ({EARTH_SPHERE_OF_INFLUENCE_M / 1e3:.4g} km from its centre): "
                "a near-escape launch (eccentricity "
                f"{self.asymptotic_eccentricity[far].max():.4g}) that the "
                "Sun and Moon perturb, which no Kepler orbit about the Earth describes",
                ModelValidityWarning,
                stacklevel=3,
            )
        if low:
            warnings.warn(
                f"MKS apogee {np.nanmin(apogee) / 1e3:.1f} km does not leave the "
                f"sensible atmosphere (below {SENSIBLE_ATMOSPHERE_M / 1e3:g} km), where "
                "the straight-line drag assumption fails (Ch. 3)",
                ModelValidityWarning,
                stacklevel=3,
            )


def gun_density_kg_m3(launch: Launch | Launches):
    """rho0 of the MKS for ``launch``: its air is eq 3.11's, rho0 exp(-k a) with rho0 =
    1.225 kg/m^3 (Chapter 3 B's fit to the 1976 standard atmosphere), taken at the site's
    altitude, whatever air the simulations fly, with the day's density change; none in a
    vacuum launch. A float for a :class:`~harp_analysis.models.launch.Launch`, an array (n,) for
    :class:`~harp_analysis.models.launch.Launches`."""
    if get_atmosphere(launch.atmosphere).density(0.0) == 0.0:
        return 0.0 if isinstance(launch, Launch) else np.zeros(len(launch))
    if isinstance(launch, Launch):
        return (
            launch.day[0]
            * SEA_LEVEL_DENSITY_KG_M3
            * math.exp(-TEXT_DECAY_CONSTANT_PER_M * launch.site_altitude_m)
        )
    density = (
        launch.day[0]
        * SEA_LEVEL_DENSITY_KG_M3
        * np.exp(-TEXT_DECAY_CONSTANT_PER_M * launch.compact("site_altitude_m"))
    )
    return np.broadcast_to(density, (len(launch),))


def for_launch(
    launch,
    *,
    n_terms: int = 3,
    decay_constant_per_m: float = TEXT_DECAY_CONSTANT_PER_M,
    warn: bool = True,
) -> ModifiedKeplerSolution:
    """The non-rotating MKS of ``launch``: a :class:`~harp_analysis.models.launch.Launch`, or many
    solved together, as :class:`~harp_analysis.models.launch.Launches` or a sequence of Launch
    sharing a projectile and an atmosphere. Cd0 of the projectile's drag law at the launch Mach
    number, rho0 of the launch's air at the gun, k of eq 3.11 (Chapter 3 B), r0 = R + the
    site's altitude. The MKS is planar and drag-only: a wind is ignored with a warning, and a
    rotating Earth is :func:`harp_analysis.engines.eci.correction_for_launch`'s.

    Parameters
    ----------
    launch : Launch or Launches or sequence of Launch
        One launch, or many solved at once (one projectile, one atmosphere), each on a
        non-rotating Earth (a ValueError otherwise) and below the vertical.
    n_terms : int
        Terms of the series of eq 3.30 (the text's three-term MKS by default).
    decay_constant_per_m : float
        k of eq 3.11's exponential air (1/m; the text's 0.117 /km by default).
    warn : bool
        Warn of a wind left out and where a launch leaves the MKS's validity (beta above 0.25,
        escape, an apogee in the sensible atmosphere).

    Returns
    -------
    ModifiedKeplerSolution
        The closed-form trajectory of every launch: apogee, impact, time of flight and the
        state at any angular range, as numbers for one Launch or arrays (m,) for many.
    """
    decay = positive_scalar(decay_constant_per_m, "decay_constant_per_m", "1/m")
    single = isinstance(launch, Launch)
    launches = Launches.from_launches(launch)
    launches.require_zero(
        "MKS",
        "rotation_rate_rad_s",
        reason="the MKS is non-rotating; eci.correction_for_launch corrects it",
    )
    vertical = launches.elevation_deg >= 90.0
    if vertical.any():
        raise ValueError(
            f"the MKS cannot fly launch.elevation_deg = 90 (launch {np.argmax(vertical)}): a "
            "vertical shot has no angular momentum and tau = k r0 tan(phi0) (eq 3.27) is infinite"
        )
    if warn:
        launches.warn_ignored(
            "MKS", "cross_wind_m_s", "head_wind_m_s", reason="the MKS has no wind (Chapter 3)"
        )
    projectile = launches.projectile
    elevation = np.radians(launches.compact("elevation_deg"))
    radius = earth.RADIUS_M + launches.compact("site_altitude_m")
    beta = decay_factor_beta(
        launches.launch_drag_coefficient,
        gun_density_kg_m3(launches),
        projectile.reference_area_m2,
        projectile.mass_kg,
        elevation,
        decay,
    )
    tau = decay_rate_tau(elevation, decay, radius)
    count = len(launches)

    def column(values):  # one number where the launches share it (the class broadcasts)
        values = np.asarray(values)
        if single or values.size == 1:
            return float(values.flat[0])
        return np.ascontiguousarray(values)

    return ModifiedKeplerSolution(
        column(launches.compact("speed_m_s")),
        column(np.broadcast_to(elevation, (count,))),  # every launch's: the solution's shape
        column(beta),
        column(tau),
        n_terms=n_terms,
        radius_m=column(radius),
        warn=warn,
    )


def simulate_mks(
    launch: Launch,
    *,
    n_terms: int = 3,
    n_points: int = 400,
    decay_constant_per_m: float = TEXT_DECAY_CONSTANT_PER_M,
    warn: bool = True,
) -> pd.DataFrame:
    """The MKS of ``launch`` (:func:`for_launch`) as the engines' trajectory table, launch to
    impact at ``n_points`` equal steps of angular range plus the apogee, with the shared
    metadata (no right-hand side is evaluated: ``rhs_evaluations = steps = 0``).

    Positions are Earth-centred (z north, x toward longitude 0) in the launch plane; Mach is
    the speed over the launch atmosphere's speed of sound; the drag coefficient is the MKS's
    constant Cd0 and drag/gravity is its drag in eq 3.11's air, rho0 exp(-k a).

    Parameters
    ----------
    launch : Launch
        The launch (its wind and spin are left out, with a warning: the MKS has none).
    n_terms : int
        Terms of the series of eq 3.30 (the text's three-term MKS by default).
    n_points : int
        Equal steps of angular range from launch to impact.
    decay_constant_per_m : float
        k of eq 3.11's exponential air (1/m; the text's 0.117 /km by default).
    warn : bool
        Warn where the launch leaves the MKS's validity (beta above 0.25, escape, an apogee
        in the sensible atmosphere).

    Returns
    -------
    pandas.DataFrame
        The MKS's flight as the engines' trajectory table
        (:mod:`harp_analysis.models.trajectory`), ``n_points`` rows in equal steps of angular
        range, with what every engine records in ``frame.attrs``.
    """
    count = whole_number(n_points, "n_points", low=2, high=MAX_ROWS)
    if not isinstance(launch, Launch):
        raise TypeError(f"launch must be a Launch; got {type(launch).__name__}")
    solution = for_launch(
        launch, n_terms=n_terms, decay_constant_per_m=decay_constant_per_m, warn=warn
    )
    if solution.escapes[0]:
        raise ValueError(
            f"the MKS of launch.speed_m_s = {launch.speed_m_s:g} escapes (its asymptotic "
            "conic is an escape orbit): there is no apogee or impact to tabulate"
        )
    apogee_angle = float(solution.apogee_angle)
    theta = np.union1d(np.linspace(0.0, float(solution.impact_angle), count), [apogee_angle])
    sample = solution.sample(theta)
    radius = sample["altitude_m"] + float(solution.radius_m[0, 0])
    up, downrange, _ = launch_frame(
        launch.latitude_rad, math.radians(launch.longitude_deg), launch.bearing_rad
    )
    position = radius[:, None] * (
        np.cos(theta)[:, None] * np.ravel(up) + np.sin(theta)[:, None] * np.ravel(downrange)
    )
    altitude = radius - earth.RADIUS_M
    cd0, projectile = launch.launch_drag_coefficient, launch.projectile
    density = gun_density_kg_m3(launch) * np.exp(
        -decay_constant_per_m * (altitude - launch.site_altitude_m)
    )
    drag = 0.5 * density * cd0 * projectile.reference_area_m2 * sample["speed_m_s"] ** 2
    sound = launch.air(np.maximum(altitude, 0.0))[1]
    frame = pd.DataFrame(
        {
            "time_s": sample["time_s"],
            "x_m": position[:, 0],
            "y_m": position[:, 1],
            "z_m": position[:, 2],
            "altitude_m": altitude,
            "ground_range_m": earth.RADIUS_M * theta,
            "cross_range_m": np.zeros_like(theta),
            "speed_m_s": sample["speed_m_s"],
            "mach": sample["speed_m_s"] / sound,
            "drag_coefficient": np.full_like(theta, cd0),
            "drag_to_gravity": drag / (projectile.mass_kg * earth.GM_M3_S2 / radius**2),
            "specific_angular_momentum_m2_s": solution.angular_momentum(theta),
            "flight_path_angle_rad": sample["flight_path_angle_rad"],
        }
    )
    top = frame.iloc[int(np.searchsorted(theta, apogee_angle))]
    return describe(
        frame,
        engine="MKS",
        launch=launch,
        apogee=(top.time_s, top.altitude_m, top.ground_range_m),
        impact=True,
        rhs_evaluations=0,
        steps=0,
        max_time_s=math.inf,
        n_terms=n_terms,
    )


def warm_up() -> None:
    """Compile the MKS's kernels now (or load them from the on-disk cache), not at first use."""
    one = ModifiedKeplerSolution(2000.0, 0.8, 0.1, 500.0)
    one.sample(np.linspace(0.0, one.impact_angle, 3))
    many = ModifiedKeplerSolution(2000.0, np.array([0.8, 0.9]), 0.1, 500.0)
    many.time(many.impact_angle[:, None])
    read_only = np.array([0.8, 0.9])  # for_launch passes launches' read-only columns
    read_only.setflags(write=False)
    ModifiedKeplerSolution(2000.0, read_only, 0.1, 500.0)
