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
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np
import pandas as pd

from . import earth
from .atmosphere import AtmosphereModel, get_atmosphere
from .integrator import Breakpoint, Event, integrate_batch
from .launch import Launch
from .trajectory import (
    BASE_COLUMNS,
    TruncatedFlightWarning,
    describe,
    flight_path_angle,
    launch_frame,
    rotate_about_axis,
    surface_ranges,
)
from .validation import check_range, finite_scalar, positive_scalar

__all__ = ["simulate_3dof", "simulate_3dof_batch"]


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
        wind = rotate_about_axis(self.wind_m_s[:, index], omega * t)
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


def _numerics(rtol, max_time_s):
    rtol = float(
        check_range(finite_scalar(rtol, "rtol"), "rtol", low=0.0, low_inclusive=False, high=1e-3)
    )
    max_time_s = float(positive_scalar(max_time_s, "max_time_s", "s"))
    return rtol, max_time_s


def _launches(launches) -> list[Launch]:
    """One or many launches that can share a batch: one projectile, air, Earth rotation and
    site altitude (the impact event, a function of the state alone, needs one site)."""
    if isinstance(launches, Launch):
        return [launches]
    if isinstance(launches, str | bytes) or not isinstance(launches, Iterable):
        raise TypeError(
            "launches must be a Launch or a sequence of Launch (harp_analysis.launch.Launch); "
            f"got {type(launches).__name__}"
        )
    launches = list(launches)
    if not launches:
        raise ValueError("launches must hold at least one Launch")
    for position, launch in enumerate(launches):
        if not isinstance(launch, Launch):
            raise TypeError(f"launches[{position}] must be a Launch; got {type(launch).__name__}")
        for name in ("projectile", "atmosphere", "rotation_rate_rad_s", "site_altitude_m"):
            if getattr(launch, name) != getattr(launches[0], name):
                raise ValueError(
                    f"launches[{position}].{name} differs from launches[0]'s: a batch shares "
                    "one projectile, atmosphere, Earth rotation and site altitude"
                )
    return launches


def _run(launches: list[Launch], rtol, max_time_s):
    first = launches[0]
    projectile, omega = first.projectile, first.rotation_rate_rad_s
    model = get_atmosphere(first.atmosphere)
    site = first.site_altitude_m  # shared: the impact event sees states, not launch numbers
    elevation, speed, latitude, longitude, bearing, head, cross = (
        np.array([getattr(launch, name) for launch in launches], dtype=float)
        for name in (
            "elevation_deg",
            "speed_m_s",
            "latitude_deg",
            "longitude_deg",
            "bearing_deg",
            "head_wind_m_s",
            "cross_wind_m_s",
        )
    )
    el, lat, lon, brg = (np.radians(x) for x in (elevation, latitude, longitude, bearing))
    up, downrange, _ = launch_frame(lat, lon, brg)
    position = (earth.RADIUS_M + site) * up
    ground_velocity = speed * (np.cos(el) * downrange + np.sin(el) * up)
    surface_velocity = omega * np.array([-position[1], position[0], np.zeros_like(lat)])
    right = np.cross(downrange, up, axis=0)
    dynamics = _Dynamics(
        model,
        projectile.drag_law,
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

    def above_site(t, y):
        return altitude(t, y) - site

    events = (
        Event("apogee", radial_velocity),
        Event("impact", above_site, terminal=True, after_s=1e-6),
    )

    def above_layer(boundary_m):
        return lambda t, y: altitude(t, y) - boundary_m

    breakpoints = tuple(Breakpoint(above_layer(b)) for b in model.breakpoints_m)
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
    return solution, dynamics, up, downrange


def _table(solution, dynamics, up, downrange, index, times_s) -> pd.DataFrame:
    """The tidy trajectory table (see :mod:`.trajectory`) of launch ``index`` at ``times_s``."""
    y = solution.sample(index, times_s)
    idx = np.full(times_s.size, index)
    radius, altitude, _, air_speed, mach, cd, density = dynamics.forces(times_s, y, idx)
    earth_fixed = rotate_about_axis(y[:3], -dynamics.rotation_rate_rad_s * times_s).T
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


def _apogee_and_end(solution, index):
    apogee_t = solution.event_times["apogee"][index]
    impact_t = solution.event_times["impact"][index]
    end_t = impact_t if np.isfinite(impact_t) else solution.times[index][-1]
    return apogee_t, bool(np.isfinite(impact_t)), end_t


def simulate_3dof(
    launch: Launch, *, rtol: float = 1e-9, max_time_s: float = 3000.0, output_step_s: float = 0.5
) -> pd.DataFrame:
    """One 3DOF flight of ``launch`` from the gun to the ground (back to the site's altitude),
    as the table of :mod:`.trajectory` with its shared metadata.

    ``rtol`` is the integrator's relative tolerance; rows come every ``output_step_s`` plus
    the impact, or the last time reached if ``max_time_s`` comes first (a
    TruncatedFlightWarning). The state is inertial; with ``launch.rotation_rate_rad_s`` the air
    turns with the Earth and ranges are measured on the turning Earth."""
    if not isinstance(launch, Launch):
        raise TypeError(
            f"launch must be a Launch (harp_analysis.launch.Launch); got {type(launch).__name__} "
            "(simulate_3dof_batch flies a sequence of them)"
        )
    step = positive_scalar(output_step_s, "output_step_s", "s")
    launches = _launches(launch)
    rtol, max_time_s = _numerics(rtol, max_time_s)
    solution, dynamics, up, downrange = _run(launches, rtol, max_time_s)
    apogee_t, impact, end_t = _apogee_and_end(solution, 0)
    times = np.append(np.arange(0.0, end_t, step), end_t)
    table = _table(solution, dynamics, up, downrange, 0, times)
    apogee = None
    if np.isfinite(apogee_t):
        top = _table(solution, dynamics, up, downrange, 0, np.array([apogee_t])).iloc[0]
        apogee = (apogee_t, top.altitude_m, top.ground_range_m)
    return describe(
        table,
        engine="3DOF",
        launch=launches[0],
        apogee=apogee,
        impact=impact,
        rhs_evaluations=solution.rhs_evaluations,
        steps=int(solution.steps[0]),
        max_time_s=max_time_s,
        rtol=rtol,
    )


def simulate_3dof_batch(
    launches, *, rtol: float = 1e-9, max_time_s: float = 3000.0
) -> pd.DataFrame:
    """Many 3DOF launches integrated together: ``launches`` is a sequence of :class:`Launch`
    sharing one projectile, atmosphere, Earth rotation and site altitude (e.g.
    ``[launch.but(elevation_deg=e) for e in elevations]``). One row per launch: its elevation,
    speed, bearing and latitude, and the metadata keys of :func:`simulate_3dof` (but
    ``engine``, ``launch`` and the batch-wide ``rhs_evaluations``, which are in
    ``frame.attrs``). Same physics and integrator as :func:`simulate_3dof`, which is a batch of
    one."""
    launches = _launches(launches)
    rtol, max_time_s = _numerics(rtol, max_time_s)
    solution, dynamics, up, downrange = _run(launches, rtol, max_time_s)
    rows = []
    for i, launch in enumerate(launches):
        apogee_t, impact, end_t = _apogee_and_end(solution, i)
        times = np.array([apogee_t if np.isfinite(apogee_t) else end_t, end_t])
        table = _table(solution, dynamics, up, downrange, i, times)
        rows.append(
            dict(
                elevation_deg=launch.elevation_deg,
                speed_m_s=launch.speed_m_s,
                bearing_deg=launch.bearing_deg,
                latitude_deg=launch.latitude_deg,
                apogee_time_s=apogee_t,
                apogee_altitude_m=table.altitude_m[0] if np.isfinite(apogee_t) else np.nan,
                apogee_ground_range_m=table.ground_range_m[0] if np.isfinite(apogee_t) else np.nan,
                time_of_flight_s=end_t,
                range_m=table.ground_range_m[1],
                cross_range_m=table.cross_range_m[1],
                impact_speed_m_s=table.speed_m_s[1],
                impact=impact,
                stop_reason="impact" if impact else "max_time",
                steps=int(solution.steps[i]),
            )
        )
    summary = pd.DataFrame(rows)
    missed = int((~summary.impact).sum())
    if missed:
        warnings.warn(
            f"{missed} of {len(summary)} 3DOF launches did not return to the ground "
            f"within max_time_s = {max_time_s:g} s",
            TruncatedFlightWarning,
            stacklevel=2,
        )
    summary.attrs.update(
        engine="3DOF",
        projectile=launches[0].projectile.name,
        rhs_evaluations=solution.rhs_evaluations,
        rtol=rtol,
    )
    return summary
