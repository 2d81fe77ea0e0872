"""What every trajectory engine returns, and the geometry they share.

Each engine (3DOF, 6DOF, and the analytic solutions of later chapters) returns a pandas
DataFrame with at least these columns, one row per output time, SI units:

============================== ===============================================================
``time_s``                     time since launch
``x_m``, ``y_m``, ``z_m``      position in the engine's own frame (documented by the engine)
``altitude_m``                 height above the spherical Earth, |r| - R
``ground_range_m``             arc along the surface in the launch plane (the great circle
                               through the launch point along the launch bearing)
``cross_range_m``              arc along the surface out of the launch plane (right positive)
``speed_m_s``                  speed in the non-rotating (inertial) frame
``mach``                       air-relative speed over the local speed of sound
``drag_coefficient``           Cd used for the drag force
``drag_to_gravity``            N = drag force / gravitational force (Fig 2.2)
``specific_angular_momentum_m2_s``  |r x v| about the Earth's centre, inertial v (Fig 2.10)
``flight_path_angle_rad``      angle of the inertial velocity above the local horizontal
============================== ===============================================================

and the same metadata in ``frame.attrs`` (:func:`describe`, :data:`METADATA_KEYS`): the engine,
the launch, the apogee (time, altitude, ground range; NaN if not reached), the end of the flight
(time of flight, range, cross range and speed at the last row), whether it reached the ground
and why it stopped, and the work it took (right-hand-side evaluations and steps, or the
engine's analogue). A flight cut off by ``max_time_s`` warns the same way in every engine
(:class:`TruncatedFlightWarning`).
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from .compiled import formula
from .earth import RADIUS_M
from .validation import ModelValidityWarning

__all__ = [
    "BASE_COLUMNS",
    "METADATA_KEYS",
    "STOP_REASONS",
    "TruncatedFlightWarning",
    "describe",
    "launch_frame",
    "cross_product",
    "rotate_about_axis",
    "turned_about_axis",
    "surface_ranges",
    "flight_path_angle",
]

BASE_COLUMNS = (
    "time_s",
    "x_m",
    "y_m",
    "z_m",
    "altitude_m",
    "ground_range_m",
    "cross_range_m",
    "speed_m_s",
    "mach",
    "drag_coefficient",
    "drag_to_gravity",
    "specific_angular_momentum_m2_s",
    "flight_path_angle_rad",
)


def surface_ranges(position_m, launch_up, launch_downrange):
    """Ground range and cross range (m) of Earth-centred positions ``position_m`` (..., 3).

    ``launch_up`` is the unit vector from the Earth's centre to the launch point and
    ``launch_downrange`` the unit horizontal vector along the launch bearing (each (3,), or
    (..., 3) with one launch per position); cross range is positive to the right of the line of
    fire (along ``downrange x up``).
    """
    position = np.asarray(position_m, dtype=float)
    up = np.asarray(launch_up, dtype=float)
    downrange = np.asarray(launch_downrange, dtype=float)
    right = np.cross(downrange, up)
    radius = np.linalg.norm(position, axis=-1)

    def along(direction):
        return np.einsum("...i,...i->...", position, direction)

    out_of_plane = np.arcsin(np.clip(along(right) / radius, -1.0, 1.0))
    in_plane = np.arctan2(along(downrange), along(up))
    return RADIUS_M * in_plane, RADIUS_M * out_of_plane


def flight_path_angle(position_m, velocity_m_s):
    """Angle (rad) of ``velocity_m_s`` above the local horizontal at ``position_m`` (..., 3)."""
    position = np.asarray(position_m, dtype=float)
    velocity = np.asarray(velocity_m_s, dtype=float)
    radial = np.sum(position * velocity, axis=-1) / np.linalg.norm(position, axis=-1)
    return np.arcsin(np.clip(radial / np.linalg.norm(velocity, axis=-1), -1.0, 1.0))


#: The keys every engine puts in ``frame.attrs``.
METADATA_KEYS = (
    "engine",
    "launch",
    "apogee_time_s",
    "apogee_altitude_m",
    "apogee_ground_range_m",
    "time_of_flight_s",
    "range_m",
    "cross_range_m",
    "impact_speed_m_s",
    "impact",
    "stop_reason",
    "rhs_evaluations",
    "steps",
)
#: Why a flight ended: it reached the ground, or ``max_time_s`` came first.
STOP_REASONS = ("impact", "max_time")


class TruncatedFlightWarning(ModelValidityWarning):
    """A flight was cut off by ``max_time_s`` before it returned to the ground."""


def describe(
    frame,
    *,
    engine: str,
    launch,
    apogee: tuple[float, float, float] | None,
    impact: bool,
    rhs_evaluations: int,
    steps: int,
    max_time_s: float,
    **extra,
):
    """Put the shared metadata on an engine's trajectory table and return it.

    ``apogee`` is (time, altitude, ground range) or None if the flight never turned down; the
    end of the flight is the table's last row. A flight that did not reach the ground warns
    (:class:`TruncatedFlightWarning`) and records ``stop_reason = "max_time"``."""
    last = frame.iloc[-1]
    apogee_time, apogee_altitude, apogee_range = apogee if apogee else (math.nan,) * 3
    if not impact:
        warnings.warn(
            f"the {engine} flight of {launch.projectile.name} did not return to the ground "
            f"within max_time_s = {max_time_s:g} s; its range and time of flight are those of "
            "the last row",
            TruncatedFlightWarning,
            stacklevel=3,
        )
    frame.attrs.update(
        engine=engine,
        launch=launch,
        apogee_time_s=float(apogee_time),
        apogee_altitude_m=float(apogee_altitude),
        apogee_ground_range_m=float(apogee_range),
        time_of_flight_s=float(last.time_s),
        range_m=float(last.ground_range_m),
        cross_range_m=float(last.cross_range_m),
        impact_speed_m_s=float(last.speed_m_s),
        impact=bool(impact),
        stop_reason="impact" if impact else "max_time",
        rhs_evaluations=int(rhs_evaluations),
        steps=int(steps),
        **extra,
    )
    return frame


def cross_product(a, b):
    """The cross product of 3-vectors along the first axis, (3, ...) each: ``np.cross(a, b,
    axis=0)`` without its generality (a tenth of its time on a launch's vectors)."""
    return np.array(
        [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    )


def launch_frame(latitude_rad, longitude_rad, bearing_rad):
    """Unit vectors (3, n) at the launch point in the Earth-centred frame (z north, x toward
    longitude 0): up, downrange (along the bearing from true north) and east."""
    lat, lon, bearing = np.broadcast_arrays(latitude_rad, longitude_rad, bearing_rad)
    up = np.array([np.cos(lat) * np.cos(lon), np.cos(lat) * np.sin(lon), np.sin(lat)])
    east = np.array([-np.sin(lon), np.cos(lon), np.zeros_like(lon)])
    north = cross_product(up, east)
    downrange = np.sin(bearing) * east + np.cos(bearing) * north
    return up, downrange, east


@formula
def turned_about_axis(x, y, angle_rad):
    """The x and y components of a vector turned by ``angle_rad`` about the Earth's axis (z)."""
    c, s = np.cos(angle_rad), np.sin(angle_rad)
    return c * x - s * y, s * x + c * y


def rotate_about_axis(vectors, angle_rad):
    """Rotate (3, n) vectors by ``angle_rad`` (n,) about the Earth's axis (z)."""
    x, y, z = vectors
    return np.array([*turned_about_axis(x, y, angle_rad), z])
