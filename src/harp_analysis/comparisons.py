"""The Modified Kepler Solution against the simulations: the cases of Chapter 4 and the
quantities the text states about them.

Every case pairs a 3DOF flight with the MKS of the same launch (three series terms unless
stated) and their total position error (:mod:`.mks_error`, the geometric reading of eq 4.7).
Cases are cached, so the notebook and the claims ledger share one run of each.
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np
import pandas as pd

from . import earth, mks, nonlinear_kepler
from .caching import cached_copies
from .launch import Launch, baseline_chapter_4, chapter_2
from .mks_error import position_errors
from .projectiles import BASELINE, get_projectile
from .threedof import simulate_3dof
from .validation import ModelValidityWarning

__all__ = [
    "BASELINE_ELEVATIONS_DEG",
    "VARIANTS",
    "chapter_4_launch",
    "fly",
    "case",
    "error_at_apogee_km",
    "error_ratio",
    "max_error_change_km",
    "elevation_error_ratio",
    "initial_natural_frequency",
    "linearisation_apogee_change_km",
    "response_ratio",
    "radius_change_below",
    "max_error_change_with_terms",
    "max_cd_change_below",
    "asymptotic_momentum_error",
    "mks_beta",
    "launch_error_m",
]

#: Chapter 4 B and C: the baseline cone "for the elevations of fire" 30 to 85 deg.
BASELINE_ELEVATIONS_DEG = (30.0, 45.0, 65.0, 85.0)


def chapter_4_launch(projectile: str, elevation_deg: float) -> Launch:
    """The launch Chapter 4 flies: HP and LP as in Chapter 2 A (5 m/s cross wind included),
    the baseline cone as Chapter 4 B describes it (no wind), at ``elevation_deg``."""
    p = get_projectile(projectile)
    if p == BASELINE:
        return baseline_chapter_4(elevation_deg)
    return chapter_2(p, elevation_deg=elevation_deg)


@cached_copies
def fly(launch: Launch, *, n_terms: int = 3, momentum_from_apogee: bool = False):
    """(3DOF table, MKS, error table) of ``launch``: the 3DOF flies it whole, the MKS (which
    has no wind) its drag-only part.

    ``momentum_from_apogee`` replaces the MKS's asymptotic angular momentum with the 3DOF's at
    apogee, L_inf = L_apogee (eq 4.9, Fig 4.13), by choosing the decay so that
    h0 exp(-beta s) = h_apogee while the driving function keeps its beta.
    """
    flight = simulate_3dof(launch, output_step_s=0.25)
    with warnings.catch_warnings():
        # HP and LP exceed beta = 0.25; the MKS leaves the wind out
        warnings.simplefilter("ignore", ModelValidityWarning)
        solution = mks.for_launch(launch, n_terms=n_terms)
        if momentum_from_apogee:
            h_apogee = np.interp(
                flight.attrs["apogee_time_s"], flight.time_s, flight.specific_angular_momentum_m2_s
            )
            scale = np.log(solution.h0 / h_apogee) / solution.beta
            solution = mks.ModifiedKeplerSolution(
                solution.speed_m_s.item(),
                solution.elevation_rad.item(),
                solution.beta.item(),
                solution.tau.item(),
                n_terms=n_terms,
                decay_scale=scale.item(),
            )
    return flight, solution, position_errors(flight, solution)


def case(
    projectile: str = "baseline",
    elevation_deg: float = 45.0,
    *,
    n_terms: int = 3,
    momentum_from_apogee: bool = False,
    **launch_changes,
):
    """:func:`fly` of Chapter 4's launch of ``projectile`` at ``elevation_deg`` with
    ``launch_changes`` (fields of :class:`~harp_analysis.launch.Launch`, e.g. the variants'
    ``atmosphere="exponential"``, Fig 4.15)."""
    launch = chapter_4_launch(projectile, elevation_deg).but(**launch_changes)
    return fly(launch, n_terms=n_terms, momentum_from_apogee=momentum_from_apogee)


def _at_apogee(errors: pd.DataFrame, flight: pd.DataFrame, column: str) -> float:
    return float(np.interp(flight.attrs["apogee_time_s"], errors.time_s, errors[column]))


def error_at_apogee_km(
    projectile: str = "baseline", elevation_deg: float = 45.0, relative: bool = False, **variant
) -> float:
    """Total position error at the 3DOF's apogee (km, or as a share of the apogee)."""
    flight, _, errors = case(projectile, elevation_deg, **variant)
    error = _at_apogee(errors, flight, "total_geometric_m")
    return error / flight.attrs["apogee_altitude_m"] if relative else error / 1e3


#: The variants of Chapter 4 C (Figs 4.13, 4.15, 4.17, 4.18) as arguments of :func:`case`.
VARIANTS: dict[str, dict[str, Any]] = {
    "exponential_density": dict(atmosphere="exponential"),
    "momentum_from_apogee": dict(momentum_from_apogee=True),
    "speed_plus_20pct": dict(speed_m_s=2590.0),
    "winds": dict(head_wind_m_s=6.0, cross_wind_m_s=6.0),
}


def error_ratio(variant: str, elevation_deg: float | None = None) -> float:
    """Error at apogee of a Chapter 4 C variant over the standard case's (baseline), at one
    elevation or, by default, summed over :data:`BASELINE_ELEVATIONS_DEG`."""
    elevations = BASELINE_ELEVATIONS_DEG if elevation_deg is None else (elevation_deg,)
    return sum(error_at_apogee_km("baseline", e, **VARIANTS[variant]) for e in elevations) / sum(
        error_at_apogee_km("baseline", e) for e in elevations
    )


def max_error_change_km(variant: str) -> float:
    """Largest change (km) of the error at apogee that a variant causes, over the elevations."""
    return max(
        abs(
            error_at_apogee_km("baseline", e, **VARIANTS[variant])
            - error_at_apogee_km("baseline", e)
        )
        for e in BASELINE_ELEVATIONS_DEG
    )


def max_error_change_with_terms(
    projectile: str = "HP", elevation_deg: float = 50.0, terms: int = 10
) -> float:
    """Largest change of the error up to apogee from 3 to ``terms`` series terms, as a share
    of the 3-term error at apogee (Ch. 4 A: more terms "do not significantly increase the
    accuracy")."""
    flight, _, three = case(projectile, elevation_deg)
    _, _, more = case(projectile, elevation_deg, n_terms=terms)
    ascent = three.time_s <= flight.attrs["apogee_time_s"]
    change = np.abs(more.total_geometric_m - three.total_geometric_m)[ascent].max()
    return float(change / _at_apogee(three, flight, "total_geometric_m"))


def max_cd_change_below(altitude_km: float = 20.0) -> float:
    """Largest relative change of the baseline's Cd from launch while below ``altitude_km``,
    over the elevations of Fig 4.16 (Ch. 4 C: "less than 5 % below 20 km")."""
    changes = []
    for elevation in BASELINE_ELEVATIONS_DEG:
        flight = case("baseline", elevation)[0]
        low = flight[
            (flight.altitude_m < altitude_km * 1e3)
            & (flight.time_s < flight.attrs["apogee_time_s"])
        ]
        changes.append(np.max(np.abs(low.drag_coefficient / low.drag_coefficient.iloc[0] - 1)))
    return float(max(changes))


def asymptotic_momentum_error(projectile: str = "baseline", elevation_deg: float = 45.0) -> float:
    """(h_inf of the MKS - h of the 3DOF at apogee) / h at apogee (Fig 4.12)."""
    flight, solution, _ = case(projectile, elevation_deg)
    h_apogee = np.interp(
        flight.attrs["apogee_time_s"], flight.time_s, flight.specific_angular_momentum_m2_s
    )
    return float(solution.h_inf[0, 0] / h_apogee - 1)


def mks_beta(projectile: str, elevation_deg: float = 50.0) -> float:
    """Eq 3.22's beta of ``projectile`` (Table 4.1's "MKS beta")."""
    return float(case(projectile, elevation_deg)[1].beta[0, 0])


def launch_error_m(projectile: str = "baseline", elevation_deg: float = 45.0) -> float:
    """Total position error at launch (m): the MKS starts exactly where the simulation does."""
    return float(case(projectile, elevation_deg)[2].direct_m.iloc[0])


def elevation_error_ratio(high_deg: float = 85.0, low_deg: float = 45.0) -> float:
    """Error at apogee at ``high_deg`` over that at ``low_deg`` (baseline, Fig 4.11)."""
    return error_at_apogee_km("baseline", high_deg) / error_at_apogee_km("baseline", low_deg)


def initial_natural_frequency(projectile: str = "HP", elevation_deg: float = 50.0) -> float:
    """Eq 3.29's natural frequency at launch (rad/rad), Chapter 3 C's "27 rad/rad" for HP."""
    return nonlinear_kepler.initial_natural_frequency(case(projectile, elevation_deg)[1])


def linearisation_apogee_change_km(
    projectile: str = "HP", elevation_deg: float = 50.0, form: str = "eq_3_25"
) -> float:
    """Apogee of the unlinearised equation ``form`` minus eq 3.30's (km), Assumption 6."""
    solution = case(projectile, elevation_deg)[1]
    return nonlinear_kepler.linearisation_error(solution, form).apogee_m / 1e3


def response_ratio(
    projectile: str = "HP", elevation_deg: float = 50.0, multiple: float = 1.0
) -> float:
    """Fig 3.4: response of the linearised system (omega_n = 1) over the nonlinear one (omega_n
    at launch) at the driving frequency ``multiple`` * tau."""
    solution = case(projectile, elevation_deg)[1]
    omega = multiple * solution.tau.item()
    return nonlinear_kepler.frequency_response(omega, 1.0) / nonlinear_kepler.frequency_response(
        omega, nonlinear_kepler.initial_natural_frequency(solution)
    )


def radius_change_below(altitude_km: float = 20.0) -> float:
    """Relative change of the radius r from r0 up to ``altitude_km`` (Assumption 5)."""
    return altitude_km * 1e3 / earth.RADIUS_M
