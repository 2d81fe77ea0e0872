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

The air the 3DOF flies is a choice the text leaves implicit. Chapter 2's simulations use eqs
2.1-2.2 (``atmosphere="two_segment"``, every function's default here, as in Chapter 4); the
3DOF listing of Appendix A, the one with the Earth's rotation (``earthspin``), hard-codes three
layers (``atmosphere="three_layer"``). Every function takes ``atmosphere`` so that Chapter 5
can be run both ways (notebook 05, the ledger's ``ch5.worst_error_high_elevations`` rows).

Two measures of Chapter 4's statements live here too, because they need the rotating-Earth
listing's numerics or a per-elevation view that :mod:`.comparisons` does not offer:
:func:`appendix_a_launch_error_m` (the "almost 200 m" at launch of Fig 4.11, Appendix A's clock
artefact) and :func:`variant_improved_share` (how many of Fig 4.15's or 4.17's elevations a
Chapter 4 C variant improves).
"""

from __future__ import annotations

import warnings
from dataclasses import replace

import numpy as np
import pandas as pd

from . import appendix_a, comparisons, earth, eci, mks
from .caching import cached_copies
from .launch import baseline_chapter_4
from .mks_error import position_errors
from .threedof import simulate_3dof
from .trajectory import TruncatedFlightWarning

__all__ = [
    "LATITUDES_DEG",
    "BEARINGS_DEG",
    "ELEVATIONS_DEG",
    "case",
    "error_at_apogee_km",
    "errors_at_apogee_km",
    "worst_case",
    "worst_error_at_apogee_km",
    "share_under_1km",
    "west_over_east",
    "west_worst_share",
    "appendix_a_launch_error_m",
    "variant_improved_share",
]

LATITUDES_DEG = (0.0, 45.0)
BEARINGS_DEG = (90.0, 0.0, 270.0)
ELEVATIONS_DEG = (30.0, 45.0, 65.0, 85.0)


@cached_copies
def case(
    latitude_deg: float,
    bearing_deg: float,
    elevation_deg: float,
    decay: str = "consistent",
    atmosphere: str = "two_segment",
):
    """(rotating 3DOF table, ECI MKS, error table) of the baseline cone: the ECI MKS of
    :data:`eci.CONSISTENT`, or with eq 6.14's printed decay (``decay="printed"``), against the
    3DOF flown through ``atmosphere`` (eqs 2.1-2.2 by default, or Appendix A's
    ``"three_layer"``; the launch's air also sets the MKS's Cd0, at the gun's Mach number)."""
    model = replace(eci.CONSISTENT, name=f"consistent, {decay} decay", decay=decay)
    launch = baseline_chapter_4(
        elevation_deg,
        latitude_deg=latitude_deg,
        bearing_deg=bearing_deg,
        rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S,
        atmosphere=atmosphere,
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
    latitude_deg: float,
    bearing_deg: float,
    elevation_deg: float,
    decay: str = "consistent",
    atmosphere: str = "two_segment",
) -> float:
    """Position error (km) at the 3DOF's apogee."""
    flight, _, errors = case(
        latitude_deg, bearing_deg, elevation_deg, decay=decay, atmosphere=atmosphere
    )
    return float(np.interp(flight.attrs["apogee_time_s"], errors.time_s, errors.error_m)) / 1e3


def errors_at_apogee_km(
    atmosphere: str = "two_segment", min_elevation_deg: float = 0.0
) -> dict[tuple[float, float, float], float]:
    """Error at apogee (km) of every case at or above ``min_elevation_deg``, keyed by
    (latitude, bearing, elevation) in degrees."""
    return {
        (lat, brg, el): error_at_apogee_km(lat, brg, el, atmosphere=atmosphere)
        for lat in LATITUDES_DEG
        for brg in BEARINGS_DEG
        for el in ELEVATIONS_DEG
        if el >= min_elevation_deg
    }


def worst_case(
    min_elevation_deg: float = 45.0, atmosphere: str = "two_segment"
) -> tuple[float, float, float]:
    """(latitude, bearing, elevation) of the largest error at apogee at or above
    ``min_elevation_deg`` (Ch. 5 D names 270T, 45 deg, the equator)."""
    errors = errors_at_apogee_km(atmosphere, min_elevation_deg)
    return max(errors, key=errors.__getitem__)


def worst_error_at_apogee_km(
    min_elevation_deg: float = 45.0, atmosphere: str = "two_segment"
) -> float:
    """Largest error at apogee over the cases at or above ``min_elevation_deg``."""
    return max(errors_at_apogee_km(atmosphere, min_elevation_deg).values())


def share_under_1km(atmosphere: str = "two_segment") -> float:
    """Share of the 24 cases whose error at apogee is under 1 km."""
    errors = np.array(list(errors_at_apogee_km(atmosphere).values()))
    return float(np.mean(errors < 1.0))


def west_over_east(atmosphere: str = "two_segment") -> float:
    """Errors at apogee summed over latitudes and elevations, 270T over 090T."""
    cases = errors_at_apogee_km(atmosphere)
    return sum(v for (_, brg, _), v in cases.items() if brg == 270.0) / sum(
        v for (_, brg, _), v in cases.items() if brg == 90.0
    )


def west_worst_share(atmosphere: str = "two_segment") -> float:
    """Share of the (latitude, elevation) pairs in which the west-fired (270T) error at apogee
    exceeds both the east-fired (090T) and the north-fired (000T) one (Ch. 5 D: "the error in
    trajectories fired due East and North are significantly lower than for those fired due
    West"; 1 if it holds everywhere)."""
    cases = errors_at_apogee_km(atmosphere)
    pairs = [(lat, el) for lat in LATITUDES_DEG for el in ELEVATIONS_DEG]
    return float(
        np.mean(
            [
                cases[lat, 270.0, el] > max(cases[lat, 90.0, el], cases[lat, 0.0, el])
                for lat, el in pairs
            ]
        )
    )


def appendix_a_launch_error_m(
    dt_s: float = 0.1, elevation_deg: float = 45.0, atmosphere: str = "three_layer"
) -> float:
    """Total position error (m, eq 4.7's geometric reading as in Fig 4.11) of the three-term MKS
    against the first row Appendix A's macro prints, for a step ``dt_s``: the baseline cone at
    ``elevation_deg`` in the listing's air (the Earth's spin off, as in Chapter 4).

    The MKS starts exactly at the gun (its own error at launch is zero,
    :func:`harp_analysis.comparisons.launch_error_m`); the macro prints its first position,
    two steps out, at the clock time 3 dt, so the MKS at that time is one step, about V0 dt,
    further along (:mod:`.appendix_a`). The sheet's dt is not printed."""
    launch = baseline_chapter_4(elevation_deg, atmosphere=atmosphere)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", TruncatedFlightWarning)  # only the first rows matter
        rows = appendix_a.simulate_appendix_a(launch, dt_s, max_time_s=2.0)
    errors = position_errors(rows, mks.for_launch(launch))
    return float(errors.total_geometric_m.iloc[0])


def variant_improved_share(variant: str) -> float:
    """Share of Chapter 4's elevations (30-85 deg) at which a Chapter 4 C variant
    (:data:`harp_analysis.comparisons.VARIANTS`) lowers the error at apogee."""
    elevations = comparisons.BASELINE_ELEVATIONS_DEG
    return float(
        np.mean([comparisons.error_ratio(variant, elevation) < 1.0 for elevation in elevations])
    )
