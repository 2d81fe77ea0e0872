"""The standard Kepler solution (Chapter 3 A, eq 3.8) of a ballistic flight without drag.

A projectile leaving radius r0 at speed V and flight-path angle phi above the horizontal flies
a conic about the Earth's centre: u(theta) = 1/r = GM/L^2 + C cos(theta - theta_a), with the
specific angular momentum L = r0 V cos(phi). This module gives its apogee, range and time of
flight in closed form (the drag-free limit every simulation must reproduce, and the beta = 0
limit of the Modified Kepler Solution).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import earth
from .validation import check_range, finite_array

__all__ = ["BallisticConic", "ballistic_conic"]


@dataclass(frozen=True)
class BallisticConic:
    """Closed-form flight from the surface back down to it (arrays broadcast over launches)."""

    semi_major_axis_m: np.ndarray
    eccentricity: np.ndarray
    apogee_radius_m: np.ndarray
    range_angle_rad: np.ndarray  # central angle from launch to return to the launch radius
    time_to_apogee_s: np.ndarray
    time_of_flight_s: np.ndarray  # back to the launch radius

    @property
    def apogee_altitude_m(self):
        return self.apogee_radius_m - earth.RADIUS_M

    @property
    def ground_range_m(self):
        return earth.RADIUS_M * self.range_angle_rad


def ballistic_conic(
    speed_m_s, flight_path_angle_rad, radius_m=earth.RADIUS_M, gm_m3_s2=earth.GM_M3_S2
) -> BallisticConic:
    """The Kepler ellipse of a launch at ``speed_m_s`` and ``flight_path_angle_rad`` from
    ``radius_m``; elliptic (sub-escape) launches only, rising (angle in (0, pi/2])."""
    speed = check_range(
        finite_array(speed_m_s, "speed_m_s"), "speed_m_s", low=0.0, low_inclusive=False, unit="m/s"
    )
    angle = check_range(
        finite_array(flight_path_angle_rad, "flight_path_angle_rad"),
        "flight_path_angle_rad",
        low=0.0,
        low_inclusive=False,
        high=np.pi / 2,
    )
    radius = check_range(
        finite_array(radius_m, "radius_m"), "radius_m", low=0.0, low_inclusive=False, unit="m"
    )
    energy = 0.5 * speed**2 - gm_m3_s2 / radius
    check_range(energy, "speed_m_s (specific energy)", high=0.0, high_inclusive=False)
    semi_major = -gm_m3_s2 / (2 * energy)
    momentum = radius * speed * np.cos(angle)
    eccentricity = np.sqrt(1 + 2 * energy * momentum**2 / gm_m3_s2**2)
    semi_latus = momentum**2 / gm_m3_s2
    # Rising at launch: true anomaly in (0, pi]; apogee at pi, return at 2 pi - nu0.
    true_anomaly = np.arccos(np.clip((semi_latus / radius - 1) / eccentricity, -1.0, 1.0))
    eccentric = 2 * np.arctan(
        np.sqrt((1 - eccentricity) / (1 + eccentricity)) * np.tan(true_anomaly / 2)
    )
    mean_anomaly = eccentric - eccentricity * np.sin(eccentric)
    mean_motion = np.sqrt(gm_m3_s2 / semi_major**3)
    to_apogee = (np.pi - mean_anomaly) / mean_motion
    return BallisticConic(
        semi_major,
        eccentricity,
        semi_major * (1 + eccentricity),
        2 * (np.pi - true_anomaly),
        to_apogee,
        2 * to_apogee,
    )
