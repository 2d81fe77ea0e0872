"""Quantities behind statements of Chapter 1 that the ledger scores (rows ``ch1.*``): the V-3's
apogee (1 B), the standard Kepler solution overshooting and flat fire undershooting (1 A),
HARP's highest round (1 B), and MLT's cost, the MKS's accuracy, flat fire's miss and the air in
low Earth orbit (1 A, 1 C).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from ...engines import kepler
from ...foundation import earth
from ...foundation.validation import Bounds, check_choice, finite_scalar
from ...models.atmosphere import standard_density
from ...models.launch import HP_CHAPTER_2
from ...models.projectiles import get_projectile
from .. import effort
from ..harp import apogees
from ..scenarios import fly_3dof
from .launches import no_wind

__all__ = [
    "tangent_line_ceiling_m",
    "v3_apogee_bound_km",
    "v3_drag_free_apogee_km",
    "flat_fire_apogee_and_range_m",
    "kepler_over_3dof",
    "flat_fire_over_3dof",
    "max_measured_apogee_km",
    "mlt_over_3dof_orders",
    "mks_apogee_miss_share",
    "flat_fire_miss_km",
    "orbital_drag_to_gravity",
]


# --- Chapter 1 B: the V-3 -------------------------------------------------------------------------
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
    angle = Bounds(low=0.0, high=np.pi / 2, low_inclusive=False).check(
        finite_scalar(ground_range_m, "ground_range_m") / radius, "ground_range_m / RADIUS_M"
    )
    elevation = Bounds(
        low=0.0, high=np.pi / 2 - angle, low_inclusive=False, high_inclusive=False
    ).scalar(elevation_rad, "elevation_rad")
    return radius * math.cos(elevation) / math.cos(angle + elevation) - radius


def v3_apogee_bound_km(range_km: float = 43.0, elevation_deg: float = 34.0) -> float:
    """Ch. 1 B: the most a shell fired at ``elevation_deg`` to ``range_km`` can climb (km),
    drag or not (:func:`tangent_line_ceiling_m`); the V-3 shell itself is not in the text."""
    return tangent_line_ceiling_m(range_km * 1e3, math.radians(elevation_deg)) / 1e3


def v3_drag_free_apogee_km(range_km: float = 43.0, elevation_deg: float = 34.0) -> float:
    """Ch. 1 B: apogee (km) of the drag-free conic that reaches ``range_km`` at
    ``elevation_deg`` (:func:`~harp_analysis.engines.kepler.speed_for_range`), the estimate without
    the shell's drag."""
    elevation = math.radians(elevation_deg)
    speed = kepler.speed_for_range(range_km * 1e3, elevation)
    return float(kepler.ballistic_conic(speed, elevation).apogee_altitude_m) / 1e3


# --- Chapter 1 A: Kepler overshoots, flat fire undershoots ----------------------------------------
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
    speed = Bounds(low=0.0).scalar(speed_m_s, "speed_m_s")
    elevation = Bounds(low=0.0, high=np.pi / 2, low_inclusive=False, high_inclusive=False).scalar(
        elevation_rad, "elevation_rad"
    )
    k = Bounds(low=0.0, low_inclusive=False).scalar(drag_per_m, "drag_per_m")
    g = Bounds(low=0.0, low_inclusive=False).scalar(gravity_m_s2, "gravity_m_s2")
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
    launch = no_wind(projectile, elevation_deg)
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
    launch = no_wind(projectile, elevation_deg)
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


# --- Chapter 1 A-C: HARP's highest round, the engines' cost and accuracy, the air in orbit --------
def max_measured_apogee_km(site: str = "yuma") -> float:
    """Highest measured apogee (km) among the appendix rows of ``site`` ("barbados", "yuma" or
    "both"): Ch. 1 B's "HARP succeeded in placing a projectile to 180 km"."""
    check_choice(site, "site", ("barbados", "yuma", "both"))
    sites = ("barbados", "yuma") if site == "both" else (site,)
    return max(float(apogees.appendix_rounds(s).apogee_m.max()) for s in sites) / 1e3


def mlt_over_3dof_orders(segment_length_m: float = 1000.0) -> float:
    """log10 of MLT's operation count over the 3DOF's for HP's reference flight (Fig 4.7's
    counting rule, :mod:`.effort`), MLT updated every ``segment_length_m`` (coefficients at
    mid-segment, spherical density altitude, as
    :func:`~harp_analysis.analyses.effort.effort_table`)."""
    length = Bounds(low=0.0, low_inclusive=False).scalar(segment_length_m, "segment_length_m")
    flops = effort.mlt_flops(
        HP_CHAPTER_2,
        density_altitude="spherical",
        segment_length_m=length,
        coefficients_at="middle",
    )
    return math.log10(flops / float(effort.effort_table().flops["3DOF"]))


def mks_apogee_miss_share(method: str = "MKS (3 terms)") -> float:
    """|apogee of ``method`` - the 6DOF's| over the 6DOF's apogee, HP at 50 deg (a row of
    :func:`~harp_analysis.analyses.effort.effort_table`): the accuracy Ch. 1 C's MKS "trades
    off"."""
    table = effort.effort_table()
    check_choice(method, "method", tuple(table.index))
    return float(table.apogee_difference_m[method] / table.apogee_m["6DOF"])


def flat_fire_miss_km(
    projectile: str = "HP", elevation_deg: float = 50.0, measure: str = "range"
) -> float:
    """|flat fire - 3DOF| (km) in range or apogee height (no wind; :func:`flat_fire_over_3dof`):
    how far standard (flat-fire) linear theory's point-mass trajectory misses."""
    check_choice(measure, "measure", ("apogee", "range"))
    flight = fly_3dof(no_wind(projectile, elevation_deg), 0.25)
    simulated = flight.attrs["apogee_altitude_m" if measure == "apogee" else "range_m"]
    ratio = flat_fire_over_3dof(projectile, elevation_deg, measure)
    return abs(ratio - 1.0) * simulated / 1e3


def orbital_drag_to_gravity(
    altitude_km: float = 200.0, drag_coefficient: float = 2.2, projectile: str = "baseline"
) -> float:
    """Drag over gravity N for ``projectile``'s mass and reference area on a circular orbit at
    ``altitude_km`` in the 1976 standard atmosphere (Ch. 1 C: "density at LEO altitudes is
    negligible"). With v^2 = GM/r and g = GM/r^2, N = rho Cd A r / (2 m). The default Cd = 2.2
    is the usual free-molecular value for satellites, far above the cone's continuum Cd."""
    altitude = Bounds(low=0.0, high=1000.0).scalar(altitude_km, "altitude_km")
    cd = Bounds(low=0.0, low_inclusive=False).scalar(drag_coefficient, "drag_coefficient")
    p = get_projectile(projectile)
    radius = earth.RADIUS_M + altitude * 1e3
    density = float(standard_density(altitude * 1e3))
    return density * cd * p.reference_area_m2 * radius / (2 * p.mass_kg)
