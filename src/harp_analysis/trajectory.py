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
"""

from __future__ import annotations

import numpy as np

from .earth import RADIUS_M

__all__ = ["BASE_COLUMNS", "surface_ranges", "flight_path_angle"]

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
    ``launch_downrange`` the unit horizontal vector along the launch bearing; cross range is
    positive to the right of the line of fire (along ``downrange x up``).
    """
    position = np.asarray(position_m, dtype=float)
    up = np.asarray(launch_up, dtype=float)
    downrange = np.asarray(launch_downrange, dtype=float)
    right = np.cross(downrange, up)
    radius = np.linalg.norm(position, axis=-1)
    out_of_plane = np.arcsin(np.clip(position @ right / radius, -1.0, 1.0))
    in_plane = np.arctan2(position @ downrange, position @ up)
    return RADIUS_M * in_plane, RADIUS_M * out_of_plane


def flight_path_angle(position_m, velocity_m_s):
    """Angle (rad) of ``velocity_m_s`` above the local horizontal at ``position_m`` (..., 3)."""
    position = np.asarray(position_m, dtype=float)
    velocity = np.asarray(velocity_m_s, dtype=float)
    radial = np.sum(position * velocity, axis=-1) / np.linalg.norm(position, axis=-1)
    return np.arcsin(np.clip(radial / np.linalg.norm(velocity, axis=-1), -1.0, 1.0))
