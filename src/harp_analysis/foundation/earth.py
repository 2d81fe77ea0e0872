"""The Earth of the dissertation: a sphere of radius 6378 km with inverse-square gravity.

Chapter 2 A (non-rotating ECEF) and Chapter 5 A (ECI, one turn in 24 h); the gravitational
parameter is Appendix A's GM = 398600.4418 km^3/s^2.
"""

import math

__all__ = [
    "RADIUS_M",
    "GM_M3_S2",
    "ROTATION_RATE_RAD_S",
    "STANDARD_GRAVITY_M_S2",
    "surface_gravity_m_s2",
]

RADIUS_M = 6_378_000.0
GM_M3_S2 = 398_600.4418e9
#: The text's rate, 2 pi / 86400 s (eq 6.16), a solar day; the sidereal rate is 7.2921e-5 rad/s.
ROTATION_RATE_RAD_S = 2.0 * math.pi / 86_400.0
STANDARD_GRAVITY_M_S2 = 9.80665


def surface_gravity_m_s2() -> float:
    """GM / R^2 at the surface of the spherical Earth: 9.7987 m/s^2."""
    return GM_M3_S2 / RADIUS_M**2
