"""The 6DOF simulation of Appendix B (Dr. Slegers' MATLAB), ported and made fast.

Appendix B integrates the rigid finned projectile of Chapter 2 A (M829 aerodynamics) in a flat
launch frame: x downrange, y cross range, z down, the Earth's centre at (0, 0, +R), the frame
non-rotating. The 12 states are ``[x y z phi theta psi u v w p q r]``: position in the flat
frame, 3-2-1 Euler angles of the body from it, and body-axis velocity and angular velocity.
RK4 with h = 0.0005 s runs to 270 s from theta = 50 deg, u = 2022 m/s, p = 10 rad/s.

:func:`appendix_b_derivatives` is a line-by-line port of ``PROJ6DOF_M829_DERV``. What the
printed code does that we keep (each faithfully ported):

- gravity: the ``Weight`` line's magnitude is m GM / ((6378 - z/1000)^2 + (x/1000)^2) (km),
  i.e. m GM / ((R - z)^2 + x^2): it omits y^2, while its direction (-x, -y, R - z)/|r| includes
  y. The relative error is y^2 / r^2, a few 1e-9 for these flights;
- the atmosphere (density and speed of sound) is evaluated at the flat-frame altitude -z, not
  at the spherical altitude |r| - R, the default ``density_altitude="flat"``. Downrange the
  Earth's surface falls x^2 / (2R) below the flat plane (4.6 km at HP's 241 km range), so on
  the way down the code flies through air that is too dense: 1.6 times too dense at 10 km
  (true) altitude, and at impact -z = -4.6 km, where the fit 1.22581 (1 + 0.00002257 z)^4.256
  extrapolates to 1.5 times sea level. HP lands at 807 m/s instead of 1094 m/s.
  ``density_altitude="spherical"`` evaluates the atmosphere at |r| - R instead;
- ``thetacorrect`` (pitch above the local horizontal) and ``TIB2`` built from it are computed
  but unused (they fed a commented-out Weight line), as is a commented-out flat-Earth weight
  ``mass*9.81*TIB*[0;0;1]`` and a commented-out ``rho=0`` (vacuum);
- CYPA and SLMAG are zero in the table, so the Magnus force and moment are inert.

What we change, each stated again in :func:`appendix_b_derivatives`:

- density, speed of sound and the nine coefficients are evaluated at the state passed; the
  code evaluates them once per RK4 step, at the step's start, outside the derivative function
  (which makes its RK4 formally first-order in the aerodynamic terms);
- wind: the text says the projectiles fly "with a 5 m/s cross wind", but the code has no wind
  term at all. We subtract a constant wind (flat-frame components) from the velocity to get the
  air-relative velocity used in every aerodynamic force and moment and in the Mach number;
- the Mach interpolation holds the table's end values outside Mach 0-8, where MATLAB's
  ``interp1`` returns NaN (see :mod:`.drag`).

Oddities of the printed code with no effect on the physics: the ``FSA`` line opens its vector
with ``(`` instead of ``[`` and the ``Weight`` line has one ``)`` too many, so the code as
printed does not run; the comment calls GM (km^3/s^2) a "gravitational acceleration km^2/s^2";
the initial theta is 0.872665 rad (50.00002 deg); the RK4 loop runs to 270 s without an impact
test; its output column 6, the "angle of attack", is sqrt(v^2 + w^2)/u in degrees (the small
angle tangent, inertial velocity), meaningless at the large angles reached above the
atmosphere; rows are written at the first step after each 0.5 s mark.

The no-roll formulation (:func:`no_roll_derivatives`, used by :func:`simulate_6dof`)
---------------------------------------------------------------------------------
The fins spin the projectile from 10 rad/s to the roll equilibrium p d / (2V) = -CLDD/CLP
(about 300 rad/s for HP, 445 for LP) within a second, so body-axis v, w, q, r oscillate at the
spin rate and an adaptive integrator needs ~1e5+ steps. The projectile is axisymmetric in the
code (Iy = Iz, one CNA for pitch and yaw) and every force and moment term is covariant under a
rotation about the body x axis, so the same equations can be written exactly in the no-roll
frame N, reached from the flat frame by psi then theta only (the body frame is N turned by phi
about x). Velocity and body angular velocity are resolved in N: ``[u v w]`` and ``[p q r]``
(u and p are unchanged; v, w and q, r are the body's rotated back by phi).

1. N turns relative to the flat frame at Omega = psi' k + theta' j', i.e. in N components
   Omega = [-psi' sin(theta), theta', psi' cos(theta)]; the body at Omega + phi' i. Hence
   theta' = q, psi' = r / cos(theta), phi' = p + r tan(theta), and Omega = [-r tan(theta), q, r].
2. Position: [x y z]' = T_N^T [u v w], T_N = Appendix B's TIB with phi = 0.
3. Translation: [u v w]' = (F_aero + Weight)/m - Omega x [u v w]: the body equation with the
   frame rate Omega in place of the body rate (p replaced by -r tan(theta) in the cross product).
4. Rotation: the angular momentum is H = [Ix p, Iy q, Iy r] in N too, because Iy = Iz makes the
   inertia invariant under the phi rotation. H' = M - Omega x H gives
   p' = Mx / Ix,  q' = (My - Ix p r - Iy tan(theta) r^2) / Iy,
   r' = (Mz + Ix p q + Iy tan(theta) q r) / Iy.
5. Forces and moments keep their Appendix B expressions with v, w, q, r read in N: v^2 + w^2
   and p are invariant, [v, w], [w, -v] and [q, r] rotate with the frame; the weight direction
   is resolved with T_N. phi enters nothing: it is integrated only for output.

Nothing in N oscillates at the spin rate: what remains is the pitch/yaw oscillation (9 Hz
for HP, 17 Hz for LP at launch, slowing as the air thins) and, above the atmosphere, the
gyroscopic nutation at Ix p / Iy (below 1 rad/s), so DOP853 at rtol 1e-9 takes about 1500
steps (25000 evaluations) for a whole flight. ``tests/test_sixdof.py`` checks that the two
derivatives agree at random states (transformed between the frames) and that the adaptive
no-roll solution agrees with Appendix B's own fixed-step RK4 on the body-frame port.

The no-roll derivatives (and the table's aerodynamics) are compiled (:mod:`.compiled`;
:func:`warm_up`): about 1 us an evaluation, so a flight takes about 0.13 s, four fifths of it
scipy's own stepping, events and dense output. Appendix B's port stays numpy (it verifies).

The Euler angles are Appendix B's and share its singularity at theta = +-90 deg.
"""

from __future__ import annotations

import math
import warnings
from bisect import bisect_right
from functools import lru_cache
from typing import NamedTuple

import numpy as np
import pandas as pd
from scipy.integrate import solve_ivp

from ..foundation import earth
from ..foundation.compiled import formula, jit
from ..foundation.validation import (
    check_choice,
    check_range,
    finite_array,
    finite_scalar,
    positive_scalar,
)
from ..models.atmosphere import AtmosphereModel, air, get_atmosphere
from ..models.launch import HP_CHAPTER_2, Launch
from ..models.projectiles import Projectile, check_rigid_body
from ..models.trajectory import (
    BASE_COLUMNS,
    TruncatedFlightWarning,
    describe,
    flight_path_angle,
    output_times,
    surface_ranges,
)

__all__ = [
    "STATE_NAMES",
    "DENSITY_ALTITUDES",
    "EXTRA_COLUMNS",
    "RigidBodyModel",
    "RigidBodyKernel",
    "rigid_body_model",
    "rigid_body_launch",
    "launch_state",
    "altitude_and_range",
    "flight_table",
    "appendix_b_derivatives",
    "no_roll_derivatives",
    "trajectory_table",
    "simulate_6dof",
    "integrate_fixed_step",
    "warm_up",
]

STATE_NAMES = ("x", "y", "z", "phi", "theta", "psi", "u", "v", "w", "p", "q", "r")
DENSITY_ALTITUDES = ("flat", "spherical")
EXTRA_COLUMNS = (
    "altitude_flat_m",
    "angle_of_attack_rad",
    "roll_rate_rad_s",
    "roll_rad",
    "pitch_rad",
    "yaw_rad",
)

_R = earth.RADIUS_M
_GM = earth.GM_M3_S2
# Absolute error floors per state for solve_ivp: micrometre positions, 1e-10 rad attitudes,
# 1e-7 m/s velocities and 1e-10 rad/s pitch/yaw rates (q, r are ~1e-3 rad/s in vacuum).
_ATOL = np.array([1e-6] * 3 + [1e-10] * 3 + [1e-7] * 3 + [1e-8, 1e-10, 1e-10])
# Appendix B's Euler angles are singular at theta = +-90 deg (tan theta, 1/cos theta): a flight
# stops with a RuntimeError when |theta| comes within this cosine of it (0.00006 deg).
_SINGULAR_COS = 1e-6


class RigidBodyKernel(NamedTuple):
    """A :class:`RigidBodyModel` as compiled code takes it: the constants under the model's
    attribute names (so one formula reads either), the M829 table as arrays and the atmosphere
    by its number and table (:func:`harp_analysis.models.atmosphere.air`)."""

    mass: float
    ix: float
    iy: float
    d: float
    wind: tuple
    spherical: bool
    atmosphere: int
    atmosphere_table: np.ndarray
    mach_table: np.ndarray
    rows: np.ndarray
    slopes: np.ndarray


# The physics below is written once, for a model that is a RigidBodyModel in Python (MLT's
# segments, Appendix B's port) or a RigidBodyKernel in compiled code (the no-roll right-hand
# side that DOP853 calls, the table's aerodynamics).
@formula
def _air_altitude(model, x, y, z):
    """Altitude (m) where the air is read: the flat (-z) or the spherical (|r| - R)."""
    return math.sqrt(x * x + y * y + (_R - z) ** 2) - _R if model.spherical else -z


@formula
def _coefficients(model, mach):
    """CX0 CX2 CNA CYPA CMQ CLP CLDD SLDEL SLMAG at ``mach``: one bracket search for all
    nine, linear between table points, end values held outside the table."""
    table = model.mach_table
    i = min(max(bisect_right(table, mach), 1), len(table) - 1) - 1
    weight = min(max((mach - table[i]) / (table[i + 1] - table[i]), 0.0), 1.0)
    row, slope = model.rows[i], model.slopes[i]
    return (
        row[0] + weight * slope[0],
        row[1] + weight * slope[1],
        row[2] + weight * slope[2],
        row[3] + weight * slope[3],
        row[4] + weight * slope[4],
        row[5] + weight * slope[5],
        row[6] + weight * slope[6],
        row[7] + weight * slope[7],
        row[8] + weight * slope[8],
    )


@jit
def _aerodynamics(model, x, y, z, c_theta, s_theta, c_psi, s_psi, u, v, w, p, q, r):
    """Aerodynamic force and moment in the no-roll frame, air-relative velocity (same
    frame), Mach and the total axial coefficient -CX0 - CX2 (v^2 + w^2)/V^2."""
    wx, wy, wz = model.wind
    ua = u - (c_theta * c_psi * wx + c_theta * s_psi * wy - s_theta * wz)
    va = v - (-s_psi * wx + c_psi * wy)
    wa = w - (s_theta * c_psi * wx + s_theta * s_psi * wy + c_theta * wz)
    lateral = va * va + wa * wa
    big_v = math.sqrt(ua * ua + lateral)
    rho, sound = air(model.atmosphere, _air_altitude(model, x, y, z), model.atmosphere_table)
    mach = big_v / sound
    cx0, cx2, cna, cypa, cmq, clp, cldd, dx, dxmag = _coefficients(model, mach)
    d = model.d
    qa = 0.125 * math.pi * rho * big_v * big_v * d * d
    magnus = 0.0625 * rho * math.pi * d**3 * p * cypa
    axial = cx0 + cx2 * lateral / (big_v * big_v)
    normal = qa * cna / big_v
    damping = qa * d * d * cmq / (2.0 * big_v)
    force = (qa * axial, -normal * va + magnus * wa, -normal * wa - magnus * va)
    moment = (
        qa * d * (cldd + p * clp * d / (2.0 * big_v)),
        normal * dx * wa + damping * q + magnus * dxmag * va,
        -normal * dx * va + damping * r + magnus * dxmag * wa,
    )
    return force, moment, (ua, va, wa), mach, -axial


@jit
def _no_roll(t, state, kernel):
    """The no-roll right-hand side (module docstring, steps 1-5) of the model whose
    :attr:`RigidBodyModel.kernel` is ``kernel``."""
    model = RigidBodyKernel(*kernel)
    x, y, z, _, theta, psi, u, v, w, p, q, r = state
    c_theta, s_theta = math.cos(theta), math.sin(theta)
    t_theta = s_theta / c_theta
    c_psi, s_psi = math.cos(psi), math.sin(psi)
    force, moment, _, _, _ = _aerodynamics(
        model, x, y, z, c_theta, s_theta, c_psi, s_psi, u, v, w, p, q, r
    )
    fx, fy, fz = force
    mx, my, mz = moment
    # Weight per unit mass, Appendix B's magnitude (no y^2), resolved in N.
    radius = math.sqrt(x * x + y * y + (_R - z) ** 2)
    g = _GM / (((_R - z) ** 2 + x * x) * radius)
    gx, gy, gz = -g * x, -g * y, g * (_R - z)
    g_u = c_theta * c_psi * gx + c_theta * s_psi * gy - s_theta * gz
    g_v = -s_psi * gx + c_psi * gy
    g_w = s_theta * c_psi * gx + s_theta * s_psi * gy + c_theta * gz
    frame_roll = -r * t_theta  # x component of the frame rate Omega
    m, ix, iy = model.mass, model.ix, model.iy
    return np.array(
        (
            c_theta * c_psi * u - s_psi * v + s_theta * c_psi * w,
            c_theta * s_psi * u + c_psi * v + s_theta * s_psi * w,
            -s_theta * u + c_theta * w,
            p - frame_roll,
            q,
            r / c_theta,
            fx / m + g_u - (q * w - r * v),
            fy / m + g_v - (r * u - frame_roll * w),
            fz / m + g_w - (frame_roll * v - q * u),
            mx / ix,
            (my - ix * p * r + iy * frame_roll * r) / iy,
            (mz + ix * p * q - iy * frame_roll * q) / iy,
        )
    )


class RigidBodyModel:
    """Constants of one projectile in one atmosphere and wind; the two derivative functions
    (Appendix B's port in numpy, the no-roll one compiled)."""

    def __init__(
        self,
        projectile: Projectile,
        atmosphere: AtmosphereModel,
        wind_m_s: tuple,
        density_altitude: str,
    ):
        projectile = check_rigid_body(projectile, "the rigid-body model")
        aero, ix, iy, d = (
            projectile.aero,
            projectile.roll_inertia_kg_m2,
            projectile.pitch_inertia_kg_m2,
            projectile.diameter_m,
        )
        assert aero is not None and ix is not None and iy is not None and d is not None
        if atmosphere.code < 0:
            raise ValueError(
                f"atmosphere {atmosphere.name!r} has no compiled form; the rigid-body engines "
                "fly the models of harp_analysis.models.atmosphere.ATMOSPHERE_NAMES"
            )
        self.mass: float = projectile.mass_kg
        self.ix: float = ix
        self.iy: float = iy  # Iz = Iy (Appendix B)
        self.d: float = d
        self.density = atmosphere.density_kernel
        self.sound = atmosphere.sound_kernel
        self.spherical = density_altitude == "spherical"
        self.wind = wind_m_s
        table = aero.table()
        # Python numbers for the Python callers: much faster than numpy's in scalar code.
        self.mach_table = list(map(float, aero.mach))
        self.rows = [tuple(map(float, row)) for row in table]
        self.slopes = [tuple(map(float, row)) for row in np.diff(table, axis=0)]
        #: The model as the compiled functions take it: the fields of RigidBodyKernel, as a
        #: plain tuple (which numba reads from Python faster than a NamedTuple).
        self.kernel = tuple(
            RigidBodyKernel(
                self.mass,
                ix,
                iy,
                d,
                self.wind,
                self.spherical,
                atmosphere.code,
                atmosphere.table(),
                np.array(self.mach_table),
                np.array(self.rows),
                np.array(self.slopes),
            )
        )

    air_altitude = _air_altitude
    coefficients = _coefficients

    def air(self, x: float, y: float, z: float) -> tuple[float, float]:
        """Density and speed of sound at the flat (-z) or spherical (|r| - R) altitude."""
        altitude = self.air_altitude(x, y, z)
        return float(self.density(altitude)), float(self.sound(altitude))

    def body(self, state) -> np.ndarray:
        """PROJ6DOF_M829_DERV line by line (matrix form), with wind and the per-state air."""
        x, y, z, phi, theta, psi, u, v, w, p, q, r = state
        c_theta, s_theta, t_theta = math.cos(theta), math.sin(theta), math.tan(theta)
        c_phi, s_phi = math.cos(phi), math.sin(phi)
        c_psi, s_psi = math.cos(psi), math.sin(psi)
        tib = np.array(
            [
                [c_theta * c_psi, c_theta * s_psi, -s_theta],
                [
                    s_phi * s_theta * c_psi - c_phi * s_psi,
                    s_phi * s_theta * s_psi + c_phi * c_psi,
                    s_phi * c_theta,
                ],
                [
                    c_phi * s_theta * c_psi + s_phi * s_psi,
                    c_phi * s_theta * s_psi - s_phi * c_psi,
                    c_phi * c_theta,
                ],
            ]
        )
        kinematic = np.array(
            [
                [1.0, s_phi * t_theta, c_phi * t_theta],
                [0.0, c_phi, -s_phi],
                [0.0, s_phi / c_theta, c_phi / c_theta],
            ]
        )
        # (6378 - z/1000)^2 + (x/1000)^2 km^2 with GM*1000 km^3/s^2 is this in SI; no y^2.
        weight = (
            (self.mass * _GM / ((_R - z) ** 2 + x**2))
            * tib
            @ (np.array([-x, -y, _R - z]) / math.sqrt(x * x + y * y + (_R - z) ** 2))
        )
        sw = np.array([[0.0, -r, q], [r, 0.0, -p], [-q, p, 0.0]])
        inertia = np.diag([self.ix, self.iy, self.iy])
        velocity, rates = np.array([u, v, w]), np.array([p, q, r])

        ua, va, wa = velocity - tib @ np.asarray(self.wind)
        big_v = math.sqrt(ua * ua + va * va + wa * wa)
        rho, sound = self.air(x, y, z)
        cx0, cx2, cna, cypa, cmq, clp, cldd, dx, dxmag = self.coefficients(big_v / sound)
        d = self.d
        qa = 0.125 * math.pi * rho * big_v**2 * d**2
        fsa = qa * np.array(
            [cx0 + cx2 * (va**2 + wa**2) / big_v**2, -cna * va / big_v, -cna * wa / big_v]
        )
        fmag = 0.0625 * rho * math.pi * d**3 * p * cypa * np.array([0.0, wa, -va])
        msa = qa * cna * dx * np.array([0.0, wa / big_v, -va / big_v])
        mua = (
            qa
            * d
            * np.array(
                [
                    cldd + p * clp * d / (2 * big_v),
                    q * cmq * d / (2 * big_v),
                    r * cmq * d / (2 * big_v),
                ]
            )
        )
        mmag = 0.0625 * rho * math.pi * d**3 * p * cypa * dxmag * np.array([0.0, va, wa])
        return np.concatenate(
            [
                tib.T @ velocity,
                kinematic @ rates,
                (fsa + fmag + weight) / self.mass - sw @ velocity,
                np.linalg.solve(inertia, msa + mua + mmag - sw @ inertia @ rates),
            ]
        )

    def no_roll(self, t, state) -> np.ndarray:
        """The same equations in the no-roll frame (module docstring, steps 1-5), compiled."""
        return _no_roll(t, state, self.kernel)


def warm_up() -> None:
    """Compile the 6DOF's kernels now (or load them from the on-disk cache), not at first use."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", TruncatedFlightWarning)  # a short flight compiles all
        simulate_6dof(HP_CHAPTER_2, max_time_s=0.1, output_step_s=0.1)


def _atmosphere_model(atmosphere) -> AtmosphereModel:
    return atmosphere if isinstance(atmosphere, AtmosphereModel) else get_atmosphere(atmosphere)


# Cached: the verification RK4 calls the public derivatives thousands of times per run.
@lru_cache(maxsize=16)
def _model(projectile, atmosphere, wind_m_s, density_altitude) -> RigidBodyModel:
    return RigidBodyModel(projectile, atmosphere, wind_m_s, density_altitude)


def rigid_body_model(projectile, atmosphere, wind_m_s, density_altitude) -> RigidBodyModel:
    """The checked, cached :class:`RigidBodyModel` of ``projectile`` (shared with the MLT)."""
    wind = finite_array(wind_m_s, "wind_m_s")
    if wind.shape != (3,):
        raise ValueError(f"wind_m_s must be 3 flat-frame components; got shape {wind.shape}")
    check_choice(density_altitude, "density_altitude", DENSITY_ALTITUDES)
    return _model(
        check_rigid_body(projectile, "the 6DOF"),
        _atmosphere_model(atmosphere),
        tuple(map(float, wind)),
        density_altitude,
    )


def _checked_state(state) -> np.ndarray:
    state = finite_array(state, "state")
    if state.shape != (12,):
        raise ValueError(f"state must hold the 12 states {STATE_NAMES}; got shape {state.shape}")
    return state


def appendix_b_derivatives(
    state,
    projectile: Projectile,
    *,
    atmosphere="two_segment",
    wind_m_s=(0.0, 0.0, 0.0),
    density_altitude: str = "flat",
) -> np.ndarray:
    """Time derivative of Appendix B's 12 states: a port of ``PROJ6DOF_M829_DERV`` (App. B).

    ``state`` is ``[x y z phi theta psi u v w p q r]`` (flat frame, z down; 3-2-1 Euler angles;
    body-axis velocity and angular velocity). Forces, moments, the kinematic matrix K, TIB and
    the weight expression (including its omitted y^2, see the module docstring) are the
    code's. Differences from the printed code:

    - density, speed of sound and the aero coefficients are evaluated at ``state`` (the code
      evaluates them once per RK4 step at the step's start, outside this function);
    - ``wind_m_s`` (flat-frame components, constant) is subtracted from the velocity to give
      the air-relative velocity of every aerodynamic force and moment and of the Mach number;
      the printed code has no wind although the text flies a 5 m/s cross wind;
    - the Mach interpolation holds the table's end values outside Mach 0-8 (interp1: NaN);
    - ``density_altitude="spherical"`` evaluates the atmosphere at |r| - R instead of the
      code's flat-frame -z (the default, ``"flat"``).

    ``atmosphere`` is a name of :data:`harp_analysis.models.atmosphere.ATMOSPHERE_NAMES` or an
    :class:`~harp_analysis.models.atmosphere.AtmosphereModel`.
    """
    model = rigid_body_model(projectile, atmosphere, wind_m_s, density_altitude)
    return model.body(_checked_state(state))


def no_roll_derivatives(
    state,
    projectile: Projectile,
    *,
    atmosphere="two_segment",
    wind_m_s=(0.0, 0.0, 0.0),
    density_altitude: str = "flat",
) -> np.ndarray:
    """The equations of :func:`appendix_b_derivatives`, exactly, in the no-roll frame
    (Appendix B; derivation in the module docstring).

    ``state`` is ``[x y z phi theta psi u v w p q r]`` with u, v, w and p, q, r resolved in the
    no-roll frame (the body's v, w and q, r rotated back by phi); phi is carried for output
    only. The arguments are those of :func:`appendix_b_derivatives`.
    """
    model = rigid_body_model(projectile, atmosphere, wind_m_s, density_altitude)
    return np.array(model.no_roll(0.0, _checked_state(state)))


def integrate_fixed_step(
    derivatives, state0, h_s: float, t_end_s: float
) -> tuple[np.ndarray, np.ndarray]:
    """Appendix B's classical RK4 with a fixed step ``h_s`` from t = 0 to ``t_end_s``.

    ``derivatives(t, state)`` returns the state's time derivative. Returns the times (n + 1,)
    and the states (n + 1, len(state0)); ``t_end_s`` must be a whole number of steps. Used to
    verify :func:`simulate_6dof` against the dissertation's own integration scheme.
    """
    y = finite_array(state0, "state0").copy()
    if y.ndim != 1:
        raise ValueError(f"state0 must be one state vector; got shape {y.shape}")
    h = float(check_range(finite_scalar(h_s, "h_s"), "h_s", low=0.0, low_inclusive=False, unit="s"))
    t_end = float(check_range(finite_scalar(t_end_s, "t_end_s"), "t_end_s", low=h, unit="s"))
    n = round(t_end / h)
    if abs(n * h - t_end) > 1e-9 * t_end:
        raise ValueError(f"t_end_s must be a whole number of steps h_s = {h:g} s; got {t_end:g} s")
    states = np.empty((n + 1, y.size))
    states[0] = y
    for i in range(n):
        t = i * h
        k1 = np.asarray(derivatives(t, y))
        k2 = np.asarray(derivatives(t + 0.5 * h, y + 0.5 * h * k1))
        k3 = np.asarray(derivatives(t + 0.5 * h, y + 0.5 * h * k2))
        k4 = np.asarray(derivatives(t + h, y + h * k3))
        y = y + (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
        states[i + 1] = y
    return np.arange(n + 1) * h, states


@formula
def _flat_velocity(theta, psi, u, v, w):
    """Flat-frame velocity components of no-roll states (numbers or arrays)."""
    ct, st, cp, sp = np.cos(theta), np.sin(theta), np.cos(psi), np.sin(psi)
    return ct * cp * u - sp * v + st * cp * w, ct * sp * u + cp * v + st * sp * w, -st * u + ct * w


@jit
def _radial_velocity(state):
    """r . dr/dt of a no-roll state up to the factor 1/|r|: the apogee event."""
    x, y, z, _, theta, psi, u, v, w, _, _, _ = state
    vx, vy, vz = _flat_velocity(theta, psi, u, v, w)
    return x * vx + y * vy + (z - _R) * vz


@jit
def _row_aerodynamics(states, kernel):
    """Mach, axial coefficient, aerodynamic force opposing the air-relative velocity (N) and
    angle of attack of no-roll states (12, n)."""
    model = RigidBodyKernel(*kernel)
    n = states.shape[1]
    mach, axial, drag, alpha = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    for k in range(n):
        x, y, z, _, theta, psi, u, v, w, p, q, r = states[:, k]
        force, _, air_velocity, mach[k], axial[k] = _aerodynamics(
            model,
            x,
            y,
            z,
            math.cos(theta),
            math.sin(theta),
            math.cos(psi),
            math.sin(psi),
            u,
            v,
            w,
            p,
            q,
            r,
        )
        ua, va, wa = air_velocity
        drag[k] = -(force[0] * ua + force[1] * va + force[2] * wa) / math.sqrt(
            ua * ua + va * va + wa * wa
        )
        alpha[k] = math.atan2(math.hypot(va, wa), ua)
    return mach, axial, drag, alpha


def _earth_centred(states: np.ndarray) -> np.ndarray:
    """Position (n, 3) from the Earth's centre, flat-frame axes."""
    return np.column_stack([states[0], states[1], states[2] - _R])


def trajectory_table(model: RigidBodyModel, times: np.ndarray, states: np.ndarray) -> pd.DataFrame:
    """The tidy trajectory table of :mod:`.trajectory` plus :data:`EXTRA_COLUMNS` for no-roll
    states (12, n); Mach, drag and angle of attack evaluated with ``model``'s aerodynamics."""
    position = _earth_centred(states)
    velocity = np.column_stack(_flat_velocity(*states[4:9]))
    radius = np.linalg.norm(position, axis=1)
    ground, cross = surface_ranges(position, (0.0, 0.0, -1.0), (1.0, 0.0, 0.0))
    mach, axial, drag, alpha = _row_aerodynamics(np.ascontiguousarray(states), model.kernel)
    columns = dict(
        time_s=times,
        x_m=states[0],
        y_m=states[1],
        z_m=states[2],
        altitude_m=radius - _R,
        ground_range_m=ground,
        cross_range_m=cross,
        speed_m_s=np.linalg.norm(velocity, axis=1),
        mach=mach,
        drag_coefficient=axial,
        drag_to_gravity=drag / (model.mass * _GM / radius**2),
        specific_angular_momentum_m2_s=np.linalg.norm(np.cross(position, velocity), axis=1),
        flight_path_angle_rad=flight_path_angle(position, velocity),
        altitude_flat_m=-states[2],
        angle_of_attack_rad=alpha,
        roll_rate_rad_s=states[9],
        roll_rad=states[3],
        pitch_rad=states[4],
        yaw_rad=states[5],
    )
    return pd.DataFrame({name: columns[name] for name in BASE_COLUMNS + EXTRA_COLUMNS})


def altitude_and_range(state) -> tuple[float, float]:
    """Altitude |r| - R and ground range (m) of one no-roll state, as in
    :func:`trajectory_table`."""
    position = _earth_centred(np.asarray(state, dtype=float)[:, None])
    ground, _ = surface_ranges(position, (0.0, 0.0, -1.0), (1.0, 0.0, 0.0))
    return float(np.linalg.norm(position, axis=1)[0] - _R), float(ground[0])


def rigid_body_launch(launch: Launch, engine: str, density_altitude: str) -> RigidBodyModel:
    """The checked rigid-body model of ``launch`` for the 6DOF or the MLT, which fly Appendix
    B's flat frame over a non-rotating Earth from sea level: the bearing, latitude and longitude
    do not change such a flight; a rotating Earth or a raised site is refused."""
    if not isinstance(launch, Launch):
        raise TypeError(f"launch must be a Launch; got {type(launch).__name__}")
    launch.require_zero(
        engine,
        "rotation_rate_rad_s",
        "site_altitude_m",
        reason="Appendix B's frame is flat, non-rotating and starts at sea level",
    )
    launch.warn_ignored(
        engine,
        "density_change_fraction",
        "temperature_change_k",
        reason="Appendix B's rigid-body model flies its atmosphere as the model gives it",
    )
    projectile = check_rigid_body(launch.projectile, f"the {engine}")
    if math.cos(launch.elevation_rad) <= _SINGULAR_COS:
        raise ValueError(
            f"launch.elevation_deg = {launch.elevation_deg:g} deg starts at the singularity of "
            "Appendix B's Euler angles (theta = 90 deg); launch a little lower"
        )
    wind = (-launch.head_wind_m_s, launch.cross_wind_m_s, 0.0)
    return rigid_body_model(projectile, launch.atmosphere, wind, density_altitude)


def launch_state(launch: Launch) -> np.ndarray:
    """The 12 states at the gun (:data:`STATE_NAMES`): the flat frame's origin, psi = phi = 0,
    theta = the elevation, body velocity [speed, 0, 0], roll rate = the launch's spin."""
    return np.array(
        [
            0.0,
            0.0,
            0.0,
            0.0,
            launch.elevation_rad,
            0.0,
            launch.speed_m_s,
            0.0,
            0.0,
            launch.spin_rad_s,
            0.0,
            0.0,
        ]
    )


def flight_table(
    model: RigidBodyModel,
    solution,
    launch: Launch,
    engine: str,
    *,
    output_step_s: float,
    max_time_s: float,
    **metadata,
) -> pd.DataFrame:
    """A rigid-body solve_ivp flight (events: impact first, apogee second) as the shared table
    every ``output_step_s`` and at the end, with the shared metadata
    (:func:`harp_analysis.models.trajectory.describe`)."""
    end = float(solution.t[-1])
    times = output_times(end, output_step_s)
    frame = trajectory_table(model, times, solution.sol(times))
    highest = None
    if solution.t_events[1].size:
        highest = (float(solution.t_events[1][0]), *altitude_and_range(solution.y_events[1][0]))
    return describe(
        frame,
        engine=engine,
        launch=launch,
        apogee=highest,
        impact=solution.status == 1,
        rhs_evaluations=solution.nfev,
        steps=solution.t.size - 1,
        max_time_s=max_time_s,
        **metadata,
    )


def simulate_6dof(
    launch: Launch,
    *,
    density_altitude: str = "flat",
    rtol: float = 1e-9,
    max_time_s: float = 400.0,
    output_step_s: float = 0.5,
) -> pd.DataFrame:
    """One 6DOF flight of Appendix B from launch to impact, as the tidy trajectory table.

    Launch from the flat frame's origin with psi = phi = 0, theta = the launch elevation, body
    velocity [speed, 0, 0] and roll rate ``launch.spin_rad_s``; the launch's cross wind blows
    along +y (toward positive cross range), its head wind along -x. The equations are Appendix
    B's (:func:`appendix_b_derivatives`) integrated in the no-roll frame
    (:func:`no_roll_derivatives`) by scipy's DOP853 with relative tolerance ``rtol``; air
    density at the flat-frame altitude as Appendix B takes it, or ``density_altitude=
    "spherical"``.

    Rows every ``output_step_s`` (dense output) and at the end: the impact, where the spherical
    altitude |r| - R returns to zero, or ``max_time_s`` if it comes first (a
    TruncatedFlightWarning). Columns: :data:`harp_analysis.models.trajectory.BASE_COLUMNS` (x_m,
    y_m, z_m in the flat frame, z down; speed relative to the non-rotating frame; Mach and angle of
    attack air-relative; ``drag_coefficient`` the applied axial coefficient -CX0 - CX2 (v^2 +
    w^2)/V^2; ``drag_to_gravity`` the aerodynamic force component opposing the air-relative
    velocity over m GM / |r|^2) and :data:`EXTRA_COLUMNS`; ``frame.attrs`` the shared metadata
    (:func:`harp_analysis.models.trajectory.describe`).
    """
    model = rigid_body_launch(launch, "6DOF", density_altitude)
    projectile = launch.projectile
    rtol = check_range(finite_scalar(rtol, "rtol"), "rtol", low=1e-13, high=1e-3)
    max_time = positive_scalar(max_time_s, "max_time_s", "s")
    step = positive_scalar(output_step_s, "output_step_s", "s")

    def impact(t, y):
        return math.sqrt(y[0] ** 2 + y[1] ** 2 + (_R - y[2]) ** 2) - _R

    def apogee(t, y):
        return _radial_velocity(y)

    def singular_pitch(t, y):
        return math.cos(y[4]) - _SINGULAR_COS

    # The launch is upward, so the altitude leaves zero increasing: only a downward crossing
    # (direction -1) is an impact and the launch point is not one.
    # (solve_ivp reads an event's options from attributes of the function)
    impact.terminal, impact.direction = True, -1  # type: ignore[attr-defined]
    apogee.direction = -1  # type: ignore[attr-defined]
    singular_pitch.terminal, singular_pitch.direction = True, -1  # type: ignore[attr-defined]
    y0 = launch_state(launch)
    try:
        solution = solve_ivp(
            model.no_roll,
            (0.0, max_time),
            y0,
            method="DOP853",
            rtol=rtol,
            atol=_ATOL,
            dense_output=True,
            events=(impact, apogee, singular_pitch),
        )
    except (ArithmeticError, ValueError) as exc:
        raise RuntimeError(f"6DOF integration of {projectile.name} failed: {exc}") from exc
    if solution.status < 0:
        raise RuntimeError(
            f"6DOF integration of {projectile.name} failed at "
            f"t = {solution.t[-1]:.3f} s: {solution.message}"
        )
    if solution.t_events[2].size:
        raise RuntimeError(
            f"6DOF flight of {projectile.name} stopped at t = "
            f"{solution.t[-1]:.3f} s: the pitch reached +-90 deg, the singularity "
            "of Appendix B's Euler angles"
        )

    return flight_table(
        model,
        solution,
        launch,
        "6DOF",
        output_step_s=step,
        max_time_s=max_time,
        rtol=rtol,
        density_altitude=density_altitude,
    )
