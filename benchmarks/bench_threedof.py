"""The 3DOF's speed against references measured in the same run (``make benchmark``).

The launch is Chapter 4's baseline cone at 45 deg (two-segment air, eq 4.8 drag), flown to
impact. References, each flying the same physics at the same tolerance (rtol 1e-9):

- a compiled reference: a lean numba DOP853 written here (the same tableau and error norm, the
  apogee and impact found by secant iterations on single steps), with none of the engine's
  events, breakpoints, records or validation: the floor the engine's overheads stand on;
- scipy's ``solve_ivp`` (DOP853, events) with a right-hand side in plain ``math``.

Targets (issue 15): one trajectory within 3x of the compiled reference, a batch within 1.5x of
it per launch at N >= 1000. Printed: the ratios, the apogee error against a tight reference, the
growth of the time per launch from 1 to 10,000 launches with peak memory, and the cold start
(compilation of one atmosphere and drag law into an empty cache, in a fresh process).
"""

import math

import numpy as np
from measure import best_of, cold_start_s, peak_memory_bytes, verdict
from numba import njit
from scipy.integrate import DOP853, solve_ivp

from harp_analysis import threedof
from harp_analysis.launch import baseline_chapter_4

RADIUS, GM = 6_378_000.0, 3.986004418e14
AREA_OVER_2M = 0.008 / (2 * 11.6)
A, B, C, E3, E5 = (
    np.ascontiguousarray(x, dtype=float)
    for x in (DOP853.A[:12, :12], DOP853.B, DOP853.C, DOP853.E3, DOP853.E5)
)
FLOOR = np.array([RADIUS] * 3 + [1e3] * 3)


@njit(cache=True)
def reference_derivative(y, out):
    r = math.sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2])
    altitude = r - RADIUS
    if altitude > 10_769.0:
        density = 0.37454745 * math.exp(-0.00015682 * (altitude - 10_769.0))
        sound = 295.92987
    else:
        density = 1.22581 * (1.0 - 0.00002257 * altitude) ** 4.256
        sound = 14.9390 * math.sqrt(518.4 - 0.01170 * altitude)
    speed = math.sqrt(y[3] * y[3] + y[4] * y[4] + y[5] * y[5])
    cd = 0.077 * math.exp(-0.38 * speed / sound) + 0.014
    drag = AREA_OVER_2M * density * cd * speed
    gravity = -GM / (r * r * r)
    for i in range(3):
        out[i] = y[3 + i]
        out[3 + i] = gravity * y[i] - drag * y[3 + i]


@njit(cache=True)
def reference_step(y, h, k, out):
    """One DOP853 step of ``h`` from ``y`` into ``out``; returns the error norm."""
    work = np.empty(6)
    reference_derivative(y, k[0])
    for s in range(1, 12):
        for i in range(6):
            total = 0.0
            for j in range(s):
                total += A[s, j] * k[j, i]
            work[i] = y[i] + h * total
        reference_derivative(work, k[s])
    for i in range(6):
        total = 0.0
        for j in range(12):
            total += B[j] * k[j, i]
        out[i] = y[i] + h * total
    reference_derivative(out, k[12])
    err5 = err3 = 0.0
    for i in range(6):
        scale = 1e-9 * max(abs(y[i]), abs(out[i]), FLOOR[i])
        five = three = 0.0
        for j in range(13):
            five += E5[j] * k[j, i]
            three += E3[j] * k[j, i]
        err5 += (five / scale) ** 2
        err3 += (three / scale) ** 2
    denominator = err5 + 0.01 * err3 if err5 + err3 > 0 else 1.0
    return h * err5 / math.sqrt(denominator * 6)


@njit(cache=True)
def radial(y):
    return y[0] * y[3] + y[1] * y[4] + y[2] * y[5]


@njit(cache=True)
def height(y):
    return math.sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]) - RADIUS


@njit(cache=True)
def event_time(kind, t, y, h, k):
    """Secant iterations on single steps from (t, y) for the zero of the event ``kind``."""
    out = np.empty(6)
    low, high = 0.0, h
    g_low = radial(y) if kind == 0 else height(y)
    reference_step(y, high, k, out)
    g_high = radial(out) if kind == 0 else height(out)
    for _ in range(20):
        middle = high - g_high * (high - low) / (g_high - g_low)
        reference_step(y, middle, k, out)
        g = radial(out) if kind == 0 else height(out)
        low, g_low, high, g_high = high, g_high, middle, g
        if abs(high - low) < 1e-10:
            break
    return t + high, out


@njit(cache=True)
def reference_flight(y0):
    """Apogee altitude and time, impact time: the lean compiled reference."""
    k = np.empty((13, 6))
    y, out = y0.copy(), np.empty(6)
    t, h = 0.0, 0.05
    apogee_t, apogee_altitude = math.nan, math.nan
    while True:
        error = reference_step(y, h, k, out)
        factor = min(max(0.9 * max(error, 1e-10) ** (-1.0 / 8.0), 0.2), 5.0)
        if error > 1.0:
            h *= min(factor, 1.0)
            continue
        if math.isnan(apogee_t) and radial(y) > 0 >= radial(out):
            apogee_t, top = event_time(0, t, y, h, k)
            apogee_altitude = height(top)
        if t > 0 and height(out) <= 0 < height(y):
            impact_t, _ = event_time(1, t, y, h, k)
            return apogee_altitude, apogee_t, impact_t
        t += h
        y[:] = out
        h = min(h * factor, 20.0)


def math_derivative(t, y):
    out = np.empty(6)
    reference_derivative.py_func(y, out)
    return out


def apogee_event(t, y):
    return radial.py_func(y)


def impact_event(t, y):
    return height.py_func(y) if t > 1e-3 else 1.0


apogee_event.direction = -1
impact_event.terminal, impact_event.direction = True, -1


def scipy_flight(y0):
    return solve_ivp(
        math_derivative,
        (0.0, 3000.0),
        y0,
        method="DOP853",
        rtol=1e-9,
        atol=1e-9 * FLOOR,
        events=(apogee_event, impact_event),
    )


COLD_START = (  # the compilation of one pair of atmosphere and drag law (make compiles all ten)
    "import time; t = time.perf_counter(); from harp_analysis import threedof; "
    "from harp_analysis.launch import baseline_chapter_4; "
    "threedof.fly_3dof(baseline_chapter_4(45.0)); print(time.perf_counter() - t)"
)


def main():
    launch = baseline_chapter_4(45.0)
    tight = threedof.simulate_3dof(launch, rtol=1e-13).attrs["apogee_altitude_m"]
    y0 = threedof._batch([launch]).y0[:, 0].copy()
    reference_flight(y0)
    threedof.fly_3dof(launch)

    engine = threedof.fly_3dof(launch)
    altitude, _, _ = reference_flight(y0)
    scipy_altitude = height.py_func(scipy_flight(y0).y_events[0][0])
    times = {
        "engine (fly_3dof)": best_of(lambda: threedof.fly_3dof(launch), repeat=20),
        "engine's table (simulate_3dof)": best_of(lambda: threedof.simulate_3dof(launch), 10),
        "compiled reference": best_of(lambda: reference_flight(y0), repeat=20),
        "scipy solve_ivp DOP853, math RHS": best_of(lambda: scipy_flight(y0), repeat=2),
    }
    errors = {
        "engine (fly_3dof)": engine.apogee_altitude_m[0] - tight,
        "engine's table (simulate_3dof)": engine.apogee_altitude_m[0] - tight,
        "compiled reference": altitude - tight,
        "scipy solve_ivp DOP853, math RHS": scipy_altitude - tight,
    }
    reference = times["compiled reference"]
    print("3DOF, baseline cone at 45 deg to impact, rtol 1e-9")
    print(f"{'':34} {'time (us)':>10} {'/ reference':>12} {'apogee error (m)':>17}")
    for name, seconds in times.items():
        print(
            f"{name:34} {seconds * 1e6:>10.1f} {seconds / reference:>12.2f} {errors[name]:>17.2e}"
        )
    ratio = times["engine (fly_3dof)"] / reference
    print(
        "target: one trajectory within 3x of the compiled reference: "
        f"{ratio:.2f}x, {verdict(ratio, 3.0)}"
    )

    print("\nbatch of N launches (20-85 deg): time per launch and peak memory")
    print(f"{'N':>6} {'engine (us)':>12} {'reference (us)':>15} {'ratio':>6} {'peak (MiB)':>11}")
    for n in (1, 10, 100, 1_000, 10_000):
        launches = [launch.but(elevation_deg=e) for e in np.linspace(20.0, 85.0, n)]
        states = threedof._batch(launches).y0
        repeat = 3 if n < 10_000 else 1
        ours = best_of(lambda: threedof.simulate_3dof_batch(launches), repeat) / n

        def loop(states=states):
            for i in range(states.shape[1]):
                reference_flight(np.ascontiguousarray(states[:, i]))

        theirs = best_of(loop, repeat) / n
        peak = peak_memory_bytes(lambda: threedof.simulate_3dof_batch(launches)) / 2**20
        note = " (target 1.5x)" if n >= 1_000 else ""
        print(
            f"{n:>6} {ours * 1e6:>12.1f} {theirs * 1e6:>15.1f} {ours / theirs:>6.2f} "
            f"{peak:>11.2f}{note}"
        )
    print(
        f"\ncold start (import, compile one atmosphere and drag law, first flight): "
        f"{cold_start_s(COLD_START):.1f} s"
    )


if __name__ == "__main__":
    main()
