"""Chapter 5 C: the ECI Modified Kepler Solution against the rotating-Earth 3DOF (Figs 5.4-5.9).

The baseline cone fired from latitude 0 and 45 deg on bearings 000T, 090T and 270T at 30-85 deg,
3DOF with the Earth turning (:data:`harp_analysis.earth.ROTATION_RATE_RAD_S`) against the
three-term ECI MKS (:func:`harp_analysis.eci.eci_solution`, with V_tangent as Chapter 5 adds it,
eq 6.15, and the decay of eq 6.14 carrying the same cos(mu) (Vrel/V)^2 as the driving terms:
eq 6.14 as printed drops (Vrel/V)^2, which puts the east- and west-fired apogees several km
off, the wrong way round; ``decay="printed"`` keeps it for comparison). The MKS lives in the
inertial plane of its corrected launch velocity; its position at
each simulation time is placed in that plane and the error is the distance between the two
positions at the same time (the direct reading of Chapter 5 C's vector error plus time error).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pandas as pd

from . import earth, eci
from .caching import cached_copies
from .launch import baseline_chapter_4
from .threedof import simulate_3dof

__all__ = [
    "LATITUDES_DEG",
    "BEARINGS_DEG",
    "ELEVATIONS_DEG",
    "case",
    "error_at_apogee_km",
    "worst_error_at_apogee_km",
    "share_under_1km",
    "west_over_east",
]

LATITUDES_DEG = (0.0, 45.0)
BEARINGS_DEG = (90.0, 0.0, 270.0)
ELEVATIONS_DEG = (30.0, 45.0, 65.0, 85.0)


@cached_copies
def case(latitude_deg: float, bearing_deg: float, elevation_deg: float, decay: str = "consistent"):
    """(rotating 3DOF table, ECI MKS, error table) of the baseline cone: the ECI MKS of
    :data:`eci.CONSISTENT`, or with eq 6.14's printed decay (``decay="printed"``)."""
    model = replace(eci.CONSISTENT, name=f"consistent, {decay} decay", decay=decay)
    launch = baseline_chapter_4(
        elevation_deg,
        latitude_deg=latitude_deg,
        bearing_deg=bearing_deg,
        rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S,
    )
    flight = simulate_3dof(launch, output_step_s=0.5)
    correction = eci.correction_for_launch(launch, model)
    solution = eci.solution_for(correction, warn=False)
    grid = np.linspace(0.0, solution.impact_angle, 4001)
    times = solution.time(grid)
    flight = flight[flight.time_s <= times[-1]]  # compare while both are in flight
    theta = np.interp(flight.time_s, times, grid)
    mks_xyz = eci.inertial_positions(solution, correction, launch.latitude_rad, theta).T
    sim_xyz = flight[["x_m", "y_m", "z_m"]].to_numpy().T
    errors = pd.DataFrame(
        {
            "time_s": flight.time_s,
            "ground_range_m": flight.ground_range_m,
            "error_m": np.linalg.norm(sim_xyz - mks_xyz, axis=0),
        }
    )
    return flight, solution, errors


def error_at_apogee_km(
    latitude_deg: float, bearing_deg: float, elevation_deg: float, decay: str = "consistent"
) -> float:
    """Position error (km) at the 3DOF's apogee."""
    flight, _, errors = case(latitude_deg, bearing_deg, elevation_deg, decay=decay)
    return float(np.interp(flight.attrs["apogee_time_s"], errors.time_s, errors.error_m)) / 1e3


def _all_cases(min_elevation_deg=0.0):
    return {
        (lat, brg, el): error_at_apogee_km(lat, brg, el)
        for lat in LATITUDES_DEG
        for brg in BEARINGS_DEG
        for el in ELEVATIONS_DEG
        if el >= min_elevation_deg
    }


def worst_error_at_apogee_km(min_elevation_deg: float = 45.0) -> float:
    """Largest error at apogee over the cases at or above ``min_elevation_deg``."""
    return max(_all_cases(min_elevation_deg).values())


def share_under_1km() -> float:
    """Share of the 24 cases whose error at apogee is under 1 km."""
    errors = np.array(list(_all_cases().values()))
    return float(np.mean(errors < 1.0))


def west_over_east() -> float:
    """Errors at apogee summed over latitudes and elevations, 270T over 090T."""
    cases = _all_cases()
    return sum(v for (_, brg, _), v in cases.items() if brg == 270.0) / sum(
        v for (_, brg, _), v in cases.items() if brg == 90.0
    )
