"""The quantities of harp_analysis.analyses.claims.appendices, checked against an independent
recomputation, the vacuum's conic and the tangent's series."""

import math

import numpy as np
import pytest

from harp_analysis.analyses import scenarios
from harp_analysis.analyses.claims import appendices
from harp_analysis.analyses.harp import apogees
from harp_analysis.engines import kepler
from harp_analysis.foundation import earth

R = earth.RADIUS_M


def test_mach_column_share_recomputed_independently():
    rounds = apogees.appendix_rounds("barbados")
    rounds = rounds[~rounds.duplicate_of_earlier_row]
    mach = rounds.muzzle_speed_m_s / apogees.speed_of_sound("barbados")[0]
    within = float(np.mean(np.abs(mach - rounds.mach) <= 0.005 + 1e-12))
    assert appendices.appendix_column_share_within_rounding("barbados", "mach") == within


def test_appendix_a_rotation_terms_in_a_vacuum():
    # at the equator the printed omega R is right and without air the sign of the air
    # velocity does not matter
    assert abs(appendices.appendix_a_rotation_effect_error_km(atmosphere="vacuum")) < 0.02
    # at 45 deg N the printed omega R adds omega R (1 - cos 45 deg) of eastward speed
    latitude, speed, elevation = math.radians(45.0), 2157.0, math.radians(45.0)
    surface = earth.ROTATION_RATE_RAD_S * R

    def apogee(east_extra):
        east, up = speed * math.cos(elevation) + east_extra, speed * math.sin(elevation)
        conic = kepler.conic_from_state(R, math.hypot(east, up), math.atan2(up, east))
        return conic.apogee_radius_m - R

    expected = apogee(surface) - apogee(surface * math.cos(latitude))
    computed = appendices.appendix_a_rotation_effect_error_km(45.0, 90.0, atmosphere="vacuum")
    assert computed * 1e3 == pytest.approx(expected, rel=0.02)


def test_printed_angle_of_attack_is_the_tangent():
    ratio = appendices.printed_angle_of_attack_ratio("HP")
    alpha = float(scenarios.reference_6dof("HP").angle_of_attack_rad.max())
    assert ratio == pytest.approx(1 + alpha**2 / 3 + 2 * alpha**4 / 15, rel=1e-5)
    assert math.degrees(alpha) > 4  # the large angle outside the air (Ch. 4 A)
