"""HARP apogees (Chapter 6 C and D): the ECI Modified Kepler Solution of every Martlet 2C round
of Appendices D (Barbados) and E (Yuma) against its measured apogee.

Each round flies the three-term ECI MKS (:func:`harp_analysis.eci.eci_solution`) from its
site's latitude, gun bearing, surface density and 85 deg elevation, with its own mass and muzzle
speed; the apogee is eq 6.4-6.5's. The launch includes V_tangent (eq 6.15) and the decay of the
angular momentum carries the same cos(mu) (Vrel/V)^2 as the driving terms (``decay=
"consistent"``), the model that also reproduces Chapter 5 (:mod:`.rotating`). Appendices D and
E's printed columns leave V_tangent out and eq 6.14 as printed drops (Vrel/V)^2; that variant
(``include_tangent=False, decay="printed"``) is available and compared in the ledger.

The Martlet's drag is not in the dissertation (it cites a McGill report [52]); the text says
the drag "derived from the Barbados data" was used unchanged for Yuma. Here it is derived from
the Barbados table itself: Cd0 A is the least-squares value that reproduces Appendix D's printed
beta column through eq 6.11 (:func:`harp_analysis.eci.fit_drag_area_m2`), and is then used for
both sites. Residuals are measured minus predicted apogee, Appendix E's sign convention.
"""

from __future__ import annotations

from functools import cache

import numpy as np
import pandas as pd

from . import eci
from .harp_data import load_appendix
from .sites import get_site
from .validation import check_choice

__all__ = ["martlet_drag_area_m2", "predicted_apogees", "residual_statistic"]


@cache
def martlet_drag_area_m2() -> float:
    """Cd0 A of the Martlet 2C (m^2), derived from Appendix D's beta column (eq 6.11)."""
    return float(eci.fit_drag_area_m2("barbados"))


@cache
def predicted_apogees(site: str, drag_area_m2: float | None = None,
                      include_tangent: bool = True, decay: str = "consistent") -> pd.DataFrame:
    """Measured and predicted apogee of every printed row of ``site``'s appendix (the
    duplicated Barbados round 181 kept and flagged), residual = measured - predicted."""
    launch_site = get_site(site)
    table = load_appendix(launch_site.name)
    solution = eci.eci_solution(
        table.muzzle_speed_m_s.to_numpy(), launch_site.elevation_rad,
        launch_site.gun_bearing_rad, launch_site.latitude_rad,
        drag_area_m2=martlet_drag_area_m2() if drag_area_m2 is None else drag_area_m2,
        mass_kg=table.mass_kg.to_numpy(), surface_density_kg_m3=launch_site.surface_density_kg_m3,
        include_tangent=include_tangent, decay=decay, warn=False)
    predicted = np.atleast_1d(solution.apogee_altitude("eq_6_4"))
    frame = pd.DataFrame({"round_number": table.round_number,
                          "measured_apogee_m": table.apogee_m,
                          "predicted_apogee_m": predicted,
                          "residual_m": table.apogee_m - predicted,
                          "duplicate_of_earlier_row": table.duplicate_of_earlier_row})
    if "apogee_error_m" in table:
        frame["printed_error_m"] = table.apogee_error_m
    return frame


def residual_statistic(site: str, statistic: str = "mean", include_duplicate: bool = True,
                       drag_area_m2: float | None = None, include_tangent: bool = True,
                       decay: str = "consistent") -> float:
    """Mean, its magnitude ("abs_mean") or sample standard deviation (km) of the apogee
    residuals of ``site``."""
    check_choice(statistic, "statistic", ("mean", "abs_mean", "std"))
    frame = predicted_apogees(site, drag_area_m2, include_tangent, decay)
    if not include_duplicate:
        frame = frame[~frame.duplicate_of_earlier_row]
    residual = frame.residual_m / 1e3
    if statistic == "std":
        return float(residual.std(ddof=1))
    return float(abs(residual.mean()) if statistic == "abs_mean" else residual.mean())
