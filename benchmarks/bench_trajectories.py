"""Time per trajectory of the simulation engines, measured in one run.

3DOF: the baseline cone at 45 deg, one trajectory at several tolerances (with its apogee error
against a tight reference, so "fast" is also "converged") and a batch of 1,000 launches; 6DOF:
one HP and one LP flight to impact. Run: `make benchmark`.
"""

import time

import numpy as np

from harp_analysis import sixdof, threedof
from harp_analysis.launch import HP_CHAPTER_2, LP_CHAPTER_2, baseline_chapter_4


def best_of(function, repeat=5):
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        result = function()
        times.append(time.perf_counter() - start)
    return min(times), result


def main():
    baseline = baseline_chapter_4(45.0)
    reference = threedof.simulate_3dof(baseline, rtol=1e-13).attrs
    print("3DOF, baseline cone at 45 deg, one trajectory (table every 0.5 s)")
    print(f"{'rtol':>8} {'time (ms)':>10} {'steps':>6} {'RHS':>6} {'apogee error (m)':>17}")
    for rtol in (1e-8, 1e-9, 1e-10):
        seconds, flight = best_of(lambda: threedof.simulate_3dof(baseline, rtol=rtol))
        error = abs(flight.attrs["apogee_altitude_m"] - reference["apogee_altitude_m"])
        print(
            f"{rtol:>8.0e} {seconds * 1e3:>10.1f} {flight.attrs['steps']:>6} "
            f"{flight.attrs['rhs_evaluations']:>6} {error:>17.3f}"
        )

    elevations = np.linspace(20.0, 85.0, 1000)
    seconds, batch = best_of(
        lambda: threedof.simulate_3dof_batch(
            [baseline.but(elevation_deg=e) for e in elevations], rtol=1e-9
        ),
        repeat=2,
    )
    single, _ = best_of(lambda: threedof.simulate_3dof_batch(baseline, rtol=1e-9))
    print(
        f"\n3DOF batch of {elevations.size} launches (20-85 deg, rtol 1e-9): "
        f"{seconds:.2f} s, {seconds / elevations.size * 1e3:.2f} ms per launch, "
        f"{single / (seconds / elevations.size):.0f}x faster per launch than one at a time; "
        f"steps per launch {batch.steps.min()}-{batch.steps.max()}"
    )

    print("\n6DOF (no-roll frame, DOP853 rtol 1e-9), 50 deg, 2022 m/s, 5 m/s cross wind")
    for launch in (HP_CHAPTER_2, LP_CHAPTER_2):
        seconds, flight = best_of(lambda: sixdof.simulate_6dof(launch), repeat=2)
        print(
            f"{launch.projectile.name}: {seconds:.2f} s, {flight.attrs['steps']} steps, "
            f"{flight.attrs['rhs_evaluations']} RHS evaluations; {seconds / single:.0f}x one 3DOF"
        )


if __name__ == "__main__":
    main()
