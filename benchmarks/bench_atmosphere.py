"""Cost of the atmosphere models, vectorised against one altitude at a time, from one run.

The simulations of later chapters call a density model at every integration step, and sweeps
call it for many trajectories at once; this prints what each costs per evaluation.
Run: `make benchmark` (or `python benchmarks/bench_atmosphere.py`).
"""

import timeit

import numpy as np

from harp_analysis import atmosphere as atm


def per_call_s(statement, number):
    return min(timeit.repeat(statement, number=number, repeat=5)) / number


def main():
    altitude = np.linspace(0.0, 100e3, 100_000)
    atm.standard_density(0.0)  # build the 1976 table once, outside the timing
    print(f"{'model':<12} {'scalar (us/call)':>17} {'vectorised (ns/point)':>22} {'ratio':>8}")
    for name in atm.ATMOSPHERE_NAMES:
        density = atm.get_atmosphere(name).density
        scalar = per_call_s(lambda: density(50e3), 2_000)
        vector = per_call_s(lambda: density(altitude), 20) / altitude.size
        print(f"{name:<12} {scalar * 1e6:>17.2f} {vector * 1e9:>22.2f} {scalar / vector:>8.0f}")


if __name__ == "__main__":
    main()
