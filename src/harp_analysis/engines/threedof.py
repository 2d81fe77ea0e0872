"""The 3DOF point-mass simulation: the physics of Appendix A with an accurate integrator.

Physics as in Appendix A: a spherical Earth of radius 6378 km, inverse-square gravity with
GM = 398600.4418 km^3/s^2, drag opposite the velocity relative to the air, and optionally the
Earth's rotation (the air turns with the Earth) and a constant head and cross wind. The
atmosphere and the drag law are pluggable by name (:mod:`~harp_analysis.models.atmosphere`,
:mod:`.drag`).

Not Appendix A's integrator: its fixed-step, second-order position recurrence is replaced by
the adaptive 8th-order scheme of :mod:`.integrator` with events for apogee and impact, so
results converge (to millimetres at the default ``rtol=1e-9``; see the benchmark). A step ends
on each discontinuity of the right-hand side it would cross, which the error estimate cannot
see: an atmosphere's breakpoints (carried across them on the step's interpolant) and the nodes
of a tabulated drag law, where Cd(Mach) turns. The state
is integrated in the Earth-centred inertial frame (x toward longitude 0 on the equator at
launch, z north); with rotation off this frame is also Earth-fixed. Winds are fixed to the
Earth, given as a head wind (blowing against the line of fire) and a cross wind (blowing toward
the right of it) at launch; the air of the launch's day (:func:`.atmosphere.day_air`) is the
model's with its density change and temperature change.

The right-hand side and the stepping loop are compiled (:mod:`.compiled`; :func:`warm_up`
compiles them ahead of use, once per version of the package), and so are a launch's initial
state, the summary of its flight and the rows of its table: one call from Python flies a batch,
so one flight costs little more than its integration, and a batch flies its launches one after
the other at the speed of one (``make benchmark``). Launches come as a
:class:`~harp_analysis.models.launch.Launch`, a :class:`~harp_analysis.models.launch.Launches`
(arrays, validated once) or a sequence of Launch.
"""

from __future__ import annotations

import math
import multiprocessing
import os
import warnings
from concurrent.futures import ProcessPoolExecutor
from functools import cache
from typing import NamedTuple

import numpy as np
import pandas as pd

from ..foundation import earth
from ..foundation.compiled import jit, vector
from ..foundation.counting import Counted
from ..foundation.validation import Bounds, finite_array, positive_scalar
from ..models.atmosphere import SOUND_SQUARED_PER_KELVIN, air, day_air, get_atmosphere
from ..models.drag import drag_coefficient
from ..models.launch import BOUNDS, Launch, Launches
from ..models.trajectory import (
    BASE_COLUMNS,
    STOP_REASONS,
    EndAltitudeNotCrossedWarning,
    TruncatedFlightWarning,
    climb_angle,
    cross,
    describe,
    dot,
    launch_axes,
    output_times,
    surface_range,
    turned_about_axis,
)
from .integrator import (
    ALTITUDE,
    MIN_CUT_S,
    RADIAL_VELOCITY,
    STAGES,
    STRADDLE,
    TABLEAU,
    crossing_fraction,
    error_norm,
    event_value,
    first_step,
    hermite,
    stage_state,
    step_factor,
    trial_step,
)

__all__ = [
    "simulate_3dof",
    "simulate_3dof_batch",
    "fly_3dof",
    "Flights",
    "Layings",
    "counted_functions",
    "warm_up",
]

# --- the physics: one launch's right-hand side, compiled ---------------------------------------
# What the launches of one batch share: the numbers of the atmosphere and the drag law
# (``air_code``, ``drag_code``: compile-time constants, so each pair gets its own machine code
# without the other models' branches, half the time of a right-hand side) and ``dynamics``, the
# atmosphere's table, the drag law's parameters and table, A / (2 m) and the Earth's rotation
# rate. ``weather`` (5,) is the launch's: its Earth-fixed wind at t = 0 in inertial components,
# then its day's density factor and gamma R dT (:attr:`.launch.Launch.day`).
_OMEGA = 5


@jit(inline=True)
def _air_velocity(t, y, weather, omega):
    """Velocity relative to the air, which turns with the Earth and carries the wind."""
    if not omega:
        return vector(y[3] - weather[0], y[4] - weather[1], y[5] - weather[2])
    wind_x, wind_y = turned_about_axis(weather[0], weather[1], omega * t)
    return vector(y[3] - omega * -y[1] - wind_x, y[4] - omega * y[0] - wind_y, y[5] - weather[2])


@jit(inline=True)
def _forces(t, y, weather, air_code, drag_code, dynamics):
    """Radius, altitude, air velocity (3 numbers) and its norm, Mach, Cd and density."""
    radius = np.sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2])
    altitude = radius - earth.RADIUS_M
    air_x, air_y, air_z = _air_velocity(t, y, weather, dynamics[_OMEGA])
    air_speed = np.sqrt(air_x * air_x + air_y * air_y + air_z * air_z)
    model_density, model_sound = air(air_code, altitude, dynamics[0])
    density, sound = day_air(model_density, model_sound, weather[3], weather[4])
    mach = air_speed / sound
    cd = drag_coefficient(drag_code, mach, dynamics[1], dynamics[2], dynamics[3])
    return radius, altitude, air_x, air_y, air_z, air_speed, mach, cd, density


@jit(inline=True)
def _acceleration(t, y, weather, air_code, drag_code, dynamics):
    """Inverse-square gravity and drag opposite the air velocity (m/s^2, 3 numbers), and the
    Mach number."""
    radius, _, air_x, air_y, air_z, air_speed, mach, cd, density = _forces(
        t, y, weather, air_code, drag_code, dynamics
    )
    drag = dynamics[4] * density * cd * air_speed
    gravity = -earth.GM_M3_S2 / radius**3
    return (
        gravity * y[0] - drag * air_x,
        gravity * y[1] - drag * air_y,
        gravity * y[2] - drag * air_z,
        mach,
    )


@jit(inline=True)
def _derivative(t, y, weather, air_code, drag_code, dynamics, out, row):
    """y' = [velocity, acceleration] into ``out[row]`` (indexed: a row view would cost
    reference counting in the stage loop); returns the Mach number."""
    out[row, 0], out[row, 1], out[row, 2] = y[3], y[4], y[5]
    out[row, 3], out[row, 4], out[row, 5], mach = _acceleration(
        t, y, weather, air_code, drag_code, dynamics
    )
    return mach


def counted_functions(launch: Launch) -> tuple[Counted, ...]:
    """The functions one evaluation of the right-hand side runs for ``launch``, each once: the
    acceleration, the forces and the air velocity, the launch's atmosphere's density and speed of
    sound, the day's air and its projectile's drag law (:mod:`harp_analysis.analyses.effort`
    counts their operations per evaluation, Fig 4.7)."""
    air = get_atmosphere(launch.atmosphere)
    return tuple(
        Counted(function)
        for function in (
            _acceleration,
            _forces,
            _air_velocity,
            air.density_kernel,
            air.sound_kernel,
            day_air,
            launch.projectile.drag_law.kernel,
        )
    )


# --- the integration: DOP853 with events, one trajectory ---------------------------------------
@jit
def _grow(array, size):
    grown = np.empty((array.shape[0], 2 * array.shape[1]))
    grown[:, :size] = array[:, :size]
    return grown


#: How a flight ends (:func:`_integrate`), as the index of its reason in
#: :data:`.trajectory.STOP_REASONS`: at its end level, cut off by ``t_max_s``, or at the ground
#: without crossing its end level.
_AT_END, _MAX_TIME, _GROUND = (
    STOP_REASONS.index(reason) for reason in ("impact", "max_time", "ground_before_end")
)


@jit
def _crosses(level, sign, y, y_new):
    """Whether the step from ``y`` to ``y_new`` crosses ``level`` falling (``sign`` +1) or
    rising (-1), from on the level (within its rounding) included."""
    above, after = event_value(ALTITUDE, level, y), event_value(ALTITUDE, level, y_new)
    return sign * above > -_ON_LEVEL_M and 0 >= sign * after


@jit
def _apogee_cut(level, t, hi, y, y_new, a, a_new, work):
    """The step (s) up to the apogee where the step from ``y`` starts on or below ``level``,
    turns over and ends below it, else 0: such a step may cross the level twice unseen. A
    flight that starts on its level and turns over within the step (a shot a hundredth of a
    degree above the horizon rises millimetres) falls through it from the apogee; one that
    tops out just above it (a step over the apogee of a flight ending where it rises through
    the level sags tens of metres below it) rises through it on the way to the apogee. A
    turn at the step's very end needs no cut: cut there, the same step would be tried again
    for ever."""
    above, after = event_value(ALTITUDE, level, y), event_value(ALTITUDE, level, y_new)
    turns = event_value(RADIAL_VELOCITY, 0.0, y) > 0 >= event_value(RADIAL_VELOCITY, 0.0, y_new)
    if above < _ON_LEVEL_M and after < 0 and turns:
        fraction = crossing_fraction(RADIAL_VELOCITY, 0.0, t, t + hi, y, y_new, a, a_new, work)
        if fraction < 1 - STRADDLE:
            return hi * fraction
    return 0.0


@jit
def _time_across(level, y, step_s):
    """The time (s) that carries a flight at ``y`` just across the breakpoint ``level`` it is
    heading for (:data:`_ACROSS_M` past it), or 0 if that is more than a thousandth of the
    step ``step_s`` that ended there (it grazes the breakpoint, or is not heading for it): so
    short a reach on the step's quintic interpolant is as accurate as the step."""
    gap = event_value(ALTITUDE, level, y)
    radius = math.sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2])
    climb = event_value(RADIAL_VELOCITY, 0.0, y) / radius
    tau = (abs(gap) + _ACROSS_M) / abs(climb) if gap * climb < 0 else math.inf
    return tau if tau <= 1e-3 * step_s else 0.0


@jit(cache=False)  # compiled per pair of models within its kernels (:func:`_kernels`)
def _integrate(y0, weather, air_code, drag_code, dynamics, numerics, record):
    """One flight from ``y0`` until it crosses its end level, falls back to the ground without
    crossing it, or reaches ``t_max_s``; ``numerics`` is ``(end_m, end_sign, ground_m,
    breakpoints_m, t_max_s, rtol, floor, max_step_s)``: the altitude that ends the flight,
    falling through it (``end_sign`` +1) or rising (-1), the ground's (the site's), the
    atmosphere's breakpoints and the integrator's settings (:func:`_fly`).

    Returns the time of the apogee (NaN if not reached) and of the end (NaN if cut off), the
    state (6,) at each (the last state for a flight cut off), how it ended (:data:`_AT_END`,
    :data:`_MAX_TIME` or :data:`_GROUND`), the right-hand-side evaluations and accepted steps,
    and, if ``record``, every accepted step: times (k,) and states with accelerations (9, k).

    One function, one loop: the trial step, its error control, the cuts at breakpoints and
    drag-table nodes, the events and the record share the loop's state (t, y, a, Mach, the
    next step, the breakpoint last cut short of, apogee and end) and call the right-hand side
    (:func:`_derivative`, its model codes folded in as constants) from three places. A piece
    split off that called it would inline it once more (numba types each inlined copy anew,
    most of a kernel's compilation) or call it through a dispatcher, passing arrays with their
    reference counting at every stage, and be compiled per pair of models as well
    (:mod:`.compiled`). What needs no right-hand side is apart already: :mod:`.integrator`'s
    building blocks, :func:`_apogee_cut`, :func:`_time_across`, :func:`_crosses`.
    """
    end_m, end_sign, ground_m, breakpoints_m, t_max_s, rtol, floor, max_step_s = numerics
    # a flight that never crosses its end level (above its apogee, or one it cannot rise
    # through) stops at the ground; one falling to a level at or below the ground gets there
    grounded = end_sign < 0 or ground_m < end_m
    k = np.empty((STAGES + 1, 6))
    y, y_new, work = y0.copy(), np.empty(6), np.empty(6)
    start = np.empty((2, 6))  # y' at the start and a trial step h0 later
    scale = np.empty(6)
    for i in range(6):
        scale[i] = rtol * max(abs(y[i]), floor[i])
    h0 = 0.0
    work[:] = y
    mach = 0.0  # at y
    for trial in range(2):  # in a loop: each call site compiles the right-hand side anew
        at_trial = _derivative(h0, work, weather, air_code, drag_code, dynamics, start, trial)
        if trial == 0:
            mach = at_trial
            h0 = trial_step(y, start[0], scale)
            for i in range(6):
                work[i] = y[i] + h0 * start[0, i]
    h = first_step(h0, start[0], start[1], scale, max_step_s)
    evaluations = 2
    a, a_new = start[0, 3:].copy(), np.empty(3)
    times = np.empty(64 if record else 1)
    steps = np.empty((9, 64 if record else 1))
    if record:
        times[0] = 0.0
        steps[:6, 0], steps[6:, 0] = y, a
    t, count = 0.0, 0
    apogee_t, stop_t, outcome = math.nan, math.nan, _MAX_TIME
    apogee, end, across = np.empty(6), np.empty(6), np.empty(6)
    c = TABLEAU[2]
    failed = False
    recorded = 0  # rows of the record: the accepted steps and the crossings of breakpoints
    jump = math.nan  # the breakpoint a step was last cut short of
    mach_new = mach  # at y_new
    while True:
        hi = min(h, t_max_s - t)
        for i in range(3):
            k[0, i], k[0, 3 + i] = y[3 + i], a[i]
        for stage in range(1, STAGES + 1):  # the last is the solution's, at t + hi
            state, node = (work, c[stage]) if stage < STAGES else (y_new, 1.0)
            stage_state(stage, y, k, hi, state)
            mach_new = _derivative(  # the last stage's: at y_new
                t + node * hi, state, weather, air_code, drag_code, dynamics, k, stage
            )
        for i in range(3):
            a_new[i] = k[STAGES, 3 + i]
        evaluations += STAGES
        error = error_norm(y, y_new, k, hi, rtol, floor)
        if not math.isfinite(error) or hi <= 1e-12 * max(1.0, t):
            failed = True  # a non-finite derivative, or a step too small to advance t
            break
        accept = error <= 1.0
        factor = step_factor(error)
        h = min(hi * (factor if accept else min(factor, 1.0)), max_step_s)
        earliest = 1.0  # the share of the step where it first crosses a breakpoint or a node
        for level in breakpoints_m:
            before = event_value(ALTITUDE, level, y)
            after = event_value(ALTITUDE, level, y_new)
            if np.sign(before) != np.sign(after):
                fraction = crossing_fraction(ALTITUDE, level, t, t + hi, y, y_new, a, a_new, work)
                if fraction * hi > MIN_CUT_S and fraction < min(earliest, 1 - STRADDLE):
                    earliest, jump = fraction, level
        if earliest < 1.0:
            h = hi * earliest * (1 - 2 * STRADDLE)
        # Cd(Mach) turns at its table's nodes: the error estimate, which assumes a smooth
        # right-hand side, does not see it (0.6 m of an HP round's apogee at rtol 1e-9). A step
        # is ended on a node (where Mach, linear in the step, reaches it) unless the node lies
        # within _NODE_MARGIN of either end, where the turn costs a billionth as much.
        for node in dynamics[2]:
            if (mach - node) * (mach_new - node) < 0.0:
                fraction = (node - mach) / (mach_new - mach)
                if _NODE_MARGIN < fraction < min(earliest, 1 - _NODE_MARGIN):
                    earliest, jump = fraction, math.nan
                    h = hi * fraction
        if earliest < 1.0:
            accept = False
        if math.isnan(stop_t):  # the levels a flight may end at, either way for the end level
            for level, ends in ((end_m, True), (ground_m, grounded)):
                cut = _apogee_cut(level, t, hi, y, y_new, a, a_new, work) if ends else 0.0
                if cut > MIN_CUT_S:
                    accept = False
                    h = cut
        if not accept:
            continue
        t_new = t + hi
        count += 1
        stopped = False
        if math.isnan(apogee_t) and t_new > 0.0:
            if event_value(RADIAL_VELOCITY, 0.0, y) > 0 >= event_value(RADIAL_VELOCITY, 0.0, y_new):
                fraction = crossing_fraction(
                    RADIAL_VELOCITY, 0.0, t, t_new, y, y_new, a, a_new, work
                )
                apogee_t = t + fraction * (t_new - t)
                hermite(t, t_new, y, y_new, a, a_new, apogee_t, apogee)
        if math.isnan(stop_t) and t_new > 1e-6:
            level, sign = end_m, end_sign
            if _crosses(end_m, end_sign, y, y_new):
                outcome = _AT_END
            elif grounded and _crosses(ground_m, 1.0, y, y_new):
                level, sign, outcome = ground_m, 1.0, _GROUND
            if outcome != _MAX_TIME:
                fraction = (  # from on the level (a rise below the rounding) it lands at once
                    crossing_fraction(ALTITUDE, level, t, t_new, y, y_new, a, a_new, work)
                    if sign * event_value(ALTITUDE, level, y) > 0
                    else 0.0
                )
                stop_t = t + fraction * (t_new - t)
                hermite(t, t_new, y, y_new, a, a_new, stop_t, end)
                stopped = True
        # A step cut short of a breakpoint ends up to centimetres before it: carried across
        # on its interpolant (microseconds past its end) and its derivative taken there, the
        # next step flies the far side's formulas from its first stage. Else that stage would
        # be the near side's, an error the step control could only reject away, and steps of
        # microseconds grow back (17 of the baseline cone's 47 steps at 45 deg).
        tau = 0.0 if stopped or math.isnan(jump) else _time_across(jump, y_new, hi)
        if tau > 0.0:
            hermite(t, t_new, y, y_new, a, a_new, t_new + tau, across)
        jump = math.nan
        t = t_new
        for i in range(6):
            y[i] = y_new[i]
        for i in range(3):
            a[i] = a_new[i]
        mach = mach_new
        for carried in range(2):  # the step's end, then the state carried across
            if record:
                recorded += 1
                if recorded == times.size:
                    times = _grow(times.reshape(1, -1), recorded)[0]
                    steps = _grow(steps, recorded)
                times[recorded] = t
                steps[:6, recorded], steps[6:, recorded] = y, a
            if carried or tau == 0.0:
                break
            t += tau
            for i in range(6):
                y[i] = across[i]
            mach = _derivative(t, y, weather, air_code, drag_code, dynamics, k, 0)
            evaluations += 1
            for i in range(3):
                a[i] = k[0, 3 + i]
        if stopped or t >= t_max_s:
            break
    if math.isnan(stop_t):
        end[:] = y
    return (
        apogee_t,
        apogee,
        stop_t,
        end,
        outcome,
        evaluations,
        count,
        failed,
        times[: recorded + 1],
        steps[:, : recorded + 1],
    )


@jit(inline=True)
def _fly_all(y0, weather, air_code, drag_code, dynamics, numerics, record):
    """:func:`_integrate` for every launch (columns of ``y0`` and ``weather``): the times of the
    apogee and end (2, n), the states there (2, 6, n), the evaluations, steps, whether the
    integration failed and how the flight ended (4, n), and the last launch's record of its
    steps (when ``record``). ``numerics`` is :func:`_integrate`'s with arrays (n,) or (1,) of
    the end altitudes and directions."""
    n = y0.shape[1]
    event_times = np.empty((2, n))
    states = np.empty((2, 6, n))
    counts = np.empty((4, n), np.int64)
    step_times, steps = np.empty(0), np.empty((9, 0))
    ends, signs, ground_m, breakpoints_m, t_max_s, rtol, floor, max_step_s = numerics
    for i in range(n):
        end, sign = ends[min(i, ends.size - 1)], signs[min(i, signs.size - 1)]
        own = (end, sign, ground_m, breakpoints_m, t_max_s, rtol, floor, max_step_s)
        flight = _integrate(
            y0[:, i].copy(), weather[:, i].copy(), air_code, drag_code, dynamics, own, record
        )
        apogee_t, apogee, stop_t, end, outcome, evaluations, count, failed, step_times, steps = (
            flight
        )
        event_times[0, i], event_times[1, i] = apogee_t, stop_t
        states[0, :, i], states[1, :, i] = apogee, end
        counts[0, i], counts[1, i], counts[2, i], counts[3, i] = evaluations, count, failed, outcome
    return event_times, states, counts, step_times, steps


@jit(inline=True)
def _rows(times_s, step_times, steps, weather, axes, air_code, drag_code, dynamics):
    """The trajectory table at ``times_s`` within the recorded steps of launch 0: one row (m,
    13) per time, with :data:`trajectory.BASE_COLUMNS` in their order."""
    m = times_s.size
    table, y = np.empty((m, 13)), np.empty(6)
    up = (axes[0, 0, 0], axes[0, 1, 0], axes[0, 2, 0])
    downrange = (axes[1, 0, 0], axes[1, 1, 0], axes[1, 2, 0])
    omega = dynamics[_OMEGA]
    last = step_times.size - 2
    for j in range(m):
        t = times_s[j]
        i = min(max(np.searchsorted(step_times, t, side="right") - 1, 0), last)
        hermite(
            step_times[i],
            step_times[i + 1],
            steps[:6, i],
            steps[:6, i + 1],
            steps[6:, i],
            steps[6:, i + 1],
            t,
            y,
        )
        radius, altitude, _, _, _, air_speed, mach, cd, density = _forces(
            t, y, weather, air_code, drag_code, dynamics
        )
        r, v = (y[0], y[1], y[2]), (y[3], y[4], y[5])
        ground, cross_range = surface_range(_earth_fixed(y[0], y[1], y[2], omega, t), up, downrange)
        drag = dynamics[4] * density * cd * air_speed**2
        momentum = cross(r, v)
        row = table[j]
        row[0], row[1], row[2], row[3], row[4] = t, y[0], y[1], y[2], altitude
        row[5], row[6], row[7], row[8], row[9] = ground, cross_range, np.sqrt(dot(v, v)), mach, cd
        row[10] = drag / (earth.GM_M3_S2 / radius**2)
        row[11] = np.sqrt(dot(momentum, momentum))
        row[12] = climb_angle(r, v)
    return table


#: The launch fields a batch's kernel takes, one row each (:func:`_setup`).
_COLUMNS = (
    "elevation_deg",
    "speed_m_s",
    "latitude_deg",
    "longitude_deg",
    "bearing_deg",
    "head_wind_m_s",
    "cross_wind_m_s",
    "density_change_fraction",
    "temperature_change_k",
)


@jit
def _setup(columns, omega, site_m):
    """Initial states (6, n), weather (5, n) and launch axes up and downrange (2, 3, n) of the
    launches whose :data:`_COLUMNS` are ``columns`` (9, n); the site's altitude is shared (the
    impact event sees states only)."""
    n = columns.shape[1]
    y0, weather, axes = np.empty((6, n)), np.empty((5, n)), np.empty((2, 3, n))
    for i in range(n):
        elevation, speed = math.radians(columns[0, i]), columns[1, i]
        up, downrange, _ = launch_axes(
            math.radians(columns[2, i]), math.radians(columns[3, i]), math.radians(columns[4, i])
        )
        right = cross(downrange, up)
        radius = earth.RADIUS_M + site_m
        for k in range(3):
            y0[k, i] = radius * up[k]
            y0[3 + k, i] = speed * (np.cos(elevation) * downrange[k] + np.sin(elevation) * up[k])
            weather[k, i] = -columns[5, i] * downrange[k] + columns[6, i] * right[k]
            axes[0, k, i], axes[1, k, i] = up[k], downrange[k]
        y0[3, i] += omega * -y0[1, i]  # the gun turns with the Earth
        y0[4, i] += omega * y0[0, i]
        weather[3, i] = 1.0 + columns[7, i]
        weather[4, i] = SOUND_SQUARED_PER_KELVIN * columns[8, i]
    return y0, weather, axes


@jit(inline=True)
def _earth_fixed(x, y, z, omega, t):
    """An inertial vector at time ``t`` in the Earth-fixed axes (the inertial ones at t = 0)."""
    x, y = turned_about_axis(x, y, -omega * t)
    return x, y, z


@jit
def _summarise(event_times, states, outcomes, axes, omega, max_time_s):
    """What :class:`Flights` holds of each launch, rows of (14, n): the apogee's time, altitude
    and ground range, the end's time, ground and cross range, inertial speed, how it ended
    (``outcomes``: :data:`_AT_END`, :data:`_MAX_TIME` or :data:`_GROUND`), Earth-fixed
    position (3) and velocity relative to the Earth (3)."""
    n = event_times.shape[1]
    out = np.empty((14, n))
    for i in range(n):
        up = (axes[0, 0, i], axes[0, 1, i], axes[0, 2, i])
        downrange = (axes[1, 0, i], axes[1, 1, i], axes[1, 2, i])
        apogee_t, stop_t = event_times[0, i], event_times[1, i]
        out[0, i], out[1, i], out[2, i] = apogee_t, math.nan, math.nan
        if not math.isnan(apogee_t):
            top = _earth_fixed(states[0, 0, i], states[0, 1, i], states[0, 2, i], omega, apogee_t)
            out[1, i] = np.sqrt(dot(top, top)) - earth.RADIUS_M
            out[2, i] = surface_range(top, up, downrange)[0]
        end_t = max_time_s if math.isnan(stop_t) else stop_t
        r = (states[1, 0, i], states[1, 1, i], states[1, 2, i])
        v = (states[1, 3, i], states[1, 4, i], states[1, 5, i])
        position = _earth_fixed(r[0], r[1], r[2], omega, end_t)
        velocity = _earth_fixed(v[0] + omega * r[1], v[1] - omega * r[0], v[2], omega, end_t)
        out[3, i] = end_t
        out[4, i], out[5, i] = surface_range(position, up, downrange)
        out[6, i] = np.sqrt(dot(v, v))
        out[7, i] = outcomes[i]
        for k in range(3):
            out[8 + k, i], out[11 + k, i] = position[k], velocity[k]
    return out


@cache
def _kernels(air_code: int, drag_code: int):
    """The flights and the table rows compiled for one atmosphere and drag law: their numbers
    are constants of the machine code, so the other models' branches fold away (half the time
    of a right-hand side). They reach :func:`_integrate` as literal arguments, which numba
    compiles once per value: each pair gets an integrator of its own, its right-hand side
    inlined, while the code that knows no model (setup, events, summary) is compiled once for
    all. Compiled at first use (:func:`warm_up`), then loaded from disk; each pair has cache
    files of its own, so that processes may compile different pairs at once."""

    def fly(columns, dynamics, numerics, site_m, record):
        omega = dynamics[_OMEGA]
        y0, weather, axes = _setup(columns, omega, site_m)
        event_times, states, counts, step_times, steps = _fly_all(
            y0, weather, air_code, drag_code, dynamics, numerics, record
        )
        summary = _summarise(event_times, states, counts[3], axes, omega, numerics[4])
        return summary, counts, weather, axes, step_times, steps

    def rows(times_s, step_times, steps, weather, axes, dynamics):
        return _rows(times_s, step_times, steps, weather, axes, air_code, drag_code, dynamics)

    for kernel in (fly, rows):  # numba names a cache file after the function
        kernel.__qualname__ = f"{kernel.__name__}_air{air_code}_drag{drag_code}"
    return jit(fly), jit(rows)


def _numerics(rtol, max_time_s):
    if type(rtol) is float and type(max_time_s) is float:  # the common case, checked cheaply
        if 0.0 < rtol <= 1e-3 and 0.0 < max_time_s < math.inf:
            return rtol, max_time_s
    rtol = float(Bounds(low=0.0, high=1e-3, low_inclusive=False).scalar(rtol, "rtol"))
    max_time_s = float(positive_scalar(max_time_s, "max_time_s", "s"))
    return rtol, max_time_s


_BATCH_REASON = "a batch shares one projectile, atmosphere, Earth rotation and site altitude"


class _Batch(NamedTuple):
    """What the launches of one batch share, and their :data:`_COLUMNS` (9, n)."""

    codes: tuple[int, int]  # the atmosphere's and the drag law's
    dynamics: tuple
    breakpoints_m: np.ndarray
    site_m: float
    columns: np.ndarray


def _batch(launches) -> _Batch:
    """A :class:`~harp_analysis.models.launch.Launch`, a
    :class:`~harp_analysis.models.launch.Launches` or a sequence of Launch as one batch: one
    projectile, air, Earth rotation and site altitude (the impact event, a function of the state
    alone, needs one site)."""
    if isinstance(launches, Launch):  # one launch, validated already: its numbers as they are
        omega, site = launches.rotation_rate_rad_s, launches.site_altitude_m
        columns = np.array([[getattr(launches, name)] for name in _COLUMNS])
    else:
        if not isinstance(launches, Launches):
            launches = Launches.from_launches(launches)
        omega = launches.shared("rotation_rate_rad_s", reason=_BATCH_REASON)
        site = launches.shared("site_altitude_m", reason=_BATCH_REASON)
        columns = np.array([getattr(launches, name) for name in _COLUMNS])
    codes, dynamics, breakpoints = _shared(launches.projectile, launches.atmosphere, omega)
    return _Batch(codes, dynamics, breakpoints, site, columns)


# A state this close to the level that ends the flight is on it: the altitude's rounding at the
# Earth's radius is about 1e-9 m.
_ON_LEVEL_M = 1e-6
#: How far past a breakpoint :func:`_time_across` carries a flight (m).
_ACROSS_M = 1e-6
#: A step that crosses a node of its drag table within this share of either end is not cut.
_NODE_MARGIN = 1e-3
_STATE_FLOOR = np.array([earth.RADIUS_M] * 3 + [1e3] * 3)  # error scale floor: m, m/s
_MAX_STEP_S = 20.0  # keeps the interpolated velocities between steps within ~1e-6 m/s


@cache
def _shared(projectile, atmosphere: str, omega: float) -> tuple:
    """The kernels' numbers for a projectile, an atmosphere and an Earth rotation rate: the
    models' codes, ``dynamics`` and the atmosphere's breakpoints (computed once)."""
    model = get_atmosphere(atmosphere)
    law = projectile.drag_law.kernel_parameters()
    dynamics = (
        model.table(),
        *law[1:],
        projectile.reference_area_m2 / (2 * projectile.mass_kg),  # the Cd-free drag, A / (2 m)
        float(omega),
    )
    return (model.code, law[0]), dynamics, np.array(model.breakpoints_m, dtype=float)


class Flights(NamedTuple):
    """Apogee and end of every launch of a batch (:func:`fly_3dof`), arrays (n,) in SI units;
    ``end`` is the impact (where the flight crossed its end altitude), or where it stopped
    without: ``stop_reason`` says why (:data:`.trajectory.STOP_REASONS`)."""

    apogee_time_s: np.ndarray
    apogee_altitude_m: np.ndarray
    apogee_ground_range_m: np.ndarray
    time_of_flight_s: np.ndarray
    range_m: np.ndarray
    cross_range_m: np.ndarray
    impact_speed_m_s: np.ndarray
    impact: np.ndarray
    stop_reason: np.ndarray  # "impact", "max_time" or "ground_before_end"
    steps: np.ndarray
    rhs_evaluations: np.ndarray
    end_position_m: np.ndarray  # (3, n) Earth-fixed (the inertial frame at t = 0)
    end_velocity_m_s: np.ndarray  # (3, n) relative to the Earth, in the same axes


def _fly(batch: _Batch, max_time_s: float, rtol: float, record: bool, end=None, rising=False):
    """The compiled flights of ``batch`` to the site's altitude, or to ``end`` (m) rising where
    ``rising`` (one of each, or arrays (n,)), each stopped at the ground if it never gets
    there; FloatingPointError if one cannot be integrated."""
    fly, _ = _kernels(*batch.codes)
    numerics = (
        np.array(batch.site_m if end is None else end, dtype=float, ndmin=1),
        np.where(rising, -1.0, 1.0).astype(float).reshape(-1),
        float(batch.site_m),  # the ground
        batch.breakpoints_m,
        max_time_s,
        rtol,
        _STATE_FLOOR,
        _MAX_STEP_S,
    )
    flights = fly(batch.columns, batch.dynamics, numerics, batch.site_m, record)
    failed = np.flatnonzero(flights[1][2])
    if failed.size:
        raise FloatingPointError(
            f"the 3DOF could not integrate launch {failed[0]} of {batch.columns.shape[1]}: a "
            "non-finite acceleration or a step too small to advance the time"
        )
    return flights


def fly_3dof(
    launches,
    *,
    rtol: float = 1e-9,
    max_time_s: float = 3000.0,
    end_altitude_m=None,
    rising=False,
) -> Flights:
    """The apogee and end of each launch in ``launches`` (one
    :class:`~harp_analysis.models.launch.Launch`, a :class:`~harp_analysis.models.launch.Launches`,
    or a sequence of Launch sharing one projectile, atmosphere, Earth rotation and site altitude),
    as arrays: the 3DOF's engine without its tables (:func:`simulate_3dof_batch` is this as a
    DataFrame).

    A flight ends where it falls back to the site's altitude, or to ``end_altitude_m`` (m) if
    given, or rises through it if ``rising`` (a target above the gun on the way up); each is
    one for every launch or an array (n,), one per launch. ``impact`` says whether it got
    there before ``max_time_s``, and ``stop_reason`` why not: cut off by ``max_time_s``, or it
    never crossed ``end_altitude_m`` (one above its apogee) and ended where it fell back to
    the ground, which warns (:class:`~.trajectory.EndAltitudeNotCrossedWarning`).

    Parameters
    ----------
    launches : Launch, Launches or list of Launch
        The launches, flown together by one compiled call.
    rtol : float
        The integrator's relative tolerance.
    max_time_s : float
        The longest flight (s).
    end_altitude_m : float or numpy.ndarray, optional
        Where a flight ends (m), for every launch or one each (n,); the site's altitude by
        default. Not below the lowest site, -500 m.
    rising : bool or numpy.ndarray
        For every launch or one each (n,): end where the flight rises through
        ``end_altitude_m``, not where it falls back.

    Returns
    -------
    Flights
        Apogee and end of every launch as arrays (n,), SI units.
    """
    rtol, max_time_s = _numerics(rtol, max_time_s)
    batch = _batch(launches)
    count = batch.columns.shape[1]
    if end_altitude_m is None and rising is False:  # to the ground: the site is validated
        ends, rising = np.array([batch.site_m]), _FALLING
    else:
        end = batch.site_m if end_altitude_m is None else end_altitude_m
        ends, rising = _ends(end, rising, count)
    flights = _flights(*_fly(batch, max_time_s, rtol, record=False, end=ends, rising=rising)[:2])
    grounded = np.flatnonzero(flights.stop_reason == "ground_before_end")
    if grounded.size:
        warnings.warn(
            _not_crossed(grounded, count, ends, rising, flights.apogee_altitude_m, batch.site_m),
            EndAltitudeNotCrossedWarning,
            stacklevel=2,
        )
    return flights


def _ends(end_altitude_m, rising, count: int) -> tuple[np.ndarray, np.ndarray]:
    """The end altitudes (m) and directions of ``count`` flights, each one for every flight or
    one per flight, as flat arrays; else an error naming the argument."""
    ends = finite_array(end_altitude_m, "end_altitude_m")
    # no ground lies below the lowest site
    Bounds(low=BOUNDS["site_altitude_m"].low, unit="m").check(ends, "end_altitude_m")
    directions = np.asarray(rising)
    if directions.dtype != bool:
        raise TypeError(f"rising must be True, False or an array of them; got {rising!r:.80}")
    return _per_launch(ends, count), _per_launch(directions, count)


def _flights(summary: np.ndarray, counts: np.ndarray) -> Flights:
    """The :class:`Flights` of the compiled flights' ``summary`` (14, n) and ``counts`` (4, n)
    (:func:`_fly`)."""
    outcomes = summary[7].astype(int)
    apogee_t, apogee, apogee_ground, end_t, ground, cross_range, speed = summary[:7]
    return Flights(
        apogee_t,
        apogee,
        apogee_ground,
        end_t,
        ground,
        cross_range,
        speed,
        outcomes == _AT_END,
        _STOP_REASONS[outcomes],
        counts[1],
        counts[0],
        summary[8:11],
        summary[11:14],
    )


_STOP_REASONS = np.asarray(STOP_REASONS)
_FALLING = np.zeros(1, dtype=bool)
_FALLING.flags.writeable = False


class Layings:
    """One gun's 3DOF flights at many layings (elevation and bearing), flown again and again
    as a shooting method iterates: the gun and the integrator's settings are validated once,
    here, and each :meth:`~harp_analysis.engines.threedof.Layings.fly` checks only what it is given
    (vectorised, no :class:`~harp_analysis.models.launch.Launches` built), so a batch of a few
    flights costs little more than the flights.

    Parameters
    ----------
    gun : Launch
        The launch whose elevation and bearing each flight replaces.
    rtol : float
        The integrator's relative tolerance.
    max_time_s : float
        The longest flight (s).
    """

    def __init__(self, gun: Launch, *, rtol: float = 1e-9, max_time_s: float = 3000.0):
        if not isinstance(gun, Launch):
            raise TypeError(
                f"gun must be a harp_analysis.models.launch.Launch; got {type(gun).__name__}"
            )
        self._rtol, self._max_time_s = _numerics(rtol, max_time_s)
        self._batch = _batch(gun)

    def fly(self, elevation_rad, bearing_rad, end_altitude_m, rising) -> Flights:
        """:func:`fly_3dof` of the gun laid at each elevation (rad, in (0, pi/2]) and bearing
        (rad from true north, any turn) of the arrays (k,), each to its end altitude (m) rising
        or falling through it (one for all or (k,) each), but quietly: a flight that never
        crosses its end altitude has ``impact`` False and no warning (a shooting method expects
        them).

        Parameters
        ----------
        elevation_rad, bearing_rad : numpy.ndarray
            The layings (k,), rad.
        end_altitude_m : float or numpy.ndarray
            Where each flight ends (m): one for every flight or one each (k,).
        rising : bool or numpy.ndarray
            For every flight or one each (k,): end where it rises through its end altitude.

        Returns
        -------
        Flights
            Apogee and end of every flight as arrays (k,), SI units.
        """
        elevation = np.ravel(finite_array(elevation_rad, "elevation_rad"))
        bearing = np.ravel(finite_array(bearing_rad, "bearing_rad"))
        if bearing.shape != elevation.shape or not elevation.size:
            raise ValueError(
                "elevation_rad and bearing_rad must be arrays of one length (k,), k > 0; got "
                f"shapes {np.shape(elevation_rad)} and {np.shape(bearing_rad)}"
            )
        outside = ~((elevation > 0.0) & (elevation <= 0.5 * math.pi))
        if outside.any():
            index = int(np.flatnonzero(outside)[0])
            raise ValueError(
                f"elevation_rad[{index}] must lie in (0, pi/2]; got {elevation[index]:g}"
            )
        count = elevation.size
        ends, rising = _ends(end_altitude_m, rising, count)
        columns = np.repeat(self._batch.columns, count, axis=1)
        columns[_COLUMNS.index("elevation_deg")] = np.degrees(elevation)
        columns[_COLUMNS.index("bearing_deg")] = np.degrees(bearing) % 360.0
        laid = self._batch._replace(columns=columns)
        return _flights(
            *_fly(laid, self._max_time_s, self._rtol, record=False, end=ends, rising=rising)[:2]
        )


#: Launches a warning of flights that never crossed their end altitudes describes one by one.
_DESCRIBED = 3


def _not_crossed(which, count, ends, rising, apogees, site_m) -> str:
    """The warning for the launches ``which`` (of ``count``) that fell back to the ground
    without crossing their end altitudes ``ends`` the way ``rising`` says (one or one per
    launch each); ``apogees`` (n,), m."""

    def missed(i):
        way = "climbs" if rising[min(i, rising.size - 1)] else "comes down"
        return (
            f"never {way} through end_altitude_m = {ends[min(i, ends.size - 1)] / 1e3:g} km "
            f"(its apogee: {apogees[i] / 1e3:.4g} km)"
        )

    outcome = (
        f"ends where it falls back to the ground (the site's altitude, {site_m:g} m), with "
        "impact False and stop_reason 'ground_before_end'"
    )
    if count == 1:
        return f"the 3DOF flight {missed(0)}: it {outcome}"
    listed = ", ".join(str(i) for i in which[:10]) + (
        f" and {which.size - 10} more" if which.size > 10 else ""
    )
    described = "; ".join(f"launch {i} {missed(i)}" for i in which[:_DESCRIBED])
    return (
        f"{which.size} of {count} 3DOF flights never cross their end altitude (launches "
        f"{listed}): {described}{'; ...' if which.size > _DESCRIBED else ''}. Each {outcome}"
    )


def _per_launch(values: np.ndarray, count: int) -> np.ndarray:
    """``values``, one for every launch or one per launch, as a flat array; else ValueError."""
    if values.ndim > 1 or values.size not in (1, count):
        raise ValueError(
            f"end_altitude_m and rising must be one value or one per launch ({count}); "
            f"got shape {values.shape}"
        )
    return values.reshape(-1)


def _warm_up_pair(projectile_name: str, atmosphere: str) -> None:
    """Compile (or load) the kernels of one projectile's drag law and one atmosphere."""
    from ..models.projectiles import get_projectile

    projectile = get_projectile(projectile_name)
    launch = Launch(projectile, projectile.launch_speed_m_s, 45.0, atmosphere=atmosphere)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", TruncatedFlightWarning)
        simulate_3dof(launch, max_time_s=1.0)  # a short flight compiles every kernel


def warm_up(processes: int | None = None) -> None:
    """Compile the 3DOF's kernels now (or load them from the disk cache), not at first use: one
    per pair of atmosphere and drag law of the named projectiles (about 8 s each, once). The
    first pair compiles what every pair shares; the others are shared out among ``processes``
    (default: one per core), each compiling pairs no other compiles."""
    from ..models.atmosphere import ATMOSPHERE_NAMES
    from ..models.projectiles import PROJECTILE_NAMES, get_projectile

    laws = {get_projectile(name).drag_law.code: name for name in PROJECTILE_NAMES}
    pairs = [(name, atmosphere) for name in laws.values() for atmosphere in ATMOSPHERE_NAMES]
    _warm_up_pair(*pairs[0])
    workers = min(processes or os.cpu_count() or 1, len(pairs) - 1)
    if workers <= 1:
        for pair in pairs[1:]:
            _warm_up_pair(*pair)
        return
    # spawned, not forked: a fork of a process that has loaded numba's compiler is not safe
    with ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("spawn")) as pool:
        list(pool.map(_warm_up_pair, *zip(*pairs[1:])))


_TABLE_COLUMNS = pd.Index(BASE_COLUMNS)  # built once: an Index costs more than the table


def simulate_3dof(
    launch: Launch, *, rtol: float = 1e-9, max_time_s: float = 3000.0, output_step_s: float = 0.5
) -> pd.DataFrame:
    """One 3DOF flight of ``launch`` from the gun to the ground (back to the site's altitude),
    as the table of :mod:`.trajectory` with its shared metadata.

    ``rtol`` is the integrator's relative tolerance; rows come every ``output_step_s`` plus
    the impact, or the last time reached if ``max_time_s`` comes first (a
    TruncatedFlightWarning). The state is inertial; with ``launch.rotation_rate_rad_s`` the air
    turns with the Earth and ranges are measured on the turning Earth.

    Parameters
    ----------
    launch : Launch
        The launch to fly: projectile, muzzle speed, elevation, bearing, site, air, wind and
        the Earth's rotation.
    rtol : float
        The integrator's relative tolerance.
    max_time_s : float
        The longest flight (s); one cut off here warns (TruncatedFlightWarning).
    output_step_s : float
        Seconds between rows.

    Returns
    -------
    pandas.DataFrame
        The 3DOF's flight as the engines' trajectory table
        (:mod:`harp_analysis.models.trajectory`), a row every ``output_step_s``; its
        ``frame.attrs`` hold what every engine records and the integrator's work.
    """
    if not isinstance(launch, Launch):
        raise TypeError(
            f"launch must be a Launch (harp_analysis.models.launch.Launch); "
            f"got {type(launch).__name__} "
            "(simulate_3dof_batch flies a sequence of them)"
        )
    step = positive_scalar(output_step_s, "output_step_s", "s")
    rtol, max_time_s = _numerics(rtol, max_time_s)
    batch = _batch(launch)
    summary, counts, weather, axes, step_times, steps = _fly(batch, max_time_s, rtol, record=True)
    impact = summary[7, 0] == _AT_END  # the site's altitude: every flight not cut off gets there
    end_t = summary[3, 0] if impact else step_times[-1]
    times = output_times(end_t, step)
    rows = _kernels(*batch.codes)[1](
        times, step_times, steps, np.ascontiguousarray(weather[:, 0]), axes, batch.dynamics
    )
    apogee_t = summary[0, 0]
    return describe(
        pd.DataFrame(rows, columns=_TABLE_COLUMNS, copy=False),  # the kernel's new array
        engine="3DOF",
        launch=launch,
        apogee=(apogee_t, summary[1, 0], summary[2, 0]) if np.isfinite(apogee_t) else None,
        impact=impact,
        rhs_evaluations=int(counts[0, 0]),
        steps=int(counts[1, 0]),
        max_time_s=max_time_s,
        rtol=rtol,
    )


def simulate_3dof_batch(
    launches, *, rtol: float = 1e-9, max_time_s: float = 3000.0
) -> pd.DataFrame:
    """Many 3DOF launches: ``launches`` is a :class:`~harp_analysis.models.launch.Launches` or a
    sequence of :class:`~harp_analysis.models.launch.Launch` sharing one projectile, atmosphere,
    Earth rotation and site altitude (e.g. ``[launch.but(elevation_deg=e) for e in elevations]``).
    One row per launch: its elevation, speed, bearing and latitude, and the metadata keys of
    :func:`simulate_3dof` (but ``engine`` and ``launch``, and ``rhs_evaluations``, the batch's
    total, which are in ``frame.attrs``). Same physics and integrator as :func:`simulate_3dof`.

    Parameters
    ----------
    launches : Launches or sequence of Launch
        The launches, flown together in one compiled call.
    rtol : float
        The integrator's relative tolerance.
    max_time_s : float
        The longest flight (s); launches cut off here warn once (TruncatedFlightWarning), and
        their row's ``stop_reason`` is "max_time".

    Returns
    -------
    pandas.DataFrame
        One row per launch, in order, in SI units: the launch's ``elevation_deg``,
        ``speed_m_s``, ``bearing_deg`` and ``latitude_deg``, then the fields of
        :class:`Flights` but the end state (apogee, time of flight, range, cross range, impact
        speed, ``impact`` and ``stop_reason``, the work it took); the engine, projectile, the
        batch's total ``rhs_evaluations`` and ``rtol`` in ``frame.attrs``.
    """
    launches = Launches.from_launches(launches)
    flights = fly_3dof(launches, rtol=rtol, max_time_s=max_time_s)
    summary = pd.DataFrame(
        {
            **{
                name: np.array(getattr(launches, name))
                for name in ("elevation_deg", "speed_m_s", "bearing_deg", "latitude_deg")
            },
            **{name: getattr(flights, name) for name in Flights._fields[:-2]},
        }
    )
    missed = int((~flights.impact).sum())
    if missed:
        warnings.warn(
            f"{missed} of {len(summary)} 3DOF launches did not return to the ground "
            f"within max_time_s = {max_time_s:g} s",
            TruncatedFlightWarning,
            stacklevel=2,
        )
    summary.attrs.update(
        engine="3DOF",
        projectile=launches.projectile.name,
        rhs_evaluations=int(flights.rhs_evaluations.sum()),
        rtol=rtol,
    )
    return summary
