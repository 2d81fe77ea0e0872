"""Chapter 7 A's claims, timed and counted in one run (issue 16 item 5): one MKS firing
solution, its 3DOF verification, the 3DOF-only iterative firing solution (from the drag-free
conic), and every MKS intercept of a raid against one iterative 3DOF intercept.

The case: HP from Barbados to the point 150 km down the gun's bearing at sea level
(:func:`harp_analysis.fire_control.barbados_case`); the raid: :func:`fire_control.raid`'s
targets, each at 50 intercept times over its flight (fewer targets with ``--targets``).
"""

import argparse
import time

import numpy as np
from measure import best_of

from harp_analysis import fire_control as fc
from harp_analysis import threedof


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--targets", type=int, default=100)
    parser.add_argument("--times", type=int, default=50)
    args = parser.parse_args()
    threedof.warm_up()
    gun, target = fc.barbados_case()
    solutions = fc.firing_solutions(gun, target)
    low = solutions.low
    verification = fc.verify_with_3dof(gun, target, low)
    alone = fc.shoot_3dof(gun, target)
    mks_s = best_of(lambda: fc.firing_solutions(gun, target))
    verify_s = best_of(lambda: fc.verify_with_3dof(gun, target, low), repeat=3)
    alone_s = best_of(lambda: fc.shoot_3dof(gun, target), repeat=3)
    print("HP from Barbados, 150 km at sea level (low root)")
    print(
        f"  MKS firing solution (both roots): {mks_s * 1e3:8.2f} ms, MKS trajectories "
        f"{solutions.mks_solves} (low root's refinement {low.mks_solves})"
    )
    print(
        f"  3DOF verification from the MKS:   {verify_s * 1e3:8.2f} ms, {verification.flights} "
        f"flights, {verification.rhs_evaluations:,} RHS; MKS miss {verification.mks_miss_m:.0f} m"
    )
    print(
        f"  3DOF-only firing solution:        {alone_s * 1e3:8.2f} ms, {alone.flights} flights, "
        f"{alone.rhs_evaluations:,} RHS (converged {alone.converged})"
    )

    targets = fc.raid(gun, args.targets)
    start = time.perf_counter()
    windows = [fc.intercept_window(gun, item, count=args.times) for item in targets]
    raid_s = time.perf_counter() - start
    intercepts = sum(len(window.intercepts) for window in windows)
    feasible = sum(int(window.feasible.sum()) for window in windows)
    mks_solves = sum(window.mks_solves for window in windows)
    items = [item for item in windows[0].intercepts if item.roots]
    aim = items[len(items) // 2].aim
    start = time.perf_counter()
    one = fc.shoot_3dof(gun, aim, branch="ascending")
    one_s = time.perf_counter() - start
    print(
        f"Raid: {len(targets)} targets x {args.times} intercept times = {intercepts} "
        f"intercepts ({feasible} feasible) by MKS in {raid_s:.2f} s, {mks_solves:,} MKS "
        "trajectories"
    )
    print(
        f"One iterative 3DOF intercept: {one_s * 1e3:.1f} ms, {one.flights} flights, "
        f"{one.rhs_evaluations:,} RHS (miss {one.miss_m:.3g} m, converged {one.converged})"
    )
    print(
        f"  time, one 3DOF intercept / the whole MKS raid: {one_s / raid_s:.3g} "
        f"(log10 {np.log10(one_s / raid_s):+.2f}: the claim holds if positive)"
    )
    print(f"  counts, 3DOF RHS / raid's MKS trajectories: {one.rhs_evaluations / mks_solves:.3g}")
    print(f"  3DOF-only / MKS firing solution time: {alone_s / mks_s:.3g}")


if __name__ == "__main__":
    main()
