"""Cost of the atmosphere models, vectorised against one altitude at a time, from one run
(``make benchmark``; ``--smoke`` for a quick check that every path runs and agrees).

The simulations of later chapters call a density model at every integration step, and sweeps
call it for many trajectories at once; this prints what each costs per evaluation. The
reference is the same model called with one altitude (a Python float) at a time, on altitudes
drawn from the vectorised call's grid (0-100 km): the same formulas, checked, and the same
densities (printed: the largest relative difference between the two).
"""

import numpy as np
from measure import agree, interleaved_best, smoke_requested

from harp_analysis.models import atmosphere as atm

SCALAR_CALLS = 200
# Scalar and vectorised calls run the same formulas; numpy's vectorised exp and power may round
# differently from its scalar ones in the last bit.
AGREEMENT = 1e-14


def main(smoke: bool = False) -> None:
    altitude = np.linspace(0.0, 100e3, 1_000 if smoke else 100_000)
    scalars = [float(a) for a in altitude[:: altitude.size // SCALAR_CALLS]]
    atm.standard_density(0.0)  # build the 1976 table once, outside the timing
    print(
        f"Density per evaluation: vectorised over {altitude.size:,} altitudes against the "
        f"reference, the same model called on {len(scalars)} of them one at a time"
    )
    print(
        f"{'model':<12} {'scalar (us/call)':>17} {'vectorised (ns/point)':>22} {'ratio':>8} "
        f"{'scalar - vectorised (relative)':>31}"
    )
    for name in atm.ATMOSPHERE_NAMES:
        density = atm.get_atmosphere(name).density
        one_at_a_time = [float(density(a)) for a in scalars]
        vectorised = density(altitude)[:: altitude.size // SCALAR_CALLS]
        expected = np.where(vectorised == 0.0, 1.0, vectorised)  # the vacuum's zeros
        difference = agree(
            f"{name}: scalar against vectorised densities",
            (np.array(one_at_a_time) - vectorised) / expected,
            AGREEMENT,
        )
        best = interleaved_best(
            {
                "scalar": lambda: [density(a) for a in scalars],
                "vectorised": lambda: density(altitude),
            },
            rounds=1 if smoke else 5,
            number=1 if smoke else 10,
        )
        scalar, vector = best["scalar"] / len(scalars), best["vectorised"] / altitude.size
        print(
            f"{name:<12} {scalar * 1e6:>17.2f} {vector * 1e9:>22.2f} {scalar / vector:>8.0f} "
            f"{difference:>31.1e}"
        )


if __name__ == "__main__":
    main(smoke=smoke_requested())
