"""Quantities behind statements of Chapter 4 that the ledger scores (rows ``ch4.*``): the speed
lost on re-entry and the HARP spread against the MKS's error (4 A), beta's accuracy limit, the
baseline's elevations and Mach numbers, and the launch error correcting itself (4 B), the
faster launch and Assumption 3 off the design launch (4 C).
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from collections.abc import Callable

import numpy as np
import pandas as pd
from scipy.optimize import brentq

from ...foundation.validation import Bounds, ModelValidityWarning, check_choice
from ...models.projectiles import BASELINE
from .. import rotating, scenarios
from ..comparisons import BASELINE_ELEVATIONS_DEG, VARIANTS, case, fly, launch_error_at_apogee_km
from .launches import no_wind

__all__ = [
    "ReentrySpeedLoss",
    "reentry_speed_loss",
    "beta_accuracy_limit",
    "beta_limit_elevation_deg",
    "min_mach_below",
    "launch_error_left_below",
    "variant_speed_increase",
    "OffDesignError",
    "off_design_error",
]


# --- Chapter 4 A: re-entry, the HARP spread -------------------------------------------------------
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


def reentry_speed_loss(
    engine: str = "6DOF", projectile: str = "HP", density_altitude: str = "flat"
) -> ReentrySpeedLoss:
    """Fig 4.3's speed drop on re-entry of Chapter 2 A's flight of ``projectile`` by the 6DOF,
    MLT or 3DOF (Ch. 4 A: "the sharp decrease in velocity that indicates reentry into the
    atmosphere in the MLT and numerical simulations"). The rigid bodies meet the air at
    ``density_altitude``: "flat", the flat frame's, as Appendix B codes it and Fig 4.3 draws
    it, or "spherical", the true altitude, as the 3DOF always does."""
    check_choice(density_altitude, "density_altitude", ("flat", "spherical"))
    flights: dict[str, Callable[[str], pd.DataFrame]] = {
        "6DOF": lambda name: scenarios.reference_6dof(name, density_altitude),
        "MLT": lambda name: scenarios.reference_mlt(name, density_altitude),
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


# --- Chapter 4 B: beta and the baseline -----------------------------------------------------------
def beta_accuracy_limit(
    error_km: float = 1.0, projectile: str = "HP", elevation_deg: float = 50.0
) -> float:
    """The MKS beta at which the error at apogee reaches ``error_km``: ``projectile`` flown as
    in Fig 4.8 (no wind) with its mass varied (beta ~ 1/m; drag law, speed and elevation
    kept), the mass found by root finding, its beta returned."""
    target = Bounds(low=0.0, low_inclusive=False).scalar(error_km, "error_km")
    base = no_wind(projectile, elevation_deg)

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
    limit = Bounds(low=0.0, low_inclusive=False).scalar(beta_limit, "beta_limit")
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


def launch_error_left_below(
    altitude_km: float = 30.0, dt_s: float = 0.1, elevation_deg: float = 45.0
) -> float:
    """Smallest error of the MKS against Appendix A's printed rows on the way up below
    ``altitude_km``, over its error at launch (Ch. 4 B, Fig 4.11: the launch error "quickly
    corrects itself"; under 0.1 if it has). The error at launch is the macro's clock, one step
    ahead of its positions (:func:`~harp_analysis.analyses.rotating.appendix_a_launch_error_m`)."""
    rows, errors = rotating.appendix_a_errors(dt_s, elevation_deg)
    climbing = (rows.time_s <= rows.attrs["apogee_time_s"]) & (rows.altitude_m < altitude_km * 1e3)
    error = errors.total_geometric_m.to_numpy()[climbing.to_numpy()[: len(errors)]]
    return float(error.min() / error[0])


# --- Chapter 4 C: the faster launch, Assumption 3 off design --------------------------------------
def variant_speed_increase(variant: str = "speed_plus_20pct") -> float:
    """Relative increase of a Chapter 4 C variant's launch speed over the baseline's (Fig 4.17's
    2.59 km/s against 2.157 km/s)."""
    check_choice(variant, "variant", tuple(VARIANTS))
    return VARIANTS[variant]["speed_m_s"] / BASELINE.launch_speed_m_s - 1


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
