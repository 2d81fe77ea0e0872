"""The 3DOF point-mass simulation: the physics of Appendix A with an accurate integrator.

Physics as in Appendix A: a spherical Earth of radius 6378 km, inverse-square gravity with
GM = 398600.4418 km^3/s^2, drag opposite the velocity relative to the air, and optionally the
Earth's rotation (the air turns with the Earth) and a constant head and cross wind. The
atmosphere and the drag law are pluggable by name (:mod:`.atmosphere`, :mod:`.drag`).

Not Appendix A's integrator: its fixed-step, second-order position recurrence is replaced by
the adaptive 8th-order scheme of :mod:`.integrator` with events for apogee and impact, so
results converge (to millimetres at the default ``rtol=1e-9``; see the benchmark). The state
is integrated in the Earth-centred inertial frame (x toward longitude 0 on the equator at
launch, z north); with
rotation off this frame is also Earth-fixed. Winds are fixed to the Earth, given as a head wind
(blowing against the line of fire) and a cross wind (blowing toward the right of it) at launch.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
import pandas as pd

from . import earth
from .atmosphere import AtmosphereModel, get_atmosphere
from .drag import get_drag_law
from .integrator import Breakpoint, Event, integrate_batch
from .projectiles import Projectile
from .trajectory import BASE_COLUMNS, flight_path_angle, surface_ranges
from .validation import ModelValidityWarning, check_range, finite_array, finite_scalar

__all__ = ["simulate_3dof", "simulate_3dof_batch", "launch_frame"]


def launch_frame(latitude_rad, longitude_rad, bearing_rad):
    """Unit vectors (3, n) at the launch point: up, downrange (along the bearing) and east."""
    lat, lon, bearing = np.broadcast_arrays(latitude_rad, longitude_rad, bearing_rad)
    up = np.array([np.cos(lat) * np.cos(lon), np.cos(lat) * np.sin(lon), np.sin(lat)])
    east = np.array([-np.sin(lon), np.cos(lon), np.zeros_like(lon)])
    north = np.cross(up, east, axis=0)
    downrange = np.sin(bearing) * east + np.cos(bearing) * north
    return up, downrange, east


def _rotate_z(vectors, angle_rad):
    """Rotate (3, n) vectors by ``angle_rad`` (n,) about the Earth's axis."""
    c, s = np.cos(angle_rad), np.sin(angle_rad)
    x, y, z = vectors
    return np.array([c * x - s * y, s * x + c * y, z])


@dataclass(frozen=True)
class _Dynamics:
    """Gravity and drag of a batch of launches that share a projectile, air and Earth."""

    atmosphere: AtmosphereModel
    drag_law: object
    drag_factor_m2_kg: float  # Cd-free part of the drag: A / (2 m)
    mass_kg: float
    rotation_rate_rad_s: float
    wind_m_s: np.ndarray  # (3, n) Earth-fixed wind at t = 0, inertial components

    def air_velocity(self, t, y, index):
        omega = self.rotation_rate_rad_s
        if not omega:
            return y[3:] - self.wind_m_s[:, index]
        wind = _rotate_z(self.wind_m_s[:, index], omega * t)
        return y[3:] - omega * np.array([-y[1], y[0], np.zeros_like(y[0])]) - wind

    def forces(self, t, y, index):
        """Radius, altitude, air velocity and its norm, Mach, Cd, density of states (6, m)."""
        radius = np.sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2])
        altitude = radius - earth.RADIUS_M
        air = self.air_velocity(t, y, index)
        air_speed = np.sqrt(air[0] * air[0] + air[1] * air[1] + air[2] * air[2])
        mach = air_speed / self.atmosphere.sound_kernel(altitude)
        cd = self.drag_law.evaluate(mach)
        density = self.atmosphere.density_kernel(altitude)
        return radius, altitude, air, air_speed, mach, cd, density

    def acceleration(self, t, y, index):
        radius, _, air, air_speed, _, cd, density = self.forces(t, y, index)
        drag = self.drag_factor_m2_kg * density * cd * air_speed
        return -earth.GM_M3_S2 / radius**3 * y[:3] - drag * air


def _positive(value, name, unit=""):
    return check_range(finite_array(value, name), name, low=0.0, low_inclusive=False, unit=unit)


def _run(
    projectile: Projectile,
    elevation_deg,
    speed_m_s,
    latitude_deg,
    longitude_deg,
    bearing_deg,
    atmosphere,
    drag_law,
    rotation_rate_rad_s,
    head_wind_m_s,
    cross_wind_m_s,
    rtol,
    max_time_s,
):
    if not isinstance(projectile, Projectile):
        raise TypeError(f"projectile must be a Projectile; got {type(projectile).__name__}")
    elevation = check_range(
        finite_array(elevation_deg, "elevation_deg"),
        "elevation_deg",
        low=0.0,
        low_inclusive=False,
        high=90.0,
        unit="deg",
    )
    speed = _positive(
        projectile.launch_speed_m_s if speed_m_s is None else speed_m_s, "speed_m_s", "m/s"
    )
    latitude = check_range(
        finite_array(latitude_deg, "latitude_deg"), "latitude_deg", low=-90.0, high=90.0, unit="deg"
    )
    longitude = finite_array(longitude_deg, "longitude_deg")
    bearing = check_range(
        finite_array(bearing_deg, "bearing_deg"),
        "bearing_deg",
        low=0.0,
        high=360.0,
        high_inclusive=False,
        unit="deg",
    )
    head, cross = (
        finite_array(head_wind_m_s, "head_wind_m_s"),
        finite_array(cross_wind_m_s, "cross_wind_m_s"),
    )
    omega = finite_scalar(rotation_rate_rad_s, "rotation_rate_rad_s")
    rtol = float(
        check_range(finite_scalar(rtol, "rtol"), "rtol", low=0.0, low_inclusive=False, high=1e-3)
    )
    max_time_s = float(_positive(finite_scalar(max_time_s, "max_time_s"), "max_time_s", "s"))
    model = atmosphere if isinstance(atmosphere, AtmosphereModel) else get_atmosphere(atmosphere)
    law = (
        projectile.drag_law
        if drag_law is None
        else (get_drag_law(drag_law) if isinstance(drag_law, str) else drag_law)
    )

    elevation, speed, latitude, longitude, bearing, head, cross = (
        np.atleast_1d(x).astype(float)
        for x in np.broadcast_arrays(elevation, speed, latitude, longitude, bearing, head, cross)
    )
    el, lat, lon, brg = (np.radians(x) for x in (elevation, latitude, longitude, bearing))
    up, downrange, _ = launch_frame(lat, lon, brg)
    position = earth.RADIUS_M * up
    ground_velocity = speed * (np.cos(el) * downrange + np.sin(el) * up)
    surface_velocity = omega * np.array([-position[1], position[0], np.zeros_like(lat)])
    right = np.cross(downrange, up, axis=0)
    dynamics = _Dynamics(
        model,
        law,
        projectile.reference_area_m2 / (2 * projectile.mass_kg),
        projectile.mass_kg,
        omega,
        -head * downrange + cross * right,
    )
    y0 = np.concatenate([position, ground_velocity + surface_velocity])

    def radial_velocity(t, y):
        return np.sum(y[:3] * y[3:], axis=0)

    def altitude(t, y):
        return np.sqrt(np.sum(y[:3] ** 2, axis=0)) - earth.RADIUS_M

    events = (
        Event("apogee", radial_velocity),
        Event("impact", altitude, terminal=True, after_s=1e-6),
    )
    breakpoints = tuple(
        Breakpoint(lambda t, y, b=b: altitude(t, y) - b) for b in model.breakpoints_m
    )
    scale = np.array([earth.RADIUS_M] * 3 + [1e3] * 3)
    solution = integrate_batch(
        dynamics.acceleration,
        y0,
        t_max_s=max_time_s,
        rtol=rtol,
        state_scale=scale,
        events=events,
        breakpoints=breakpoints,
    )
    missed = np.isnan(solution.event_times["impact"])
    if missed.any():
        warnings.warn(
            f"{missed.sum()} of {missed.size} launches did not return to the ground "
            f"within max_time_s = {max_time_s:g} s",
            ModelValidityWarning,
            stacklevel=3,
        )
    launch = dict(
        elevation_deg=elevation,
        speed_m_s=speed,
        latitude_deg=latitude,
        longitude_deg=longitude,
        bearing_deg=bearing,
        head_wind_m_s=head,
        cross_wind_m_s=cross,
    )
    return solution, dynamics, up, downrange, launch


def _table(solution, dynamics, up, downrange, index, times_s) -> pd.DataFrame:
    """The tidy trajectory table (see :mod:`.trajectory`) of launch ``index`` at ``times_s``."""
    y = solution.sample(index, times_s)
    idx = np.full(times_s.size, index)
    radius, altitude, _, air_speed, mach, cd, density = dynamics.forces(times_s, y, idx)
    earth_fixed = _rotate_z(y[:3], -dynamics.rotation_rate_rad_s * times_s).T
    ground, cross = surface_ranges(earth_fixed, up[:, index], downrange[:, index])
    drag = dynamics.drag_factor_m2_kg * density * cd * air_speed**2
    columns = dict(
        time_s=times_s,
        x_m=y[0],
        y_m=y[1],
        z_m=y[2],
        altitude_m=altitude,
        ground_range_m=ground,
        cross_range_m=cross,
        speed_m_s=np.sqrt(np.sum(y[3:] ** 2, axis=0)),
        mach=mach,
        drag_coefficient=cd,
        drag_to_gravity=drag / (earth.GM_M3_S2 / radius**2),
        specific_angular_momentum_m2_s=np.linalg.norm(np.cross(y[:3].T, y[3:].T), axis=1),
        flight_path_angle_rad=flight_path_angle(y[:3].T, y[3:].T),
    )
    return pd.DataFrame({name: columns[name] for name in BASE_COLUMNS})


def _summary(solution, dynamics, up, downrange, launch) -> pd.DataFrame:
    rows = []
    for i in range(solution.steps.size):
        apogee_t = solution.event_times["apogee"][i]
        impact_t = solution.event_times["impact"][i]
        end_t = impact_t if np.isfinite(impact_t) else solution.times[i][-1]
        times = np.array([apogee_t, end_t]) if np.isfinite(apogee_t) else np.array([end_t, end_t])
        table = _table(solution, dynamics, up, downrange, i, times)
        rows.append(
            dict(
                apogee_time_s=apogee_t,
                apogee_altitude_m=table.altitude_m[0] if np.isfinite(apogee_t) else np.nan,
                apogee_ground_range_m=table.ground_range_m[0] if np.isfinite(apogee_t) else np.nan,
                impact=bool(np.isfinite(impact_t)),
                time_of_flight_s=end_t,
                range_m=table.ground_range_m[1],
                cross_range_m=table.cross_range_m[1],
                impact_speed_m_s=table.speed_m_s[1],
                steps=int(solution.steps[i]),
            )
        )
    return pd.concat([pd.DataFrame(launch), pd.DataFrame(rows)], axis=1)


def simulate_3dof(
    projectile: Projectile,
    elevation_deg: float,
    *,
    speed_m_s: float | None = None,
    latitude_deg: float = 0.0,
    longitude_deg: float = 0.0,
    bearing_deg: float = 90.0,
    atmosphere: str | AtmosphereModel = "two_segment",
    drag_law=None,
    rotation_rate_rad_s: float = 0.0,
    head_wind_m_s: float = 0.0,
    cross_wind_m_s: float = 0.0,
    rtol: float = 1e-9,
    max_time_s: float = 3000.0,
    output_step_s: float = 0.5,
) -> pd.DataFrame:
    """One 3DOF trajectory from launch to impact, as the tidy table of :mod:`.trajectory`.

    ``speed_m_s`` is relative to the ground (the projectile's nominal speed if omitted) and
    ``elevation_deg`` and ``bearing_deg`` are the gun's. ``drag_law`` defaults to the
    projectile's own; pass a name of :data:`harp_analysis.drag.DRAG_LAW_NAMES` or a law object
    to override it. Rows come every ``output_step_s`` plus the impact; ``frame.attrs`` holds
    the apogee, the impact, the launch and the integration statistics. The Earth's rotation is
    off by default (the non-rotating ECEF of Chapters 2-4); the text's rate is
    :data:`harp_analysis.earth.ROTATION_RATE_RAD_S`.
    """
    step = finite_scalar(output_step_s, "output_step_s")
    check_range(step, "output_step_s", low=0.0, low_inclusive=False, unit="s")
    for name, value in (
        ("elevation_deg", elevation_deg),
        ("speed_m_s", speed_m_s),
        ("latitude_deg", latitude_deg),
        ("bearing_deg", bearing_deg),
    ):
        if value is not None:
            finite_scalar(value, name)
    solution, dynamics, up, downrange, launch = _run(
        projectile,
        elevation_deg,
        speed_m_s,
        latitude_deg,
        longitude_deg,
        bearing_deg,
        atmosphere,
        drag_law,
        rotation_rate_rad_s,
        head_wind_m_s,
        cross_wind_m_s,
        rtol,
        max_time_s,
    )
    summary = _summary(solution, dynamics, up, downrange, launch).iloc[0]
    end = summary.time_of_flight_s
    times = np.append(np.arange(0.0, end, step), end)
    table = _table(solution, dynamics, up, downrange, 0, times)
    table.attrs.update(
        summary.to_dict(),
        projectile=projectile.name,
        rhs_evaluations=solution.rhs_evaluations,
        rotation_rate_rad_s=rotation_rate_rad_s,
        rtol=rtol,
    )
    return table


def simulate_3dof_batch(
    projectile: Projectile,
    elevation_deg,
    *,
    speed_m_s=None,
    latitude_deg=0.0,
    longitude_deg=0.0,
    bearing_deg=90.0,
    atmosphere="two_segment",
    drag_law=None,
    rotation_rate_rad_s=0.0,
    head_wind_m_s=0.0,
    cross_wind_m_s=0.0,
    rtol=1e-9,
    max_time_s=3000.0,
) -> pd.DataFrame:
    """Many 3DOF launches integrated together (arguments broadcast against each other).

    Returns one row per launch: its inputs, apogee (time, altitude, ground range), impact
    (time of flight, range, cross range, speed) and the steps taken. Same physics and
    integrator as :func:`simulate_3dof`, which is a batch of one.
    """
    solution, dynamics, up, downrange, launch = _run(
        projectile,
        elevation_deg,
        speed_m_s,
        latitude_deg,
        longitude_deg,
        bearing_deg,
        atmosphere,
        drag_law,
        rotation_rate_rad_s,
        head_wind_m_s,
        cross_wind_m_s,
        rtol,
        max_time_s,
    )
    summary = _summary(solution, dynamics, up, downrange, launch)
    summary.attrs.update(projectile=projectile.name, rhs_evaluations=solution.rhs_evaluations)
    return summary
