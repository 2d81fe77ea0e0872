"""Quantities behind statements of Chapters 1-7 that the ledger scores and no other module
computes: each turns a qualitative remark of the text into a number (its docstring says how).

SI units inside; arguments name their units. Flights come from the cached engines of
:mod:`.scenarios` and :mod:`.comparisons`, so the ledger and the notebooks share one run.
"""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np
from scipy.optimize import brentq

from . import earth, eci, harp, kepler, rotating
from .comparisons import BASELINE_ELEVATIONS_DEG, VARIANTS, case, chapter_4_launch, fly
from .launch import Launch
from .projectiles import BASELINE
from .scenarios import fly_3dof
from .validation import ModelValidityWarning, check_choice, check_range, finite_scalar

__all__ = [
    "STANDARD_PRESSURE_PA",
    "AIR_GAS_CONSTANT_J_KG_K",
    "tangent_line_ceiling_m",
    "v3_apogee_bound_km",
    "v3_drag_free_apogee_km",
    "flat_fire_apogee_and_range_m",
    "kepler_over_3dof",
    "flat_fire_over_3dof",
    "kepler_handoff_error_km",
    "natural_over_driving_frequency",
    "beta_accuracy_limit",
    "beta_limit_elevation_deg",
    "min_mach_below",
    "variant_speed_increase",
    "min_measured_apogee_km",
    "apogee_drive_ratio",
    "apogee_simplification_shift_km",
    "harp_solution",
    "density_at_temperature_kg_m3",
    "fahrenheit_to_kelvin",
    "site_density_kg_m3",
    "spread_over_mks_error",
    "late_arrival_miss_m",
]

#: Sea-level pressure of the 1976 standard atmosphere (Pa).
STANDARD_PRESSURE_PA = 101_325.0
#: Specific gas constant of dry air (J/(kg K)), the 1976 standard's.
AIR_GAS_CONSTANT_J_KG_K = 287.05287


def _no_wind(projectile: str, elevation_deg: float) -> Launch:
    """Chapter 4's launch of ``projectile`` without wind or spin: a planar flight, the one the
    drag-free conic and Fig 4.8 ("with no wind") compare with."""
    return chapter_4_launch(projectile, elevation_deg).but(
        cross_wind_m_s=0.0, head_wind_m_s=0.0, spin_rad_s=0.0
    )


# --- Chapter 1 B: the V-3 ----------------------------------------------------------------------
def tangent_line_ceiling_m(ground_range_m: float, elevation_rad: float) -> float:
    """Highest altitude (m) any gun trajectory of ground range ``ground_range_m`` fired at
    ``elevation_rad`` can reach, whatever its drag: the launch tangent line's height above the
    sphere at the range.

    Gravity is the only force across the velocity (drag lies along it, still air, non-rotating
    Earth), and it always points to the centre's side, so the path turns one way only and
    stays on the centre's side of its launch tangent line (it turns by less than 180 deg before
    it lands). A point at central angle theta is then no farther from the centre than that
    line, R cos(phi)/cos(theta + phi), and theta <= Theta = range/R."""
    radius = earth.RADIUS_M
    angle = check_range(
        finite_scalar(ground_range_m, "ground_range_m") / radius,
        "ground_range_m / RADIUS_M",
        low=0.0,
        low_inclusive=False,
        high=np.pi / 2,
    )
    elevation = check_range(
        finite_scalar(elevation_rad, "elevation_rad"),
        "elevation_rad",
        low=0.0,
        low_inclusive=False,
        high=np.pi / 2 - angle,
        high_inclusive=False,
    )
    return radius * math.cos(elevation) / math.cos(angle + elevation) - radius


def v3_apogee_bound_km(range_km: float = 43.0, elevation_deg: float = 34.0) -> float:
    """Ch. 1 B: the most a shell fired at ``elevation_deg`` to ``range_km`` can climb (km),
    drag or not (:func:`tangent_line_ceiling_m`); the V-3 shell itself is not in the text."""
    return tangent_line_ceiling_m(range_km * 1e3, math.radians(elevation_deg)) / 1e3


def v3_drag_free_apogee_km(range_km: float = 43.0, elevation_deg: float = 34.0) -> float:
    """Ch. 1 B: apogee (km) of the drag-free conic that reaches ``range_km`` at
    ``elevation_deg`` (:func:`kepler.speed_for_range`), the estimate without the shell's drag."""
    elevation = math.radians(elevation_deg)
    speed = kepler.speed_for_range(range_km * 1e3, elevation)
    return float(kepler.ballistic_conic(speed, elevation).apogee_altitude_m) / 1e3


# --- Chapter 1 A: Kepler overshoots, flat fire undershoots ------------------------------------
def flat_fire_apogee_and_range_m(
    speed_m_s: float,
    elevation_rad: float,
    drag_per_m: float,
    gravity_m_s2: float,
) -> tuple[float, float]:
    """(apogee height, range) in m of the constant-density flat-fire trajectory.

    Point mass, flat Earth, constant gravity g, drag deceleration k V^2 with k = rho0 Cd0 A /
    (2 m) constant (constant density and drag coefficient). Exactly, d(w/u)/dt = -g/u and
    du/dx = -k V; flat fire replaces V/u = sec(psi) by its launch value, so u = u0 e^{-k' x},
    k' = k sec(phi0), and the height is

        y(x) = x tan(phi0) - g (e^{2 k' x} - 1 - 2 k' x) / (4 k'^2 u0^2),

    which tends to the vacuum parabola as k' -> 0 (McCoy's flat-fire form)."""
    speed = check_range(finite_scalar(speed_m_s, "speed_m_s"), "speed_m_s", low=0.0)
    elevation = check_range(
        finite_scalar(elevation_rad, "elevation_rad"),
        "elevation_rad",
        low=0.0,
        low_inclusive=False,
        high=np.pi / 2,
        high_inclusive=False,
    )
    k = check_range(
        finite_scalar(drag_per_m, "drag_per_m"), "drag_per_m", low=0.0, low_inclusive=False
    )
    g = check_range(
        finite_scalar(gravity_m_s2, "gravity_m_s2"), "gravity_m_s2", low=0.0, low_inclusive=False
    )
    rate, u0, slope = k / math.cos(elevation), speed * math.cos(elevation), math.tan(elevation)

    def height(x):
        return x * slope - g * (math.expm1(2 * rate * x) - 2 * rate * x) / (4 * rate**2 * u0**2)

    top = math.log1p(2 * rate * u0**2 * slope / g) / (2 * rate)  # dy/dx = 0
    far = 2 * top
    while height(far) > 0:
        far *= 2
    return height(top), brentq(height, top, far, xtol=1e-6, rtol=1e-12)


def kepler_over_3dof(
    projectile: str = "HP", elevation_deg: float = 50.0, measure: str = "apogee"
) -> float:
    """Drag-free conic of the launch over the 3DOF (no wind): its apogee height or range over
    the simulated one (Ch. 1 A: "the standard Kepler solution overshoots")."""
    check_choice(measure, "measure", ("apogee", "range"))
    launch = _no_wind(projectile, elevation_deg)
    flight = fly_3dof(launch, 0.25)
    conic = kepler.ballistic_conic(launch.speed_m_s, launch.elevation_rad)
    if measure == "apogee":
        return float(conic.apogee_altitude_m) / flight.attrs["apogee_altitude_m"]
    return float(conic.ground_range_m) / flight.attrs["range_m"]


def flat_fire_over_3dof(
    projectile: str = "HP", elevation_deg: float = 50.0, measure: str = "apogee"
) -> float:
    """Constant-density flat fire (:func:`flat_fire_apogee_and_range_m` with the gun's air
    density, Cd0 at the launch Mach and g = GM/R^2) over the 3DOF (no wind): its apogee height
    or range over the simulated one (Ch. 1 A: flat fire "undershoots")."""
    check_choice(measure, "measure", ("apogee", "range"))
    launch = _no_wind(projectile, elevation_deg)
    flight = fly_3dof(launch, 0.25)
    p = launch.projectile
    k = (
        launch.surface_density_kg_m3
        * launch.launch_drag_coefficient
        * p.reference_area_m2
        / (2 * p.mass_kg)
    )
    apogee, reach = flat_fire_apogee_and_range_m(
        launch.speed_m_s, launch.elevation_rad, k, earth.surface_gravity_m_s2()
    )
    if measure == "apogee":
        return apogee / flight.attrs["apogee_altitude_m"]
    return reach / flight.attrs["range_m"]


# --- Chapter 3: where the standard Kepler solution holds ---------------------------------------
def kepler_handoff_error_km(
    projectile: str = "HP",
    elevation_deg: float = 50.0,
    altitude_km: float = 30.0,
    measure: str = "path",
    atmosphere: str = "two_segment",
) -> float:
    """The standard Kepler solution handed the 3DOF's state where the flight climbs through
    ``altitude_km``, against the 3DOF while it stays above that altitude (no wind).

    ``measure``:

    - "path" (default): the largest distance (km) from the 3DOF's path to the conic's,
      |r_3DOF - r_conic| cos(phi_conic) at the same angular range (the Kepler solution is a
      path r(theta); to first order in distance over the path's radius of curvature, hundreds
      of km);
    - "radial": the largest |r_3DOF - r_conic| (km) at the same angular range, which
      overstates the distance where the path is steep (by 1/cos(phi));
    - "apogee": the conic's apogee minus the 3DOF's (km).

    ``atmosphere`` names the 3DOF's air (``"vacuum"``: the conic must then match exactly)."""
    check_choice(measure, "measure", ("path", "radial", "apogee"))
    altitude = check_range(
        finite_scalar(altitude_km, "altitude_km"), "altitude_km", low=0.0, low_inclusive=False
    )
    flight = fly_3dof(_no_wind(projectile, elevation_deg).but(atmosphere=atmosphere), 0.01)
    if altitude * 1e3 >= flight.attrs["apogee_altitude_m"]:
        raise ValueError(
            f"the flight's apogee ({flight.attrs['apogee_altitude_m'] / 1e3:.4g} km) lies below "
            f"altitude_km = {altitude:g}"
        )
    xyz = flight[["x_m", "y_m", "z_m"]].to_numpy()
    theta = np.arctan2(np.linalg.norm(np.cross(xyz[0], xyz), axis=1), xyz @ xyz[0])
    heights = flight.altitude_m.to_numpy()
    ascent = flight.time_s.to_numpy() <= flight.attrs["apogee_time_s"]
    at = altitude * 1e3
    speed, angle, theta_at = (
        float(np.interp(at, heights[ascent], values[ascent]))
        for values in (flight.speed_m_s.to_numpy(), flight.flight_path_angle_rad.to_numpy(), theta)
    )
    conic = kepler.conic_from_state(earth.RADIUS_M + at, speed, angle, earth.GM_M3_S2)
    if measure == "apogee":
        return (conic.apogee_radius_m - earth.RADIUS_M - flight.attrs["apogee_altitude_m"]) / 1e3
    first = int(np.argmax(ascent & (heights >= at)))
    below = np.flatnonzero((np.arange(heights.size) > first) & (heights < at))
    rows = slice(first, below[0] if below.size else heights.size)
    along = theta[rows] - theta_at
    difference = np.abs(earth.RADIUS_M + heights[rows] - conic.radius(along))
    if measure == "path":
        difference *= np.cos(conic.flight_path_angle(along))
    return float(np.max(difference)) / 1e3


def natural_over_driving_frequency(projectile: str = "HP", elevation_deg: float = 50.0) -> float:
    """Fig 3.4's resonance: the linearised natural frequency (1 rad/rad, eq 3.30) over the
    slowest rate of the driving function, tau (eq 3.27), for Chapter 4's launch."""
    return 1.0 / float(case(projectile, elevation_deg)[1].tau[0, 0])


# --- Chapter 4 B: beta and the baseline --------------------------------------------------------
def _error_at_apogee_km(launch: Launch) -> float:
    flight, _, errors = fly(launch)
    return (
        float(np.interp(flight.attrs["apogee_time_s"], errors.time_s, errors.total_geometric_m))
        / 1e3
    )


def beta_accuracy_limit(
    error_km: float = 1.0, projectile: str = "HP", elevation_deg: float = 50.0
) -> float:
    """The MKS beta at which the error at apogee reaches ``error_km``: ``projectile`` flown as
    in Fig 4.8 (no wind) with its mass varied (beta ~ 1/m; drag law, speed and elevation
    kept), the mass found by root finding, its beta returned."""
    target = check_range(
        finite_scalar(error_km, "error_km"), "error_km", low=0.0, low_inclusive=False
    )
    base = _no_wind(projectile, elevation_deg)

    def launch(log_mass):
        changed = dataclasses.replace(base.projectile, mass_kg=math.exp(log_mass))
        return base.but(projectile=changed)

    def excess(log_mass):
        return _error_at_apogee_km(launch(log_mass)) - target

    nominal = math.log(base.projectile.mass_kg)
    log_mass = brentq(excess, nominal - math.log(3.0), nominal + math.log(6.0), xtol=1e-5)
    return float(fly(launch(log_mass))[1].beta[0, 0])


def beta_limit_elevation_deg(projectile: str = "baseline", beta_limit: float = 0.25) -> float:
    """Lowest barrel elevation (deg) at which ``projectile``'s MKS beta (eq 3.22) is under
    ``beta_limit``: beta = beta_90 / sin(phi0), Cd0 at the launch Mach being the same at every
    elevation."""
    limit = check_range(
        finite_scalar(beta_limit, "beta_limit"), "beta_limit", low=0.0, low_inclusive=False
    )
    elevation = math.radians(50.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelValidityWarning)
        beta_90 = float(case(projectile, 50.0)[1].beta[0, 0]) * math.sin(elevation)
    if beta_90 >= limit:
        return float("nan")
    return math.degrees(math.asin(beta_90 / limit))


def min_mach_below(
    altitude_km: float = 40.0, part: str = "ascent", elevations_deg=BASELINE_ELEVATIONS_DEG
) -> float:
    """Lowest Mach number of the baseline's 3DOF flights (Ch. 4 B, no wind) below
    ``altitude_km``, over ``elevations_deg``: on the way up (``part="ascent"``) or over the
    whole flight, re-entry included (``"flight"``)."""
    check_choice(part, "part", ("ascent", "flight"))
    lowest = math.inf
    for elevation in elevations_deg:
        flight = case("baseline", float(elevation))[0]
        rows = flight.altitude_m < altitude_km * 1e3
        if part == "ascent":
            rows &= flight.time_s <= flight.attrs["apogee_time_s"]
        lowest = min(lowest, float(flight.mach[rows].min()))
    return lowest


# --- Chapter 4 C: the faster launch -------------------------------------------------------------
def variant_speed_increase(variant: str = "speed_plus_20pct") -> float:
    """Relative increase of a Chapter 4 C variant's launch speed over the baseline's (Fig 4.17's
    2.59 km/s against 2.157 km/s)."""
    check_choice(variant, "variant", tuple(VARIANTS))
    return VARIANTS[variant]["speed_m_s"] / BASELINE.launch_speed_m_s - 1


# --- Chapter 6: the HARP apogees ---------------------------------------------------------------
def min_measured_apogee_km(site: str = "barbados") -> float:
    """Lowest measured apogee (km) among the appendix rows of ``site``."""
    return float(harp.appendix_rounds(site).apogee_m.min()) / 1e3


def apogee_drive_ratio(site: str = "barbados", model: str = "dissertation") -> float:
    """Largest ratio over the rounds of the driving terms of eq 6.1 at eq 6.4's apogee angle,
    |tau c4 e^{-tau theta} + 2 tau c5 e^{-2 tau theta}|, to |c1 cos(theta)| (the terms eq 6.2
    drops, against one it keeps)."""
    solution = harp_solution(site, model)
    theta = np.atleast_1d(solution.apogee_angle_eq_6_4)[:, None]
    drive = np.abs(
        np.sum(solution.rates * solution.amplitudes * np.exp(-solution.rates * theta), 1)
    )
    kept = np.abs(solution.c1[:, 0] * np.cos(theta[:, 0]))
    return float(np.max(drive / kept))


def apogee_simplification_shift_km(site: str = "barbados", model: str = "dissertation") -> float:
    """Largest |apogee at eq 6.4's angle - apogee at the true zero of eq 6.1| (km) over the
    rounds: what dropping the atmosphere's terms at apogee costs."""
    solution = harp_solution(site, model)
    shift = solution.apogee_altitude("eq_6_4") - solution.apogee_altitude("first_zero")
    return float(np.max(np.abs(shift))) / 1e3


def harp_solution(site: str, model: str = "dissertation"):
    """The three-term ECI MKS of every appendix row of ``site`` under ``model``."""
    return eci.solution_for(harp.launch_corrections(site, model), warn=False)


def fahrenheit_to_kelvin(temperature_f: float) -> float:
    return (finite_scalar(temperature_f, "temperature_f") - 32.0) * 5.0 / 9.0 + 273.15


def density_at_temperature_kg_m3(
    temperature_k: float, pressure_pa: float = STANDARD_PRESSURE_PA
) -> float:
    """Dry-air density p / (R T) (kg/m^3)."""
    temperature = check_range(
        finite_scalar(temperature_k, "temperature_k"), "temperature_k", low=0.0, low_inclusive=False
    )
    pressure = check_range(
        finite_scalar(pressure_pa, "pressure_pa"), "pressure_pa", low=0.0, low_inclusive=False
    )
    return pressure / (AIR_GAS_CONSTANT_J_KG_K * temperature)


def site_density_kg_m3(
    site: str = "barbados", source: str = "mach_column", temperature_f: float = 75.0
) -> float:
    """Sea-level dry-air density (kg/m^3) at ``site`` at standard pressure, at the temperature
    of the speed of sound behind the appendix's Mach column (``source="mach_column"``,
    :func:`harp.speed_of_sound`) or at ``temperature_f`` (``"temperature"``; Ch. 6 C gives
    Barbados 80 F by day and 70 F by night)."""
    check_choice(source, "source", ("mach_column", "temperature"))
    if source == "mach_column":
        temperature = harp.air_temperature_k(harp.speed_of_sound(site)[0])
    else:
        temperature = fahrenheit_to_kelvin(temperature_f)
    return density_at_temperature_kg_m3(temperature)


def spread_over_mks_error(
    site: str = "barbados",
    latitude_deg: float = 0.0,
    bearing_deg: float = 90.0,
    elevation_deg: float = 85.0,
) -> float:
    """Standard deviation of the apogee residuals at ``site`` (dissertation model) over the ECI
    MKS's error at apogee against the rotating 3DOF for the baseline fired at
    ``elevation_deg`` on ``bearing_deg`` from ``latitude_deg`` (Ch. 5's 85 deg east case)."""
    spread = harp.residual_statistic(site, "std")
    return spread / rotating.error_at_apogee_km(latitude_deg, bearing_deg, elevation_deg)


# --- Chapter 7 C: timing --------------------------------------------------------------------------
def late_arrival_miss_m(
    speed_m_s: float = 2000.0,
    delay_s: float = 0.5,
    flight_path_angle_deg: float = 0.0,
    gravity_m_s2: float = earth.STANDARD_GRAVITY_M_S2,
) -> float:
    """Distance (m) a body moving at ``speed_m_s`` on a ballistic path covers in ``delay_s``:
    |v dt + g dt^2 / 2| under uniform gravity (over half a second the conic's curvature is
    that of the parabola)."""
    speed = check_range(finite_scalar(speed_m_s, "speed_m_s"), "speed_m_s", low=0.0)
    delay = check_range(finite_scalar(delay_s, "delay_s"), "delay_s", low=0.0)
    angle = math.radians(finite_scalar(flight_path_angle_deg, "flight_path_angle_deg"))
    g = finite_scalar(gravity_m_s2, "gravity_m_s2")
    horizontal = speed * math.cos(angle) * delay
    vertical = speed * math.sin(angle) * delay - 0.5 * g * delay**2
    return math.hypot(horizontal, vertical)
