"""Speed of the Modified Kepler Solution, measured in one run against the 3DOF.

- apogees per second, vectorised over a million launches (class and straight-line code);
- one full MKS trajectory (500 points with the time of flight) against one 3DOF trajectory;
- the ratio of the time per apogee, MKS against 3DOF.
Run: `make benchmark`.
"""

import numpy as np

from harp_analysis import effort, mks, threedof
from harp_analysis.launch import baseline_chapter_4


def main():
    launch = baseline_chapter_4(45.0)
    n = 1_000_000
    elevations = np.radians(np.linspace(30.0, 85.0, n))
    solution = mks.for_launch(launch)
    beta, tau = solution.beta.item(), solution.tau.item()
    cd0 = launch.launch_drag_coefficient

    def many():
        return mks.ModifiedKeplerSolution(
            2157.0, elevations, beta, tau, warn=False
        ).apogee_altitude("eq_6_4")

    def straight():
        return effort.mks_apogee(2157.0, elevations, cd0, 11.6, 0.008)

    class_rate = n / effort.best_time(many, repeat=3)
    straight_rate = n / effort.best_time(straight, repeat=3)
    print(
        f"MKS apogees per second, {n:,} launches at once: {class_rate:.3g} (class), "
        f"{straight_rate:.3g} (straight-line eqs 6.4-6.10)"
    )

    def full_trajectory():
        return solution.sample(np.linspace(0.0, solution.impact_angle, 500))

    mks_full = effort.best_time(full_trajectory, number=20)
    three = effort.best_time(lambda: threedof.simulate_3dof(launch))
    print(
        f"one trajectory: MKS (500 points with time of flight) {mks_full * 1e6:.0f} us, "
        f"3DOF {three * 1e3:.1f} ms, ratio {three / mks_full:.0f}"
    )
    print(
        f"per apogee: 3DOF {three * 1e3:.1f} ms against MKS {1e9 / straight_rate:.1f} ns "
        f"vectorised: {three * straight_rate:.2g} times faster"
    )


if __name__ == "__main__":
    main()
