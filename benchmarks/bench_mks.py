"""The Modified Kepler Solution's speed against references measured in the same run
(``make benchmark``).

A million launches of Chapter 4's baseline cone at 2157 m/s, elevations 30-85 deg, each with
its own beta and tau (eqs 3.22, 3.27, computed outside the timings). References:

- the straight-line numpy code of eqs 6.4-6.10 (:func:`harp_analysis.effort.mks_apogee`, the
  operations Fig 4.7 counts), the same eq 6.4 apogee;
- a copy of the elevations: the memory-bound floor per launch.

Targets (issue 15): the class (constructed with ``warn=False``) within 1.5x of the straight-line
code per apogee at a million launches, both at eq 6.4's angle and at the first zero of
du/dtheta (Newton's iteration); a single launch (constants, apogee, impact) under 10 us. The
first zero costs eq 6.4's apogee and a second pass over the launches, in which Newton's
iteration evaluates the solution about twice a launch (an exponential and a small angle's sine
and cosine each).
Printed: the ratios, the growth of the time per launch from 1 to a million launches with
peak memory, the single launch, and the cold start (compilation into an empty cache).
"""

import numpy as np
from measure import best_of, cold_start_s, interleaved_best, peak_memory_bytes, verdict

from harp_analysis import effort, mks
from harp_analysis.launch import baseline_chapter_4

SPEED_M_S = 2157.0
SINGLE_TARGET_S = 10e-6
RATIO_TARGET = 1.5


def main():
    launch = baseline_chapter_4(45.0)
    cd0, projectile = launch.launch_drag_coefficient, launch.projectile
    mass, area = projectile.mass_kg, projectile.reference_area_m2
    mks.warm_up()

    n = 1_000_000
    elevations = np.radians(np.linspace(30.0, 85.0, n))
    rho0 = mks.gun_density_kg_m3(launch)
    beta = mks.decay_factor_beta(cd0, rho0, area, mass, elevations)
    tau = mks.decay_rate_tau(elevations)

    def solution():
        return mks.ModifiedKeplerSolution(SPEED_M_S, elevations, beta, tau, warn=False)

    functions = {
        "class, eq 6.4": lambda: solution().apogee_altitude("eq_6_4"),
        "class, first zero (Newton)": lambda: solution().apogee_altitude(),
        "straight-line numpy, eq 6.4": lambda: effort.mks_apogee(
            SPEED_M_S, elevations, cd0, mass, area
        ),
        "copy of the elevations": elevations.copy,
    }
    agreement = np.max(
        np.abs(functions["class, eq 6.4"]() / functions["straight-line numpy, eq 6.4"]() - 1)
    )
    times = interleaved_best(functions, rounds=7)
    reference = times["straight-line numpy, eq 6.4"]
    print(f"MKS apogees of {n:,} launches at once (class constructed with warn=False)")
    print(f"{'':30} {'ns/launch':>10} {'/ straight-line':>16}")
    for name, seconds in times.items():
        print(f"{name:30} {seconds / n * 1e9:>10.1f} {seconds / reference:>16.2f}")
    print(
        f"class against straight-line apogees (eq 6.4): largest relative difference {agreement:.1e}"
    )
    for name in ("class, eq 6.4", "class, first zero (Newton)"):
        ratio = times[name] / reference
        print(
            f"target: {name} within {RATIO_TARGET}x of the straight-line code: "
            f"{ratio:.2f}x, {verdict(ratio, RATIO_TARGET)}"
        )

    print("\ngrowth: construction and first-zero apogee of N launches")
    print(f"{'N':>9} {'us/launch':>10} {'peak (bytes/launch)':>20}")
    for count in (1, 10, 100, 1_000, 10_000, 100_000, 1_000_000):
        subset = np.radians(np.linspace(30.0, 85.0, count))
        subset_beta = mks.decay_factor_beta(cd0, rho0, area, mass, subset)
        subset_tau = mks.decay_rate_tau(subset)

        def apogees(subset=subset, subset_beta=subset_beta, subset_tau=subset_tau):
            return mks.ModifiedKeplerSolution(
                SPEED_M_S, subset, subset_beta, subset_tau, warn=False
            ).apogee_altitude()

        number = max(1, 20_000 // count)
        seconds = best_of(apogees, repeat=5 if count < n else 3, number=number) / count
        peak = peak_memory_bytes(apogees) / count
        print(f"{count:>9,} {seconds * 1e6:>10.3f} {peak:>20.0f}")

    solved = mks.for_launch(launch)
    numbers = (SPEED_M_S, launch.elevation_rad, solved.beta.item(), solved.tau.item())

    def single():
        one = mks.ModifiedKeplerSolution(*numbers)
        return one.apogee_altitude(), one.impact_angle

    seconds = best_of(single, repeat=7, number=2_000)
    print(
        f"\nsingle launch (numbers; construction with its validity warnings, first-zero apogee, "
        f"impact): {seconds * 1e6:.1f} us; target under {SINGLE_TARGET_S * 1e6:.0f} us: "
        f"{verdict(seconds, SINGLE_TARGET_S)}"
    )
    cold = cold_start_s(
        "import time; t = time.perf_counter(); from harp_analysis import mks; "
        "mks.warm_up(); print(time.perf_counter() - t)"
    )
    print(f"cold start (import, compile into an empty cache, warm-up): {cold:.1f} s")


if __name__ == "__main__":
    main()
