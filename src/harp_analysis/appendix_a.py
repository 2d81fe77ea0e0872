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

from . import earth
from .atmosphere import get_atmosphere
from .drag import BASELINE_CONE
from .projectiles import Projectile
from .validation import check_range, finite_scalar

__all__ = ["simulate_appendix_a"]


def simulate_appendix_a(
    projectile: Projectile,
    elevation_deg: float,
    dt_s: float,
    *,
    speed_m_s: float | None = None,
    latitude_deg: float = 0.0,
    longitude_deg: float = 0.0,
    azimuth_deg: float = 90.0,
    earth_spin_rad_s: float = 0.0,
    max_time_s: float = 3000.0,
) -> pd.DataFrame:
    """Run Appendix A's macro; returns the rows it would write (every 0.5 s of its clock).

    Columns: ``time_s`` (the macro's clock), ``altitude_m``, ``ground_range_m`` (R times the
    angle from the launch point), ``speed_m_s`` (backward-difference speed),
    ``radius_m`` and ``specific_angular_momentum_m2_s`` as the macro computes them.
    """
    elevation = check_range(
        finite_scalar(elevation_deg, "elevation_deg"),
        "elevation_deg",
        low=0.0,
        low_inclusive=False,
        high=90.0,
        unit="deg",
    )
    dt = check_range(
        finite_scalar(dt_s, "dt_s"), "dt_s", low=0.0, low_inclusive=False, high=1.0, unit="s"
    )
    speed = check_range(
        finite_scalar(projectile.launch_speed_m_s if speed_m_s is None else speed_m_s, "speed_m_s"),
        "speed_m_s",
        low=0.0,
        low_inclusive=False,
        unit="m/s",
    )
    lat = math.radians(
        check_range(
            finite_scalar(latitude_deg, "latitude_deg"),
            "latitude_deg",
            low=-90.0,
            high=90.0,
            unit="deg",
        )
    )
    lon = math.radians(finite_scalar(longitude_deg, "longitude_deg"))
    az, el = math.radians(finite_scalar(azimuth_deg, "azimuth_deg")), math.radians(elevation)
    spin = finite_scalar(earth_spin_rad_s, "earth_spin_rad_s")
    air = get_atmosphere("three_layer")
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
    launch, x1 = x0.copy(), x0 + v0 * dt

    rows, clock, row = [], 3 * dt, 0
    while clock < max_time_s:
        r1 = math.sqrt(x1 @ x1)
        altitude = r1 - R
        velocity = (x1 - x0) / dt + spin * np.array([-x1[1], x1[0], 0.0])  # sign as printed
        v = math.sqrt(velocity @ velocity)
        temperature_speed = float(air.sound_kernel(altitude))
        cd = float(BASELINE_CONE.evaluate(v / temperature_speed)) if temperature_speed > 0 else 0.0
        drag = 0.5 * float(air.density_kernel(altitude)) * cd * area * v * velocity
        x2 = 2 * x1 - x0 - GM * x1 / r1**3 * dt**2 - drag / mass * dt**2
        r2 = math.sqrt(x2 @ x2)
        step_angle = math.acos(min(1.0, x2 @ x1 / (r2 * r1)))
        if clock > row * 0.5:
            rows.append(
                (
                    clock,
                    r2 - R,
                    R * math.acos(min(1.0, x2 @ launch / (r2 * R))),
                    v,
                    r1,
                    r2**2 * step_angle / dt,
                )
            )
            row += 1
        x0, x1 = x1, x2
        clock = round(clock + dt, 4)
        if r2 <= R:
            break
    return pd.DataFrame(
        rows,
        columns=[
            "time_s",
            "altitude_m",
            "ground_range_m",
            "speed_m_s",
            "radius_m",
            "specific_angular_momentum_m2_s",
        ],
    )
