"""The 3DOF's speed against a lean reference measured in the same run (``make benchmark``;
``--smoke`` for a quick check that every path runs and the reference agrees).

The launch is Chapter 4's baseline cone at 45 deg (two-segment air, eq 4.8 drag, no wind, a
non-rotating Earth), flown to impact at rtol 1e-9. The reference is a lean numba DOP853 written
here, independent of the package's code: the same physics, the same error scale
(rtol max(|y|, |y_new|, floor)), the same outputs (the apogee's time, altitude and ground range;
the impact's time, range, cross range, speed and state), and no more work than that needs:

- scipy's DOP853 tableau, error norm and step control (SAFETY 0.9, MIN_FACTOR 0.2, MAX_FACTOR
  10, no growth right after a rejection), Hairer's starting step (scipy's
  ``select_initial_step``) and the package's 20 s cap on the step (on the long steps of the
  vacuum arc the interpolant below would lose centimetres at the apogee);
- the air's 10.769 km breakpoint: there the density jumps by 0.05 %, and a Runge-Kutta step
  whose stages straddle it takes an O(h) error that the step control can only reject away. So
  each step flies one layer's formulas, chosen at its start, and a trial step that would end
  beyond the breakpoint is cut to end on it (the package cuts such steps a little short of it
  and carries the state across on the step's interpolant, its right-hand side picking the
  layer by altitude);
- the apogee and the impact located on each step's quintic Hermite interpolant (from both ends'
  positions, velocities and accelerations, free with DOP853's last stage) by Illinois
  iterations, with no step re-integrated;
- none of the engine's validation, records, tables or general models (wind, rotation, day air).

Both count their right-hand-side evaluations; both are checked against two tight references,
the package and the lean reference at rtol 1e-13. Scipy's ``solve_ivp`` (DOP853, events, a
right-hand side in plain ``math``) is shown for scale. Targets: ``fly_3dof`` one trajectory
within 1.5x of the lean reference, a batch within 1.2x per launch at N >= 1000, the table
(``simulate_3dof``) within 3x; a Launch built or changed in 10 us. Also printed: the growth of
the time per launch from 1 to 10,000 launches with peak memory, and the cold start
(compilation of one atmosphere and drag law into an empty cache, in a fresh process: a first
flight within 15 s).
"""

import math

import numpy as np
from measure import (
    agree,
    cold_start_s,
    interleaved_best,
    peak_memory_bytes,
    smoke_requested,
    verdict,
)
from numba import njit
from scipy.integrate import DOP853, solve_ivp

from harp_analysis.engines import threedof
from harp_analysis.models.launch import Launch, baseline_chapter_4

RADIUS_M, GM_M3_S2 = 6_378_000.0, 3.986004418e14
AREA_OVER_2M = 0.008 / (2 * 11.6)  # the baseline cone: base area 0.008 m^2, 11.6 kg
# Where the two-segment air's formulas meet: the density jumps there by 0.05 % (0.37473 below,
# 0.37455 kg/m^3 above), which a Runge-Kutta step straddling it feels as an O(h) error. Each
# step flies one layer's formulas, chosen at its start (the layer it moves into when it starts
# within BAND_M of the jump); a trial step that ends beyond the band is cut to end on the jump.
KINK_M, BAND_M = 10_769.0, 0.01
SPEED_M_S, ELEVATION_DEG = 2157.0, 45.0
RTOL, TIGHT_RTOL, T_END_S, MAX_STEP_S = 1e-9, 1e-13, 3000.0, 20.0
# scipy's DOP853 tableau (its nodes C unused: the equations do not depend on the time)
A, B, E3, E5 = (
    np.ascontiguousarray(x, dtype=float)
    for x in (DOP853.A[:12, :12], DOP853.B, DOP853.E3, DOP853.E5)
)
FLOOR = np.array([RADIUS_M] * 3 + [1e3] * 3)  # the error scale's floor: m, m/s
SAFETY, MIN_FACTOR, MAX_FACTOR, EXPONENT = 0.9, 0.2, 10.0, -1.0 / 8.0  # scipy's DOP853
RADIAL_VELOCITY, ALTITUDE = 0, 1
# The reference's outputs per launch, columns of its table.
OUTPUTS = (
    "apogee_time_s",
    "apogee_altitude_m",
    "apogee_ground_range_m",
    "time_of_flight_s",
    "range_m",
    "cross_range_m",
    "impact_speed_m_s",
    "rhs_evaluations",
)
END = len(OUTPUTS)  # then the impact's state (6)

# The agreement every run checks: each flight at rtol 1e-9, and the two tight references, must
# agree with the package's tight flight this closely, and the batch's engine with the lean
# reference. Over 20-85 deg the engine's worst errors are 3.7 mm, 5.6 us and 9.5 mm (the lean
# reference's 0.12 mm, 5.5 us and 3.6 mm): a third of these.
AGREEMENT = {"apogee_altitude_m": 0.01, "time_of_flight_s": 2e-5, "range_m": 0.03}


@njit(cache=True)
def event(kind, level, y):
    """r.v (zero at the apogee), or the altitude minus ``level``."""
    if kind == RADIAL_VELOCITY:
        return y[0] * y[3] + y[1] * y[4] + y[2] * y[5]
    return math.sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]) - RADIUS_M - level


@njit(cache=True)
def derivative(y, upper, k, row):
    """y' = [velocity, gravity + drag] into ``k[row]``: eq 2.1 air if ``upper`` else eq 2.2,
    eq 4.8 drag."""
    r = math.sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2])
    altitude = r - RADIUS_M
    if upper:
        density = 0.37454745 * math.exp(-0.00015682 * (altitude - KINK_M))
        sound = 295.92987
    else:
        density = 1.22581 * (1.0 - 0.00002257 * altitude) ** 4.256
        sound = 14.9390 * math.sqrt(518.4 - 0.01170 * altitude)
    speed = math.sqrt(y[3] * y[3] + y[4] * y[4] + y[5] * y[5])
    drag = AREA_OVER_2M * density * (0.077 * math.exp(-0.38 * speed / sound) + 0.014) * speed
    gravity = -GM_M3_S2 / (r * r * r)
    for i in range(3):
        k[row, i] = y[3 + i]
        k[row, 3 + i] = gravity * y[i] - drag * y[3 + i]


@njit(cache=True)
def upper_layer(y):
    """Whether a step from ``y`` flies eq 2.1's layer: above the jump, or within BAND_M below it
    and rising (within BAND_M above it and falling is below)."""
    rising = y[0] * y[3] + y[1] * y[4] + y[2] * y[5] > 0
    return event(ALTITUDE, KINK_M, y) + (BAND_M if rising else -BAND_M) > 0


@njit(cache=True)
def hermite(h, y0, y1, k, s, out):
    """The quintic Hermite interpolant at fraction ``s`` of a step of ``h`` from ``y0`` to
    ``y1``, whose derivatives are ``k[0]`` and ``k[12]``: position and velocity into ``out``."""
    s2 = s * s
    s3 = s2 * s
    # the basis of p0, h v0, h^2 a0, h^2 a1, h v1 and p1 (positions), and its derivative
    p0, p5 = 1 - s3 * (10 - 15 * s + 6 * s2), s3 * (10 - 15 * s + 6 * s2)
    p1, p4 = s - s3 * (6 - 8 * s + 3 * s2), -s3 * (4 - 7 * s + 3 * s2)
    p2, p3 = 0.5 * s2 * (1 - s) ** 3, 0.5 * s3 * (1 - s) ** 2
    d5 = 30 * s2 * (1 - s) ** 2
    d1, d4 = 1 - s2 * (18 - 32 * s + 15 * s2), -s2 * (12 - 28 * s + 15 * s2)
    d2, d3 = s * (1 - s) ** 2 * (1 - 2.5 * s), s2 * (1.5 - 4 * s + 2.5 * s2)
    for i in range(3):
        v0, v1 = h * y0[3 + i], h * y1[3 + i]
        a0, a1 = h * h * k[0, 3 + i], h * h * k[12, 3 + i]
        out[i] = p0 * y0[i] + p1 * v0 + p2 * a0 + p3 * a1 + p4 * v1 + p5 * y1[i]
        out[3 + i] = (d5 * (y1[i] - y0[i]) + d1 * v0 + d2 * a0 + d3 * a1 + d4 * v1) / h


@njit(cache=True)
def crossing(kind, level, h, y0, y1, k, out):
    """The fraction of the step where the event changes sign, by Illinois iterations on the
    interpolant (to 1e-13 of the step), and the state there into ``out``."""
    low, high = 0.0, 1.0
    g_low, g_high = event(kind, level, y0), event(kind, level, y1)
    s, side = 0.5, 0
    for _ in range(30):
        previous = s
        s = (low * g_high - high * g_low) / (g_high - g_low)
        hermite(h, y0, y1, k, s, out)
        g = event(kind, level, out)
        if (g > 0) == (g_low > 0):
            low, g_low = s, g
            g_high *= 0.5 if side == 1 else 1.0
            side = 1
        else:
            high, g_high = s, g
            g_low *= 0.5 if side == -1 else 1.0
            side = -1
        if abs(s - previous) < 1e-13:
            break
    return s


@njit(cache=True)
def rms_scaled(values, scale):
    """The root mean square of ``values / scale`` (6,): scipy's norm."""
    total = 0.0
    for i in range(6):
        total += (values[i] / scale[i]) ** 2
    return math.sqrt(total / 6)


@njit(cache=True)
def fly(speed, elevation, rtol, out):
    """One flight to impact into ``out`` (the columns of OUTPUTS, then the impact's state)."""
    k, y, y_new = np.empty((13, 6)), np.zeros(6), np.empty(6)
    work, scale = np.empty(6), np.empty(6)
    y[0], y[3], y[4] = RADIUS_M, speed * math.sin(elevation), speed * math.cos(elevation)
    upper = upper_layer(y)
    derivative(y, upper, k, 0)
    for i in range(6):  # Hairer's starting step (scipy's select_initial_step)
        scale[i] = rtol * max(abs(y[i]), FLOOR[i])
    d0, d1 = rms_scaled(y, scale), rms_scaled(k[0], scale)
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    for i in range(6):
        work[i] = y[i] + h0 * k[0, i]
    derivative(work, upper, k, 1)
    for i in range(6):
        work[i] = k[1, i] - k[0, i]
    d2 = rms_scaled(work, scale) / h0
    h1 = max(1e-6, h0 * 1e-3) if max(d1, d2) <= 1e-15 else (0.01 / max(d1, d2)) ** (1 / 8)
    h, t, evaluations, rejected = min(100 * h0, h1, T_END_S), 0.0, 2, False
    out[:] = math.nan
    while t < T_END_S:
        h = min(h, T_END_S - t, MAX_STEP_S)
        for stage in range(1, 13):  # the last is the solution's, at t + h
            state = work if stage < 12 else y_new
            for i in range(6):
                total = 0.0
                for j in range(stage):
                    total += (A[stage, j] if stage < 12 else B[j]) * k[j, i]
                state[i] = y[i] + h * total
            derivative(state, upper, k, stage)
        evaluations += 12
        err5 = err3 = 0.0
        for i in range(6):
            scale[i] = rtol * max(abs(y[i]), abs(y_new[i]), FLOOR[i])
            five = three = 0.0
            for j in range(13):
                five += E5[j] * k[j, i]
                three += E3[j] * k[j, i]
            err5 += (five / scale[i]) ** 2
            err3 += (three / scale[i]) ** 2
        error = 0.0 if err5 == 0 and err3 == 0 else h * err5 / math.sqrt((err5 + 0.01 * err3) * 6)
        cut = math.inf  # the step that ends on the jump, if this one goes beyond its band
        beyond = event(ALTITUDE, KINK_M, y_new)
        if (beyond < -BAND_M if upper else beyond > BAND_M) and (
            (event(ALTITUDE, KINK_M, y) > 0) != (beyond > 0)
        ):
            cut = crossing(ALTITUDE, KINK_M, h, y, y_new, k, work) * h
        if not error <= 1.0:
            if not math.isfinite(error):
                break
            h, rejected = min(h * max(MIN_FACTOR, SAFETY * error**EXPONENT), cut), True
            continue
        if cut < h:  # not an error's rejection: the step control goes on from the cut step
            h = cut
            continue
        factor = MAX_FACTOR if error == 0 else min(MAX_FACTOR, SAFETY * error**EXPONENT)
        if rejected:
            factor = min(1.0, factor)
        if math.isnan(out[0]) and (
            event(RADIAL_VELOCITY, 0.0, y) > 0 >= event(RADIAL_VELOCITY, 0.0, y_new)
        ):
            out[0] = t + crossing(RADIAL_VELOCITY, 0.0, h, y, y_new, k, work) * h
            out[1] = event(ALTITUDE, 0.0, work)
            out[2] = RADIUS_M * math.atan2(work[1], work[0])
        if t + h > 1e-6 and event(ALTITUDE, 0.0, y) > 0 >= event(ALTITUDE, 0.0, y_new):
            out[3] = t + crossing(ALTITUDE, 0.0, h, y, y_new, k, work) * h
            radius = RADIUS_M + event(ALTITUDE, 0.0, work)
            out[4] = RADIUS_M * math.atan2(work[1], work[0])  # launched east from (R, 0, 0)
            out[5] = RADIUS_M * math.asin(-work[2] / radius)  # right of the line of fire: -z
            out[6] = math.sqrt(work[3] * work[3] + work[4] * work[4] + work[5] * work[5])
            out[END:] = work
            break
        t += h
        h, rejected = h * factor, False
        for i in range(6):
            y[i], k[0, i] = y_new[i], k[12, i]
        if upper_layer(y) != upper:  # on the jump: the next step's y' is the other layer's
            upper = not upper
            derivative(y, upper, k, 0)
            evaluations += 1
    out[7] = evaluations


@njit(cache=True)
def reference_flights(speed, elevations, rtol, out):
    """:func:`fly` for every elevation (rad) into the rows of ``out`` (n, COLUMNS)."""
    for i in range(elevations.size):
        fly(speed, elevations[i], rtol, out[i])
    return out


COLUMNS = END + 6


def check_same_launch(launch: Launch) -> None:
    """The reference hard-codes the physics of ``launch``: fail if the package's launch moved."""
    projectile, law = launch.projectile, launch.projectile.drag_law
    same = (
        launch.atmosphere == "two_segment"
        and projectile.reference_area_m2 / (2 * projectile.mass_kg) == AREA_OVER_2M
        and (law.a, law.b, law.c) == (0.077, -0.38, 0.014)
        and launch.speed_m_s == SPEED_M_S
        and not launch.has_wind
        and not launch.has_day_air
        and launch.rotation_rate_rad_s == 0.0
        and launch.site_altitude_m == 0.0
        and (launch.latitude_deg, launch.longitude_deg, launch.bearing_deg) == (0.0, 0.0, 90.0)
    )
    if not same:
        raise AssertionError(f"the reference no longer flies the package's launch: {launch}")


def scipy_flight(elevation_rad):
    """Scipy's solve_ivp (DOP853, events) on the same right-hand side run as Python."""

    def rhs(t, y):
        k = np.empty((1, 6))
        derivative.py_func(y, event.py_func(ALTITUDE, KINK_M, y) > 0, k, 0)
        return k[0]

    def apogee(t, y):
        return event.py_func(RADIAL_VELOCITY, 0.0, y)

    def impact(t, y):
        return event.py_func(ALTITUDE, 0.0, y) if t > 1e-6 else 1.0

    apogee.direction = -1
    impact.terminal, impact.direction = True, -1
    y0 = [RADIUS_M, 0.0, 0.0, SPEED_M_S * math.sin(elevation_rad)]
    y0 += [SPEED_M_S * math.cos(elevation_rad), 0.0]
    return solve_ivp(
        rhs, (0.0, T_END_S), y0, "DOP853", rtol=RTOL, atol=RTOL * FLOOR, events=(apogee, impact)
    )


def scipy_outcome(solution) -> dict:
    top, end = solution.y_events[0][0], solution.y_events[1][0]
    return {
        "apogee_altitude_m": event.py_func(ALTITUDE, 0.0, top),
        "time_of_flight_s": solution.t_events[1][0],
        "range_m": RADIUS_M * math.atan2(end[1], end[0]),
        "rhs_evaluations": solution.nfev,
    }


def column(rows, name):
    """The reference's output ``name`` over its flights (rows)."""
    return rows[:, OUTPUTS.index(name)]


def outcome(row) -> dict:
    """The checked outputs of a reference's row, a package's Flights or a table's attrs."""
    if isinstance(row, np.ndarray):
        return dict(zip(OUTPUTS, row[:END].tolist()))
    if isinstance(row, threedof.Flights):
        return {name: float(getattr(row, name)[0]) for name in (*AGREEMENT, "rhs_evaluations")}
    return row  # a table's attrs, named alike


COLD_START = (  # the compilation of one pair of atmosphere and drag law (make compiles all ten)
    "import time; t = time.perf_counter(); from harp_analysis.engines import threedof; "
    "from harp_analysis.models.launch import baseline_chapter_4; "
    "threedof.fly_3dof(baseline_chapter_4(45.0)); print(time.perf_counter() - t)"
)


def main(smoke: bool = False) -> None:
    launch = baseline_chapter_4(ELEVATION_DEG)
    check_same_launch(launch)
    elevation = np.array([launch.elevation_rad])
    one = np.empty((1, COLUMNS))
    rounds, number = (1, 1) if smoke else (30, 20)

    def lean(rtol=RTOL):
        return reference_flights(SPEED_M_S, elevation, rtol, one)[0].copy()

    results = {
        "engine (fly_3dof)": outcome(threedof.fly_3dof(launch)),
        "engine's table (simulate_3dof)": outcome(threedof.simulate_3dof(launch).attrs),
        "lean reference": outcome(lean()),
        "scipy solve_ivp DOP853, Python RHS": scipy_outcome(scipy_flight(launch.elevation_rad)),
    }
    tight = {
        "package": outcome(threedof.fly_3dof(launch, rtol=TIGHT_RTOL)),
        "lean": outcome(lean(TIGHT_RTOL)),
    }
    times = interleaved_best(
        {
            "engine (fly_3dof)": lambda: threedof.fly_3dof(launch),
            "engine's table (simulate_3dof)": lambda: threedof.simulate_3dof(launch),
            "lean reference": lean,
        },
        rounds,
        number,
    )
    times["scipy solve_ivp DOP853, Python RHS"] = interleaved_best(
        {"": lambda: scipy_flight(launch.elevation_rad)}, 1 if smoke else 2
    )[""]
    reference = times["lean reference"]
    print(
        f"3DOF, baseline cone at {ELEVATION_DEG:g} deg to impact, rtol {RTOL:g}. The lean "
        "reference: a numba DOP853 of the same physics and error scale (scipy's step control "
        "and starting step, the package's 20 s step cap, one air layer per step with steps cut "
        "at the 10.769 km breakpoint, apogee and impact on a quintic Hermite), computing the "
        "engine's outputs and nothing else."
    )
    print(
        f"Errors against the package at rtol {TIGHT_RTOL:g} (in brackets: against the lean "
        f"reference at rtol {TIGHT_RTOL:g})"
    )
    print(
        f"{'':34} {'time (us)':>9} {'/ lean':>7} {'RHS evals':>9} {'apogee altitude (m)':>21} "
        f"{'time of flight (s)':>21} {'range (m)':>21}"
    )
    for name, seconds in times.items():
        result = results[name]
        errors = " ".join(
            f"{result[key] - tight['package'][key]:>+12.1e} "
            f"({result[key] - tight['lean'][key]:+.0e})"
            for key in AGREEMENT
        )
        print(
            f"{name:34} {seconds * 1e6:>9.1f} {seconds / reference:>7.2f} "
            f"{result['rhs_evaluations']:>9.0f} {errors}"
        )
    print(
        f"{'tight: lean - package':34} {'':>9} {'':>7} "
        f"{tight['lean']['rhs_evaluations']:>5.0f}/{tight['package']['rhs_evaluations']:<3.0f} "
        + " ".join(f"{tight['lean'][key] - tight['package'][key]:>+21.1e}" for key in AGREEMENT)
    )
    for key, tolerance in AGREEMENT.items():
        agree(f"the tight references' {key}", tight["lean"][key] - tight["package"][key], tolerance)
        for name in ("engine (fly_3dof)", "engine's table (simulate_3dof)", "lean reference"):
            agree(f"{name}'s {key}", results[name][key] - tight["package"][key], tolerance)
    for name, target in (
        ("engine (fly_3dof)", 1.5),
        ("engine's table (simulate_3dof)", 3.0),
    ):
        ratio = times[name] / reference
        print(
            f"target: {name} within {target}x of the lean reference: {ratio:.2f}x, "
            f"{verdict(ratio, target)}"
        )

    launch_times = interleaved_best(
        {
            "Launch(BASELINE, 2157 m/s, 45 deg)": lambda: Launch(
                launch.projectile, SPEED_M_S, ELEVATION_DEG
            ),
            "launch.but(elevation_deg=50)": lambda: launch.but(elevation_deg=50.0),
        },
        rounds,
        10 if smoke else 2_000,
    )
    for name, seconds in launch_times.items():
        print(f"target: {name} within 10 us: {seconds * 1e6:.2f} us, {verdict(seconds, 10e-6)}")

    print(
        "\nbatch of N launches (20-85 deg): time per launch, the engine's arrays (fly_3dof) and "
        "table (simulate_3dof_batch) against the lean reference's (its kernel loops over the "
        "elevations), RHS evaluations per launch, and the engine's peak memory"
    )
    print(
        f"{'N':>6} {'fly_3dof (us)':>14} {'batch table (us)':>17} {'lean (us)':>10} "
        f"{'ratio':>6} {'table ratio':>12} {'evals':>9} {'peak (MiB)':>11}"
    )
    accuracy_n = 10 if smoke else 1_000
    for n in (1, 10) if smoke else (1, 10, 100, 1_000, 10_000):
        elevations_deg = np.linspace(20.0, 85.0, n)
        launches = [launch.but(elevation_deg=e) for e in elevations_deg]
        elevations = np.radians(elevations_deg)
        batch = {
            "fly": lambda: threedof.fly_3dof(launches),
            "table": lambda: threedof.simulate_3dof_batch(launches),
            "lean": lambda: reference_flights(SPEED_M_S, elevations, RTOL, np.empty((n, COLUMNS))),
        }
        engine, ours = batch["fly"](), batch["lean"]()
        for key, tolerance in AGREEMENT.items():
            agree(f"the batch's {key}", getattr(engine, key) - column(ours, key), tolerance)
        if n == accuracy_n:
            tight_batch = threedof.fly_3dof(launches, rtol=TIGHT_RTOL)
            accuracy = {
                who: {
                    key: agree(
                        f"the batch's {who} {key}",
                        values(key) - getattr(tight_batch, key),
                        tolerance,
                    )
                    for key, tolerance in AGREEMENT.items()
                }
                for who, values in (
                    ("engine", lambda key: getattr(engine, key)),
                    ("lean reference", lambda key: column(ours, key)),
                )
            }
        seconds = interleaved_best(batch, 1 if smoke else 2 if n >= 10_000 else 3)
        fly, table, ours_s = (seconds[name] / n for name in batch)
        evaluations = f"{engine.rhs_evaluations.mean():.0f}/{ours[:, END - 1].mean():.0f}"
        peak = peak_memory_bytes(batch["fly"]) / 2**20
        note = f"  target 1.2x: {verdict(fly / ours_s, 1.2)}" if n >= 1_000 else ""
        print(
            f"{n:>6} {fly * 1e6:>14.1f} {table * 1e6:>17.1f} {ours_s * 1e6:>10.1f} "
            f"{fly / ours_s:>6.2f} {table / ours_s:>12.2f} {evaluations:>9} {peak:>11.2f}{note}"
        )
    for who, worst in accuracy.items():
        print(
            f"{who}'s largest errors over the {accuracy_n:,} launches against the package at "
            f"rtol {TIGHT_RTOL:g}: apogee {worst['apogee_altitude_m']:.1e} m, time of flight "
            f"{worst['time_of_flight_s']:.1e} s, range {worst['range_m']:.1e} m"
        )
    if not smoke:
        cold_s = cold_start_s(COLD_START)
        print(
            f"\ncold start (import, compile one atmosphere and drag law, first flight): "
            f"{cold_s:.1f} s; target: a first flight within 15 s of an empty kernel cache: "
            f"{verdict(cold_s, 15.0)}"
        )


if __name__ == "__main__":
    main(smoke=smoke_requested())
