"""What every trajectory engine returns, and the geometry they share.

Each engine (3DOF, 6DOF, and the analytic solutions of later chapters) returns a pandas
DataFrame with at least these columns, one row per output time, SI units:

=================================== ===============================================================
``time_s``                          time since launch
``x_m``, ``y_m``, ``z_m``           position in the engine's own frame (documented by the engine)
``altitude_m``                      height above the spherical Earth, |r| - R
``ground_range_m``                  arc along the surface in the launch plane (the great circle
                                    through the launch point along the launch bearing)
``cross_range_m``                   arc along the surface out of the launch plane (right positive)
``speed_m_s``                       speed in the non-rotating (inertial) frame
``mach``                            air-relative speed over the local speed of sound
``drag_coefficient``                Cd used for the drag force
``drag_to_gravity``                 N = drag force / gravitational force (Fig 2.2)
``specific_angular_momentum_m2_s``  |r x v| about the Earth's centre, inertial v (Fig 2.10)
``flight_path_angle_rad``           angle of the inertial velocity above the local horizontal
=================================== ===============================================================

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

from ..foundation.compiled import formula
from ..foundation.earth import RADIUS_M
from ..foundation.validation import ModelValidityWarning

__all__ = [
    "BASE_COLUMNS",
    "MAX_ROWS",
    "METADATA_KEYS",
    "STOP_REASONS",
    "TruncatedFlightWarning",
    "EndAltitudeNotCrossedWarning",
    "describe",
    "launch_frame",
    "rotate_about_axis",
    "turned_about_axis",
    "surface_ranges",
    "flight_path_angle",
    "dot",
    "cross",
    "launch_axes",
    "surface_range",
    "climb_angle",
    "output_times",
]

#: Rows of a trajectory table at most (a table of about 100 MB): a step that asks for more is
#: refused by name, not allocated until the machine stops.
MAX_ROWS = 10**6


def output_times(end_s: float, output_step_s: float) -> np.ndarray:
    """The output times of a flight that ended at ``end_s``: every ``output_step_s`` from the
    launch, and the end. ValueError naming ``output_step_s`` beyond :data:`MAX_ROWS` rows."""
    rows = end_s / output_step_s
    if rows > MAX_ROWS:
        raise ValueError(
            f"output_step_s = {output_step_s:g} s asks for {rows:.3g} rows of a flight of "
            f"{end_s:.4g} s (at most {MAX_ROWS:,}): choose a longer step"
        )
    return np.append(np.arange(0.0, end_s, output_step_s), end_s)


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


@formula
def dot(a, b):
    """a . b of two 3-vectors given as component triples (numbers, or arrays alike)."""
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@formula
def cross(a, b):
    """a x b of two 3-vectors given as component triples (numbers, or arrays alike)."""
    return a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]


@formula
def surface_range(position, up, downrange):
    """:func:`surface_ranges` of component triples: one position (or arrays of them) and
    its launch's up and downrange."""
    right = cross(downrange, up)
    radius = np.sqrt(dot(position, position))
    sine = np.minimum(np.maximum(dot(position, right) / radius, -1.0), 1.0)
    in_plane = np.arctan2(dot(position, downrange), dot(position, up))
    return RADIUS_M * in_plane, RADIUS_M * np.arcsin(sine)


def _components(vectors) -> tuple:
    """The x, y and z components of vectors (..., 3)."""
    array = np.asarray(vectors, dtype=float)
    return array[..., 0], array[..., 1], array[..., 2]


def surface_ranges(position_m, launch_up, launch_downrange):
    """Ground range and cross range (m) of Earth-centred positions ``position_m`` (..., 3).

    ``launch_up`` is the unit vector from the Earth's centre to the launch point and
    ``launch_downrange`` the unit horizontal vector along the launch bearing (each (3,), or
    (..., 3) with one launch per position); cross range is positive to the right of the line of
    fire (along ``downrange x up``).
    """
    return surface_range(
        _components(position_m), _components(launch_up), _components(launch_downrange)
    )


@formula
def climb_angle(position, velocity):
    """:func:`flight_path_angle` of component triples."""
    radial = dot(position, velocity) / np.sqrt(dot(position, position))
    sine = radial / np.sqrt(dot(velocity, velocity))
    return np.arcsin(np.minimum(np.maximum(sine, -1.0), 1.0))


def flight_path_angle(position_m, velocity_m_s):
    """Angle (rad) of ``velocity_m_s`` above the local horizontal at ``position_m`` (..., 3)."""
    return climb_angle(_components(position_m), _components(velocity_m_s))


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
#: Why a flight ended: it reached the ground (or the altitude it was to end at), ``max_time_s``
#: came first, or it fell back to the ground without crossing the altitude it was to end at.
STOP_REASONS = ("impact", "max_time", "ground_before_end")


class TruncatedFlightWarning(ModelValidityWarning):
    """A flight was cut off by ``max_time_s`` before it returned to the ground."""


class EndAltitudeNotCrossedWarning(ModelValidityWarning):
    """A flight asked to end at an altitude never crossed it the way it was to (falling
    through one above its apogee, or rising through one it never climbs through) and ended
    where it fell back to the ground instead (``stop_reason = "ground_before_end"``)."""


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
    last = frame.iloc[-1].to_dict()  # a dict: a Series' attribute lookups cost microseconds
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
        time_of_flight_s=float(last["time_s"]),
        range_m=float(last["ground_range_m"]),
        cross_range_m=float(last["cross_range_m"]),
        impact_speed_m_s=float(last["speed_m_s"]),
        impact=bool(impact),
        stop_reason="impact" if impact else "max_time",
        rhs_evaluations=int(rhs_evaluations),
        steps=int(steps),
        **extra,
    )
    return frame


@formula
def launch_axes(latitude_rad, longitude_rad, bearing_rad):
    """:func:`launch_frame` as component triples: up, downrange and east (numbers in compiled
    code, arrays of one shape in numpy)."""
    cos_latitude = np.cos(latitude_rad)
    up = (
        cos_latitude * np.cos(longitude_rad),
        cos_latitude * np.sin(longitude_rad),
        np.sin(latitude_rad),
    )
    east = (-np.sin(longitude_rad), np.cos(longitude_rad), 0.0 * longitude_rad)
    north = cross(up, east)
    sine, cosine = np.sin(bearing_rad), np.cos(bearing_rad)
    downrange = (
        sine * east[0] + cosine * north[0],
        sine * east[1] + cosine * north[1],
        sine * east[2] + cosine * north[2],
    )
    return up, downrange, east


def launch_frame(latitude_rad, longitude_rad, bearing_rad):
    """Unit vectors (3, n) at the launch point in the Earth-centred frame (z north, x toward
    longitude 0): up, downrange (along the bearing from true north) and east."""
    axes = launch_axes(*np.broadcast_arrays(latitude_rad, longitude_rad, bearing_rad))
    return tuple(np.array(axis) for axis in axes)


@formula
def turned_about_axis(x, y, angle_rad):
    """The x and y components of a vector turned by ``angle_rad`` about the Earth's axis (z)."""
    c, s = np.cos(angle_rad), np.sin(angle_rad)
    return c * x - s * y, s * x + c * y


def rotate_about_axis(vectors, angle_rad):
    """Rotate (3, n) vectors by ``angle_rad`` (n,) about the Earth's axis (z)."""
    x, y, z = vectors
    return np.array([*turned_about_axis(x, y, angle_rad), z])
