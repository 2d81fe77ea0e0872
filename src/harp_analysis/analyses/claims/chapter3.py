"""Quantities behind statements of Chapter 3 that the ledger scores (rows ``ch3.*``; the
baseline's angular momentum lost below 20 km also scores ``ch4.momentum_below_20km_almost_all``):
where the standard Kepler solution holds (the introduction), Fig 3.4's resonance and the series
terms needed (3 C), and Assumption 5's angular momentum (3 B).
"""

from __future__ import annotations

import numpy as np

from ...engines import kepler, mks
from ...foundation import earth
from ...foundation.validation import Bounds, check_choice, finite_scalar, positive_scalar
from .. import scenarios
from ..comparisons import BASELINE_ELEVATIONS_DEG, case, chapter_4_launch
from ..scenarios import fly_3dof
from .launches import no_wind

__all__ = [
    "kepler_handoff_error_km",
    "natural_over_driving_frequency",
    "baseline_momentum_loss_share_below",
    "series_terms_needed",
    "extra_series_terms",
]


# --- Chapter 3: where the standard Kepler solution holds ------------------------------------------
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
    altitude = Bounds(low=0.0, low_inclusive=False).scalar(altitude_km, "altitude_km")
    flight = fly_3dof(no_wind(projectile, elevation_deg).but(atmosphere=atmosphere), 0.01)
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


# --- Chapter 3 B-C: Assumption 5, the series' terms -----------------------------------------------
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
