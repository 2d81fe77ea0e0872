"""The rigid finned projectile of Appendix B (Chapter 2 A's HP and LP, M829 aerodynamics), as the
6DOF (:mod:`harp_analysis.engines.sixdof`) and Modified Linear Theory
(:mod:`harp_analysis.engines.mlt`) both fly it.

The frame is Appendix B's: flat, non-rotating, x downrange, y cross range, z down, the Earth's
centre at (0, 0, +R). The 12 states are ``[x y z phi theta psi u v w p q r]``
(:data:`STATE_NAMES`): position in the flat frame, 3-2-1 Euler angles, and velocity and angular
velocity, here resolved in the no-roll frame N (reached from the flat frame by psi then theta
only; the derivation is in the 6DOF's module docstring). What the two engines share lives here,
written once:

- :class:`RigidBodyModel`: one projectile's mass, inertias (Iy = Iz, Appendix B) and diameter, its
  M829 table of nine coefficients, the atmosphere (read at the flat altitude -z as Appendix B does,
  or at the spherical |r| - R, :data:`DENSITY_ALTITUDES`) and a constant wind; its
  :attr:`RigidBodyModel.kernel` is the same model as compiled code takes it
  (:class:`RigidBodyKernel`);
- :func:`aerodynamics`: Appendix B's aerodynamic force and moment in the no-roll frame (the
  ``FSA``, ``FMAG``, ``MSA``, ``MUA`` and ``MMAG`` lines of ``PROJ6DOF_M829_DERV``, with the wind
  subtracted from the velocity and the air read at the state passed);
- :func:`rigid_body_launch` and :func:`launch_state`: a :class:`~harp_analysis.models.launch.Launch`
  as the model and the 12 states at the gun;
- :func:`trajectory_table` and :func:`flight_table`: no-roll states as the shared trajectory table
  of :mod:`.trajectory` plus :data:`EXTRA_COLUMNS`.

The Mach interpolation holds the table's end values outside Mach 0-8, where MATLAB's ``interp1``
returns NaN (see :mod:`.drag`). The Euler angles are Appendix B's and share its singularity at
theta = +-90 deg (:data:`SINGULAR_PITCH_COSINE`).
"""

from __future__ import annotations

import math
from bisect import bisect_right
from functools import lru_cache
from typing import NamedTuple

import numpy as np
import pandas as pd

from ..foundation import earth
from ..foundation.compiled import formula, jit
from ..foundation.validation import check_choice, finite_array
from .atmosphere import AtmosphereModel, air, get_atmosphere
from .launch import Launch
from .projectiles import Projectile, check_rigid_body
from .trajectory import (
    BASE_COLUMNS,
    describe,
    flight_path_angle,
    output_times,
    surface_ranges,
)

__all__ = [
    "STATE_NAMES",
    "DENSITY_ALTITUDES",
    "EXTRA_COLUMNS",
    "SINGULAR_PITCH_COSINE",
    "RigidBodyModel",
    "RigidBodyKernel",
    "rigid_body_model",
    "rigid_body_launch",
    "launch_state",
    "aerodynamics",
    "flat_velocity",
    "altitude_and_range",
    "trajectory_table",
    "flight_table",
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
#: Appendix B's Euler angles are singular at theta = +-90 deg (tan theta, 1/cos theta): a launch
#: this close to the vertical (cosine of the pitch; 0.00006 deg) is refused, and a 6DOF flight that
#: comes within it stops with a RuntimeError.
SINGULAR_PITCH_COSINE = 1e-6


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
# segments, Appendix B's port in the 6DOF) or a RigidBodyKernel in compiled code (the 6DOF's
# no-roll right-hand side that DOP853 calls, the table's aerodynamics).
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
def aerodynamics(model, x, y, z, c_theta, s_theta, c_psi, s_psi, u, v, w, p, q, r):
    """Aerodynamic force and moment in the no-roll frame, air-relative velocity (same
    frame), Mach and the total axial coefficient -CX0 - CX2 (v^2 + w^2)/V^2, of ``model`` (a
    :class:`RigidBodyKernel`) at a state given by its position, the cosines and sines of its
    pitch and yaw, and its no-roll velocity and angular velocity: Appendix B's force and moment
    lines with v, w, q, r read in the no-roll frame (the 6DOF's module docstring, step 5)."""
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


class RigidBodyModel:
    """Constants of one projectile in one atmosphere and wind, its M829 table and where it reads
    the air; :attr:`~harp_analysis.models.rigid_body.RigidBodyModel.kernel` is the same model as
    compiled code takes it."""

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


def _atmosphere_model(atmosphere) -> AtmosphereModel:
    return atmosphere if isinstance(atmosphere, AtmosphereModel) else get_atmosphere(atmosphere)


# Cached: the 6DOF's verification RK4 calls its public derivatives thousands of times per run.
@lru_cache(maxsize=16)
def _model(projectile, atmosphere, wind_m_s, density_altitude) -> RigidBodyModel:
    return RigidBodyModel(projectile, atmosphere, wind_m_s, density_altitude)


def rigid_body_model(projectile, atmosphere, wind_m_s, density_altitude) -> RigidBodyModel:
    """The checked, cached :class:`RigidBodyModel` of ``projectile`` in ``atmosphere`` (a name of
    :data:`harp_analysis.models.atmosphere.ATMOSPHERE_NAMES` or an
    :class:`~harp_analysis.models.atmosphere.AtmosphereModel`), with the constant wind
    ``wind_m_s`` (3 flat-frame components) and the air read at ``density_altitude``
    (:data:`DENSITY_ALTITUDES`)."""
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


@formula
def flat_velocity(theta, psi, u, v, w):
    """Flat-frame velocity components of no-roll states (numbers or arrays)."""
    ct, st, cp, sp = np.cos(theta), np.sin(theta), np.cos(psi), np.sin(psi)
    return ct * cp * u - sp * v + st * cp * w, ct * sp * u + cp * v + st * sp * w, -st * u + ct * w


@jit
def _row_aerodynamics(states, kernel):
    """Mach, axial coefficient, aerodynamic force opposing the air-relative velocity (N) and
    angle of attack of no-roll states (12, n)."""
    model = RigidBodyKernel(*kernel)
    n = states.shape[1]
    mach, axial, drag, alpha = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    for k in range(n):
        x, y, z, _, theta, psi, u, v, w, p, q, r = states[:, k]
        force, _, air_velocity, mach[k], axial[k] = aerodynamics(
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
    velocity = np.column_stack(flat_velocity(*states[4:9]))
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
    if math.cos(launch.elevation_rad) <= SINGULAR_PITCH_COSINE:
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
