"""Appendix A's own 3DOF scheme, kept only to explain artefacts of the original figures.

The physics of Appendix A lives in :mod:`.threedof` with an accurate integrator; this module
reproduces the VBA macro's *numerics* line by line (in SI units instead of km), so that the
dissertation's curves can be told apart from the integrator's fingerprints:

- a fixed step ``dt`` (a spreadsheet cell the text does not print) and a second-order
  position recurrence x2 = 2 x1 - x0 + (gravity + drag / m) dt^2;
- the first step is an Euler step without gravity or drag: x1 = x0 + v0 dt;
- drag uses the backward-difference velocity (x1 - x0) / dt, half a step old;
- the clock starts at ``3 dt`` while the first computed position belongs to ``2 dt``: every
  printed time leads its position by one step;
- the macro writes a row whenever the clock passes the next multiple of 0.5 s;
- the atmosphere is the three-layer model and the drag law eq 4.8, hard-coded;
- the rotation terms (``earthspin``, zero in the listing) add omega R, not omega R cos(lat), to
  the east velocity and use v + omega x r instead of v - omega x r for the air: we keep them as
  printed, since the listing runs with the rotation off.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ..foundation import earth
from ..foundation.validation import Bounds, positive_scalar
from ..models.atmosphere import day_air, get_atmosphere
from ..models.launch import Launch
from ..models.trajectory import describe, surface_ranges

__all__ = ["simulate_appendix_a"]


def simulate_appendix_a(launch: Launch, dt_s: float, *, max_time_s: float = 3000.0) -> pd.DataFrame:
    """Run Appendix A's macro on ``launch`` with its fixed step ``dt_s``; returns the rows it
    would write (every 0.5 s of its clock) with the shared metadata
    (:func:`harp_analysis.models.trajectory.describe`).

    The physics are the launch's (its projectile's drag law and its atmosphere; the listing
    hard-codes eq 4.8 and the three-layer air, ``atmosphere="three_layer"``), the numerics the
    macro's. The macro has no wind (a launch's wind is ignored, with a warning) and starts at
    sea level; its Earth rotation is ``launch.rotation_rate_rad_s`` with the printed terms.
    Columns: ``time_s`` (the macro's clock), ``altitude_m``, ``ground_range_m`` (R times the
    angle from the launch point), ``cross_range_m`` (right of the launch plane), ``speed_m_s``
    (backward-difference speed), ``radius_m`` and ``specific_angular_momentum_m2_s`` as the
    macro computes them.

    Parameters
    ----------
    launch : Launch
        The launch (its wind is ignored, with a warning).
    dt_s : float
        The macro's fixed step (s).
    max_time_s : float
        The longest flight (s).

    Returns
    -------
    pandas.DataFrame
        The rows the macro would write, with the shared metadata in ``frame.attrs``.
    """
    if not isinstance(launch, Launch):
        raise TypeError(f"launch must be a Launch; got {type(launch).__name__}")
    launch.require_zero("Appendix A macro", "site_altitude_m", reason="it launches at sea level")
    launch.warn_ignored(
        "Appendix A macro", "cross_wind_m_s", "head_wind_m_s", reason="the macro has no wind"
    )
    dt = Bounds(low=0.0, high=1.0, low_inclusive=False, unit="s").scalar(dt_s, "dt_s")
    max_time_s = positive_scalar(max_time_s, "max_time_s", "s")
    projectile, speed = launch.projectile, launch.speed_m_s
    lat, lon = launch.latitude_rad, math.radians(launch.longitude_deg)
    az, el = launch.bearing_rad, launch.elevation_rad
    spin = launch.rotation_rate_rad_s
    air, law = get_atmosphere(launch.atmosphere), projectile.drag_law
    R, GM, area, mass = (
        earth.RADIUS_M,
        earth.GM_M3_S2,
        projectile.reference_area_m2,
        projectile.mass_kg,
    )

    up = (math.cos(lat) * math.cos(lon), math.cos(lat) * math.sin(lon), math.sin(lat))
    east = (-math.sin(lon), math.cos(lon), 0.0)
    north = (-math.sin(lat) * math.cos(lon), -math.sin(lat) * math.sin(lon), math.cos(lat))
    v_up, v_east = speed * math.sin(el), speed * math.cos(el) * math.sin(az) + spin * R
    v_north = speed * math.cos(el) * math.cos(az)
    x0 = np.multiply(R, up)
    v0 = v_up * np.array(up) + v_east * np.array(east) + v_north * np.array(north)
    origin, x1 = x0.copy(), x0 + v0 * dt
    downrange = math.sin(az) * np.array(east) + math.cos(az) * np.array(north)

    rows, clock, row, steps, impact = [], 3 * dt, 0, 0, False
    while clock < max_time_s:
        steps += 1
        r1 = math.sqrt(x1 @ x1)
        altitude = r1 - R
        velocity = (x1 - x0) / dt + spin * np.array([-x1[1], x1[0], 0.0])  # sign as printed
        v = math.sqrt(velocity @ velocity)
        density, temperature_speed = day_air(
            float(air.density_kernel(altitude)), float(air.sound_kernel(altitude)), *launch.day
        )
        cd = float(law.evaluate(v / temperature_speed)) if temperature_speed > 0 else 0.0
        drag = 0.5 * density * cd * area * v * velocity
        x2 = 2 * x1 - x0 - GM * x1 / r1**3 * dt**2 - drag / mass * dt**2
        r2 = math.sqrt(x2 @ x2)
        step_angle = math.acos(min(1.0, x2 @ x1 / (r2 * r1)))
        if clock > row * 0.5:
            rows.append(
                (
                    clock,
                    r2 - R,
                    R * math.acos(min(1.0, x2 @ origin / (r2 * R))),
                    v,
                    r1,
                    r2**2 * step_angle / dt,
                    float(surface_ranges(x2, up, downrange)[1]),
                )
            )
            row += 1
        x0, x1 = x1, x2
        clock = round(clock + dt, 4)
        if r2 <= R:
            impact = True
            break
    frame = pd.DataFrame(
        rows,
        columns=[
            "time_s",
            "altitude_m",
            "ground_range_m",
            "speed_m_s",
            "radius_m",
            "specific_angular_momentum_m2_s",
            "cross_range_m",
        ],
    )
    top = frame.loc[frame.altitude_m.idxmax()]
    return describe(
        frame,
        engine="Appendix A macro",
        launch=launch,
        apogee=(top.time_s, top.altitude_m, top.ground_range_m),
        impact=impact,
        rhs_evaluations=steps,
        steps=steps,
        max_time_s=max_time_s,
        dt_s=dt,
    )
