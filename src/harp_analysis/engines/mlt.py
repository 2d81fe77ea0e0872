"""Modified Linear Theory (MLT): a reconstruction of Hainz and Costello (J. Guid. Control Dyn.
28(5), 2005), the third reference method of Chapters 2 and 4.

**This is a reconstruction.** The paper's equations are not public and the dissertation only
describes MLT (Chapter 1, Chapter 2 A): projectile linear theory (symmetric projectile, small
aerodynamic angles of attack, Magnus force ignored, Magnus moment kept) with the small-pitch
assumption relaxed: the pitch angle is held constant where it multiplies other states and
integrated with the trapezoid rule inside trigonometric functions, and the linear solution is
restarted every 500 m to 2 km so that density, Mach and the coefficients follow the flight.
What follows derives such a theory from the 6DOF's own equations (:mod:`.sixdof`, the no-roll
frame N of Appendix B's projectile) and the standard linear theory of the public literature
(McCoy, *Modern Exterior Ballistics*, ch. 9-10; Costello's projectile linear theory).

Equations, one by one
---------------------
States are the 6DOF's ``[x y z phi theta psi u v w p q r]``: flat-frame position (z down), the
Euler angles of N, velocity and angular velocity in N. The independent variable is the
dimensionless arc length s, ds = V dt / D (calibres), ``( )' = d/ds = (D/V) d/dt``. Let
k = pi rho D^3 / 8 and (v_w, w_w) the wind resolved in N.

(L1) Linear-theory assumptions on the 6DOF's translation and rotation equations: the lateral
     states v, w, q, r are small, so their products (the frame-rate terms q w - r v,
     r tan(theta) w, r tan(theta) v, tan(theta) r^2, tan(theta) q r, and the yaw-drag term
     CX2 (v^2 + w^2)/V^2) are dropped and u = V where u multiplies q or r (which also drops
     r u_w and q u_w, first order in the wind but a 1e-4 relative effect for 5 m/s).

(L2) Axial velocity, drag with one factor V frozen: ``u' = -a (u - u_w) + D g_u / V``,
     a = -k CX0 / m. With V and the gravity component g_u frozen over a segment this is
     linear with constant coefficients: u(s) = u0 e^{-a s} + (a u_w + D g_u/V) s phi1(-a s),
     the total velocity's closed-form decay (phi_k are the functions below).

(L3) Epicyclic states in complex form, v~ = v + i w, q~ = q + i r:
         v~' = -A v~ + i D q~ + (A v~_w + D (g_v + i g_w) / V),      A = k CNA / m,
         q~' = -i B v~ + (C + i E) q~ + i B v~_w,

     B = k CNA SLDEL / Iy (the static moment, SLDEL the centre-of-pressure arm),
     C = k D^2 CMQ / (2 Iy) (pitch damping), E = (Ix / Iy) p D / V (gyroscopic coupling).
     The 6DOF's v' = F_y/m + g_v - r u, w' = F_z/m + g_w + q u, q' = (M_y - Ix p r)/Iy,
     r' = (M_z + Ix p q)/Iy give exactly these after (L1).

(L4) Roll: ``p' = kappa p + P_d``, kappa = k D^2 CLP / (2 Ix), P_d = k D V CLDD / Ix: closed form.

(L5) Over a segment, X = [v~, q~] obeys X' = M X + F with a constant 2x2 complex matrix M and
     forcing F. Its eigenvalues lambda = m +- delta, m = (C - A + i E)/2,
     delta^2 = ((A + C + i E)/2)^2 + D B, are the fast and slow epicyclic modes (their
     imaginary parts the mode frequencies per calibre, real parts the damping rates). By
     Cayley-Hamilton every function of M is f(M) = (f(l1) + f(l2))/2 I + f[l1, l2] (M - m I),
     with the divided difference f[l1, l2] = (f(l1) - f(l2)) / (2 delta) (or f'(m) when the
     modes coincide), so

         X(s) = f0(M) X0 + f1(M) F,          integral_0^s X = f1(M) X0 + f2(M) F,

     f0(l) = e^{l s}, f_k(l) = s^k phi_k(l s), phi_k(z) = sum_n z^n / (n + k)!. No ODE solver:
     a segment is a handful of exponentials.

(L6) Attitude, the pitch angle kept constant where it multiplies: theta(s) = theta0 +
     (D/V) Re integral q~, psi(s) = psi0 + (D/V) sec(theta) Im integral q~,
     phi(s) = phi0 + (D/V) integral p (r tan(theta) dropped, L1).

(L7) Position and gravity, the pitch angle trapezoid-integrated inside the trigonometric
     functions: the rotation T(theta, psi) from the flat frame to N is replaced over a segment
     by the trapezoid mean T = (T(theta0, psi0) + T(theta1, psi1)) / 2, and
     [x y z](s) = [x y z]0 + (D/V) T^T integral_0^s [u v w] ds;
     the gravity and wind components in (L2)-(L3) are T g and T wind.

(L8) The end angles theta1, psi1 come from a first pass of the segment with T at its start;
     the second pass uses the trapezoid T. Coefficients (density, Mach, CX0 ... CLDD, V, p,
     and the gravity vector) are frozen at ``coefficients_at``: the segment's ``"start"``,
     its ``"middle"`` (from the first pass) or the ``"average"`` of start and end.

Time: with V frozen, dt = D ds / V, so a segment of ``segment_length_m`` L lasts L / V. The
Earth, gravity (central, GM/r^2, frozen per segment; ``gravity="uniform"`` keeps GM/R^2 along
the launch vertical for a flat-Earth check), atmosphere (flat or spherical altitude), wind and
M829 tables are the 6DOF's (:class:`harp_analysis.models.rigid_body.RigidBodyModel`, which both
fly), so differences between the two come from linear theory alone.

Cost: segments are sequential (each starts where the last ended), so there is nothing to
vectorise across them, and a segment's internals are 2x2 complex closed forms on which numpy's
per-call overhead would exceed the arithmetic: they run as Python scalars, which also lets
:mod:`harp_analysis.analyses.effort` count the segment loop call by call (Fig 4.7). One segment (two
coefficient evaluations, three closed-form propagations, the impact and apogee checks) takes
about 40 us; the table's rows, after the loop, run the same closed forms compiled
(:mod:`.compiled`; :func:`warm_up`). A whole HP flight at 1 km takes about 14 ms (``make
benchmark`` measures it against the 3DOF and 6DOF at each segment length).

Consequences, each checked in ``tests/test_mlt.py``:

- without aerodynamics, (L2)-(L7) are exact for constant gravity: u, v, w grow linearly in t,
  the attitude stays fixed, the position is the exact parabola at any segment length;
- as segments shrink MLT converges to its continuous limit (:func:`linear_theory_derivatives`
  integrated tightly, a diagnostic, not part of MLT), and the difference between that limit
  and the 6DOF is what the dropped products (L1) cost;
- the eigenvalues of (L5) are McCoy's epicyclic roots for the same coefficients.

Where linear theory is pushed past its assumptions: above the sensible atmosphere nothing
turns the body into the curving velocity, so v, w grow (the angle of attack reaches 12 deg for
HP); (L1) then drops products that are no longer small. A flight whose angle of attack grows
beyond :data:`MAX_SMALL_ANGLE_DEG`, or whose epicyclic modes grow (a dynamically unstable
projectile), while the dynamic pressure is above :data:`DENSE_AIR_PA` (where aerodynamic loads
act on it) gets a ``ModelValidityWarning``, as do segments over :data:`MAX_SEGMENT_LENGTH_M`.
The re-entry is checked too: above about 55 deg (HP) or 65 deg (LP) the body keeps its
attitude through the vacuum arc and comes back down broadside or backwards (an angle of attack
beyond 90 deg); linear theory cannot turn it into the wind as the 6DOF does, and its flight
bounces off the thin air above 60 km and climbs again. A flight that climbs back more than
:data:`REBOUND_M` after its apogee is warned of by name, wherever the air is.
"""

from __future__ import annotations

import cmath
import math
import warnings
from typing import NamedTuple

import numpy as np
import pandas as pd
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from ..foundation import earth
from ..foundation.compiled import formula, jit
from ..foundation.counting import Counted
from ..foundation.validation import (
    Bounds,
    ModelValidityWarning,
    check_choice,
    positive_scalar,
)
from ..models.atmosphere import get_atmosphere
from ..models.launch import HP_CHAPTER_2, Launch
from ..models.rigid_body import (
    DENSITY_ALTITUDES,
    RigidBodyKernel,
    RigidBodyModel,
    altitude_and_range,
    flight_table,
    launch_state,
    rigid_body_launch,
    trajectory_table,
)
from ..models.trajectory import TruncatedFlightWarning, describe, output_times
from . import kepler

__all__ = [
    "SEGMENT_LENGTH_M",
    "MAX_SEGMENT_LENGTH_M",
    "COEFFICIENT_POINTS",
    "GRAVITY_MODELS",
    "MAX_SMALL_ANGLE_DEG",
    "DENSE_AIR_PA",
    "REBOUND_M",
    "MAX_SEGMENTS",
    "MAX_PITCH_CHANGE_RAD",
    "MIN_SEGMENTS",
    "SegmentCoefficients",
    "segment_coefficients",
    "epicyclic_roots",
    "propagate_segment",
    "simulate_mlt",
    "linear_theory_derivatives",
    "simulate_linear_theory_limit",
    "counted_functions",
    "DIAGNOSTICS",
    "SEGMENT_LOOP",
    "warm_up",
]

SEGMENT_LENGTH_M = 1000.0
COEFFICIENT_POINTS = ("start", "middle", "average")
GRAVITY_MODELS = ("central", "uniform")
MAX_SMALL_ANGLE_DEG = 10.0
MAX_SEGMENT_LENGTH_M = 10_000.0
DENSE_AIR_PA = 1000.0
#: A flight that climbs back this far after its apogee (far beyond the centimetres of the
#: closed forms' kinks at segment ends) is flying outside linear theory (:func:`simulate_mlt`).
REBOUND_M = 100.0
#: The most segments a flight may need: about 8 s of linear solutions.
MAX_SEGMENTS = 200_000
#: Beyond this change of pitch within one segment (about 15 deg: a slow shot near its apex) the
#: segment's frozen speed, coefficients and trapezoid rotation (L7-L8) no longer stand for it.
MAX_PITCH_CHANGE_RAD = 0.25
#: A flight of fewer segments is a few frozen linear solutions end to end (a slow, flat shot
#: of a kilometre or two at the default 1 km).
MIN_SEGMENTS = 4

_R = earth.RADIUS_M
_GM = earth.GM_M3_S2
# phi_3(z) = sum_n z^n / (n + 3)! to n = 17: below 1e-19 of the sum for |z| <= 1.
_PHI3_SERIES = tuple(1.0 / math.factorial(n + 3) for n in range(18))[::-1]
# Below this |l1 - l2| s the two modes are one (confluent) within rounding: f'(m) is used.
_CONFLUENT = 1e-6


class SegmentCoefficients(NamedTuple):
    """The constants of one segment's linear system (eqs L2-L5; per calibre of arc length)."""

    speed: float  # V (m/s), air-relative
    axial_drag: float  # a = -k CX0 / m
    lift: float  # A = k CNA / m
    static_moment: float  # B = k CNA SLDEL / Iy (1/(m s) ... per calibre)
    damping: float  # C = k D^2 CMQ / (2 Iy)
    gyroscopic: float  # E = (Ix / Iy) p D / V
    roll_damping: float  # kappa = k D^2 CLP / (2 Ix)
    roll_drive: float  # P_d = k D V CLDD / Ix
    gravity: tuple  # flat-frame gravity vector (m/s^2)
    dynamic_pressure: float  # rho V^2 / 2 (Pa), for the validity check


def _rotation(theta: float, psi: float) -> tuple:
    """Rows of T(theta, psi), flat frame to N (Appendix B's TIB with phi = 0)."""
    ct, st, cp, sp = math.cos(theta), math.sin(theta), math.cos(psi), math.sin(psi)
    return ((ct * cp, ct * sp, -st), (-sp, cp, 0.0), (st * cp, st * sp, ct))


@formula
def _apply(rows: tuple, vector) -> tuple:
    first, second, third = rows
    x, y, z = vector
    return (
        first[0] * x + first[1] * y + first[2] * z,
        second[0] * x + second[1] * y + second[2] * z,
        third[0] * x + third[1] * y + third[2] * z,
    )


@formula
def _apply_transpose(rows: tuple, vector) -> tuple:
    first, second, third = rows
    x, y, z = vector
    return (
        first[0] * x + second[0] * y + third[0] * z,
        first[1] * x + second[1] * y + third[1] * z,
        first[2] * x + second[2] * y + third[2] * z,
    )


def _gravity(x: float, y: float, z: float, uniform: bool) -> tuple:
    if uniform:
        return (0.0, 0.0, _GM / _R**2)
    radius = math.sqrt(x * x + y * y + (_R - z) ** 2)
    g = _GM / radius**3
    return (-g * x, -g * y, g * (_R - z))


def segment_coefficients(
    model: RigidBodyModel, state, *, aerodynamics: bool = True, uniform_gravity: bool = False
) -> SegmentCoefficients:
    """The coefficients of eqs L2-L5 at ``state`` (12 no-roll states, see module docstring)."""
    x, y, z, _, theta, psi, u, v, w, p, _, _ = state
    rows = _rotation(theta, psi)
    u_w, v_w, w_w = _apply(rows, model.wind)
    speed = math.sqrt((u - u_w) ** 2 + (v - v_w) ** 2 + (w - w_w) ** 2)
    gravity = _gravity(x, y, z, uniform_gravity)
    gyroscopic = model.ix * p * model.d / (model.iy * speed)
    if not aerodynamics:
        return SegmentCoefficients(speed, 0.0, 0.0, 0.0, 0.0, gyroscopic, 0.0, 0.0, gravity, 0.0)
    rho, sound = model.air(x, y, z)
    cx0, _, cna, _, cmq, clp, cldd, arm, _ = model.coefficients(speed / sound)
    d = model.d
    k = math.pi * rho * d**3 / 8.0
    return SegmentCoefficients(
        speed,
        -k * cx0 / model.mass,
        k * cna / model.mass,
        k * cna * arm / model.iy,
        k * d * d * cmq / (2.0 * model.iy),
        gyroscopic,
        k * d * d * clp / (2.0 * model.ix),
        k * d * speed * cldd / model.ix,
        gravity,
        0.5 * rho * speed * speed,
    )


def _average(a: SegmentCoefficients, b: SegmentCoefficients) -> SegmentCoefficients:
    # (the fields are floats and tuples of floats, which mypy cannot follow through zip)
    return SegmentCoefficients(
        *(
            tuple((i + j) / 2 for i, j in zip(x, y)) if isinstance(x, tuple) else (x + y) / 2  # type: ignore[call-overload, operator]
            for x, y in zip(a, b)
        )  # type: ignore[arg-type]
    )


def epicyclic_roots(c: SegmentCoefficients, diameter_m: float) -> tuple[complex, complex]:
    """The eigenvalues m +- delta of eq L5's matrix, fast mode (larger |imaginary part|) first:
    imaginary parts are the mode frequencies (rad per calibre), real parts the damping rates."""
    mean = 0.5 * complex(c.damping - c.lift, c.gyroscopic)
    delta = cmath.sqrt(
        0.25 * complex(c.lift + c.damping, c.gyroscopic) ** 2 + diameter_m * c.static_moment
    )
    first, second = mean + delta, mean - delta
    return (first, second) if abs(first.imag) >= abs(second.imag) else (second, first)


@formula
def _phi(z: complex) -> tuple:
    """e^z, phi1, phi2, phi3 (phi_k(z) = sum z^n/(n+k)!), accurate for every z."""
    if abs(z) > 1.0:
        e = cmath.exp(z)
        phi1 = (e - 1.0) / z
        phi2 = (phi1 - 1.0) / z
        return e, phi1, phi2, (phi2 - 0.5) / z
    phi3: complex = 0.0
    for coefficient in _PHI3_SERIES:
        phi3 = phi3 * z + coefficient
    phi2 = 0.5 + z * phi3
    phi1 = 1.0 + z * phi2
    return 1.0 + z * phi1, phi1, phi2, phi3


@formula
def _scalar_solution(rate: float, forcing: float, x0: float, s: float) -> tuple[float, float]:
    """x(s) and integral_0^s x of x' = rate x + forcing (closed form)."""
    e, phi1, phi2, _ = _phi(complex(rate * s))
    f1, f2 = s * phi1.real, s * s * phi2.real
    return e.real * x0 + f1 * forcing, f1 * x0 + f2 * forcing


@formula
def _epicyclic_solution(
    c: SegmentCoefficients,
    d: float,
    v0: complex,
    q0: complex,
    force_v: complex,
    force_q: complex,
    s: float,
) -> tuple:
    """X(s) and integral_0^s X of eq L5 (Cayley-Hamilton, module docstring)."""
    a11, a12, a21, a22 = -c.lift, 1j * d, -1j * c.static_moment, complex(c.damping, c.gyroscopic)
    mean = 0.5 * (a11 + a22)
    delta = cmath.sqrt(0.25 * (a11 - a22) ** 2 + a12 * a21)
    e1, p11, p21, _ = _phi((mean + delta) * s)
    e2, p12, p22, _ = _phi((mean - delta) * s)
    # f0, f1, f2 at both roots; their means and divided differences.
    if abs(2.0 * delta * s) > _CONFLUENT:
        f0, f1, f2 = (e1 + e2) / 2, s * (p11 + p12) / 2, s * s * (p21 + p22) / 2
        df0, df1, df2 = (
            (e1 - e2) / (2 * delta),
            s * (p11 - p12) / (2 * delta),
            s * s * (p21 - p22) / (2 * delta),
        )
    else:
        e, phi1, phi2, phi3 = _phi(mean * s)
        f0, f1, f2 = e, s * phi1, s * s * phi2
        df0, df1, df2 = s * e, s * s * (phi1 - phi2), s**3 * (phi2 - 2.0 * phi3)
    # X(s) = f0(M) X0 + f1(M) F and its integral f1(M) X0 + f2(M) F, each f(M) [v, q] being
    # f [v, q] + df (M - m I) [v, q]
    v = (f0 * v0 + df0 * ((a11 - mean) * v0 + a12 * q0)) + (
        f1 * force_v + df1 * ((a11 - mean) * force_v + a12 * force_q)
    )
    q = (f0 * q0 + df0 * (a21 * v0 + (a22 - mean) * q0)) + (
        f1 * force_q + df1 * (a21 * force_v + (a22 - mean) * force_q)
    )
    v_integral = (f1 * v0 + df1 * ((a11 - mean) * v0 + a12 * q0)) + (
        f2 * force_v + df2 * ((a11 - mean) * force_v + a12 * force_q)
    )
    q_integral = (f1 * q0 + df1 * (a21 * v0 + (a22 - mean) * q0)) + (
        f2 * force_q + df2 * (a21 * force_v + (a22 - mean) * force_q)
    )
    return v, q, v_integral, q_integral


@formula
def propagate_segment(
    model: RigidBodyModel | RigidBodyKernel,
    state,
    c: SegmentCoefficients,
    rows: tuple,
    secant: float,
    s: float,
) -> tuple:
    """The 12 states at arc length ``s`` (calibres) into a segment starting at ``state``, with
    coefficients ``c``, the flat-to-N rotation ``rows`` used for gravity, wind and position
    (eq L7) and sec(theta) ``secant`` (eq L6). Closed form throughout (eqs L2-L7); ``model``
    gives the diameter and the wind (a RigidBodyKernel in compiled code)."""
    x, y, z, phi, theta, psi, u, v, w, p, q, r = state
    d, speed = model.d, c.speed
    g_u, g_v, g_w = _apply(rows, c.gravity)
    u_w, v_w, w_w = _apply(rows, model.wind)
    u1, u_int = _scalar_solution(-c.axial_drag, c.axial_drag * u_w + d * g_u / speed, u, s)
    p1, p_int = _scalar_solution(c.roll_damping, c.roll_drive, p, s)
    wind = complex(v_w, w_w)
    lateral, rate, lateral_int, rate_int = _epicyclic_solution(
        c,
        d,
        complex(v, w),
        complex(q, r),
        c.lift * wind + d * complex(g_v, g_w) / speed,
        1j * c.static_moment * wind,
        s,
    )
    scale = d / speed
    dx, dy, dz = _apply_transpose(rows, (u_int, lateral_int.real, lateral_int.imag))
    return (
        x + scale * dx,
        y + scale * dy,
        z + scale * dz,
        phi + scale * p_int,
        theta + scale * rate_int.real,
        psi + scale * secant * rate_int.imag,
        u1,
        lateral.real,
        lateral.imag,
        p1,
        rate.real,
        rate.imag,
    )


class _Segment(NamedTuple):
    start: tuple
    coefficients: SegmentCoefficients  # frozen at coefficients_at (eq L8)
    start_coefficients: SegmentCoefficients
    rows: tuple
    secant: float
    time_s: float
    length: float  # calibres

    def at(self, model, s):
        return propagate_segment(model, self.start, self.coefficients, self.rows, self.secant, s)

    def duration_s(self, model) -> float:
        return self.length * model.d / self.coefficients.speed


def _solve_segment(
    model, state, time_s, length, coefficients_at, aerodynamics, uniform
) -> _Segment:
    """Eq L8: a first pass at the start's attitude and coefficients, then the second pass with
    the trapezoid rotation and the coefficients at ``coefficients_at``."""

    def coefficients(at):
        return segment_coefficients(model, at, aerodynamics=aerodynamics, uniform_gravity=uniform)

    start = coefficients(state)
    rows0 = _rotation(state[4], state[5])
    secant0 = 1.0 / math.cos(state[4])
    end = propagate_segment(model, state, start, rows0, secant0, length)
    if coefficients_at == "middle":
        chosen = coefficients(propagate_segment(model, state, start, rows0, secant0, length / 2))
    elif coefficients_at == "average":
        chosen = _average(start, coefficients(end))
    else:
        chosen = start
    rows1 = _rotation(end[4], end[5])
    rows = tuple(
        ((a0 + b0) / 2, (a1 + b1) / 2, (a2 + b2) / 2)
        for (a0, a1, a2), (b0, b1, b2) in zip(rows0, rows1)
    )
    secant = (secant0 + 1.0 / math.cos(end[4])) / 2
    return _Segment(state, chosen, start, rows, secant, time_s, length)


def _states_at(model: RigidBodyModel, segments: list[_Segment], times: np.ndarray) -> np.ndarray:
    """The 12 states (12, n) at ``times`` (s), each from the segment it falls in."""
    starts = np.array([segment.time_s for segment in segments])
    index = np.clip(np.searchsorted(starts, times, side="right") - 1, 0, len(segments) - 1)
    coefficients = np.array(
        [(*segment.coefficients[:_GRAVITY], *segment.coefficients.gravity) for segment in segments]
    )
    lengths = (times - starts[index]) * coefficients[index, 0] / model.d
    return _propagate_rows(
        model.kernel,
        np.array([segment.start for segment in segments]),
        coefficients,
        np.array([segment.rows for segment in segments]),
        np.array([segment.secant for segment in segments]),
        index,
        lengths,
    )


# Compiled code takes a segment's coefficients as a row: the 8 numbers before ``gravity``, then
# its 3 components (the dynamic pressure, for the validity check only, is left out).
_GRAVITY = SegmentCoefficients._fields.index("gravity")
if (_GRAVITY, SegmentCoefficients._fields[-1]) != (8, "dynamic_pressure"):
    raise ImportError("_propagate_rows unpacks SegmentCoefficients by position: update it")


@jit
def _propagate_rows(kernel, starts, coefficients, rows, secants, index, lengths):
    """:func:`propagate_segment` of segment ``index[k]`` to ``lengths[k]`` calibres, for each
    k: the segments as arrays (their SegmentCoefficients without the dynamic pressure)."""
    model = RigidBodyKernel(*kernel)
    states = np.empty((12, lengths.size))
    for k in range(lengths.size):
        i = index[k]
        c = coefficients[i]
        state = propagate_segment(
            model,
            starts[i],
            SegmentCoefficients(
                c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], (c[8], c[9], c[10]), 0.0
            ),
            rows[i],
            secants[i],
            lengths[k],
        )
        for j in range(12):
            states[j, k] = state[j]
    return states


def _altitude(state) -> float:
    x, y, z = state[:3]
    return math.sqrt(x * x + y * y + (_R - z) ** 2) - _R


def _radial_velocity(segment: _Segment, state) -> float:
    """r . dr/dt of the segment's closed-form positions (eq L7) at ``state`` (up to 1/|r|)."""
    vx, vy, vz = _apply_transpose(segment.rows, state[6:9])
    return state[0] * vx + state[1] * vy + (state[2] - _R) * vz


def _where(segment: _Segment) -> str:
    """Where ``segment`` starts, for a validity problem."""
    pressure = segment.start_coefficients.dynamic_pressure
    return f"at {_altitude(segment.start) / 1e3:.1f} km ({pressure / 1e3:.1f} kPa dynamic pressure)"


def _angle_of_attack_deg(state, model) -> float:
    u_w, v_w, w_w = _apply(_rotation(state[4], state[5]), model.wind)
    return math.degrees(math.atan2(math.hypot(state[7] - v_w, state[8] - w_w), state[6] - u_w))


def _climb_problem(segment: _Segment, model, lowest_m: float) -> str | None:
    """Why the flight climbs again after its apogee, or None: a body that only drag and small
    angles act on cannot, so linear theory is then flying angles of attack far from small (a
    projectile that kept its attitude through the vacuum arc re-enters broadside or backwards,
    and only the 6DOF turns it into the wind)."""
    altitude = _altitude(segment.start)
    if altitude - lowest_m <= REBOUND_M:
        return None
    return (
        f"after its apogee it comes down to {lowest_m / 1e3:.1f} km and climbs back to "
        f"{altitude / 1e3:.1f} km, its angle of attack at "
        f"{_angle_of_attack_deg(segment.start, model):.0f} deg: linear theory cannot turn a "
        "projectile that re-enters the air that far from its nose"
    )


def _validity_problem(segment: _Segment, model) -> str | None:
    """Why ``segment`` is outside linear theory's validity in the air, or None: a growing
    epicyclic mode or an angle of attack beyond :data:`MAX_SMALL_ANGLE_DEG`, at its start,
    where the dynamic pressure exceeds :data:`DENSE_AIR_PA`."""
    state, pressure = segment.start, segment.start_coefficients.dynamic_pressure
    if pressure <= DENSE_AIR_PA:  # also every flight without aerodynamics
        return None
    fast, slow = epicyclic_roots(segment.start_coefficients, model.d)
    growth = max(fast.real, slow.real)
    if growth * segment.length > 1.0:
        return (
            f"an epicyclic mode grows e-fold every {model.d / growth:.3g} m {_where(segment)}: the "
            "projectile is dynamically unstable there and its angle of attack cannot stay "
            "small"
        )
    alpha = _angle_of_attack_deg(state, model)
    if alpha > MAX_SMALL_ANGLE_DEG:
        return (
            f"the angle of attack reaches {alpha:.1f} deg {_where(segment)}; linear theory assumes "
            "small angles where the air acts"
        )
    return None


def _divergence(launch: Launch, time_s: float, state, problem: str | None) -> str:
    """Why MLT cannot fly ``launch``: its linear solution left the finite numbers in the
    segment that starts at ``time_s`` in ``state``."""
    speed = math.hypot(state[6], state[7], state[8])
    return (
        f"MLT cannot fly {launch.projectile.name} at elevation_deg = {launch.elevation_deg:g}, "
        f"speed_m_s = {launch.speed_m_s:g}: its linear solution diverges in the segment from "
        f"{time_s:.1f} s at {_altitude(state) / 1e3:.1f} km, speed {speed:.0f} m/s"
        + (f" ({problem})" if problem else "")
        + "; linear theory follows the arc length at a speed frozen per segment, which fails "
        "where the speed falls toward zero (a near-vertical apogee): the 6DOF flies it"
    )


#: The check of each segment's start against linear theory's assumptions (a growing epicyclic
#: mode, an angle of attack beyond :data:`MAX_SMALL_ANGLE_DEG` where the air acts): a diagnostic,
#: not the flight, so Fig 4.7 counts none of the calls made within it.
DIAGNOSTICS = (_validity_problem,)


def counted_functions(launch: Launch) -> tuple[Counted, ...]:
    """Every function :func:`simulate_mlt`'s segment loop calls for ``launch``, each counted
    once per call (:mod:`harp_analysis.analyses.effort`, Fig 4.7): the segment's coefficients
    with the rotation, wind, gravity, air and coefficient table they read, the launch's
    atmosphere's density and speed of sound, the closed-form propagation with its scalar and
    epicyclic solutions (the latter and ``_phi`` in complex numbers), the two passes of eq L8,
    a segment's duration and the impact and apogee checks."""
    air = get_atmosphere(launch.atmosphere)
    averaged = {"zip(a, b)": len(SegmentCoefficients._fields), "zip(x, y)": 3}
    return (
        Counted(segment_coefficients),
        Counted(_rotation),
        Counted(_apply),
        Counted(_apply_transpose),
        Counted(_gravity),
        Counted(RigidBodyModel.air_altitude),
        Counted(RigidBodyModel.coefficients),
        Counted(air.density_kernel),
        Counted(air.sound_kernel),
        Counted(propagate_segment),
        Counted(_scalar_solution),
        Counted(_phi, complex_numbers=True),
        Counted(_epicyclic_solution, complex_numbers=True),
        Counted(_solve_segment, trips={"zip(rows0, rows1)": 3}),
        Counted(_average, trips=averaged),
        Counted(_Segment.duration_s),
        Counted(_altitude),
        Counted(_radial_velocity),
    )


class _Flight(NamedTuple):
    """What :func:`_march` flew: its segments, whether the last one lands, the apogee's time
    and state (None if it has none), the first validity problem (None), and the time and
    state of the last segment's start."""

    segments: list[_Segment]
    impact: bool
    apogee: tuple | None
    problem: str | None
    time: float
    state: tuple


def _check_segment_length(length_m: float, launch: Launch, max_time: float) -> None:
    """Raise if segments of ``length_m`` cannot fly ``launch``: one is longer than the whole
    flight, or it would take more than :data:`MAX_SEGMENTS` of them within ``max_time`` (s);
    warn beyond :data:`MAX_SEGMENT_LENGTH_M`, where a segment's frozen coefficients no longer
    stand for it."""
    elevation, speed = launch.elevation_deg, launch.speed_m_s
    try:  # no flight, with or without drag, travels farther than a drag-free one at V0
        conic = kepler.ballistic_conic(speed, math.radians(elevation))
        longest_m = float(speed * conic.time_of_flight_s)
    except ValueError:  # escape speed: no bound
        longest_m = math.inf
    if length_m > longest_m:
        raise ValueError(
            f"segment_length_m = {length_m:g} m is longer than the flight: even "
            f"without drag it travels at most {longest_m:.4g} m"
        )
    if length_m > MAX_SEGMENT_LENGTH_M:
        warnings.warn(
            f"segment_length_m = {length_m:g} m: MLT updates its coefficients every "
            f"500 m to 2 km; beyond {MAX_SEGMENT_LENGTH_M / 1e3:g} km, density, Mach "
            "and the coefficients change too much within a segment to be frozen",
            ModelValidityWarning,
            stacklevel=3,
        )

    needed = min(longest_m, speed * max_time) / length_m
    if needed > MAX_SEGMENTS:
        raise ValueError(
            f"segment_length_m = {length_m:g} m would need up to {needed:.3g} segments for this "
            f"flight (at most {MAX_SEGMENTS:,}); MLT updates every 500 m to 2 km"
        )


def _march(
    model, launch: Launch, length_m, coefficients_at, aerodynamics, uniform, max_time
) -> _Flight:
    """Segment after segment of ``length_m`` (eq L8's passes, :func:`_solve_segment`) from the
    launch until the impact or ``max_time`` (s), noting the apogee and the first departure
    from linear theory's validity. Its loop is the one Fig 4.7 counts
    (:data:`SEGMENT_LOOP`)."""
    projectile = launch.projectile
    length = length_m / model.d
    state = tuple(launch_state(launch).tolist())
    segments: list[_Segment] = []
    time, impact, problem = 0.0, False, None
    apogee: tuple | None = None
    lowest_m = math.inf  # since the apogee
    try:  # a linear solution that diverges overflows or divides by a vanishing speed
        while time < max_time:
            segment = _solve_segment(
                model, state, time, length, coefficients_at, aerodynamics, uniform
            )
            problem = problem or _validity_problem(segment, model)
            if apogee is not None:
                lowest_m = min(lowest_m, _altitude(segment.start))
                problem = problem or _climb_problem(segment, model, lowest_m)
            duration = segment.duration_s(model)
            end = segment.at(model, length)
            lands = _altitude(end) < 0.0
            if lands:
                if not segments:
                    raise ValueError(
                        f"segment_length_m = {length_m:g} m is longer than the flight: "
                        f"{projectile.name} lands inside the first segment"
                    )
                s_hit = brentq(lambda s: _altitude(segment.at(model, s)), 0.0, length, xtol=1e-9)
                segment = segment._replace(length=s_hit)
                end = segment.at(model, s_hit)
            if abs(end[4] - segment.start[4]) > MAX_PITCH_CHANGE_RAD and not problem:
                problem = (
                    f"its pitch turns {math.degrees(abs(end[4] - segment.start[4])):.0f} deg "
                    f"within one segment {_where(segment)}, whose speed and coefficients linear "
                    "theory freezes: shorten segment_length_m"
                )
            if apogee is None and _radial_velocity(segment, end) < 0.0:
                # The positions are piecewise closed forms whose rotation T (eq L7) is fixed
                # within a segment and steps at its ends, where the direction of dr/dt turns by the
                # segment's change of pitch: the highest point is usually a segment boundary.
                s_top = (
                    brentq(
                        lambda s: _radial_velocity(segment, segment.at(model, s)),
                        0.0,
                        segment.length,
                        xtol=1e-9,
                    )
                    if _radial_velocity(segment, segment.start) > 0.0
                    else 0.0
                )
                apogee = (
                    time + s_top * model.d / segment.coefficients.speed,
                    segment.at(model, s_top),
                )
            if lands:
                segments.append(segment)
                impact = True
                break
            if time + duration > max_time:
                segments.append(
                    segment._replace(
                        length=(max_time - time) * segment.coefficients.speed / model.d
                    )
                )
                break
            segments.append(segment)
            state, time = end, time + duration
    except ArithmeticError as error:
        raise ValueError(_divergence(launch, time, state, problem)) from error
    return _Flight(segments, impact, apogee, problem, time, state)


#: The function whose loop over segments is MLT's flight, the calls and own operations of which
#: Fig 4.7 counts (:mod:`harp_analysis.analyses.effort`).
SEGMENT_LOOP = _march


def _rows(model, segments: list[_Segment], step: float, length_m: float, name: str):
    """The flight's table, a row every ``step`` (s) and at its end, or None if its linear
    solution left the finite numbers; a RuntimeError if it passes below the ground inside a
    segment."""
    end_time = segments[-1].time_s + segments[-1].duration_s(model)
    if not math.isfinite(end_time):
        return None
    times = output_times(end_time, step)
    frame = trajectory_table(model, times, _states_at(model, segments, times))
    if not np.isfinite(frame.altitude_m.to_numpy()).all():
        return None
    if np.any(frame.altitude_m.to_numpy()[:-1] < -1.0):
        raise RuntimeError(
            f"the MLT flight of {name} passes below the ground inside "
            f"a segment of {length_m:g} m (ends are checked for the impact): "
            "shorten segment_length_m"
        )
    return frame


def simulate_mlt(
    launch: Launch,
    *,
    density_altitude: str = "flat",
    segment_length_m: float = SEGMENT_LENGTH_M,
    coefficients_at: str = "middle",
    gravity: str = "central",
    aerodynamics: bool = True,
    max_time_s: float = 400.0,
    output_step_s: float = 0.5,
) -> pd.DataFrame:
    """One MLT flight (module docstring, eqs L1-L8) from launch to impact, as the 6DOF's table.

    ``launch`` and ``density_altitude`` are flown as by
    :func:`harp_analysis.engines.sixdof.simulate_6dof`. ``segment_length_m`` is the arc length
    between updates of the linear solution; ``coefficients_at`` where in a segment the coefficients
    are frozen (:data:`COEFFICIENT_POINTS`); ``gravity`` the central field of the 6DOF (frozen per
    segment) or ``"uniform"`` (GM/R^2 down the launch vertical); ``aerodynamics=False`` flies
    in vacuum. Rows every ``output_step_s`` and at impact (spherical altitude back to zero);
    Mach, drag coefficient, drag/gravity and angle of attack are evaluated from the states by
    the 6DOF's aerodynamics, so the two tables mean the same thing. ``frame.attrs`` holds the
    shared metadata (``steps`` = segments, ``rhs_evaluations`` = coefficient evaluations, the
    6DOF's right-hand side without its derivatives) and MLT's options.

    Parameters
    ----------
    launch : Launch
        The launch to fly, as by the 6DOF (HP or LP).
    density_altitude : str
        ``"flat"`` or ``"spherical"``, as the 6DOF's.
    segment_length_m : float
        Arc length (m) between updates of the linear solution.
    coefficients_at : str
        Where in a segment the coefficients are frozen: ``"start"``, ``"middle"`` or
        ``"average"``.
    gravity : str
        ``"central"`` (the 6DOF's field, frozen per segment) or ``"uniform"``.
    aerodynamics : bool
        False flies in vacuum.
    max_time_s : float
        The longest flight (s).
    output_step_s : float
        Seconds between rows.

    Returns
    -------
    pandas.DataFrame
        The trajectory table of :mod:`harp_analysis.models.trajectory`, one row per output
        time in SI units, with the shared metadata in ``frame.attrs`` (apogee, range, time of
        flight, why the flight stopped, the work it took).
    """
    check_choice(density_altitude, "density_altitude", DENSITY_ALTITUDES)
    model = rigid_body_launch(launch, "MLT", density_altitude)
    projectile = launch.projectile
    length_m = positive_scalar(segment_length_m, "segment_length_m", "m")
    check_choice(coefficients_at, "coefficients_at", COEFFICIENT_POINTS)
    check_choice(gravity, "gravity", GRAVITY_MODELS)
    max_time = positive_scalar(max_time_s, "max_time_s", "s")
    step = positive_scalar(output_step_s, "output_step_s", "s")
    _check_segment_length(length_m, launch, max_time)
    uniform = gravity == "uniform"
    segments, impact, apogee, problem, time, state = _march(
        model, launch, length_m, coefficients_at, aerodynamics, uniform, max_time
    )
    if impact and len(segments) < MIN_SEGMENTS and not problem:
        problem = (
            f"the whole flight is {len(segments)} segments of {length_m:g} m, each frozen at "
            f"one speed and set of coefficients: shorten segment_length_m to a few hundredths of "
            "its range"
        )
    if problem:
        warnings.warn(
            f"MLT flight of {projectile.name} is outside linear theory's validity: {problem}",
            ModelValidityWarning,
            stacklevel=2,
        )

    frame = _rows(model, segments, step, length_m, projectile.name)
    if frame is None:
        raise ValueError(_divergence(launch, time, state, problem))
    apogee_values = None
    if apogee is not None:
        apogee_values = (apogee[0], *altitude_and_range(apogee[1]))
    # each segment evaluates its coefficients at its start (eq L8's first pass), and again at
    # its middle or its end unless they stay frozen at the start
    per_segment = 1 if coefficients_at == "start" else 2
    describe(
        frame,
        engine="MLT",
        launch=launch,
        apogee=apogee_values,
        impact=impact,
        rhs_evaluations=per_segment * len(segments),
        steps=len(segments),
        max_time_s=max_time,
        density_altitude=density_altitude,
        segment_length_m=length_m,
        coefficients_at=coefficients_at,
        gravity=gravity,
        aerodynamics=aerodynamics,
    )
    return frame


def warm_up() -> None:
    """Compile MLT's kernels (its table's rows, the rigid-body model's) now, or load them from the
    on-disk cache, not at first use."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", TruncatedFlightWarning)  # a short flight compiles all
        simulate_mlt(HP_CHAPTER_2, max_time_s=1.0)


def linear_theory_derivatives(
    model: RigidBodyModel,
    state,
    *,
    aerodynamics: bool = True,
    uniform_gravity: bool = False,
    frame_coupling: bool = False,
) -> list:
    """Time derivative of the 12 states under eqs L1-L4, L6 and L7 with every coefficient,
    gravity and the attitude at ``state`` itself: MLT's limit as segments shrink to nothing.

    A diagnostic, not part of MLT: integrated tightly (:func:`simulate_linear_theory_limit`) it
    separates what the segments cost (MLT against this limit) from what the dropped products
    cost (this limit against the 6DOF, which keeps them). ``frame_coupling=True`` restores the
    one dropped product that matters for HP: the no-roll frame's roll rate -r tan(theta)
    coupling w into v' and v into w' (``+ r tan(theta) w`` ... see :mod:`.sixdof`, step 3).
    """
    c = segment_coefficients(
        model, state, aerodynamics=aerodynamics, uniform_gravity=uniform_gravity
    )
    x, y, z, phi, theta, psi, u, v, w, p, q, r = state
    rows = _rotation(theta, psi)
    g_u, g_v, g_w = _apply(rows, c.gravity)
    u_w, v_w, w_w = _apply(rows, model.wind)
    per_time = c.speed / model.d  # d/dt = (V/D) d/ds
    d = model.d
    frame_roll = -r * math.tan(theta) if frame_coupling else 0.0
    return [
        *_apply_transpose(rows, (u, v, w)),
        p,
        q,
        r / math.cos(theta),
        per_time * (-c.axial_drag * (u - u_w)) + g_u,
        per_time * (-c.lift * (v - v_w) - d * r) + g_v + frame_roll * w,
        per_time * (-c.lift * (w - w_w) + d * q) + g_w - frame_roll * v,
        per_time * (c.roll_damping * p + c.roll_drive),
        per_time * (c.static_moment * (w - w_w) + c.damping * q - c.gyroscopic * r),
        per_time * (-c.static_moment * (v - v_w) + c.damping * r + c.gyroscopic * q),
    ]


def simulate_linear_theory_limit(
    launch: Launch,
    *,
    density_altitude: str = "flat",
    frame_coupling: bool = False,
    rtol: float = 1e-10,
    max_time_s: float = 400.0,
    output_step_s: float = 0.5,
) -> pd.DataFrame:
    """:func:`linear_theory_derivatives` integrated by DOP853 from launch to impact: the limit
    MLT converges to, for measuring its segment error and the cost of the dropped products.

    ``launch`` and ``density_altitude`` are flown as by :func:`simulate_mlt`; rows every
    ``output_step_s`` and at the end, the impact or ``max_time_s`` (a TruncatedFlightWarning);
    ``frame.attrs`` the shared metadata, the apogee where the radial velocity changes sign (NaN
    if the flight is cut off before it)."""
    model = rigid_body_launch(launch, "linear-theory limit", density_altitude)
    rtol = Bounds(low=1e-13, high=1e-3).scalar(rtol, "rtol")
    max_time = positive_scalar(max_time_s, "max_time_s", "s")
    step = positive_scalar(output_step_s, "output_step_s", "s")

    def impact(t, y):
        return _altitude(y)

    def apogee(t, y):  # radial velocity of eq L7's positions, up to the factor 1/|r|
        vx, vy, vz = _apply_transpose(_rotation(y[4], y[5]), y[6:9])
        return y[0] * vx + y[1] * vy + (y[2] - _R) * vz

    # (solve_ivp reads an event's options from attributes of the function)
    impact.terminal, impact.direction = True, -1  # type: ignore[attr-defined]
    apogee.direction = -1  # type: ignore[attr-defined]
    y0 = launch_state(launch)
    solution = solve_ivp(
        lambda t, y: linear_theory_derivatives(model, y.tolist(), frame_coupling=frame_coupling),
        (0.0, max_time),
        y0,
        method="DOP853",
        rtol=rtol,
        atol=1e-9,
        dense_output=True,
        events=(impact, apogee),
    )
    if solution.status < 0:
        raise RuntimeError(
            f"linear-theory limit of {launch.projectile.name} failed at "
            f"t = {solution.t[-1]:.3f} s: {solution.message}"
        )
    return flight_table(
        model,
        solution,
        launch,
        "linear-theory limit",
        output_step_s=step,
        max_time_s=max_time,
        rtol=rtol,
        density_altitude=density_altitude,
        frame_coupling=frame_coupling,
    )
