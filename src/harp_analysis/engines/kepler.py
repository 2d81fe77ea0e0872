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

from ..foundation import earth
from ..foundation.validation import Bounds, finite_array

__all__ = [
    "BallisticConic",
    "ballistic_conic",
    "speed_for_range",
    "conic_from_state",
    "ConicFromState",
]


#: A launch's speed and radius (positive) and, rising, its flight-path angle (0, pi/2].
_SPEED = Bounds(0.0, low_inclusive=False, unit="m/s")
_RADIUS = Bounds(0.0, low_inclusive=False, unit="m")
_RISING = Bounds(0.0, np.pi / 2, low_inclusive=False)


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
    speed = _SPEED.finite(speed_m_s, "speed_m_s")
    angle = _RISING.finite(flight_path_angle_rad, "flight_path_angle_rad")
    radius = _RADIUS.finite(radius_m, "radius_m")
    energy = 0.5 * speed**2 - gm_m3_s2 / radius
    Bounds(high=0.0, high_inclusive=False).check(energy, "speed_m_s (specific energy)")
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


def speed_for_range(
    ground_range_m, flight_path_angle_rad, radius_m=earth.RADIUS_M, gm_m3_s2=earth.GM_M3_S2
):
    """Launch speed (m/s) whose drag-free conic from ``radius_m`` at ``flight_path_angle_rad``
    comes back to that radius ``ground_range_m`` (measured on the sphere of ``radius_m``) away.

    Eq 3.8 with u(0) = u(Theta) = 1/r0 and u'(0) = -tan(phi)/r0 gives GM/h^2 = (1 + tan(phi) /
    tan(Theta/2))/r0 with h = r0 V cos(phi), Theta = range/r0: V^2 = GM / (r0 cos^2(phi)
    (1 + tan(phi)/tan(Theta/2))). Flat limit: V^2 = g range / sin(2 phi)."""
    radius = _RADIUS.finite(radius_m, "radius_m")
    range_angle = Bounds(
        low=0.0, high=np.pi, low_inclusive=False, high_inclusive=False, unit="rad"
    ).check(
        finite_array(ground_range_m, "ground_range_m") / radius,
        "ground_range_m / radius_m (the range angle)",
    )
    angle = Bounds(0.0, np.pi / 2, low_inclusive=False, high_inclusive=False).finite(
        flight_path_angle_rad, "flight_path_angle_rad"
    )
    half_range = range_angle / 2
    return np.sqrt(
        gm_m3_s2 / (radius * np.cos(angle) ** 2 * (1 + np.tan(angle) / np.tan(half_range)))
    )


@dataclass(frozen=True)
class ConicFromState:
    """Eq 3.8 started from one state: u(theta) = GM/h^2 + A cos(dtheta) + B sin(dtheta), dtheta
    the angular range from that state (the standard Kepler solution handed the state of a
    simulation, Chapter 3's "valid above 30 km")."""

    gm_over_h2_per_m: float
    cos_amplitude_per_m: float  # A = 1/r - GM/h^2
    sin_amplitude_per_m: float  # B = u'(0) = -tan(phi)/r, eq 3.28

    def _u(self, theta):
        """u = 1/r (1/m) at angular range ``theta`` (rad, finite) from the state."""
        return (
            self.gm_over_h2_per_m
            + self.cos_amplitude_per_m * np.cos(theta)
            + self.sin_amplitude_per_m * np.sin(theta)
        )

    def radius(self, delta_theta_rad):
        """Distance from the Earth's centre (m) at angular range ``delta_theta_rad`` from the
        state (a conic that escapes or passes through the centre gives inf or a negative)."""
        u = self._u(finite_array(delta_theta_rad, "delta_theta_rad"))
        with np.errstate(divide="ignore"):
            return 1 / u

    def flight_path_angle(self, delta_theta_rad):
        """Angle (rad) of the velocity above the local horizontal, tan(phi) = -u'/u (eq 3.28)."""
        theta = finite_array(delta_theta_rad, "delta_theta_rad")
        u = self._u(theta)
        slope = -self.cos_amplitude_per_m * np.sin(theta) + self.sin_amplitude_per_m * np.cos(theta)
        return np.arctan2(-slope, u)

    @property
    def apogee_radius_m(self) -> float:
        """1 / (GM/h^2 - sqrt(A^2 + B^2)): inf for an open (escape) conic."""
        low = self.gm_over_h2_per_m - np.hypot(self.cos_amplitude_per_m, self.sin_amplitude_per_m)
        return float(1 / low) if low > 0 else float("inf")


def conic_from_state(
    radius_m, speed_m_s, flight_path_angle_rad, gm_m3_s2=earth.GM_M3_S2
) -> ConicFromState:
    """The drag-free conic through a state at ``radius_m`` with ``speed_m_s`` at
    ``flight_path_angle_rad`` above the local horizontal (any sign), h = r V cos(phi)."""
    radius = Bounds(low=0.0, low_inclusive=False, unit="m").scalar(radius_m, "radius_m")
    speed = Bounds(low=0.0, low_inclusive=False).scalar(speed_m_s, "speed_m_s")
    angle = Bounds(
        low=-np.pi / 2, high=np.pi / 2, low_inclusive=False, high_inclusive=False
    ).scalar(flight_path_angle_rad, "flight_path_angle_rad")
    gm_over_h2 = gm_m3_s2 / (radius * speed * np.cos(angle)) ** 2
    return ConicFromState(
        float(gm_over_h2), float(1 / radius - gm_over_h2), float(-np.tan(angle) / radius)
    )
