"""Quantities behind statements of the appendices that the ledger scores (rows ``appA.*``,
``appB.*``, ``appD.*`` and ``appE.*``): Appendix A's rotation terms as printed, Appendix B's
printed angle of attack, and the share of the rounds of Appendices D and E whose derived columns
the package recomputes to within rounding.
"""

from __future__ import annotations

import math

from ...engines import appendix_a, threedof
from ...foundation import earth
from ...foundation.validation import check_choice
from ...models.launch import baseline_chapter_4
from .. import scenarios
from ..harp import apogees

__all__ = [
    "appendix_column_share_within_rounding",
    "appendix_a_rotation_effect_error_km",
    "printed_angle_of_attack_ratio",
]


def appendix_column_share_within_rounding(site: str = "barbados", column: str = "mach") -> float:
    """Share of the distinct rounds of Appendix D or E whose printed ``column`` the package
    recomputes (dissertation model) to within half a unit of the last printed digit
    (:func:`~harp_analysis.analyses.harp.apogees.column_agreement`)."""
    table = apogees.column_agreement(site)
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
