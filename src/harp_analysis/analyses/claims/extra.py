"""Quantities behind statements of Chapters 1-7 that the ledger scores and no other module
computes: each turns a qualitative remark of the text into a number (its docstring says how).

SI units inside; arguments name their units. Flights come from the cached engines of
:mod:`.scenarios` and :mod:`.comparisons`, so the ledger and the notebooks share one run.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from collections.abc import Callable

import numpy as np
import pandas as pd
from scipy import constants
from scipy.optimize import brentq

from ...engines import appendix_a, eci, kepler, mks, threedof
from ...foundation import earth
from ...foundation.validation import (
    ModelValidityWarning,
    check_choice,
    check_range,
    finite_scalar,
    positive_scalar,
)
from ...models import trajectory
from ...models.atmosphere import DRY_AIR_GAS_CONSTANT_J_KG_K, standard_density, two_segment_density
from ...models.launch import HP_CHAPTER_2, Launch, baseline_chapter_4
from ...models.projectiles import BASELINE, HP, LP, get_projectile
from .. import effort, rotating, scenarios
from ..comparisons import (
    BASELINE_ELEVATIONS_DEG,
    VARIANTS,
    case,
    chapter_4_launch,
    fly,
    launch_error_at_apogee_km,
)
from ..harp import apogees as harp
from ..scenarios import fly_3dof

__all__ = [
    "launch_error_left_below",
    "ReentrySpeedLoss",
    "reentry_speed_loss",
    "OffDesignError",
    "off_design_error",
    "ErrorGrowth",
    "error_growth",
    "STANDARD_PRESSURE_PA",
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
    "max_measured_apogee_km",
    "mlt_over_3dof_orders",
    "mks_apogee_miss_share",
    "flat_fire_miss_km",
    "TEXT_EARTH_MASS_KG",
    "orbital_drag_to_gravity",
    "observed_order",
    "appendix_a_convergence_order",
    "similar_inertia_kg_m2",
    "max_angle_of_attack_below_deg",
    "mach_over_speed_ratio_max",
    "ascent_change_below",
    "heavy_over_light",
    "gravity_dominant_share",
    "text_gm_over_appendix_gm",
    "two_segment_break_jump",
    "momentum_loss",
    "momentum_loss_ratio",
    "rotation_impact_shift_km",
    "rotation_shift_growth",
    "nonrotating_spread_m",
    "baseline_momentum_loss_share_below",
    "series_terms_needed",
    "extra_series_terms",
    "firing_solution",
    "firing_solution_evaluations",
    "firing_solutions_per_3dof_solution",
    "position_shift_m",
    "pointing_shift_over_mks_error",
    "mks_impact_miss_km",
    "impact_miss_over_total_error",
    "appendix_column_share_within_rounding",
    "appendix_a_rotation_effect_error_km",
    "printed_angle_of_attack_ratio",
]

#: Sea-level pressure of the 1976 standard atmosphere (Pa).
STANDARD_PRESSURE_PA = 101_325.0


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
        return launch_error_at_apogee_km(launch(log_mass)) - target

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
    return pressure / (DRY_AIR_GAS_CONSTANT_J_KG_K * temperature)


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


# === Chapters 1-3 and 7, Appendices A-E: the sweep's statements ============================


# --- Chapter 1 ----------------------------------------------------------------------------------
def max_measured_apogee_km(site: str = "yuma") -> float:
    """Highest measured apogee (km) among the appendix rows of ``site`` ("barbados", "yuma" or
    "both"): Ch. 1 B's "HARP succeeded in placing a projectile to 180 km"."""
    check_choice(site, "site", ("barbados", "yuma", "both"))
    sites = ("barbados", "yuma") if site == "both" else (site,)
    return max(float(harp.appendix_rounds(s).apogee_m.max()) for s in sites) / 1e3


def mlt_over_3dof_orders(segment_length_m: float = 1000.0) -> float:
    """log10 of MLT's operation count over the 3DOF's for HP's reference flight (Fig 4.7's
    counting rule, :mod:`.effort`), MLT updated every ``segment_length_m`` (coefficients at
    mid-segment, spherical density altitude, as :func:`effort.effort_table`)."""
    length = check_range(
        finite_scalar(segment_length_m, "segment_length_m"),
        "segment_length_m",
        low=0.0,
        low_inclusive=False,
    )
    flops = effort.mlt_flops(
        HP_CHAPTER_2,
        density_altitude="spherical",
        segment_length_m=length,
        coefficients_at="middle",
    )
    return math.log10(flops / float(effort.effort_table().flops["3DOF"]))


def mks_apogee_miss_share(method: str = "MKS (3 terms)") -> float:
    """|apogee of ``method`` - the 6DOF's| over the 6DOF's apogee, HP at 50 deg (a row of
    :func:`effort.effort_table`): the accuracy Ch. 1 C's MKS "trades off"."""
    table = effort.effort_table()
    check_choice(method, "method", tuple(table.index))
    return float(table.apogee_difference_m[method] / table.apogee_m["6DOF"])


def flat_fire_miss_km(
    projectile: str = "HP", elevation_deg: float = 50.0, measure: str = "range"
) -> float:
    """|flat fire - 3DOF| (km) in range or apogee height (no wind; :func:`flat_fire_over_3dof`):
    how far standard (flat-fire) linear theory's point-mass trajectory misses."""
    check_choice(measure, "measure", ("apogee", "range"))
    flight = fly_3dof(_no_wind(projectile, elevation_deg), 0.25)
    simulated = flight.attrs["apogee_altitude_m" if measure == "apogee" else "range_m"]
    ratio = flat_fire_over_3dof(projectile, elevation_deg, measure)
    return abs(ratio - 1.0) * simulated / 1e3


#: Ch. 2 A: the Earth's mass (kg).
TEXT_EARTH_MASS_KG = 5.972e24


def orbital_drag_to_gravity(
    altitude_km: float = 200.0, drag_coefficient: float = 2.2, projectile: str = "baseline"
) -> float:
    """Drag over gravity N for ``projectile``'s mass and reference area on a circular orbit at
    ``altitude_km`` in the 1976 standard atmosphere (Ch. 1 C: "density at LEO altitudes is
    negligible"). With v^2 = GM/r and g = GM/r^2, N = rho Cd A r / (2 m). The default Cd = 2.2
    is the usual free-molecular value for satellites, far above the cone's continuum Cd."""
    altitude = check_range(
        finite_scalar(altitude_km, "altitude_km"), "altitude_km", low=0.0, high=1000.0
    )
    cd = check_range(
        finite_scalar(drag_coefficient, "drag_coefficient"),
        "drag_coefficient",
        low=0.0,
        low_inclusive=False,
    )
    p = get_projectile(projectile)
    radius = earth.RADIUS_M + altitude * 1e3
    density = float(standard_density(altitude * 1e3))
    return density * cd * p.reference_area_m2 * radius / (2 * p.mass_kg)


# --- Chapter 2 ----------------------------------------------------------------------------------
def observed_order(coarse: float, medium: float, fine: float) -> float:
    """Observed order of convergence p of a result computed with steps h, h/2 and h/4:
    log2((coarse - medium) / (medium - fine)) (the error goes as h^p)."""
    values = [finite_scalar(v, name) for v, name in ((coarse, "coarse"), (medium, "medium"))]
    values.append(finite_scalar(fine, "fine"))
    first, second = values[0] - values[1], values[1] - values[2]
    if first == 0.0 or second == 0.0 or (first > 0) != (second > 0):
        return float("nan")
    return math.log2(first / second)


def appendix_a_convergence_order(
    elevation_deg: float = 45.0, dt_s: float = 0.1, atmosphere: str = "three_layer"
) -> float:
    """Observed order of Appendix A's scheme (Ch. 2 A: "a custom written 2nd order 3DOF
    simulation"): the baseline's apogee height flown by the macro with steps ``dt_s``,
    ``dt_s``/2 and ``dt_s``/4 (:func:`observed_order`)."""
    launch = baseline_chapter_4(elevation_deg, atmosphere=atmosphere)
    step = positive_scalar(dt_s, "dt_s", "s")
    apogees = [
        appendix_a.simulate_appendix_a(launch, step / 2**n).attrs["apogee_altitude_m"]
        for n in range(3)
    ]
    return observed_order(*apogees)


def similar_inertia_kg_m2(axis: str = "pitch") -> float:
    """HP's roll or pitch inertia (kg m^2) if HP were LP scaled up geometrically (same shape,
    same density): LP's stated inertia times s^5, s = (m_HP / m_LP)^(1/3) (mass goes as s^3,
    inertia as mass times length^2). Ch. 2 A gives HP 6.20934 (pitch) and 0.00853 (roll)."""
    check_choice(axis, "axis", ("roll", "pitch"))
    scale = (HP.mass_kg / LP.mass_kg) ** (1.0 / 3.0)
    inertia = LP.pitch_inertia_kg_m2 if axis == "pitch" else LP.roll_inertia_kg_m2
    if inertia is None:
        raise ValueError(f"LP carries no {axis} inertia")
    return inertia * scale**5


def max_angle_of_attack_below_deg(projectile: str = "HP", altitude_km: float = 30.0) -> float:
    """Largest total angle of attack (deg) of Chapter 2 A's 6DOF flight while below
    ``altitude_km``, on the way up and on the way down (Fig 2.5)."""
    flight = scenarios.reference_6dof(projectile)
    low = flight.altitude_m < finite_scalar(altitude_km, "altitude_km") * 1e3
    return float(np.degrees(flight.angle_of_attack_rad[low].max()))


def mach_over_speed_ratio_max(projectile: str = "HP") -> float:
    """Largest (Mach / launch Mach) / (speed / launch speed) on the way up of Chapter 2 A's 3DOF
    flight (Fig 2.8): how much more slowly the Mach number falls than the speed."""
    ascent = scenarios.ascent(scenarios.reference_3dof(projectile))
    mach = ascent.mach.to_numpy() / ascent.mach.iloc[0]
    speed = ascent.speed_m_s.to_numpy() / ascent.speed_m_s.iloc[0]
    return float(np.max(mach / speed))


def ascent_change_below(
    projectile: str = "HP",
    quantity: str = "drag_coefficient",
    altitude_km: float = 20.0,
    atmosphere: str = "two_segment",
) -> float:
    """Change of a quantity over the ascent of Chapter 2 A's 3DOF flight (5 m/s cross wind) up
    to ``altitude_km``:

    - ``"drag_coefficient"``: largest |Cd / Cd0 - 1| (Fig 2.8);
    - ``"speed"``: 1 - V / V0 at the altitude (the speed lost);
    - ``"turn"``: launch flight-path angle minus the one at the altitude (deg), the curvature
      of Fig 2.9's path in the lower atmosphere.
    """
    check_choice(quantity, "quantity", ("drag_coefficient", "speed", "turn"))
    top = finite_scalar(altitude_km, "altitude_km") * 1e3
    launch = scenarios.reference_launch(projectile).but(atmosphere=atmosphere)
    ascent = scenarios.ascent(fly_3dof(launch))
    low = ascent[ascent.altitude_m <= top]
    if quantity == "drag_coefficient":
        cd = low.drag_coefficient.to_numpy()
        return float(np.max(np.abs(cd / cd[0] - 1.0)))
    heights = ascent.altitude_m.to_numpy()
    if quantity == "speed":
        return float(1.0 - np.interp(top, heights, ascent.speed_m_s) / ascent.speed_m_s.iloc[0])
    angle = ascent.flight_path_angle_rad.to_numpy()
    return math.degrees(angle[0] - float(np.interp(top, heights, angle)))


def heavy_over_light(quantity: str = "drag_coefficient", altitude_km: float = 20.0) -> float:
    """:func:`ascent_change_below` of HP over LP's (Ch. 2 B: the heavier projectile "slows down
    much less" and "shows less curvature")."""
    return ascent_change_below("HP", quantity, altitude_km) / ascent_change_below(
        "LP", quantity, altitude_km
    )


def gravity_dominant_share(projectile: str = "HP", ratio: float = 1.0) -> float:
    """Share of Chapter 2 A's ground range flown with drag under ``ratio`` times gravity (N <
    ``ratio``, Fig 2.2): "gravity is the dominant force over the vast majority of the
    trajectory"."""
    limit = check_range(finite_scalar(ratio, "ratio"), "ratio", low=0.0, low_inclusive=False)
    flight = scenarios.reference_3dof(projectile)
    n = flight.drag_to_gravity.to_numpy()
    steps = np.diff(flight.ground_range_m.to_numpy())
    below = 0.5 * (n[1:] + n[:-1]) < limit
    return float(steps[below].sum() / flight.attrs["range_m"])


def text_gm_over_appendix_gm(earth_mass_kg: float = TEXT_EARTH_MASS_KG) -> float:
    """G M with Ch. 2 A's Earth mass and CODATA 2018's G (scipy.constants) over Appendices A and
    B's GM = 398600.4418 km^3/s^2."""
    return constants.G * finite_scalar(earth_mass_kg, "earth_mass_kg") / earth.GM_M3_S2


def two_segment_break_jump(break_m: float = 10_769.0, offset_m: float = 1e-3) -> float:
    """Relative jump of eqs 2.1-2.2's density across their break: rho just above over rho just
    below, minus 1 (0 for a continuous fit)."""
    at = finite_scalar(break_m, "break_m")
    step = positive_scalar(offset_m, "offset_m", "m")
    above, below = two_segment_density(np.array([at + step, at - step]))
    return float(above / below - 1.0)


def momentum_loss(projectile: str = "HP", part: str = "ascent", altitude_km: float = 20.0) -> float:
    """Relative loss of specific angular momentum of Chapter 2 A's 3DOF flight (Fig 2.10):
    over the whole ascent (``"ascent"``), or on the way down from ``altitude_km`` to impact
    (``"reentry"``)."""
    check_choice(part, "part", ("ascent", "reentry"))
    flight = scenarios.reference_3dof(projectile)
    momentum = flight.specific_angular_momentum_m2_s.to_numpy()
    if part == "ascent":
        ascent = scenarios.ascent(flight).specific_angular_momentum_m2_s.to_numpy()
        return float(1.0 - ascent[-1] / ascent[0])
    down = flight.time_s.to_numpy() > flight.attrs["apogee_time_s"]
    heights = flight.altitude_m.to_numpy()[down][::-1]
    start = np.interp(
        finite_scalar(altitude_km, "altitude_km") * 1e3, heights, momentum[down][::-1]
    )
    return float(1.0 - momentum[-1] / start)


def momentum_loss_ratio(
    numerator: str = "LP", denominator: str = "HP", part: str = "ascent"
) -> float:
    """:func:`momentum_loss` of ``numerator`` over ``denominator``'s."""
    return momentum_loss(numerator, part) / momentum_loss(denominator, part)


def _earth_fixed_impact_m(launch: Launch) -> tuple[np.ndarray, float]:
    """Impact point (Earth-fixed, m) and range (m) of the 3DOF flight of ``launch``."""
    flight = threedof.simulate_3dof(launch, output_step_s=1.0)
    inertial = flight[["x_m", "y_m", "z_m"]].to_numpy()[-1]
    turned = launch.rotation_rate_rad_s * flight.attrs["time_of_flight_s"]
    return trajectory.rotate_about_axis(inertial, -turned), flight.attrs["range_m"]


def rotation_impact_shift_km(
    speed_m_s: float = 2157.0,
    elevation_deg: float = 45.0,
    latitude_deg: float = 45.0,
    bearing_deg: float = 0.0,
    relative: bool = False,
    atmosphere: str = "two_segment",
) -> float:
    """Distance (km) between the impact points of the baseline fired on a rotating and on a
    non-rotating Earth (3DOF, Earth-fixed): the Coriolis and centrifugal correction of Ch. 2 A;
    over the non-rotating range if ``relative``."""
    launch = baseline_chapter_4(
        elevation_deg,
        speed_m_s=speed_m_s,
        latitude_deg=latitude_deg,
        bearing_deg=bearing_deg,
        atmosphere=atmosphere,
    )
    still, reach = _earth_fixed_impact_m(launch)
    turning, _ = _earth_fixed_impact_m(launch.but(rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S))
    shift = float(np.linalg.norm(turning - still))
    return shift / reach if relative else shift / 1e3


def rotation_shift_growth(
    low_speed_m_s: float = 800.0,
    high_speed_m_s: float = 2157.0,
    elevation_deg: float = 45.0,
    latitude_deg: float = 45.0,
    bearing_deg: float = 0.0,
) -> float:
    """The rotation's impact shift as a share of the range at ``high_speed_m_s`` over that at
    ``low_speed_m_s`` (:func:`rotation_impact_shift_km`): "more pronounced as the projectile
    velocities and range increase" (Ch. 2 A)."""
    shifts = [
        rotation_impact_shift_km(v, elevation_deg, latitude_deg, bearing_deg, relative=True)
        for v in (high_speed_m_s, low_speed_m_s)
    ]
    return shifts[0] / shifts[1]


def nonrotating_spread_m(
    elevation_deg: float = 45.0,
    rotation_rate_rad_s: float = 0.0,
    latitudes_deg=(0.0, 30.0, 60.0, 85.0),
    bearings_deg=(0.0, 90.0, 200.0, 315.0),
) -> float:
    """Largest spread (m) of the baseline's apogee height and range over launch latitudes and
    bearings (3DOF): zero on Ch. 2 A's non-rotating Earth, where "it is unimportant where the
    launch point is located or what bearing it is launched"."""
    apogees, ranges = [], []
    for latitude in latitudes_deg:
        for bearing in bearings_deg:
            flight = threedof.simulate_3dof(
                baseline_chapter_4(
                    elevation_deg,
                    latitude_deg=latitude,
                    bearing_deg=bearing,
                    rotation_rate_rad_s=rotation_rate_rad_s,
                ),
                output_step_s=10.0,
            )
            apogees.append(flight.attrs["apogee_altitude_m"])
            ranges.append(flight.attrs["range_m"])
    return float(max(np.ptp(apogees), np.ptp(ranges)))


# --- Chapter 3 ----------------------------------------------------------------------------------
def baseline_momentum_loss_share_below(
    altitude_km: float = 20.0, elevations_deg=BASELINE_ELEVATIONS_DEG
) -> float:
    """Smallest share, over ``elevations_deg``, of the baseline's ascent loss of specific
    angular momentum spent below ``altitude_km`` (Ch. 4 B's flights, no wind)."""
    top = finite_scalar(altitude_km, "altitude_km")
    return min(
        scenarios.loss_share_below(case("baseline", float(elevation))[0], top)
        for elevation in elevations_deg
    )


def series_terms_needed(
    projectile: str = "baseline",
    elevation_deg: float = 45.0,
    apogee_tolerance_m: float = 1.0,
    max_terms: int = 15,
) -> int:
    """Fewest series terms (eq 3.30) whose MKS apogee lies within ``apogee_tolerance_m`` of the
    ``max_terms`` one (the converged series), for Chapter 4's launch of ``projectile``."""
    tolerance = positive_scalar(apogee_tolerance_m, "apogee_tolerance_m", "m")
    launch = chapter_4_launch(projectile, elevation_deg)

    def apogee(n):
        return float(mks.for_launch(launch, n_terms=n, warn=False).apogee_altitude())

    converged = apogee(max_terms)
    return next(n for n in range(1, max_terms + 1) if abs(apogee(n) - converged) <= tolerance)


def extra_series_terms(
    heavy: str = "LP",
    light: str = "baseline",
    apogee_tolerance_m: float = 1.0,
    elevation_deg: float = 50.0,
) -> int:
    """:func:`series_terms_needed` of ``heavy`` minus that of ``light`` (Ch. 3 C: "the larger
    the ballistic coefficient, the more terms are needed"), both at ``elevation_deg``."""
    return series_terms_needed(heavy, elevation_deg, apogee_tolerance_m) - series_terms_needed(
        light, elevation_deg, apogee_tolerance_m
    )


# --- Chapter 7 A: firing solutions ------------------------------------------------------------
def firing_solution(
    method: str = "mks",
    target_range_km: float = 150.0,
    target_altitude_km: float = 100.0,
    elevation_bracket_deg: tuple[float, float] = (45.0, 75.0),
    elevation_tolerance_deg: float = 1e-6,
) -> tuple[float, int, int]:
    """(elevation in deg, solver iterations, right-hand-side evaluations) of the baseline's
    firing solution through a point ``target_altitude_km`` up and ``target_range_km``
    downrange, by Brent's method on the elevation (the bearing is the target's on a
    non-rotating Earth). ``method``: the three-term MKS (each iteration one closed-form
    evaluation, counted as one) or the 3DOF (each iteration a whole adaptive flight)."""
    check_choice(method, "method", ("mks", "3dof"))
    reach = finite_scalar(target_range_km, "target_range_km") * 1e3
    height = finite_scalar(target_altitude_km, "target_altitude_km") * 1e3
    calls: list[int] = []

    def miss(elevation_deg):
        launch = baseline_chapter_4(float(elevation_deg))
        if method == "mks":
            solution = mks.for_launch(launch, warn=False)
            calls.append(1)
            return float(solution.altitude(np.array([reach / earth.RADIUS_M]))[0]) - height
        flight = threedof.simulate_3dof(launch, output_step_s=0.1)
        calls.append(flight.attrs["rhs_evaluations"])
        ranges = flight.ground_range_m.to_numpy()
        up = flight.time_s.to_numpy() <= flight.attrs["apogee_time_s"]
        part = up if ranges[up][-1] >= reach else ~up
        return float(np.interp(reach, ranges[part], flight.altitude_m.to_numpy()[part])) - height

    low, high = elevation_bracket_deg
    elevation = brentq(miss, low, high, xtol=positive_scalar(elevation_tolerance_deg, "tolerance"))
    return float(elevation), len(calls), int(sum(calls))


@dataclasses.dataclass(frozen=True)
class FiringEvaluations:
    """A firing solution's count (:func:`firing_solution`): ``evaluations`` (MKS solutions, or
    the 3DOF's right-hand sides), the solver's iterations and the elevation found."""

    evaluations: int
    iterations: int
    elevation_deg: float

    @property
    def per_iteration(self) -> float:
        return self.evaluations / self.iterations


def firing_solution_evaluations(method: str = "mks", **target) -> FiringEvaluations:
    """Evaluations a firing solution takes (:func:`firing_solution`): MKS solutions for
    ``method="mks"``, the 3DOF's right-hand-side evaluations for ``"3dof"``."""
    elevation, iterations, evaluations = firing_solution(method, **target)
    return FiringEvaluations(iterations if method == "mks" else evaluations, iterations, elevation)


@dataclasses.dataclass(frozen=True)
class SolutionsPerSolve:
    """MKS firing solutions against one 3DOF firing solution, by operations
    (:func:`firing_solutions_per_3dof_solution`)."""

    three_dof_evaluations: int
    operations_per_evaluation: float
    mks_iterations: int
    mks_operations: float  # of one MKS evaluation

    @property
    def three_dof_operations(self) -> float:
        return self.three_dof_evaluations * self.operations_per_evaluation

    @property
    def mks_solution_operations(self) -> float:
        return self.mks_iterations * self.mks_operations

    @property
    def solutions(self) -> float:
        """MKS firing solutions that cost the operations of one 3DOF firing solution."""
        return self.three_dof_operations / self.mks_solution_operations

    @property
    def log10_solutions(self) -> float:
        return math.log10(self.solutions)


def firing_solutions_per_3dof_solution(**target) -> SolutionsPerSolve:
    """How many MKS firing solutions cost the operations of one 3DOF firing solution, as
    ``log10_solutions`` (:func:`firing_solution`; operations per 3DOF evaluation and per MKS
    evaluation from :func:`effort.effort_table`'s counts for HP's flight and apogee)."""
    table = effort.effort_table()
    per_evaluation = (
        float(table.flops["3DOF"]) / threedof.simulate_3dof(HP_CHAPTER_2).attrs["rhs_evaluations"]
    )
    _, iterations, _ = firing_solution("mks", **target)
    three = firing_solution("3dof", **target)[2]
    return SolutionsPerSolve(three, per_evaluation, iterations, float(table.flops["MKS (3 terms)"]))


# --- Chapter 7 B-C: other uncertainties, ground fire ---------------------------------------------
def position_shift_m(
    launch: Launch, elevation_error_mrad: float = 0.0, speed_error_m_s: float = 0.0, at_s=None
) -> float:
    """Distance (m) between the 3DOF positions of ``launch`` and of the launch with its
    elevation raised by ``elevation_error_mrad`` and its speed by ``speed_error_m_s``, at time
    ``at_s`` (default: the unperturbed apogee time)."""
    changed = launch.but(
        elevation_deg=launch.elevation_deg
        + math.degrees(finite_scalar(elevation_error_mrad, "elevation_error_mrad") * 1e-3),
        speed_m_s=launch.speed_m_s + finite_scalar(speed_error_m_s, "speed_error_m_s"),
    )
    flights = [threedof.simulate_3dof(x, output_step_s=0.25) for x in (launch, changed)]
    time = flights[0].attrs["apogee_time_s"] if at_s is None else finite_scalar(at_s, "at_s")
    points = [
        np.array([np.interp(time, f.time_s, f[c]) for c in ("x_m", "y_m", "z_m")]) for f in flights
    ]
    return float(np.linalg.norm(points[1] - points[0]))


def pointing_shift_over_mks_error(
    elevation_deg: float = 45.0, elevation_error_mrad: float = 1.0, speed_error_m_s: float = 0.0
) -> float:
    """Position change at the apogee time from a pointing error (and a muzzle-speed error) over
    the three-term MKS's error at apogee, baseline at ``elevation_deg`` (Ch. 7 B: these
    uncertainties "may end up being much larger" than the MKS's)."""
    shift = position_shift_m(
        baseline_chapter_4(elevation_deg), elevation_error_mrad, speed_error_m_s
    )
    return shift / 1e3 / launch_error_at_apogee_km(chapter_4_launch("baseline", elevation_deg))


def mks_impact_miss_km(
    projectile: str = "baseline", elevation_deg: float = 85.0, **launch_changes
) -> float:
    """|MKS impact range - 3DOF range| (km) of Chapter 4's launch (:func:`case`): where the
    MKS puts a ground-fire round against where the simulation lands it."""
    flight, solution, _ = case(projectile, elevation_deg, **launch_changes)
    return abs(float(solution.impact_angle) * earth.RADIUS_M - flight.attrs["range_m"]) / 1e3


def impact_miss_over_total_error(
    projectile: str = "baseline", elevation_deg: float = 85.0
) -> float:
    """Ground-fire miss (:func:`mks_impact_miss_km`) over the total position error at the
    3DOF's impact (eq 4.7, geometric reading): what Ch. 7 C calls "slightly misleading"."""
    errors = case(projectile, elevation_deg)[2]
    miss_m = mks_impact_miss_km(projectile, elevation_deg) * 1e3
    return miss_m / float(errors.total_geometric_m.iloc[-1])


# --- Appendices ---------------------------------------------------------------------------------
def appendix_column_share_within_rounding(site: str = "barbados", column: str = "mach") -> float:
    """Share of the distinct rounds of Appendix D or E whose printed ``column`` the package
    recomputes (dissertation model) to within half a unit of the last printed digit
    (:func:`harp.column_agreement`)."""
    table = harp.column_agreement(site)
    check_choice(column, "column", tuple(table.index))
    return float(table.rounds_within[column] / table.rounds[column])


def appendix_a_rotation_effect_error_km(
    latitude_deg: float = 0.0,
    bearing_deg: float = 90.0,
    elevation_deg: float = 45.0,
    dt_s: float = 0.05,
    atmosphere: str = "three_layer",
) -> float:
    """The apogee change (km) that turning the Earth's rotation on makes with Appendix A's
    rotation terms as printed (earthspin = 0.0000727221: omega R on the east velocity, air
    velocity v + omega x r), minus the change it makes in the rotating 3DOF (omega R cos(lat),
    v - omega x r); the baseline, the macro's step ``dt_s`` (its step error cancels in the
    difference)."""
    launch = baseline_chapter_4(
        elevation_deg, latitude_deg=latitude_deg, bearing_deg=bearing_deg, atmosphere=atmosphere
    )
    turning = launch.but(rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S)
    printed = [
        appendix_a.simulate_appendix_a(x, dt_s).attrs["apogee_altitude_m"]
        for x in (turning, launch)
    ]
    physical = [threedof.simulate_3dof(x).attrs["apogee_altitude_m"] for x in (turning, launch)]
    return ((printed[0] - printed[1]) - (physical[0] - physical[1])) / 1e3


def printed_angle_of_attack_ratio(projectile: str = "HP") -> float:
    """Appendix B's printed angle of attack, sqrt(v^2 + w^2)/u in degrees (the tangent), over
    the angle itself at the largest angle of attack of Chapter 2 A's 6DOF flight (Fig 2.5)."""
    alpha = float(scenarios.reference_6dof(projectile).angle_of_attack_rad.max())
    return math.tan(alpha) / alpha


# --- Issue 26: statements scored ----------------------------------------------------------------
def launch_error_left_below(
    altitude_km: float = 30.0, dt_s: float = 0.1, elevation_deg: float = 45.0
) -> float:
    """Smallest error of the MKS against Appendix A's printed rows on the way up below
    ``altitude_km``, over its error at launch (Ch. 4 B, Fig 4.11: the launch error "quickly
    corrects itself"; under 0.1 if it has). The error at launch is the macro's clock, one step
    ahead of its positions (:func:`rotating.appendix_a_launch_error_m`)."""
    rows, errors = rotating.appendix_a_errors(dt_s, elevation_deg)
    climbing = (rows.time_s <= rows.attrs["apogee_time_s"]) & (rows.altitude_m < altitude_km * 1e3)
    error = errors.total_geometric_m.to_numpy()[climbing.to_numpy()[: len(errors)]]
    return float(error.min() / error[0])


@dataclasses.dataclass(frozen=True)
class ReentrySpeedLoss:
    """The speed a flight loses from its fastest point on the way down to impact."""

    peak_speed_m_s: float
    impact_speed_m_s: float
    peak_altitude_km: float
    flight_share: float  # the time from the peak to impact, as a share of the time of flight

    @property
    def loss(self) -> float:
        return 1.0 - self.impact_speed_m_s / self.peak_speed_m_s


def reentry_speed_loss(engine: str = "6DOF", projectile: str = "HP") -> ReentrySpeedLoss:
    """Fig 4.3's speed drop on re-entry of Chapter 2 A's flight of ``projectile`` by the 6DOF,
    MLT or 3DOF (Ch. 4 A: "the sharp decrease in velocity that indicates reentry into the
    atmosphere in the MLT and numerical simulations")."""
    flights: dict[str, Callable[[str], pd.DataFrame]] = {
        "6DOF": scenarios.reference_6dof,
        "MLT": scenarios.reference_mlt,
        "3DOF": scenarios.reference_3dof,
    }
    flight = flights[check_choice(engine, "engine", tuple(flights))](projectile)
    descent = flight[flight.time_s >= flight.attrs["apogee_time_s"]]
    peak = descent.loc[descent.speed_m_s.idxmax()]
    duration = flight.time_s.iloc[-1]
    return ReentrySpeedLoss(
        float(peak.speed_m_s),
        float(flight.speed_m_s.iloc[-1]),
        float(peak.altitude_m) / 1e3,
        float((duration - peak.time_s) / duration),
    )


@dataclasses.dataclass(frozen=True)
class OffDesignError:
    """The MKS's error at the 3DOF's apogee for a launch off Chapter 4's design."""

    error_km: float
    apogee_km: float

    @property
    def share_of_apogee(self) -> float:
        return self.error_km / self.apogee_km


def off_design_error(elevation_deg: float = 45.0, speed_m_s: float = 2157.0) -> OffDesignError:
    """Error at apogee of the baseline cone launched at ``elevation_deg`` and ``speed_m_s``
    (Ch. 4 C: Assumption 3, the straight path through the air, "would not be accurate for flat
    fire approaches or low speed trajectories that curve significantly")."""
    flight, _, errors = case("baseline", elevation_deg, speed_m_s=speed_m_s)
    apogee = flight.attrs["apogee_time_s"]
    error = float(np.interp(apogee, errors.time_s, errors.total_geometric_m))
    return OffDesignError(error / 1e3, flight.attrs["apogee_altitude_m"] / 1e3)


@dataclasses.dataclass(frozen=True)
class ErrorGrowth:
    """The MKS's error at impact over its error at apogee, smallest over Chapter 4's
    elevations, as printed and with the asymptotic angular momentum taken from the 3DOF's
    apogee (Fig 4.13's correction)."""

    impact_over_apogee: float
    corrected_impact_over_apogee: float
    impact_km: float  # largest over the elevations, as printed
    corrected_impact_km: float  # the same elevation, corrected


def error_growth() -> ErrorGrowth:
    """How the MKS's error grows from apogee to impact (Ch. 7 C: "the minor mismatch of
    predicted angular momentum with reality that causes the error of the projectile to grow
    over the trajectory"), the baseline at 30-85 deg."""

    def ends(momentum_from_apogee: bool) -> np.ndarray:
        rows = []
        for elevation in BASELINE_ELEVATIONS_DEG:
            flight, _, errors = case(
                "baseline", elevation, momentum_from_apogee=momentum_from_apogee
            )
            at_apogee = np.interp(
                flight.attrs["apogee_time_s"], errors.time_s, errors.total_geometric_m
            )
            rows.append((errors.total_geometric_m.iloc[-1], at_apogee))
        return np.array(rows)

    printed, corrected = ends(False), ends(True)
    worst = int(np.argmax(printed[:, 0]))
    return ErrorGrowth(
        float(np.min(printed[:, 0] / printed[:, 1])),
        float(np.min(corrected[:, 0] / corrected[:, 1])),
        float(printed[worst, 0]) / 1e3,
        float(corrected[worst, 0]) / 1e3,
    )
