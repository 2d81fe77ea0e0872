"""Quantities behind statements of Chapter 6 that the ledger scores (rows ``ch6.*``): the lowest
measured apogees, the atmosphere's terms at eq 6.4's apogee angle, and the sea-level density at
Barbados and Yuma (6 C-D). The rounds are those of
:mod:`~harp_analysis.analyses.harp.apogees`.
"""

from __future__ import annotations

import numpy as np

from ...foundation.validation import Bounds, check_choice, finite_scalar
from ...models.atmosphere import DRY_AIR_GAS_CONSTANT_J_KG_K
from ..harp import apogees

__all__ = [
    "STANDARD_PRESSURE_PA",
    "min_measured_apogee_km",
    "apogee_drive_ratio",
    "apogee_simplification_shift_km",
    "harp_solution",
    "fahrenheit_to_kelvin",
    "density_at_temperature_kg_m3",
    "site_density_kg_m3",
]


#: Sea-level pressure of the 1976 standard atmosphere (Pa).
STANDARD_PRESSURE_PA = 101_325.0


# --- Chapter 6: the HARP apogees ------------------------------------------------------------------
def min_measured_apogee_km(site: str = "barbados") -> float:
    """Lowest measured apogee (km) among the appendix rows of ``site``."""
    return float(apogees.appendix_rounds(site).apogee_m.min()) / 1e3


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
    return apogees.launch_corrections(site, model).solution(warn=False)


def fahrenheit_to_kelvin(temperature_f: float) -> float:
    return (finite_scalar(temperature_f, "temperature_f") - 32.0) * 5.0 / 9.0 + 273.15


def density_at_temperature_kg_m3(
    temperature_k: float, pressure_pa: float = STANDARD_PRESSURE_PA
) -> float:
    """Dry-air density p / (R T) (kg/m^3)."""
    temperature = Bounds(low=0.0, low_inclusive=False).scalar(temperature_k, "temperature_k")
    pressure = Bounds(low=0.0, low_inclusive=False).scalar(pressure_pa, "pressure_pa")
    return pressure / (DRY_AIR_GAS_CONSTANT_J_KG_K * temperature)


def site_density_kg_m3(
    site: str = "barbados", source: str = "mach_column", temperature_f: float = 75.0
) -> float:
    """Sea-level dry-air density (kg/m^3) at ``site`` at standard pressure, at the temperature
    of the speed of sound behind the appendix's Mach column (``source="mach_column"``,
    :func:`~harp_analysis.analyses.harp.apogees.speed_of_sound`) or at ``temperature_f``
    (``"temperature"``; Ch. 6 C gives Barbados 80 F by day and 70 F by night)."""
    check_choice(source, "source", ("mach_column", "temperature"))
    if source == "mach_column":
        temperature = apogees.air_temperature_k(apogees.speed_of_sound(site)[0])
    else:
        temperature = fahrenheit_to_kelvin(temperature_f)
    return density_at_temperature_kg_m3(temperature)
