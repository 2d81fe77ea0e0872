"""Modified Linear Theory against the 6DOF and 3DOF, and the choices that change its answer
(issue #7): the 6DOF's own convergence, where in a segment the coefficients are frozen, what
the products dropped by linear theory cost, and which inertias the projectiles carry.

Distances between two flights are taken at the same time along the flight
(:func:`harp_analysis.analyses.scenarios.max_distance_m`, on the launch point's axes). "Like
with like" means the same ``density_altitude`` for 6DOF and MLT; the 3DOF always takes the
atmosphere at the spherical altitude, so its comparison with the 6DOF is like with like only
for ``density_altitude="spherical"`` (:mod:`.sixdof` explains the flat-altitude gap).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
import pandas as pd

from ..engines import mlt
from ..engines.sixdof import simulate_6dof
from ..foundation.caching import cached_copies
from ..foundation.validation import ModelValidityWarning
from ..models.projectiles import get_projectile
from . import scenarios
from .scenarios import max_distance_m

__all__ = [
    "method_comparison",
    "MltAgainst6dof",
    "mlt_against_6dof",
    "sixdof_convergence",
    "coefficient_point_convergence",
    "linear_theory_budget",
    "inertia_comparison",
    "SEGMENT_LENGTHS_M",
]

SEGMENT_LENGTHS_M = (2000.0, 1000.0, 500.0, 100.0)


def _summary(flight: pd.DataFrame) -> dict:
    return {
        "apogee_m": flight.attrs["apogee_altitude_m"],
        "range_m": flight.attrs["range_m"],
        "time_of_flight_s": flight.attrs["time_of_flight_s"],
        "cross_range_m": flight.attrs["cross_range_m"],
    }


@cached_copies
def method_comparison(projectile: str, density_altitude: str = "spherical") -> pd.DataFrame:
    """MLT against 6DOF and 3DOF against 6DOF for ``projectile``'s reference flight: the largest
    position difference along the flight and the differences of apogee, range, time of flight
    and cross range (method minus 6DOF), with the 6DOF's own values for scale."""
    six = scenarios.reference_6dof(projectile, density_altitude)
    others = {
        "MLT": (scenarios.reference_mlt(projectile, density_altitude), False),
        "3DOF": (scenarios.reference_3dof(projectile), True),
    }
    reference = _summary(six)
    rows = {"6DOF (value)": {"max_position_difference_m": 0.0, **reference}}
    for name, (flight, three_dof) in others.items():
        values = _summary(flight)
        rows[f"{name} - 6DOF"] = {
            "max_position_difference_m": max_distance_m(six, flight, b_three_dof=three_dof),
            **{key: values[key] - reference[key] for key in reference},
        }
    return pd.DataFrame(rows).T


@dataclass(frozen=True)
class MltAgainst6dof:
    """MLT against the 6DOF over one reference flight (:func:`mlt_against_6dof`)."""

    max_position_difference_km: float  # the largest distance at the same time
    mlt_cross_range_km: float  # at impact
    sixdof_cross_range_km: float
    apogee_difference_m: float  # MLT minus 6DOF
    range_difference_share: float  # of the 6DOF's range
    time_of_flight_difference_s: float


def mlt_against_6dof(projectile: str, density_altitude: str = "spherical") -> MltAgainst6dof:
    """MLT against the 6DOF for ``projectile``'s reference flight (:func:`method_comparison`):
    the largest distance at the same time along the flight, the ledger's measure of "MLT
    predict the projectile motion accurately" (Ch. 2 B), and where it comes from."""
    table = method_comparison(projectile, density_altitude)
    six, gap = table.loc["6DOF (value)"], table.loc["MLT - 6DOF"]
    return MltAgainst6dof(
        float(gap.max_position_difference_m) / 1e3,
        float(six.cross_range_m + gap.cross_range_m) / 1e3,
        float(six.cross_range_m) / 1e3,
        float(gap.apogee_m),
        float(gap.range_m / six.range_m),
        float(gap.time_of_flight_s),
    )


@cached_copies
def sixdof_convergence(
    projectile: str, density_altitude: str = "spherical", rtols: tuple = (1e-7, 1e-9, 1e-11)
) -> pd.DataFrame:
    """The reference 6DOF (rtol 1e-9) against looser and tighter tolerances: the largest
    position difference along the flight and the apogee and range differences (m)."""
    launch = scenarios.reference_launch(projectile)
    flights = {
        rtol: simulate_6dof(launch, density_altitude=density_altitude, rtol=rtol) for rtol in rtols
    }
    reference = scenarios.reference_6dof(projectile, density_altitude)
    return pd.DataFrame(
        {
            rtol: {
                "max_position_difference_m": max_distance_m(reference, flight),
                "apogee_difference_m": flight.attrs["apogee_altitude_m"]
                - reference.attrs["apogee_altitude_m"],
                "range_difference_m": flight.attrs["range_m"] - reference.attrs["range_m"],
                "rhs_evaluations": flight.attrs["rhs_evaluations"],
            }
            for rtol, flight in flights.items()
        }
    ).T.rename_axis("rtol")


@cached_copies
def _limit(projectile: str, density_altitude: str, frame_coupling: bool = False):
    return mlt.simulate_linear_theory_limit(
        scenarios.reference_launch(projectile),
        density_altitude=density_altitude,
        frame_coupling=frame_coupling,
        rtol=1e-11,
    )


@cached_copies
def coefficient_point_convergence(
    projectile: str, density_altitude: str = "spherical", lengths_m: tuple = SEGMENT_LENGTHS_M
) -> pd.DataFrame:
    """Largest position difference (m) between MLT and its continuous limit for each
    coefficient evaluation point and segment length: the segment error alone."""
    limit = _limit(projectile, density_altitude)
    launch = scenarios.reference_launch(projectile)
    rows = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelValidityWarning)
        for at in mlt.COEFFICIENT_POINTS:
            rows[at] = {
                length: max_distance_m(
                    limit,
                    mlt.simulate_mlt(
                        launch,
                        density_altitude=density_altitude,
                        segment_length_m=length,
                        coefficients_at=at,
                    ),
                )
                for length in lengths_m
            }
    return pd.DataFrame(rows).T.rename_axis("coefficients_at")


@cached_copies
def linear_theory_budget(projectile: str, density_altitude: str = "spherical") -> pd.DataFrame:
    """Where MLT's difference from the 6DOF comes from: the segments (MLT at 1 km against its
    continuous limit), the products linear theory drops (the limit against the 6DOF), and of
    those the no-roll frame's roll-rate coupling alone (the limit with it restored)."""
    six = scenarios.reference_6dof(projectile, density_altitude)
    mlt_flight = scenarios.reference_mlt(projectile, density_altitude)
    limit, coupled = (
        _limit(projectile, density_altitude),
        _limit(projectile, density_altitude, True),
    )
    pairs = {
        "segments (MLT 1 km - limit)": (mlt_flight, limit),
        "dropped products (limit - 6DOF)": (limit, six),
        "of which frame coupling (limit - limit with it)": (limit, coupled),
        "the rest (limit with frame coupling - 6DOF)": (coupled, six),
    }
    return pd.DataFrame(
        {
            name: {
                "max_position_difference_m": max_distance_m(a, b),
                "cross_range_difference_m": a.attrs["cross_range_m"] - b.attrs["cross_range_m"],
                "range_difference_m": a.attrs["range_m"] - b.attrs["range_m"],
            }
            for name, (a, b) in pairs.items()
        }
    ).T


@cached_copies
def inertia_comparison(density_altitude: str = "spherical") -> pd.DataFrame:
    """6DOF and MLT for both inertia sets of each projectile (HP: Appendix B's code against the
    text; LP: the text's 26.8 mm against Appendix B's 25.6 mm diameter): apogee, range, cross
    range, largest angle of attack, and the largest MLT-6DOF position difference."""
    rows = {}
    for name in ("HP", "HP_text", "LP", "LP_appendix_b"):
        p = get_projectile(name)
        launch = scenarios.reference_launch(name)
        six = simulate_6dof(launch, density_altitude=density_altitude)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", ModelValidityWarning)
            linear = mlt.simulate_mlt(launch, density_altitude=density_altitude)
        for method, flight in (("6DOF", six), ("MLT", linear)):
            rows[name, method] = {
                "pitch_inertia_kg_m2": p.pitch_inertia_kg_m2,
                "diameter_m": p.diameter_m,
                **_summary(flight),
                "max_angle_of_attack_deg": float(np.degrees(flight.angle_of_attack_rad.max())),
                "max_difference_from_6dof_m": max_distance_m(six, flight),
                "validity_warning": bool(caught) if method == "MLT" else False,
            }
    return pd.DataFrame(rows).T.rename_axis(["projectile", "method"])
