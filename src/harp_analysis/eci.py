"""The rotating-Earth (ECI) corrections of Chapter 5 and the derived columns of Appendices D and E.

The gun fires at ``speed_m_s`` (Vrel, relative to the ground and the air), elevation and bearing;
in the Earth-centred inertial frame the launch velocity is (eq 6.15)

    V = Vrel + omega x r0 + V_tangent,

with omega x r0 the eastward surface velocity (eq 6.16) and V_tangent the velocity given by the
drag component across the inertial velocity (eqs 5.4-5.8). The drag lies along Vrel, at the
misalignment angle mu from V (Ch. 5 B), so only cos(mu) of it decays the angular momentum
(eq 5.1) and, referred to the inertial speed, the decay carries (Vrel/V)^2 (eqs 5.2-5.3). These
enter :class:`mks.ModifiedKeplerSolution` as ``drive_scale`` = cos(mu) (Vrel/V)^2 (eqs 6.9-6.10)
and ``decay_scale`` = cos(mu) (eq 6.14).

Vectors are (3, ...) arrays in the inertial frame of :func:`threedof.launch_frame` at longitude 0
(z along the Earth's axis); angles in rad, speeds in m/s, SI throughout.

Sign of V_tangent (the text leaves it open: "in the plane created by the relative velocity and
the velocity corrected for Earth rotation and tangent to the corrected velocity"). The drag
acceleration is along -Vrel = -(V - omega x r0); its part normal to V is +(omega x r0)_perp,
because V has none. So V_tangent points along the part of omega x r0 normal to V, i.e. AWAY
from Vrel: drag drains the air-relative velocity and leaves the projectile moving more with the
air, turning V further from the gun line (lower and more eastward for an eastward shot), and mu
grows. Rotating V back toward Vrel would need a force with a component along +Vrel, which drag
has not. The printed Appendix D/E columns do not include V_tangent at all (see
:func:`appendix_columns`).

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
from dataclasses import dataclass

import numpy as np
import pandas as pd

from . import earth, mks
from .atmosphere import TEXT_DECAY_CONSTANT_PER_M
from .harp_data import load_appendix
from .sites import get_site
from .threedof import launch_frame
from .validation import check_choice, check_range, finite_array

__all__ = ["LaunchCorrection", "surface_velocity", "relative_velocity", "misalignment_angle",
           "speed_ratio_squared", "speed_ratio_squared_eq_5_3", "tangent_speed",
           "tangent_direction", "elevation_azimuth", "initial_angular_momentum",
           "asymptotic_angular_momentum", "launch_correction", "eci_solution",
           "fit_speed_of_sound_m_s", "fit_drag_area_m2", "appendix_columns", "site_surface_speed_km_s",
           "inertial_positions"]

_Z_AXIS = np.array([0.0, 0.0, 1.0])


def _check_launch(speed_m_s, elevation_rad, bearing_rad, latitude_rad):
    speed = check_range(finite_array(speed_m_s, "speed_m_s"), "speed_m_s", low=0.0,
                        low_inclusive=False, unit="m/s")
    elevation = check_range(finite_array(elevation_rad, "elevation_rad"), "elevation_rad",
                            low=0.0, low_inclusive=False, high=math.pi / 2, unit="rad")
    bearing = check_range(finite_array(bearing_rad, "bearing_rad"), "bearing_rad", low=0.0,
                          high=2 * math.pi, high_inclusive=False, unit="rad")
    return np.broadcast_arrays(speed, elevation, bearing, _check_latitude(latitude_rad))


def _check_latitude(latitude_rad):
    return check_range(finite_array(latitude_rad, "latitude_rad"), "latitude_rad",
                       low=-math.pi / 2, high=math.pi / 2, unit="rad")


def _dot(a, b):
    return np.sum(a * b, axis=0)


def _norm(a):
    return np.sqrt(_dot(a, a))


def surface_velocity(latitude_rad, *, rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S,
                     radius_m=earth.RADIUS_M):
    """Eq 6.16: omega x r0 (m/s), the launch site's velocity, a (3, ...) vector due east of
    magnitude omega r0 cos(latitude): 451.8 m/s at Barbados."""
    latitude = _check_latitude(latitude_rad)
    up, _, _ = launch_frame(latitude, 0.0, 0.0)
    return np.cross(rotation_rate_rad_s * _Z_AXIS, radius_m * up, axis=0)


def relative_velocity(speed_m_s, elevation_rad, bearing_rad, latitude_rad):
    """Vrel (m/s), the muzzle velocity relative to the ground: ``speed_m_s`` at ``elevation_rad``
    above the horizon along ``bearing_rad`` from true north (Fig 5.1)."""
    speed, elevation, bearing, latitude = _check_launch(speed_m_s, elevation_rad, bearing_rad,
                                                        latitude_rad)
    up, downrange, _ = launch_frame(latitude, 0.0, bearing)
    return speed * (np.cos(elevation) * downrange + np.sin(elevation) * up)


def misalignment_angle(relative_m_s, inertial_m_s):
    """Ch. 5 B: mu (rad), the angle between the drag line (Vrel) and the inertial velocity V."""
    cosine = _dot(relative_m_s, inertial_m_s) / (_norm(relative_m_s) * _norm(inertial_m_s))
    return np.arccos(np.clip(cosine, -1.0, 1.0))


def speed_ratio_squared(relative_m_s, inertial_m_s):
    """(Vrel/V)^2 of eqs 5.2-5.3, exactly, from the two vectors."""
    return _dot(relative_m_s, relative_m_s) / _dot(inertial_m_s, inertial_m_s)


def speed_ratio_squared_eq_5_3(inertial_m_s, latitude_rad, *,
                               rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S,
                               radius_m=earth.RADIUS_M):
    """Eq 5.3 as printed: 1 - 2 Vx omega r cos(LA)/V^2 + (omega r)^2 cos^2(LA)/V^2.

    With Vx the EASTWARD component of the inertial V (not of Vrel) this is |V - omega x r|^2/V^2
    exactly, not an expansion: omega x r is due east with magnitude omega r cos(LA)."""
    latitude = _check_latitude(latitude_rad)
    _, _, east = launch_frame(latitude, 0.0, 0.0)
    v_squared = _dot(inertial_m_s, inertial_m_s)
    surface = rotation_rate_rad_s * radius_m * np.cos(latitude)
    return 1 - 2 * _dot(inertial_m_s, east) * surface / v_squared + surface**2 / v_squared


def tangent_speed(drag_area_m2, surface_density_kg_m3, mass_kg, misalignment_rad,
                  relative_speed_m_s, relative_elevation_rad,
                  decay_constant_per_m=TEXT_DECAY_CONSTANT_PER_M):
    """Eq 5.8: V_tangent = Cd A rho0 sin(mu) Vrel / (2 m k sin(phi_rel)) (m/s), the integral of
    the cross-track drag (eq 5.5) along the straight climb a = Vrel sin(phi_rel) t (eq 5.7);
    ``drag_area_m2`` is Cd A."""
    return (np.asarray(drag_area_m2) * surface_density_kg_m3 * np.sin(misalignment_rad)
            * relative_speed_m_s
            / (2 * mass_kg * decay_constant_per_m * np.sin(relative_elevation_rad)))


def tangent_direction(relative_m_s, inertial_m_s):
    """Unit vector of V_tangent (eq 6.15): normal to V in the plane of Vrel and V, on the side
    AWAY from Vrel, the side of the cross-track drag -Vrel (module docstring). Zero if mu = 0."""
    unit = inertial_m_s / _norm(inertial_m_s)
    across = -(relative_m_s - _dot(relative_m_s, unit) * unit)
    size = _norm(across)
    return np.divide(across, size, out=np.zeros_like(across), where=size > 0)


def elevation_azimuth(velocity_m_s, latitude_rad):
    """Elevation above the local horizon and azimuth from true north (rad, in [0, 2 pi)) of a
    (3, ...) inertial velocity at the launch point (longitude 0) on ``latitude_rad``."""
    up, _, east = launch_frame(_check_latitude(latitude_rad), 0.0, 0.0)
    north = np.cross(up, east, axis=0)
    elevation = np.arcsin(_dot(velocity_m_s, up) / _norm(velocity_m_s))
    azimuth = np.arctan2(_dot(velocity_m_s, east), _dot(velocity_m_s, north)) % (2 * math.pi)
    return elevation, azimuth


def initial_angular_momentum(speed_m_s, elevation_rad, radius_m=earth.RADIUS_M):
    """Eq 6.13: L0 = |V| r0 cos(phi) (m^2/s), per unit mass."""
    return speed_m_s * radius_m * np.cos(elevation_rad)


def asymptotic_angular_momentum(initial_m2_s, beta, misalignment_rad):
    """Eq 6.14 as printed: L_inf = L0 exp(-beta cos mu), without eq 6.9's (Vrel/V)^2."""
    return initial_m2_s * np.exp(-beta * np.cos(misalignment_rad))


@dataclass(frozen=True)
class LaunchCorrection:
    """Chapter 5's corrections of one or many launches (arrays broadcast together)."""

    relative_m_s: np.ndarray           # Vrel, (3, ...)
    surface_m_s: np.ndarray            # omega x r0, (3, ...)
    misalignment_rad: np.ndarray       # mu between Vrel and Vrel + omega x r0
    speed_ratio_squared: np.ndarray    # (Vrel/V)^2, V = Vrel + omega x r0
    tangent_speed_m_s: np.ndarray      # eq 5.8
    velocity_m_s: np.ndarray           # the launch velocity used: eq 6.15, with or without V_t
    speed_m_s: np.ndarray
    elevation_rad: np.ndarray
    azimuth_rad: np.ndarray
    beta: np.ndarray                   # eq 6.11 at the corrected elevation
    initial_angular_momentum_m2_s: np.ndarray      # eq 6.13
    asymptotic_angular_momentum_m2_s: np.ndarray   # eq 6.14


def launch_correction(speed_m_s, elevation_rad, bearing_rad, latitude_rad, *, drag_area_m2,
                      mass_kg, surface_density_kg_m3,
                      decay_constant_per_m=TEXT_DECAY_CONSTANT_PER_M,
                      rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S, radius_m=earth.RADIUS_M,
                      include_tangent: bool = True) -> LaunchCorrection:
    """Eqs 5.1-5.8 and 6.11-6.16 for guns firing at ``speed_m_s`` (relative to the ground),
    ``elevation_rad``, ``bearing_rad`` from ``latitude_rad``; ``drag_area_m2`` is Cd0 A.

    mu and (Vrel/V)^2 refer to V = Vrel + omega x r0, as in Figs 5.2-5.3 and eq 5.3; the launch
    velocity adds V_tangent (eq 6.15) only if ``include_tangent``."""
    mass = check_range(finite_array(mass_kg, "mass_kg"), "mass_kg", low=0.0, low_inclusive=False,
                       unit="kg")
    drag_area = check_range(finite_array(drag_area_m2, "drag_area_m2"), "drag_area_m2", low=0.0,
                            unit="m^2")
    density = check_range(finite_array(surface_density_kg_m3, "surface_density_kg_m3"),
                          "surface_density_kg_m3", low=0.0, unit="kg/m^3")
    speed_m_s, elevation_rad, bearing_rad, latitude_rad = np.broadcast_arrays(
        *_check_launch(speed_m_s, elevation_rad, bearing_rad, latitude_rad), mass, drag_area,
        density)[:4]
    relative = relative_velocity(speed_m_s, elevation_rad, bearing_rad, latitude_rad)
    surface = surface_velocity(latitude_rad, rotation_rate_rad_s=rotation_rate_rad_s,
                               radius_m=radius_m)
    corrected = relative + surface
    mu = misalignment_angle(relative, corrected)
    tangent = tangent_speed(drag_area, density, mass, mu, _norm(relative), elevation_rad,
                            decay_constant_per_m)
    velocity = corrected + include_tangent * tangent * tangent_direction(relative, corrected)
    elevation, azimuth = elevation_azimuth(velocity, latitude_rad)
    beta = mks.decay_factor_beta(drag_area, density, 1.0, mass, elevation,
                                 decay_constant_per_m)                            # eq 6.11
    speed = _norm(velocity)
    initial = initial_angular_momentum(speed, elevation, radius_m)
    return LaunchCorrection(relative, surface, mu, speed_ratio_squared(relative, corrected),
                            tangent, velocity, speed, elevation, azimuth, beta, initial,
                            asymptotic_angular_momentum(initial, beta, mu))


def eci_solution(speed_m_s, elevation_rad, bearing_rad, latitude_rad, *, drag_area_m2, mass_kg,
                 surface_density_kg_m3, decay_constant_per_m=TEXT_DECAY_CONSTANT_PER_M,
                 rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S, radius_m=earth.RADIUS_M,
                 include_tangent: bool = True, n_terms: int = 3, decay: str = "printed",
                 warn: bool = True) -> mks.ModifiedKeplerSolution:
    """The ECI Modified Kepler solution (eqs 6.6-6.15): the MKS launched at the corrected speed
    and elevation, beta of eq 6.11, tau of eq 6.12, drive_scale = cos(mu) (Vrel/V)^2 (eqs 6.9-6.10)
    and decay_scale = cos(mu) (eq 6.14 as printed, ``decay="printed"``) or cos(mu) (Vrel/V)^2
    (``decay="consistent"``: the same beta' in the decay as in the driving terms, as eq 3.23
    requires; see the module docstring)."""
    check_choice(decay, "decay", ("printed", "consistent"))
    launch = launch_correction(speed_m_s, elevation_rad, bearing_rad, latitude_rad,
                               drag_area_m2=drag_area_m2, mass_kg=mass_kg,
                               surface_density_kg_m3=surface_density_kg_m3,
                               decay_constant_per_m=decay_constant_per_m,
                               rotation_rate_rad_s=rotation_rate_rad_s, radius_m=radius_m,
                               include_tangent=include_tangent)
    cos_mu = np.cos(launch.misalignment_rad)
    return mks.ModifiedKeplerSolution(
        launch.speed_m_s, launch.elevation_rad, launch.beta,
        mks.decay_rate_tau(launch.elevation_rad, decay_constant_per_m, radius_m),
        n_terms=n_terms, radius_m=radius_m, drive_scale=cos_mu * launch.speed_ratio_squared,
        decay_scale=cos_mu * (launch.speed_ratio_squared if decay == "consistent" else 1.0),
        warn=warn)


# --- Appendices D and E ------------------------------------------------------------------------
def _rounds(site):
    frame = load_appendix(get_site(site).name)
    return frame[~frame["duplicate_of_earlier_row"]].reset_index(drop=True)


def fit_speed_of_sound_m_s(site: str) -> float:
    """The speed of sound a behind the printed Mach column, Mach = Vo / a, by least squares in
    1/a over the site's distinct rounds (343.46 m/s Barbados, 337.15 m/s Yuma)."""
    rounds = _rounds(site)
    speed, mach = rounds["muzzle_speed_m_s"].to_numpy(), rounds["mach"].to_numpy()
    return float(speed @ speed / (mach @ speed))


def fit_drag_area_m2(site: str = "barbados", **kwargs) -> float:
    """Cd0 A (m^2), which the text does not give, by least squares of the printed Beta column of
    ``site`` against eq 6.11 at the corrected elevation (Ch. 6 D: Barbados drag properties were
    used for Yuma). ``kwargs`` go to :func:`launch_correction` (e.g. ``include_tangent``)."""
    launch_site = get_site(site)
    rounds = _rounds(site)
    unit = launch_correction(rounds["muzzle_speed_m_s"].to_numpy(), launch_site.elevation_rad,
                             launch_site.gun_bearing_rad, launch_site.latitude_rad,
                             drag_area_m2=1.0, mass_kg=rounds["mass_kg"].to_numpy(),
                             surface_density_kg_m3=launch_site.surface_density_kg_m3,
                             **{"include_tangent": False, **kwargs}).beta
    return float(unit @ rounds["beta"].to_numpy() / (unit @ unit))


def appendix_columns(site: str, *, drag_area_m2: float | None = None,
                     speed_of_sound_m_s: float | None = None,
                     include_tangent: bool = False) -> pd.DataFrame:
    """The derived columns of Appendix D ("barbados") or E ("yuma") recomputed from the round's
    mass and printed Vo and the site's latitude, bearing, surface density and 85 deg elevation,
    in the loaded (SI) column names of :mod:`.harp_data`, one row per distinct round, printed
    order.

    Unknowns: ``drag_area_m2`` (Cd0 A, default :func:`fit_drag_area_m2` of Barbados) and
    ``speed_of_sound_m_s`` (default :func:`fit_speed_of_sound_m_s` of the site); k = 0.117 /km.
    The printed corrected elevation, velocity and azimuth and Li are those of Vrel + omega x r0,
    without V_tangent (``include_tangent=False``); Li is L0 (eq 6.13), not L_inf."""
    launch_site = get_site(site)
    rounds = _rounds(site)
    drag_area = fit_drag_area_m2("barbados") if drag_area_m2 is None else drag_area_m2
    sound = fit_speed_of_sound_m_s(site) if speed_of_sound_m_s is None else speed_of_sound_m_s
    speed = rounds["muzzle_speed_m_s"].to_numpy()
    launch = launch_correction(speed, launch_site.elevation_rad, launch_site.gun_bearing_rad,
                               launch_site.latitude_rad, drag_area_m2=drag_area,
                               mass_kg=rounds["mass_kg"].to_numpy(),
                               surface_density_kg_m3=launch_site.surface_density_kg_m3,
                               include_tangent=include_tangent)
    return pd.DataFrame({
        "round_number": rounds["round_number"],
        "mach": speed / sound,
        "misalignment_angle_rad": launch.misalignment_rad,
        "tangent_speed_m_s": launch.tangent_speed_m_s,
        "corrected_elevation_rad": launch.elevation_rad,
        "corrected_speed_m_s": launch.speed_m_s,
        "corrected_azimuth_rad": launch.azimuth_rad,
        "beta": launch.beta,
        "initial_angular_momentum_m2_s": launch.initial_angular_momentum_m2_s,
    })


def site_surface_speed_km_s(site: str) -> float:
    """Speed of the Earth's surface at ``site`` (km/s), eq 6.16's 0.4518 km/s at Barbados."""
    return float(_norm(surface_velocity(get_site(site).latitude_rad))) / 1e3


def inertial_positions(solution: mks.ModifiedKeplerSolution, launch: LaunchCorrection,
                       latitude_rad: float, theta_rad) -> np.ndarray:
    """Positions (n, 3) of a single-launch ECI MKS at angular ranges ``theta_rad``: r(theta)
    in the plane of the launch point's radius and the corrected velocity's horizontal part,
    in the inertial frame of :func:`threedof.launch_frame` at longitude 0 and time zero."""
    up = np.ravel(launch_frame(latitude_rad, 0.0, 0.0)[0])
    velocity = np.ravel(launch.velocity_m_s)
    along = velocity - (velocity @ up) * up
    along /= np.linalg.norm(along)
    theta = np.asarray(theta_rad, dtype=float)
    radius = np.ravel(solution.radius(theta))
    return radius[:, None] * (np.cos(theta)[:, None] * up + np.sin(theta)[:, None] * along)
