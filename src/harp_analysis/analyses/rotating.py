"""Chapter 5 C: the ECI Modified Kepler Solution against the rotating-Earth 3DOF (Figs 5.4-5.9).

The baseline cone fired from latitude 0 and 45 deg on bearings 000T, 090T and 270T at 30-85 deg,
3DOF with the Earth turning (:data:`harp_analysis.foundation.earth.ROTATION_RATE_RAD_S`) against
the three-term ECI MKS (its table, :func:`harp_analysis.engines.eci.simulate_eci_mks`, with
V_tangent as Chapter 5 adds it, eq 6.15, and the decay of eq 6.14 carrying the same cos(mu)
(Vrel/V)^2 as the driving terms: eq 6.14 as printed drops (Vrel/V)^2, which puts the east- and
west-fired apogees several km off, the wrong way round; ``decay="printed"`` keeps it for
comparison). The MKS lives in the inertial plane of its corrected launch velocity; its position
at each simulation time is placed in that plane and the error is the distance between the two
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

from ..engines import appendix_a, eci, mks
from ..engines.threedof import simulate_3dof
from ..foundation import earth
from ..foundation.caching import cached_copies
from ..models.atmosphere import get_atmosphere
from ..models.launch import baseline_chapter_4
from ..models.trajectory import TruncatedFlightWarning
from . import comparisons
from .mks_error import position_errors

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
    """(rotating 3DOF table, ECI MKS table, error table) of the baseline cone: the ECI MKS of
    :data:`~harp_analysis.engines.eci.CONSISTENT`, or with eq 6.14's printed decay
    (``decay="printed"``), against the 3DOF flown through ``atmosphere`` (eqs 2.1-2.2 by default, or
    Appendix A's ``"three_layer"``; the launch's air also sets the MKS's Cd0, at the gun's Mach
    number). The 3DOF's rows are those while both fly; the MKS's
    (:func:`~harp_analysis.engines.eci.simulate_eci_mks`) are at the same times, and its impact."""
    model = replace(eci.CONSISTENT, name=f"consistent, {decay} decay", decay=decay)
    launch = baseline_chapter_4(
        elevation_deg,
        latitude_deg=latitude_deg,
        bearing_deg=bearing_deg,
        rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S,
        atmosphere=atmosphere,
    )
    flight = simulate_3dof(launch, output_step_s=0.5)
    table = eci.simulate_eci_mks(launch, model=model, times_s=flight.time_s, warn=False)
    flight = flight.iloc[: len(table) - 1]  # compare while both are in flight
    mks_xyz = table[["x_m", "y_m", "z_m"]].to_numpy()[:-1].T
    sim_xyz = flight[["x_m", "y_m", "z_m"]].to_numpy().T
    errors = pd.DataFrame(
        {
            "time_s": flight.time_s,
            "ground_range_m": flight.ground_range_m,
            "error_m": np.linalg.norm(sim_xyz - mks_xyz, axis=0),
        }
    )
    return flight, table, errors


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
    atmosphere: str = "two_segment", min_elevation_deg: float = 0.0, decay: str = "consistent"
) -> dict[tuple[float, float, float], float]:
    """Error at apogee (km) of every case at or above ``min_elevation_deg``, keyed by
    (latitude, bearing, elevation) in degrees, with the ECI MKS's ``decay`` (:func:`case`)."""
    return {
        (lat, brg, el): error_at_apogee_km(lat, brg, el, decay=decay, atmosphere=atmosphere)
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
    :func:`harp_analysis.analyses.comparisons.launch_error_m`); the macro prints its first position,
    two steps out, at the clock time 3 dt, so the MKS at that time is one step, about V0 dt,
    further along (:mod:`.appendix_a`). The sheet's dt is not printed."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", TruncatedFlightWarning)  # only the first rows matter
        _, errors = appendix_a_errors(dt_s, elevation_deg, atmosphere, max_time_s=2.0)
    return float(errors.total_geometric_m.iloc[0])


def appendix_a_errors(
    dt_s: float = 0.1,
    elevation_deg: float = 45.0,
    atmosphere: str = "three_layer",
    max_time_s: float | None = None,
):
    """The rows Appendix A's macro prints for the baseline cone at ``elevation_deg`` (step
    ``dt_s``, the listing's air, the Earth's spin off) and the three-term MKS's position errors
    against them (:func:`harp_analysis.analyses.mks_error.position_errors`)."""
    launch = baseline_chapter_4(elevation_deg, atmosphere=atmosphere)
    limit = {} if max_time_s is None else {"max_time_s": max_time_s}
    rows = appendix_a.simulate_appendix_a(launch, dt_s, **limit)
    return rows, position_errors(rows, mks.for_launch(launch))


def variant_improved_share(variant: str) -> float:
    """Share of Chapter 4's elevations (30-85 deg) at which a Chapter 4 C variant
    (:data:`harp_analysis.analyses.comparisons.VARIANTS`) lowers the error at apogee."""
    elevations = comparisons.BASELINE_ELEVATIONS_DEG
    return float(
        np.mean([comparisons.error_ratio(variant, elevation) < 1.0 for elevation in elevations])
    )


# --- Further Chapter 5 statements (the sweep's rows) ----------------------------------------------
__all__ += [
    "west_over",
    "lowest_elevation_worst_share",
    "west_ordering_share",
    "largest_extent_under_km",
    "air_profile",
    "misalignment_growth_share",
    "speed_ratio_change_below",
]


def west_over(bearing_deg: float = 0.0, atmosphere: str = "two_segment") -> float:
    """Errors at apogee summed over latitudes and elevations, 270T over ``bearing_deg``
    (:func:`west_over_east` is ``bearing_deg=90``)."""
    cases = errors_at_apogee_km(atmosphere)
    return sum(v for (_, brg, _), v in cases.items() if brg == 270.0) / sum(
        v for (_, brg, _), v in cases.items() if brg == bearing_deg
    )


def lowest_elevation_worst_share(atmosphere: str = "two_segment") -> float:
    """Share of the six (latitude, bearing) pairs whose largest error at apogee is at the
    lowest elevation, 30 deg (Ch. 5 D: "the error grows for lower elevations")."""
    cases = errors_at_apogee_km(atmosphere)
    lowest = min(ELEVATIONS_DEG)
    return float(
        np.mean(
            [
                max(ELEVATIONS_DEG, key=lambda el: cases[lat, brg, el]) == lowest
                for lat in LATITUDES_DEG
                for brg in BEARINGS_DEG
            ]
        )
    )


def west_ordering_share(by: str = "latitude", atmosphere: str = "two_segment") -> float:
    """Ch. 5 D on west-fired (270T) shots, "the lower the trajectory and closer to the equator
    ... the greater the error", as the share of comparisons that agree: ``by="latitude"``, the
    four elevations at which the equator's error at apogee exceeds 45 deg N's; ``by="elevation"``,
    the steps between neighbouring elevations (both latitudes) across which it falls as the
    elevation rises."""
    cases = errors_at_apogee_km(atmosphere)
    if by == "latitude":
        return float(
            np.mean([cases[0.0, 270.0, el] > cases[45.0, 270.0, el] for el in ELEVATIONS_DEG])
        )
    if by == "elevation":
        steps = [
            cases[lat, 270.0, low] > cases[lat, 270.0, high]
            for lat in LATITUDES_DEG
            for low, high in zip(ELEVATIONS_DEG[:-1], ELEVATIONS_DEG[1:])
        ]
        return float(np.mean(steps))
    raise ValueError(f"by must be 'latitude' or 'elevation', got {by!r}")


def largest_extent_under_km(
    quantity: str = "range", max_error_km: float = 1.0, atmosphere: str = "two_segment"
) -> float:
    """Largest ground range at impact (``quantity="range"``) or apogee (``"apogee"``), km, of
    the rotating 3DOF over the 24 cases whose error at apogee is under ``max_error_km``."""
    if quantity not in ("range", "apogee"):
        raise ValueError(f"quantity must be 'range' or 'apogee', got {quantity!r}")
    key = "range_m" if quantity == "range" else "apogee_altitude_m"
    return max(
        case(lat, brg, el, atmosphere=atmosphere)[0].attrs[key] / 1e3
        for (lat, brg, el), error in errors_at_apogee_km(atmosphere).items()
        if error < max_error_km
    )


def air_profile(
    latitude_deg: float,
    bearing_deg: float,
    elevation_deg: float,
    atmosphere: str = "two_segment",
) -> pd.DataFrame:
    """The rotating 3DOF's ascent with the inertial speed V, the air-relative speed Vrel (Mach
    times the local speed of sound) and, from the two and the air's own speed omega r_perp
    (r_perp: the distance from the Earth's axis; no wind), the misalignment angle mu between
    them (law of cosines) and (Vrel/V)^2 (eqs 5.2-5.3)."""
    flight = case(latitude_deg, bearing_deg, elevation_deg, atmosphere=atmosphere)[0]
    ascent = flight[flight.time_s <= flight.attrs["apogee_time_s"]]
    altitude = ascent.altitude_m.to_numpy()
    speed = ascent.speed_m_s.to_numpy()
    air_speed = ascent.mach.to_numpy() * get_atmosphere(atmosphere).speed_of_sound(altitude)
    carried = earth.ROTATION_RATE_RAD_S * np.hypot(ascent.x_m, ascent.y_m).to_numpy()
    cosine = (speed**2 + air_speed**2 - carried**2) / (2 * speed * air_speed)
    return pd.DataFrame(
        {
            "time_s": ascent.time_s.to_numpy(),
            "altitude_m": altitude,
            "speed_m_s": speed,
            "air_speed_m_s": air_speed,
            "misalignment_rad": np.arccos(np.clip(cosine, -1.0, 1.0)),
            "speed_ratio_squared": (air_speed / speed) ** 2,
        }
    )


def _at_altitude(profile: pd.DataFrame, column: str, altitude_km: float) -> float:
    return float(np.interp(altitude_km * 1e3, profile.altitude_m, profile[column]))


def misalignment_growth_share(
    bearing_deg: float = 90.0, altitude_km: float = 20.0, atmosphere: str = "two_segment"
) -> float:
    """Share of the eight cases fired on ``bearing_deg`` (two latitudes, four elevations) whose
    misalignment angle mu is larger at ``altitude_km`` on the way up than at the gun (Ch. 5 D:
    it "becomes smaller over time" when fired east, the curve "increases" it when fired west)."""
    grows = []
    for lat in LATITUDES_DEG:
        for el in ELEVATIONS_DEG:
            profile = air_profile(lat, bearing_deg, el, atmosphere)
            mu = _at_altitude(profile, "misalignment_rad", altitude_km)
            grows.append(mu > profile.misalignment_rad.iloc[0])
    return float(np.mean(grows))


def speed_ratio_change_below(altitude_km: float = 20.0, atmosphere: str = "two_segment") -> float:
    """Largest relative change of (Vrel/V)^2 from its launch value while below ``altitude_km``
    on the way up, over the 24 cases (eq 5.2 holds it constant at the launch value)."""
    changes = []
    for lat in LATITUDES_DEG:
        for brg in BEARINGS_DEG:
            for el in ELEVATIONS_DEG:
                profile = air_profile(lat, brg, el, atmosphere)
                low = profile[profile.altitude_m <= altitude_km * 1e3].speed_ratio_squared
                changes.append(np.max(np.abs(low / low.iloc[0] - 1)))
    return float(max(changes))
