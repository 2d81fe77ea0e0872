"""The Modified Kepler Solution's speed against references measured in the same run
(``make benchmark``; ``--smoke`` for a quick check that every path runs and agrees).

A million launches of Chapter 4's baseline cone at 2157 m/s, elevations 30-85 deg, each with
its own beta and tau (eqs 3.22, 3.27). The references are straight-line numpy of the same
three-term MKS (eqs 6.6-6.10, 6.13, 6.14):

- at eq 6.4's angle, :func:`harp_analysis.analyses.effort.mks_apogee` (the operations Fig 4.7
  counts), which computes beta and tau itself, and the same code handed them
  (:func:`handed_apogee`);
- at the first zero of du/dtheta, one Newton step from eq 6.4's angle (:func:`first_zero`; the
  zero lies so near eq 6.4's angle on these launches that one step converges to 1e-16 rad);
- a copy of the elevations: the memory-bound floor per launch.

Each is paired with the class (constructed with ``warn=False``) counted alike: both handed
beta and tau, or both computing them inside the timing (the class through
:func:`mks.decay_factor_beta` and :func:`mks.decay_rate_tau`). Targets: the class per apogee
at a million launches within 1.3x of the straight-line code at eq 6.4 (issue 36), and within
1.5x of it at the first zero (Newton's iteration), in both pairings; a single launch
(constants, apogee, impact) under 10 us; the moonshot, an apogee in 20 ns. Printed: the ratios,
the agreement of each reference with the class, where the class's time goes (its constants'
kernel alone, and the first touch of the memory it holds), the growth of the time per launch
from 1 to a million launches with peak memory, the single launch, and the cold start
(compilation into an empty cache).
"""

import numpy as np
from measure import (
    agree,
    best_of,
    cold_start_s,
    interleaved_best,
    peak_memory_bytes,
    smoke_requested,
    verdict,
)

from harp_analysis.analyses import effort
from harp_analysis.engines import mks
from harp_analysis.foundation import earth
from harp_analysis.models.atmosphere import SEA_LEVEL_DENSITY_KG_M3, TEXT_DECAY_CONSTANT_PER_M
from harp_analysis.models.launch import Launches, baseline_chapter_4
from harp_analysis.models.projectiles import BASELINE

SPEED_M_S = 2157.0
SINGLE_TARGET_S, MOONSHOT_S = 10e-6, 20e-9
TARGETS = {"eq 6.4": 1.3, "first zero": 1.5}  # the first zero by Newton's iteration
# The references and the class round differently (the class writes the conic about eq 6.4's
# angle): their apogees agree to this share of the altitude, a hundred times what they differ.
AGREEMENT = 1e-9


def conic_constants(speed, sin_phi, cos_phi, beta, tau, r0=earth.RADIUS_M, gm=earth.GM_M3_S2):
    """c1 ... c5 of the three-term MKS (eqs 6.13, 6.14, 6.6-6.10), as effort.mks_apogee."""
    h_inf = speed * r0 * cos_phi * np.exp(-beta)
    c3 = gm / (h_inf * h_inf)
    c4 = -2 * beta * c3 / (1 + tau * tau)
    c5 = 2 * beta * beta * c3 / (1 + 4 * tau * tau)
    c1 = -sin_phi / (cos_phi * r0) + tau * c4 + 2 * tau * c5
    c2 = 1 / r0 - c3 - c4 - c5
    return c1, c2, c3, c4, c5


def handed_apogee(speed, elevation, beta, tau, r0=earth.RADIUS_M):
    """effort.mks_apogee handed beta and tau: eq 6.4's apogee altitude (m)."""
    c1, c2, c3, c4, c5 = conic_constants(speed, np.sin(elevation), np.cos(elevation), beta, tau)
    decay = np.exp(-tau * np.arctan(c1 / c2))
    u = c3 - np.sqrt(c1 * c1 + c2 * c2) + c4 * decay + c5 * decay * decay
    return 1 / u - r0


def first_zero(speed, elevation, beta, tau, r0=earth.RADIUS_M):
    """The apogee altitude (m) at the first zero of du/dtheta: one Newton step from eq 6.4's
    angle (on these launches the next would move it by less than 1e-16 rad)."""
    c1, c2, c3, c4, c5 = conic_constants(speed, np.sin(elevation), np.cos(elevation), beta, tau)
    theta = np.arctan(c1 / c2)
    sin, cos, decay = np.sin(theta), np.cos(theta), np.exp(-tau * theta)
    slope = c1 * cos - c2 * sin - tau * decay * (c4 + 2 * c5 * decay)
    curvature = -c1 * sin - c2 * cos + tau * tau * decay * (c4 + 4 * c5 * decay)
    theta = theta - slope / curvature
    decay = np.exp(-tau * theta)
    u = c1 * np.sin(theta) + c2 * np.cos(theta) + c3 + decay * (c4 + c5 * decay)
    return 1 / u - r0


def main(smoke: bool = False) -> None:
    launch = baseline_chapter_4(45.0)
    cd0, projectile = launch.launch_drag_coefficient, launch.projectile
    mass, area = projectile.mass_kg, projectile.reference_area_m2
    rho0 = mks.gun_density_kg_m3(launch)
    if rho0 != SEA_LEVEL_DENSITY_KG_M3:  # effort.mks_apogee's rho0, which the class must share
        raise AssertionError(f"the launch's rho0 {rho0} is not effort.mks_apogee's")
    mks.warm_up()

    n = 1_000 if smoke else 1_000_000
    elevations = np.radians(np.linspace(30.0, 85.0, n))
    beta = mks.decay_factor_beta(cd0, rho0, area, mass, elevations)
    tau = mks.decay_rate_tau(elevations)

    def solution(beta, tau):
        return mks.ModifiedKeplerSolution(SPEED_M_S, elevations, beta, tau, warn=False)

    def computed():
        """beta and tau as the class's callers compute them (eqs 3.22, 3.27)."""
        return mks.decay_factor_beta(cd0, rho0, area, mass, elevations), mks.decay_rate_tau(
            elevations
        )

    def computing_first_zero():
        """first_zero computing beta and tau as effort.mks_apogee does (one sine, one cosine)."""
        sin_phi, cos_phi = np.sin(elevations), np.cos(elevations)
        k = TEXT_DECAY_CONSTANT_PER_M
        computed_beta = cd0 * rho0 * area / (2 * k * mass * sin_phi)
        return first_zero(
            SPEED_M_S, elevations, computed_beta, k * earth.RADIUS_M * sin_phi / cos_phi
        )

    pairings = {
        "handed beta and tau": {
            "class, eq 6.4": lambda: solution(beta, tau).apogee_altitude("eq_6_4"),
            "class, first zero": lambda: solution(beta, tau).apogee_altitude(),
            "straight-line numpy, eq 6.4": lambda: handed_apogee(SPEED_M_S, elevations, beta, tau),
            "straight-line numpy, first zero": lambda: first_zero(SPEED_M_S, elevations, beta, tau),
        },
        "computing beta and tau": {
            "class, eq 6.4": lambda: solution(*computed()).apogee_altitude("eq_6_4"),
            "class, first zero": lambda: solution(*computed()).apogee_altitude(),
            "straight-line numpy, eq 6.4": lambda: effort.mks_apogee(
                SPEED_M_S, elevations, cd0, mass, area
            ),
            "straight-line numpy, first zero": computing_first_zero,
        },
    }
    results = {
        (pairing, name): function()
        for pairing, cases in pairings.items()
        for name, function in cases.items()
    }
    print(
        f"MKS apogees of {n:,} launches at once (the class constructed with warn=False). "
        "References: straight-line numpy of the same three-term MKS, at eq 6.4's angle "
        "(effort.mks_apogee, Fig 4.7's count; and it handed beta and tau) and at the first zero "
        "of du/dtheta (one Newton step from eq 6.4's angle)."
    )
    apogee = results["handed beta and tau", "class, first zero"]
    for pairing in pairings:
        for method in TARGETS:
            largest = agree(
                f"{pairing}: straight-line {method} against the class",
                results[pairing, f"straight-line numpy, {method}"]
                / results[pairing, f"class, {method}"]
                - 1,
                AGREEMENT,
            )
            print(
                f"  {pairing}, {method}: straight-line apogees against the class's, largest "
                f"relative difference {largest:.1e} ({largest * np.max(apogee) * 1e6:.1f} um)"
            )
    eq_6_4 = results["handed beta and tau", "class, eq 6.4"]
    print(
        f"  first zero - eq 6.4 apogee: {np.min(apogee - eq_6_4) * 1e9:+.0f} to "
        f"{np.max(apogee - eq_6_4) * 1e9:+.0f} nm"
    )
    functions = {
        (pairing, name): function
        for pairing, cases in pairings.items()
        for name, function in cases.items()
    }
    functions["", "copy of the elevations"] = elevations.copy
    times = interleaved_best(functions, rounds=1 if smoke else 7)
    print(f"{'ns/launch':>52} {'/ straight-line, eq 6.4':>24} {'/ straight-line, same apogee':>29}")
    for pairing, cases in pairings.items():
        print(pairing)
        reference = times[pairing, "straight-line numpy, eq 6.4"]
        for name in cases:
            seconds = times[pairing, name]
            same = times[pairing, "straight-line numpy, " + name.split(", ")[1]]
            print(
                f"  {name:36} {seconds / n * 1e9:>13.1f} {seconds / reference:>24.2f} "
                f"{seconds / same:>29.2f}"
            )
    print(f"  {'copy of the elevations':36} {times['', 'copy of the elevations'] / n * 1e9:>13.1f}")
    for pairing in pairings:
        reference = times[pairing, "straight-line numpy, eq 6.4"]
        for method, target in TARGETS.items():
            ratio = times[pairing, f"class, {method}"] / reference
            print(
                f"target ({pairing}): class, {method} within {target}x of the straight-line "
                f"code at eq 6.4: {ratio:.2f}x, {verdict(ratio, target)}"
            )
    for method in TARGETS:
        seconds = times["handed beta and tau", f"class, {method}"] / n
        print(
            f"moonshot: an apogee in {MOONSHOT_S * 1e9:.0f} ns (class, {method}, handed beta and "
            f"tau): {seconds * 1e9:.1f} ns, {verdict(seconds, MOONSHOT_S)}"
        )
    where_the_time_goes(elevations, beta, tau, times["handed beta and tau", "class, eq 6.4"], n)

    print("\ngrowth: construction and first-zero apogee of N launches, handed beta and tau")
    print(f"{'N':>9} {'us/launch':>10} {'peak (bytes/launch)':>20}")
    for count in (1, 10, 1_000) if smoke else (1, 10, 100, 1_000, 10_000, 100_000, 1_000_000):
        subset = np.radians(np.linspace(30.0, 85.0, count))
        subset_beta = mks.decay_factor_beta(cd0, rho0, area, mass, subset)
        subset_tau = mks.decay_rate_tau(subset)

        def apogees(subset=subset, subset_beta=subset_beta, subset_tau=subset_tau):
            return mks.ModifiedKeplerSolution(
                SPEED_M_S, subset, subset_beta, subset_tau, warn=False
            ).apogee_altitude()

        number = 1 if smoke else max(1, 20_000 // count)
        seconds = best_of(apogees, repeat=1 if smoke else 5 if count < n else 3, number=number)
        peak = peak_memory_bytes(apogees) / count
        print(f"{count:>9,} {seconds / count * 1e6:>10.3f} {peak:>20.0f}")

    public_api(smoke)

    solved = mks.for_launch(launch)
    numbers = (SPEED_M_S, launch.elevation_rad, solved.beta.item(), solved.tau.item())

    def single():
        one = mks.ModifiedKeplerSolution(*numbers)
        return one.apogee_altitude(), one.impact_angle

    straight_line = first_zero(SPEED_M_S, *numbers[1:])
    agree("the single launch's apogee", single()[0] / straight_line - 1, AGREEMENT)
    seconds = best_of(single, repeat=1 if smoke else 7, number=10 if smoke else 2_000)
    print(
        f"\nsingle launch (numbers; construction with its validity warnings, first-zero apogee, "
        f"impact): {seconds * 1e6:.1f} us; target under {SINGLE_TARGET_S * 1e6:.0f} us: "
        f"{verdict(seconds, SINGLE_TARGET_S)}"
    )
    if not smoke:
        cold = cold_start_s(
            "import time; t = time.perf_counter(); from harp_analysis.engines import mks; "
            "mks.warm_up(); print(time.perf_counter() - t)"
        )
        print(f"cold start (import, compile into an empty cache, warm-up): {cold:.1f} s")


def where_the_time_goes(elevations, beta, tau, class_seconds, n) -> None:
    """The class at eq 6.4 taken apart: its constants' kernel writing into a table it has
    written before (the arithmetic), the same into a new table (the memory's first touch: a
    table over glibc's 32 MB mmap threshold comes fresh from the kernel every time), and the
    rest (the arguments' copies, the returned copy)."""
    rows = mks.AMPLITUDES_ROW + 3
    table, escapes = np.empty((rows, n)), np.empty(n, dtype=bool)
    speed, one, radius = np.array([SPEED_M_S]), np.ones(1), np.array([earth.RADIUS_M])

    def kernel(table=table, escapes=escapes):
        mks.solve_constants(speed, elevations, beta, tau, radius, one, one, table, escapes)

    def kernel_new_table():
        kernel(np.empty((rows, n)), np.empty(n, dtype=bool))

    times = interleaved_best({"kernel": kernel, "new table": kernel_new_table}, rounds=5)
    arithmetic, memory = times["kernel"], times["new table"] - times["kernel"]
    rest = class_seconds - times["new table"]
    print(
        f"  where the class's {class_seconds / n * 1e9:.1f} ns at eq 6.4 go (handed beta and "
        f"tau): its constants' kernel {arithmetic / n * 1e9:.1f} ns, the first touch of its "
        f"{rows * 8}-byte table {memory / n * 1e9:.1f} ns, the rest (the arguments' copies, the "
        f"result's) {rest / n * 1e9:.1f} ns"
    )


def public_api(smoke: bool) -> None:
    """The MKS through the public API, mks.for_launch, against the class computing beta and tau
    (the same work: the launch Mach's Cd0, rho0, beta, tau, the solution, its first-zero
    apogee): from Launches (arrays, validated once), and from a list of Launch."""
    print(
        "\npublic API: mks.for_launch(...).apogee_altitude() against the class computing beta "
        "and tau from the same numbers"
    )
    print(f"{'N':>9} {'source':>16} {'ns/launch':>10} {'/ class':>8}")
    for count in (1_000,) if smoke else (10_000, 1_000_000):
        elevations_deg = np.linspace(30.0, 85.0, count)
        launches = Launches(BASELINE, SPEED_M_S, elevations_deg)
        listed = list(launches) if count <= 10_000 else None
        elevations = np.radians(elevations_deg)
        cd0 = float(launches[0].launch_drag_coefficient)
        area, mass = BASELINE.reference_area_m2, BASELINE.mass_kg

        def by_class(elevations=elevations, cd0=cd0):
            beta = mks.decay_factor_beta(cd0, SEA_LEVEL_DENSITY_KG_M3, area, mass, elevations)
            tau = mks.decay_rate_tau(elevations)
            solution = mks.ModifiedKeplerSolution(SPEED_M_S, elevations, beta, tau, warn=False)
            return solution.apogee_altitude()

        functions = {
            "class": by_class,
            "Launches": lambda launches=launches: mks.for_launch(
                launches, warn=False
            ).apogee_altitude(),
        }
        if listed is not None:
            functions["list of Launch"] = lambda listed=listed: mks.for_launch(
                listed, warn=False
            ).apogee_altitude()
        for name, function in functions.items():
            agree(f"{name}'s apogees", np.max(np.abs(function() / by_class() - 1)), 1e-15)
        times = interleaved_best(functions, rounds=1 if smoke else 5)
        for name, seconds in times.items():
            ratio = seconds / times["class"]
            print(f"{count:>9,} {name:>16} {seconds / count * 1e9:>10.1f} {ratio:>8.2f}")
        target = 2.0 if count == 10_000 else 1.5
        ratio = times["Launches"] / times["class"]
        print(f"target: Launches within {target}x of the class: {ratio:.2f}x, ", end="")
        print(verdict(ratio, target))


if __name__ == "__main__":
    main(smoke=smoke_requested())
