"""The rotating-Earth (ECI) corrections of Chapter 5 and the derived columns of Appendices D and E.

The gun fires at ``speed_m_s`` (Vrel, relative to the ground and the air), elevation and bearing;
in the Earth-centred inertial frame the launch velocity is (eq 6.15)

    V = Vrel + omega x r0 + V_tangent,

with omega x r0 the eastward surface velocity (eq 6.16) and V_tangent the velocity given by the
drag component across the inertial velocity (eqs 5.4-5.8). The drag lies along Vrel, at the
misalignment angle mu from V (Ch. 5 B), so only cos(mu) of it decays the angular momentum
(eq 5.1) and, referred to the inertial speed, the decay carries (Vrel/V)^2 (eqs 5.2-5.3). These
enter :class:`~harp_analysis.engines.mks.ModifiedKeplerSolution` as ``drive_scale`` = cos(mu)
(Vrel/V)^2 (eqs 6.9-6.10) and ``decay_scale`` = cos(mu) (eq 6.14).

Vectors are (3, ...) arrays in the inertial frame of
:func:`~harp_analysis.models.trajectory.launch_frame` at longitude 0 (z along the Earth's axis);
angles in rad, speeds in m/s, SI throughout. The door from a
:class:`~harp_analysis.models.launch.Launch` or :class:`~harp_analysis.models.launch.Launches` is
:func:`correction_for_launch`, and from loose arrays (the appendices' rounds)
:func:`correction_for_arrays`, which checks them; either gives a :class:`LaunchCorrection`, whose
:meth:`~LaunchCorrection.solution` is the ECI MKS. :func:`simulate_eci_mks` flies it as the engines'
trajectory table, in the 3DOF's frame on a rotating Earth. :func:`corrected_launch` is the compiled
formula behind both doors, shared with the fire-control solver's kernels.

Sign of V_tangent (the text leaves it open: "in the plane created by the relative velocity and
the velocity corrected for Earth rotation and tangent to the corrected velocity"). The drag
acceleration is along -Vrel = -(V - omega x r0); its part normal to V is +(omega x r0)_perp,
because V has none. So V_tangent points along the part of omega x r0 normal to V, i.e. AWAY
from Vrel: drag drains the air-relative velocity and leaves the projectile moving more with the
air, turning V further from the gun line (lower and more eastward for an eastward shot), and mu
grows. Rotating V back toward Vrel would need a force with a component along +Vrel, which drag
has not. The printed Appendix D/E columns do not include V_tangent at all (see
:func:`~harp_analysis.analyses.harp.apogees.appendix_columns`, model ``"printed_columns"`` and
:data:`PRINTED_COLUMNS`).

The printed equations, checked: eq 5.3 is exact, not an expansion, if Vx is the eastward
component of the inertial V (omega x r is due east, of size omega r cos LA). Eqs 6.6-6.10 are
mks's general-n constants for n = 3 (c4 = A_1, c5 = A_2, the c3 term = A_0) with beta ->
beta cos(mu) (Vrel/V)^2, signs included. Eq 6.8's m^2 MG / L_inf^2 needs L per unit mass
without the m^2 (eq 6.13's L0 and Appendix Li, km^2/s, are per unit mass); eq 6.11's "2 km" is
2 k m. Eq 6.14 decays L with beta cos(mu) but drives with beta cos(mu) (Vrel/V)^2, whereas
h = h_inf exp(beta' gamma) gives both the same beta' (eq 3.23); as printed, and here, they differ
(Barbados round 181: apogee 120.5 km as printed, 124.6 km with (Vrel/V)^2 in eq 6.14 too).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import pandas as pd

from ..foundation import earth
from ..foundation.compiled import formula, select
from ..foundation.validation import Bounds, check_choice, finite_array, whole_number
from ..models.atmosphere import TEXT_DECAY_CONSTANT_PER_M
from ..models.launch import Launch, Launches
from ..models.sites import get_site
from ..models.trajectory import (
    MAX_ROWS,
    cross,
    describe,
    dot,
    launch_axes,
    launch_frame,
    rotate_about_axis,
    surface_ranges,
)
from . import mks

__all__ = [
    "EciModel",
    "CONSISTENT",
    "DISSERTATION",
    "PRINTED_COLUMNS",
    "MODELS",
    "get_model",
    "LaunchCorrection",
    "surface_velocity",
    "relative_velocity",
    "misalignment_angle",
    "speed_ratio_squared",
    "speed_ratio_squared_eq_5_3",
    "tangent_speed",
    "tangent_direction",
    "elevation_azimuth",
    "initial_angular_momentum",
    "correction_for_launch",
    "correction_for_arrays",
    "site_surface_speed_km_s",
    "flight_plane",
    "inertial_positions",
    "simulate_eci_mks",
    "TIME_GRID_POINTS",
]


def _check_launch(speed_m_s, elevation_rad, bearing_rad, latitude_rad):
    speed = Bounds(low=0.0, low_inclusive=False, unit="m/s").finite(speed_m_s, "speed_m_s")
    elevation = Bounds(low=0.0, high=math.pi / 2, low_inclusive=False, unit="rad").finite(
        elevation_rad, "elevation_rad"
    )
    bearing = Bounds(low=0.0, high=2 * math.pi, high_inclusive=False, unit="rad").finite(
        bearing_rad, "bearing_rad"
    )
    return np.broadcast_arrays(speed, elevation, bearing, _check_latitude(latitude_rad))


def _check_latitude(latitude_rad):
    return Bounds(low=-math.pi / 2, high=math.pi / 2, unit="rad").finite(
        latitude_rad, "latitude_rad"
    )


def _components(vectors) -> tuple:
    """The x, y and z rows of (3, ...) vectors."""
    array = np.asarray(vectors, dtype=float)
    return array[0], array[1], array[2]


@formula
def _surface(up, rotation_rate_rad_s, radius_m):
    """omega x r0 of component triples: omega along the Earth's axis (z), r0 = radius up."""
    scale = rotation_rate_rad_s * radius_m
    return -scale * up[1], scale * up[0], 0.0 * up[2]


@formula
def _misalignment(relative, inertial):
    cosine = dot(relative, inertial) / np.sqrt(dot(relative, relative) * dot(inertial, inertial))
    return np.arccos(np.minimum(np.maximum(cosine, -1.0), 1.0))


@formula
def _speed_ratio_squared(relative, inertial):
    return dot(relative, relative) / dot(inertial, inertial)


@formula
def _tangent_speed(
    drag_area_m2, density, mass_kg, misalignment, relative_speed, climb, decay_constant_per_m
):
    return (
        drag_area_m2
        * density
        * np.sin(misalignment)
        * relative_speed
        / (2 * mass_kg * decay_constant_per_m * np.sin(climb))
    )


@formula
def _tangent_direction(relative, inertial):
    speed = np.sqrt(dot(inertial, inertial))
    along = dot(relative, inertial) / speed  # Vrel's component along V
    across = (
        along * inertial[0] / speed - relative[0],
        along * inertial[1] / speed - relative[1],
        along * inertial[2] / speed - relative[2],
    )
    size = np.sqrt(dot(across, across))
    inverse = select(size > 0, 1.0 / select(size > 0, size, 1.0), 0.0 * size)
    return inverse * across[0], inverse * across[1], inverse * across[2]


@formula
def _elevation_azimuth(velocity, up, east):
    north = cross(up, east)
    speed = np.sqrt(dot(velocity, velocity))
    elevation = np.arcsin(np.minimum(np.maximum(dot(velocity, up) / speed, -1.0), 1.0))
    azimuth = np.arctan2(dot(velocity, east), dot(velocity, north)) % (2 * math.pi)
    return elevation, azimuth


@formula
def _initial_angular_momentum(speed_m_s, elevation_rad, radius_m):
    return speed_m_s * radius_m * np.cos(elevation_rad)


@formula
def corrected_launch(
    speed_m_s,
    elevation_rad,
    bearing_rad,
    latitude_rad,
    drag_area_m2,
    mass_kg,
    surface_density_kg_m3,
    decay_constant_per_m,
    rotation_rate_rad_s,
    radius_m,
    include_tangent,
    tangent_sine_corrected,
    beta_at_launch,
    tau_at_launch,
    ratio_at_launch,
):
    """Eqs 5.1-5.8 and 6.11-6.16 of guns at the launch point (longitude 0), written once for
    numpy (arrays of one shape, the model's flags plain bools) and compiled code (numbers):
    Vrel, omega x r0, mu, the corrected speed, elevation and azimuth, V_tangent, the launch
    velocity, its speed, elevation and azimuth, (Vrel/V)^2, beta, tau and L0, vectors as
    component triples (:class:`LaunchCorrection` names them). The flags are
    :class:`EciModel`'s choices: ``include_tangent``, ``tangent_sine == "corrected"``,
    ``beta_elevation == "launch"``, ``tau_elevation == "launch"``, ``speed_ratio == "launch"``."""
    up, downrange, east = launch_axes(latitude_rad, 0.0 * latitude_rad, bearing_rad)
    horizontal, vertical = speed_m_s * np.cos(elevation_rad), speed_m_s * np.sin(elevation_rad)
    relative = (
        horizontal * downrange[0] + vertical * up[0],
        horizontal * downrange[1] + vertical * up[1],
        horizontal * downrange[2] + vertical * up[2],
    )
    surface = _surface(up, rotation_rate_rad_s, radius_m)
    corrected = (relative[0] + surface[0], relative[1] + surface[1], relative[2] + surface[2])
    mu = _misalignment(relative, corrected)
    corrected_elevation, corrected_azimuth = _elevation_azimuth(corrected, up, east)
    climb = select(tangent_sine_corrected, corrected_elevation, elevation_rad)
    relative_speed = np.sqrt(dot(relative, relative))
    tangent = _tangent_speed(
        drag_area_m2,
        surface_density_kg_m3,
        mass_kg,
        mu,
        relative_speed,
        climb,
        decay_constant_per_m,
    )
    push = select(include_tangent, tangent, 0.0 * tangent)
    direction = _tangent_direction(relative, corrected)
    velocity = (
        corrected[0] + push * direction[0],
        corrected[1] + push * direction[1],
        corrected[2] + push * direction[2],
    )
    elevation, azimuth = _elevation_azimuth(velocity, up, east)
    ratio_of = (
        select(ratio_at_launch, velocity[0], corrected[0]),
        select(ratio_at_launch, velocity[1], corrected[1]),
        select(ratio_at_launch, velocity[2], corrected[2]),
    )
    air = (ratio_of[0] - surface[0], ratio_of[1] - surface[1], ratio_of[2] - surface[2])
    beta = mks.beta_formula(
        drag_area_m2,
        surface_density_kg_m3,
        1.0,
        mass_kg,
        select(beta_at_launch, elevation, elevation_rad),
        decay_constant_per_m,
    )
    tau = mks.decay_rate_tau(
        select(tau_at_launch, elevation, corrected_elevation), decay_constant_per_m, radius_m
    )
    speed = np.sqrt(dot(velocity, velocity))
    return (
        relative,
        surface,
        mu,
        np.sqrt(dot(corrected, corrected)),
        corrected_elevation,
        corrected_azimuth,
        tangent,
        velocity,
        speed,
        elevation,
        azimuth,
        _speed_ratio_squared(air, ratio_of),
        beta,
        tau,
        _initial_angular_momentum(speed, elevation, radius_m),
    )


def surface_velocity(
    latitude_rad, *, rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S, radius_m=earth.RADIUS_M
):
    """Eq 6.16: omega x r0 (m/s), the launch site's velocity, a (3, ...) vector due east of
    magnitude omega r0 cos(latitude): 451.8 m/s at Barbados."""
    latitude = _check_latitude(latitude_rad)
    up, _, _ = launch_axes(latitude, 0.0 * latitude, 0.0 * latitude)
    return np.array(_surface(up, rotation_rate_rad_s, radius_m))


def relative_velocity(speed_m_s, elevation_rad, bearing_rad, latitude_rad):
    """Vrel (m/s), the muzzle velocity relative to the ground: ``speed_m_s`` at ``elevation_rad``
    above the horizon along ``bearing_rad`` from true north (Fig 5.1)."""
    speed, elevation, bearing, latitude = _check_launch(
        speed_m_s, elevation_rad, bearing_rad, latitude_rad
    )
    up, downrange, _ = launch_frame(latitude, 0.0, bearing)
    return speed * (np.cos(elevation) * downrange + np.sin(elevation) * up)


def misalignment_angle(relative_m_s, inertial_m_s):
    """Ch. 5 B: mu (rad), the angle between the drag line (Vrel) and the inertial velocity V."""
    return _misalignment(_components(relative_m_s), _components(inertial_m_s))


def speed_ratio_squared(relative_m_s, inertial_m_s):
    """(Vrel/V)^2 of eqs 5.2-5.3, exactly, from the two vectors."""
    return _speed_ratio_squared(_components(relative_m_s), _components(inertial_m_s))


def speed_ratio_squared_eq_5_3(
    inertial_m_s,
    latitude_rad,
    *,
    rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S,
    radius_m=earth.RADIUS_M,
):
    """Eq 5.3 as printed: 1 - 2 Vx omega r cos(LA)/V^2 + (omega r)^2 cos^2(LA)/V^2.

    With Vx the EASTWARD component of the inertial V (not of Vrel) this is |V - omega x r|^2/V^2
    exactly, not an expansion: omega x r is due east with magnitude omega r cos(LA)."""
    latitude = _check_latitude(latitude_rad)
    _, _, east = launch_frame(latitude, 0.0, 0.0)
    v_squared = np.sum(inertial_m_s * inertial_m_s, axis=0)
    surface = rotation_rate_rad_s * radius_m * np.cos(latitude)
    eastward = np.sum(inertial_m_s * east, axis=0)
    return 1 - 2 * eastward * surface / v_squared + surface**2 / v_squared


def tangent_speed(
    drag_area_m2,
    surface_density_kg_m3,
    mass_kg,
    misalignment_rad,
    relative_speed_m_s,
    relative_elevation_rad,
    decay_constant_per_m=TEXT_DECAY_CONSTANT_PER_M,
):
    """Eq 5.8: V_tangent = Cd A rho0 sin(mu) Vrel / (2 m k sin(phi_rel)) (m/s), the integral of
    the cross-track drag (eq 5.5) along the straight climb a = Vrel sin(phi_rel) t (eq 5.7);
    ``drag_area_m2`` is Cd A."""
    return _tangent_speed(
        np.asarray(drag_area_m2),
        surface_density_kg_m3,
        mass_kg,
        misalignment_rad,
        relative_speed_m_s,
        relative_elevation_rad,
        decay_constant_per_m,
    )


def tangent_direction(relative_m_s, inertial_m_s):
    """Unit vector of V_tangent (eq 6.15): normal to V in the plane of Vrel and V, on the side
    AWAY from Vrel, the side of the cross-track drag -Vrel (module docstring). Zero if mu = 0."""
    return np.array(_tangent_direction(_components(relative_m_s), _components(inertial_m_s)))


def elevation_azimuth(velocity_m_s, latitude_rad):
    """Elevation above the local horizon and azimuth from true north (rad, in [0, 2 pi)) of a
    (3, ...) inertial velocity at the launch point (longitude 0) on ``latitude_rad``."""
    latitude = _check_latitude(latitude_rad)
    up, _, east = launch_axes(latitude, 0.0 * latitude, 0.0 * latitude)
    return _elevation_azimuth(_components(velocity_m_s), up, east)


def initial_angular_momentum(speed_m_s, elevation_rad, radius_m=earth.RADIUS_M):
    """Eq 6.13: L0 = |V| r0 cos(phi) (m^2/s), per unit mass."""
    return _initial_angular_momentum(speed_m_s, elevation_rad, radius_m)


@dataclass(frozen=True)
class EciModel:
    """The choices Chapters 5-6 leave open in launching the ECI MKS, named.

    - ``include_tangent``: eq 6.15's V_tangent in the launch velocity.
    - ``tangent_sine``: the sin(phi) of eq 5.8's straight climb: ``"gun"`` (phi_rel, the gun's
      elevation, as printed) or ``"corrected"`` (the elevation of Vrel + omega x r0).
    - ``beta_elevation``: eq 6.11's phi: ``"gun"`` or ``"launch"`` (of the launch velocity).
    - ``tau_elevation``: eq 6.12's phi: ``"corrected"`` or ``"launch"``.
    - ``speed_ratio``: (Vrel/V)^2 of eq 5.3 with V = ``"corrected"`` (Vrel + omega x r0) or
      ``"launch"`` (the launch velocity, V_tangent included, against its air-relative part).
    - ``decay``: ``"printed"`` (eq 6.14, L_inf = L0 exp(-beta cos mu)) or ``"consistent"``
      (cos mu (Vrel/V)^2 in the decay as in the driving terms, as eq 3.23 requires).
    - ``beta_column``: what the appendices' Beta column holds under this model: ``"beta"``
      (eq 6.11) or ``"beta_cos_mu"`` (eq 6.14's exponent, beta cos mu).
    """

    name: str
    include_tangent: bool
    tangent_sine: str
    beta_elevation: str
    tau_elevation: str
    speed_ratio: str
    decay: str
    beta_column: str = "beta"

    def __post_init__(self):
        for name, choices in (
            ("tangent_sine", ("gun", "corrected")),
            ("beta_elevation", ("gun", "launch")),
            ("tau_elevation", ("corrected", "launch")),
            ("speed_ratio", ("corrected", "launch")),
            ("decay", ("printed", "consistent")),
            ("beta_column", ("beta", "beta_cos_mu")),
        ):
            check_choice(getattr(self, name), name, choices)

    @property
    def flags(self) -> tuple[bool, bool, bool, bool, bool]:
        """The choices as :func:`corrected_launch`'s flags, in its order."""
        return (
            self.include_tangent,
            self.tangent_sine == "corrected",
            self.beta_elevation == "launch",
            self.tau_elevation == "launch",
            self.speed_ratio == "launch",
        )


#: The project's model: eqs 5.8 and 6.11-6.15 as printed, except the decay (eq 3.23).
CONSISTENT = EciModel(
    "consistent",
    include_tangent=True,
    tangent_sine="gun",
    beta_elevation="launch",
    tau_elevation="launch",
    speed_ratio="corrected",
    decay="consistent",
)
#: The dissertation's own pipeline, recovered from Appendix E's Error column (:mod:`.apogees`).
DISSERTATION = EciModel(
    "dissertation",
    include_tangent=True,
    tangent_sine="corrected",
    beta_elevation="gun",
    tau_elevation="corrected",
    speed_ratio="launch",
    decay="consistent",
    beta_column="beta_cos_mu",
)
#: What Appendices D and E's corrected columns describe: the project's model with no V_tangent
#: and eq 6.14 as printed.
PRINTED_COLUMNS = replace(
    CONSISTENT, name="printed_columns", include_tangent=False, decay="printed"
)
MODELS = {model.name: model for model in (DISSERTATION, CONSISTENT, PRINTED_COLUMNS)}


def get_model(model: str | EciModel) -> EciModel:
    """``model`` itself, or the named one of :data:`MODELS`; else ValueError naming it."""
    if isinstance(model, EciModel):
        return model
    return MODELS[check_choice(model, "model", MODELS)]


@dataclass(frozen=True)
class LaunchCorrection:
    """Chapter 5's corrections of one or many launches (arrays broadcast together)."""

    model: EciModel
    relative_m_s: np.ndarray  # Vrel, (3, ...)
    surface_m_s: np.ndarray  # omega x r0, (3, ...)
    misalignment_rad: np.ndarray  # mu between Vrel and Vrel + omega x r0
    corrected_speed_m_s: np.ndarray  # |Vrel + omega x r0|, Appendices D/E's corrected columns
    corrected_elevation_rad: np.ndarray
    corrected_azimuth_rad: np.ndarray
    tangent_speed_m_s: np.ndarray  # eq 5.8
    velocity_m_s: np.ndarray  # the launch velocity: eq 6.15, with or without V_t
    speed_m_s: np.ndarray
    elevation_rad: np.ndarray
    azimuth_rad: np.ndarray
    speed_ratio_squared: np.ndarray  # (Vrel/V)^2, eq 5.3
    beta: np.ndarray  # eq 6.11
    tau: np.ndarray  # eq 6.12
    initial_angular_momentum_m2_s: np.ndarray  # eq 6.13
    # what the corrections were computed from, beside the gun's speed and angles: what
    # re-lays the same gun at other angles (the fire-control solver) or flies it needs
    drag_area_m2: np.ndarray  # Cd0 A
    mass_kg: np.ndarray
    surface_density_kg_m3: np.ndarray  # rho0, eq 3.11's air at the gun
    decay_constant_per_m: float  # k of eq 3.11
    rotation_rate_rad_s: float
    radius_m: float = earth.RADIUS_M  # r0

    def solution(self, *, n_terms: int = 3, warn: bool = True) -> mks.ModifiedKeplerSolution:
        """The ECI Modified Kepler solution of these launches (eqs 6.6-6.15): the MKS launched
        at the launch speed and elevation with their beta and tau, :attr:`drive_scale` on beta
        in its driving terms (eqs 6.9-6.10) and :attr:`decay_scale` in its decay (eq 6.14).

        Parameters
        ----------
        n_terms : int
            Terms of the series of eq 3.30.
        warn : bool
            Warn where a launch leaves the MKS's validity (beta above 0.25, escape, an apogee
            in the sensible atmosphere).

        Returns
        -------
        mks.ModifiedKeplerSolution
            Apogee, impact and the state at any angular range, numbers for one launch or
            arrays for many.
        """
        return mks.ModifiedKeplerSolution(
            self.speed_m_s,
            self.elevation_rad,
            self.beta,
            self.tau,
            n_terms=n_terms,
            radius_m=self.radius_m,
            drive_scale=self.drive_scale,
            decay_scale=self.decay_scale,
            warn=warn,
        )

    @property
    def drive_scale(self) -> np.ndarray:
        """cos(mu) (Vrel/V)^2, the factor on beta in eqs 6.6-6.10."""
        return np.cos(self.misalignment_rad) * self.speed_ratio_squared

    @property
    def decay_scale(self) -> np.ndarray:
        """The factor on beta in the decay of the angular momentum (eq 6.14)."""
        consistent = self.model.decay == "consistent"
        return np.cos(self.misalignment_rad) * (self.speed_ratio_squared if consistent else 1.0)

    @property
    def beta_column(self) -> np.ndarray:
        """The appendices' Beta column as ``model.beta_column`` reads it."""
        cosine = np.cos(self.misalignment_rad) if self.model.beta_column == "beta_cos_mu" else 1.0
        return self.beta * cosine

    @property
    def asymptotic_angular_momentum_m2_s(self) -> np.ndarray:
        """L_inf = L0 exp(-beta x decay scale) (eq 6.14 or its consistent form)."""
        return self.initial_angular_momentum_m2_s * np.exp(-self.beta * self.decay_scale)


def _corrections(
    speed_m_s,
    elevation_rad,
    bearing_rad,
    latitude_rad,
    drag_area_m2,
    mass_kg,
    surface_density_kg_m3,
    decay_constant_per_m: float,
    rotation_rate_rad_s: float,
    radius_m: float,
    model: EciModel,
) -> LaunchCorrection:
    """:func:`corrected_launch` of launches whose values were checked at their door
    (:func:`correction_for_launch`, :func:`correction_for_arrays`), broadcast together."""
    speed, elevation, bearing, latitude, mass, drag_area, density = np.broadcast_arrays(
        speed_m_s, elevation_rad, bearing_rad, latitude_rad, mass_kg, drag_area_m2,
        surface_density_kg_m3,
    )  # fmt: skip
    (
        relative,
        surface,
        mu,
        corrected_speed,
        corrected_elevation,
        corrected_azimuth,
        tangent,
        velocity,
        launch_speed,
        launch_elevation,
        launch_azimuth,
        ratio,
        beta,
        tau,
        momentum,
    ) = corrected_launch(
        speed,
        elevation,
        bearing,
        latitude,
        drag_area,
        mass,
        density,
        decay_constant_per_m,
        rotation_rate_rad_s,
        radius_m,
        *model.flags,
    )
    return LaunchCorrection(
        model,
        np.array(relative),
        np.array(surface),
        mu,
        corrected_speed,
        corrected_elevation,
        corrected_azimuth,
        tangent,
        np.array(velocity),
        launch_speed,
        launch_elevation,
        launch_azimuth,
        ratio,
        beta,
        tau,
        momentum,
        np.array(drag_area),  # copies: not views of the caller's arrays
        np.array(mass),
        np.array(density),
        decay_constant_per_m,
        rotation_rate_rad_s,
        radius_m,
    )


def _check_mass(mass_kg):
    return Bounds(low=0.0, low_inclusive=False, unit="kg").finite(mass_kg, "mass_kg")


def _check_drag_area(drag_area_m2):
    return Bounds(low=0.0, unit="m^2").finite(drag_area_m2, "drag_area_m2")


def _check_density(surface_density_kg_m3):
    return Bounds(low=0.0, unit="kg/m^3").finite(surface_density_kg_m3, "surface_density_kg_m3")


def correction_for_arrays(
    speed_m_s,
    elevation_rad,
    bearing_rad,
    latitude_rad,
    *,
    drag_area_m2,
    mass_kg,
    surface_density_kg_m3,
    decay_constant_per_m=TEXT_DECAY_CONSTANT_PER_M,
    rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S,
    radius_m=earth.RADIUS_M,
    model: str | EciModel = CONSISTENT,
) -> LaunchCorrection:
    """Eqs 5.1-5.8 and 6.11-6.16 for guns given as loose numbers or arrays (the appendices'
    rounds), each checked here: firing at ``speed_m_s`` (relative to the ground),
    ``elevation_rad``, ``bearing_rad`` from ``latitude_rad``; ``drag_area_m2`` is Cd0 A and
    ``model`` (an :class:`EciModel` or its name) settles what the text leaves open. A
    :class:`~harp_analysis.models.launch.Launch` goes in by :func:`correction_for_launch`.

    mu refers to V = Vrel + omega x r0, as in Figs 5.2-5.3 and the appendices' mu column."""
    speed, elevation, bearing, latitude = _check_launch(
        speed_m_s, elevation_rad, bearing_rad, latitude_rad
    )
    return _corrections(
        speed,
        elevation,
        bearing,
        latitude,
        _check_drag_area(drag_area_m2),
        _check_mass(mass_kg),
        _check_density(surface_density_kg_m3),
        decay_constant_per_m,
        rotation_rate_rad_s,
        radius_m,
        get_model(model),
    )


def correction_for_launch(
    launch: Launch | Launches,
    model: str | EciModel = CONSISTENT,
    *,
    mass_kg=None,
    drag_area_m2=None,
    surface_density_kg_m3=None,
) -> LaunchCorrection:
    """The ECI corrections (eqs 5.1-5.8 and 6.11-6.16) of a
    :class:`~harp_analysis.models.launch.Launch` (or of
    :class:`~harp_analysis.models.launch.Launches` sharing one Earth rotation, each launch a
    column), the one door into the ECI MKS from a launch: its speed, elevation, bearing and
    latitude (checked when the launch was made, so not again), Cd0 A at the launch Mach, its
    mass, its air's density at the gun (:func:`~harp_analysis.engines.mks.gun_density_kg_m3`) and
    its Earth rotation. :meth:`LaunchCorrection.solution` is its MKS. The ECI MKS is drag-only: a
    wind is ignored with a warning; it launches from the Earth's surface (r0 = R).

    Parameters
    ----------
    launch : Launch or Launches
        The launch, or launches sharing one Earth rotation.
    model : str or EciModel
        How the corrections read the text: "consistent" (the default), "dissertation" or
        "printed_columns" (:data:`MODELS`), or a model of your own.
    mass_kg, drag_area_m2, surface_density_kg_m3 : float or array, optional
        Mass (kg), Cd0 A (m^2) and rho0 at the gun (kg/m^3) in place of what the launch's
        projectile and air give, each a number or an array broadcasting with the launches: the
        rounds of one gun whose masses, drag or air differ (HARP's rounds, each with its own
        mass; a drag area being fitted; a site's measured air). Only these are checked.

    Returns
    -------
    LaunchCorrection
        The corrected launch of each launch (eqs 5.1-5.8) and its MKS constants (eqs 6.11-6.16),
        arrays for Launches.
    """
    if not isinstance(launch, Launch | Launches):
        raise TypeError(f"launch must be a Launch or Launches; got {type(launch).__name__}")
    model = get_model(model)
    launch.require_zero("ECI MKS", "site_altitude_m", reason="it launches from r0 = R")
    launch.warn_ignored(
        "ECI MKS", "cross_wind_m_s", "head_wind_m_s", reason="the MKS has no wind (Chapter 3)"
    )
    rotation = (
        launch.rotation_rate_rad_s
        if isinstance(launch, Launch)
        else launch.shared("rotation_rate_rad_s")
    )
    projectile = launch.projectile
    return _corrections(
        launch.speed_m_s,
        launch.elevation_rad,
        launch.bearing_rad,
        launch.latitude_rad,
        (
            launch.launch_drag_coefficient * projectile.reference_area_m2
            if drag_area_m2 is None
            else _check_drag_area(drag_area_m2)
        ),
        projectile.mass_kg if mass_kg is None else _check_mass(mass_kg),
        (
            mks.gun_density_kg_m3(launch)
            if surface_density_kg_m3 is None
            else _check_density(surface_density_kg_m3)
        ),
        TEXT_DECAY_CONSTANT_PER_M,
        rotation,
        earth.RADIUS_M,
        model,
    )


def site_surface_speed_km_s(site: str) -> float:
    """Speed of the Earth's surface at ``site`` (km/s), eq 6.16's 0.4518 km/s at Barbados."""
    return float(np.linalg.norm(surface_velocity(get_site(site).latitude_rad))) / 1e3


def flight_plane(launch: LaunchCorrection, latitude_rad) -> tuple[np.ndarray, np.ndarray]:
    """The plane of the ECI MKS of each corrected launch in the inertial frame at longitude 0:
    unit vectors (3, n) up at the launch point and along the launch velocity's horizontal part
    (``latitude_rad`` one, or one per launch)."""
    up = np.reshape(launch_frame(np.ravel(latitude_rad), 0.0, 0.0)[0], (3, -1))
    velocity = np.reshape(launch.velocity_m_s, (3, -1))
    along = velocity - np.sum(velocity * up, axis=0) * up
    return np.broadcast_to(up, along.shape), along / np.linalg.norm(along, axis=0)


def _flight_plane(launch: LaunchCorrection, latitude_rad: float) -> tuple[np.ndarray, np.ndarray]:
    """:func:`flight_plane` of a single launch: unit vectors (3,)."""
    up, along = flight_plane(launch, latitude_rad)
    return up[:, 0], along[:, 0]


def inertial_positions(
    solution: mks.ModifiedKeplerSolution, launch: LaunchCorrection, latitude_rad: float, theta_rad
) -> np.ndarray:
    """Positions (n, 3) of a single-launch ECI MKS at angular ranges ``theta_rad``: r(theta)
    in the plane of the launch point's radius and the corrected velocity's horizontal part,
    in the inertial frame of :func:`~harp_analysis.models.trajectory.launch_frame` at longitude 0
    and time zero."""
    up, along = _flight_plane(launch, latitude_rad)
    theta = np.asarray(theta_rad, dtype=float)
    radius = np.ravel(solution.radius(theta))
    return radius[:, None] * (np.cos(theta)[:, None] * up + np.sin(theta)[:, None] * along)


#: Equal steps of angular range on which :func:`simulate_eci_mks` inverts eq 3.32's t(theta)
#: for rows at given times (linearly between them: within 4 cm of the path on Chapter 5's
#: flights, against a grid 16 times finer).
TIME_GRID_POINTS = 4001


def _time_at(solution: mks.ModifiedKeplerSolution, grid, grid_times, theta: float) -> float:
    """Eq 3.32's time (s) at ``theta`` within the sorted angles ``grid`` whose times are
    ``grid_times``: the time at the grid's angle before it, and 3-point Gauss-Legendre over
    the rest of the way."""
    before = max(int(np.searchsorted(grid, theta, side="right")) - 1, 0)
    start, end = solution.time(np.array([grid[before], theta]))
    return float(grid_times[before] + (end - start))


def _check_times(times_s) -> np.ndarray:
    times = np.atleast_1d(finite_array(times_s, "times_s"))
    if times.ndim != 1 or times.size > MAX_ROWS:
        raise ValueError(
            f"times_s must be a sequence of at most {MAX_ROWS:,} times; got shape {times.shape}"
        )
    if times.size and (times[0] < 0.0 or np.any(np.diff(times) < 0.0)):
        raise ValueError("times_s must be sorted and non-negative (s from launch)")
    return times


def simulate_eci_mks(
    launch: Launch,
    *,
    model: str | EciModel = CONSISTENT,
    n_terms: int = 3,
    n_points: int = 400,
    times_s=None,
    surface_density_kg_m3: float | None = None,
    warn: bool = True,
) -> pd.DataFrame:
    """The ECI MKS of ``launch`` (:func:`correction_for_launch` under ``model`` and its
    :meth:`~LaunchCorrection.solution`, eqs 6.6-6.15)
    as the engines' trajectory table (:mod:`harp_analysis.models.trajectory`), launch to
    impact, with the shared metadata (no right-hand side is evaluated: ``rhs_evaluations =
    steps = 0``), ``n_terms``, ``model`` (its name), ``beta`` (eq 6.11) and ``decay_scale``
    (the factor on beta in the decay of eq 6.14).

    Rows: at ``n_points`` equal steps of angular range and the apogee, each step's time by
    eq 3.32 (3-point Gauss-Legendre between consecutive steps,
    :meth:`~harp_analysis.engines.mks.ModifiedKeplerSolution.time`; the apogee's from the step
    before it), or, given ``times_s`` (s from launch, sorted), at those of them before the impact
    and at the impact, each placed by linear interpolation of t(theta) on :data:`TIME_GRID_POINTS`
    equal steps of angular range (the impact's time is that grid's last).

    Frame: the 3DOF's on a rotating Earth (:func:`harp_analysis.engines.threedof.simulate_3dof`).
    Positions are inertial and Earth-centred, in the axes the Earth has at launch (x toward
    longitude 0 on the equator, z north), the MKS's plane (the launch point's radius and the
    launch velocity's horizontal part) turned to the launch's longitude; ``ground_range_m``
    and ``cross_range_m`` are measured on the turning Earth, from the launch point along and
    to the right of its bearing (each position turned back by omega t into the Earth's axes);
    speed, angular momentum and flight-path angle are inertial; Mach is the speed relative to
    the air, which turns with the Earth, over the speed of sound of the launch's air. The drag
    coefficient is the MKS's constant Cd0, and drag/gravity its drag on the air-relative speed
    in eq 3.11's air, rho0 exp(-k a). On a non-rotating Earth the table is
    :func:`~harp_analysis.engines.mks.simulate_mks`'s.

    ``surface_density_kg_m3`` replaces rho0 (kg/m^3; :func:`correction_for_launch`): a site's
    measured air. ValueError for a launch whose MKS escapes (no apogee or impact).

    Parameters
    ----------
    launch : Launch
        The launch, on a rotating Earth or not (its wind is left out: the MKS has none).
    model : str or EciModel
        The reading of Chapters 5-6's corrections (one of :data:`MODELS`' names, or a model).
    n_terms : int
        Terms of the series of eq 3.30.
    n_points : int
        Equal steps of angular range from launch to impact (without ``times_s``).
    times_s : array_like, optional
        Times (s from launch, sorted) at which to give rows instead.
    surface_density_kg_m3 : float, optional
        The air's surface density rho0 (kg/m^3), in place of the launch atmosphere's.
    warn : bool
        Warn where the launch leaves the MKS's validity.

    Returns
    -------
    pandas.DataFrame
        The trajectory table of :mod:`harp_analysis.models.trajectory`, one row per output
        time in SI units, with the shared metadata in ``frame.attrs``.
    """
    count = whole_number(n_points, "n_points", low=2, high=MAX_ROWS)
    if not isinstance(launch, Launch):
        raise TypeError(
            f"launch must be a Launch; got {type(launch).__name__} (correction_for_launch "
            "corrects Launches together)"
        )
    times = None if times_s is None else _check_times(times_s)
    correction = correction_for_launch(launch, model, surface_density_kg_m3=surface_density_kg_m3)
    solution = correction.solution(n_terms=n_terms, warn=warn)
    if solution.escapes[0]:
        raise ValueError(
            f"the ECI MKS of launch.speed_m_s = {launch.speed_m_s:g} escapes (its asymptotic "
            "conic is an escape orbit): there is no apogee or impact to tabulate"
        )
    impact, apogee = float(solution.impact_angle), float(solution.apogee_angle)
    if times is None:
        grid = np.linspace(0.0, impact, count)
        grid_times = solution.time(grid)
        apogee_time = _time_at(solution, grid, grid_times, apogee)
        at = int(np.searchsorted(grid, apogee))
        on_grid = at < count and grid[at] == apogee
        theta = grid if on_grid else np.insert(grid, at, apogee)
        time = grid_times if on_grid else np.insert(grid_times, at, apogee_time)
    else:
        grid = np.linspace(0.0, impact, TIME_GRID_POINTS)
        grid_times = solution.time(grid)
        apogee_time = _time_at(solution, grid, grid_times, apogee)
        before_impact = times[times <= grid_times[-1]]
        theta = np.append(np.interp(before_impact, grid_times, grid), impact)
        time = np.append(before_impact, grid_times[-1])
    frame = pd.DataFrame(_table_columns(launch, correction, solution, theta, time))
    apogee_row = _table_columns(
        launch, correction, solution, np.array([apogee]), np.array([apogee_time])
    )
    return describe(
        frame,
        engine="ECI MKS",
        launch=launch,
        apogee=(apogee_time, float(solution.apogee_altitude()), apogee_row["ground_range_m"][0]),
        impact=True,
        rhs_evaluations=0,
        steps=0,
        max_time_s=math.inf,
        n_terms=n_terms,
        model=correction.model.name,
        beta=float(correction.beta),
        decay_scale=float(correction.decay_scale),
    )


def _table_columns(
    launch: Launch,
    correction: LaunchCorrection,
    solution: mks.ModifiedKeplerSolution,
    theta: np.ndarray,
    time: np.ndarray,
) -> dict:
    """The columns of :func:`simulate_eci_mks`'s table at the angular ranges ``theta`` (rad),
    reached at ``time`` (s)."""
    u, slope = solution.u(theta), solution.du_dtheta(theta)
    radius = 1 / u
    altitude = radius - earth.RADIUS_M  # r0 = R: correction_for_launch refuses a site altitude
    speed = solution.angular_momentum(theta) * np.hypot(u, slope)
    climb = np.arctan2(-slope, u)
    # the inertial position and velocity at longitude 0: along r-hat and the in-plane normal
    up, along = _flight_plane(correction, launch.latitude_rad)
    inertial = inertial_positions(solution, correction, launch.latitude_rad, theta).T
    outward = np.cos(theta) * up[:, None] + np.sin(theta) * along[:, None]
    onward = -np.sin(theta) * up[:, None] + np.cos(theta) * along[:, None]
    velocity = speed * (np.cos(climb) * onward + np.sin(climb) * outward)
    omega = correction.rotation_rate_rad_s
    air_velocity = velocity - omega * np.array([-inertial[1], inertial[0], 0.0 * inertial[2]])
    air_speed = np.sqrt(np.sum(air_velocity * air_velocity, axis=0))
    longitude = math.radians(launch.longitude_deg)
    turned = rotate_about_axis(inertial, np.full(theta.size, longitude))
    fixed = rotate_about_axis(inertial, longitude - omega * time)
    launch_up, downrange, _ = launch_frame(launch.latitude_rad, longitude, launch.bearing_rad)
    ground, cross_range = surface_ranges(fixed.T, np.ravel(launch_up), np.ravel(downrange))
    density = correction.surface_density_kg_m3 * np.exp(-correction.decay_constant_per_m * altitude)
    drag = 0.5 * density * correction.drag_area_m2 * air_speed**2
    return {
        "time_s": time,
        "x_m": turned[0],
        "y_m": turned[1],
        "z_m": turned[2],
        "altitude_m": altitude,
        "ground_range_m": ground,
        "cross_range_m": cross_range,
        "speed_m_s": speed,
        "mach": air_speed / launch.air(np.maximum(altitude, 0.0))[1],
        "drag_coefficient": np.full_like(theta, launch.launch_drag_coefficient),
        "drag_to_gravity": drag / (correction.mass_kg * earth.GM_M3_S2 / radius**2),
        "specific_angular_momentum_m2_s": solution.angular_momentum(theta),
        "flight_path_angle_rad": climb,
    }
