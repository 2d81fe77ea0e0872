"""Time per trajectory of Modified Linear Theory against its time before the speed work, and
against the 3DOF and the 6DOF, from one run.

First, issue 15's target: MLT's time per trajectory halved. HP and LP of Chapter 2 with MLT's
defaults, and HP in the effort count's setting (Fig 4.7: spherical density altitude, 1 km
segments, coefficients at each segment's middle), each the best of interleaved rounds, as
ratios to the yardstick measured in the same run (``bench_sixdof.yardstick``, a fixed scipy
workload outside the package). Before (commit 1fd3336: the table's rows propagated and its
aerodynamics evaluated in Python), measured on the 2-core machine in one process with the same
yardstick (52.6 ms), best of 10 interleaved rounds: HP 30.8 ms, LP 24.5 ms, the effort setting
30.0 ms (BEFORE below). The segment loop is Python by design: the effort count (Fig 4.7) counts
the calls it makes, so its closed forms run as Python and only the table's rows, after the
loop, run compiled (the same formulas; ``mlt.warm_up()`` compiles them in about 2 s once per
version of the package, on top of the 6DOF's kernels that the table shares).

Then HP at 50 deg, 2022 m/s, 5 m/s cross wind, to impact: MLT with 2000, 1000, 500 and 100 m
segments (coefficients at each segment's middle) against one 3DOF and one 6DOF trajectory,
each the best of interleaved rounds, with every run's apogee and range minus the 6DOF's. The
6DOF is the accuracy reference: the same rigid body and density altitude as MLT, "flat" (-z,
the figures' setting), integrated by DOP853 at rtol 1e-9 (its own error printed against rtol
1e-12). The 3DOF is another method, not the same physics: the point mass on its spherical
altitude, timed for scale. Every time includes the method's trajectory table (a row every
0.5 s). Run: `make benchmark` (``--smoke``: one round, one segment length, to check that every
path runs and MLT stays near the 6DOF).
"""

from bench_sixdof import yardstick
from measure import agree, interleaved_best, smoke_requested

from harp_analysis.engines import mlt, sixdof, threedof
from harp_analysis.models import rigid_body
from harp_analysis.models.launch import HP_CHAPTER_2, LP_CHAPTER_2

SEGMENTS_M = (2000.0, 1000.0, 500.0, 100.0)
# Fig 4.7's MLT flight (harp_analysis.analyses.effort.effort_table)
EFFORT_FLIGHT = dict(
    density_altitude="spherical", segment_length_m=mlt.SEGMENT_LENGTH_M, coefficients_at="middle"
)
# Before the speed work (module docstring): seconds per trajectory, and the yardstick's.
BEFORE = {"HP": 0.0308, "LP": 0.0245, "HP, effort setting": 0.0300, "yardstick": 0.0526}
# How near MLT's 1 km segments must stay to the 6DOF (m; they differ by about 10 m and 300 m),
# and the 6DOF at rtol 1e-9 to its own flight at rtol 1e-12 (it differs by a millimetre).
MLT_AGREEMENT_M = {"apogee_altitude_m": 100.0, "range_m": 1_000.0}
SIXDOF_AGREEMENT_M = 0.01


def halving(smoke: bool = False) -> None:
    mlt.warm_up()
    model = rigid_body.rigid_body_launch(HP_CHAPTER_2, "MLT", "flat")
    reads = 100 if smoke else 10_000

    def air():  # the atmosphere as the segment loop reads it (numpy's formulas on a float)
        for _ in range(reads):
            model.air(0.0, 0.0, -5000.0)

    cases = {
        "yardstick": yardstick,
        "HP": lambda: mlt.simulate_mlt(HP_CHAPTER_2),
        "LP": lambda: mlt.simulate_mlt(LP_CHAPTER_2),
        "HP, effort setting": lambda: mlt.simulate_mlt(HP_CHAPTER_2, **EFFORT_FLIGHT),
        "air": air,
    }
    best = interleaved_best(cases, rounds=1 if smoke else 15)
    yard = best["yardstick"]
    print(
        f"MLT per trajectory against the yardstick ({yard * 1e3:.1f} ms; before: "
        f"{BEFORE['yardstick'] * 1e3:.1f} ms; bench_sixdof's fixed scipy workload, which carries "
        "the times before the speed work to this machine; MLT's accuracy is below, against the "
        "6DOF)"
    )
    print(
        f"{'':>18} {'time (ms)':>10} {'/yardstick':>11} {'before':>7} {'speed-up':>9}  target (2x)"
    )
    for name in [name for name in BEFORE if name != "yardstick"]:
        ratio, before = best[name] / yard, BEFORE[name] / BEFORE["yardstick"]
        print(
            f"{name:>18} {best[name] * 1e3:>10.2f} {ratio:>11.3f} {before:>7.3f} "
            f"{before / ratio:>8.2f}x  {'met' if before / ratio >= 2.0 else 'missed'}"
        )
    # Where a miss comes from: the loop stays Python (the effort count follows its calls), and
    # a sixth of it reads the atmosphere through numpy's formulas on floats.
    evaluations = mlt.simulate_mlt(HP_CHAPTER_2).attrs["rhs_evaluations"]
    air_s = evaluations * best["air"] / reads
    print(
        f"HP's segment loop reads the air {evaluations} times, {best['air'] / reads * 1e6:.1f} us "
        f"each: {air_s * 1e3:.1f} ms, {air_s / best['HP']:.0%} of its time"
    )


def main(smoke: bool = False) -> None:
    halving(smoke)
    hp = HP_CHAPTER_2

    def mlt_flight(length):
        return mlt.simulate_mlt(
            hp, segment_length_m=length, coefficients_at="middle", density_altitude="flat"
        )

    cases = {
        "3DOF": lambda: threedof.simulate_3dof(hp),
        "6DOF": lambda: sixdof.simulate_6dof(hp, density_altitude="flat"),
    }
    for length in (1000.0,) if smoke else SEGMENTS_M:
        cases[length] = lambda length=length: mlt_flight(length)
    flights = {name: run().attrs for name, run in cases.items()}
    best = interleaved_best(cases, rounds=1 if smoke else 3)
    reference = flights["6DOF"]
    tight = sixdof.simulate_6dof(hp, density_altitude="flat", rtol=1e-12).attrs
    keys = ("apogee_altitude_m", "range_m")
    for key in keys:
        agree(
            f"the 6DOF's {key} against rtol 1e-12", reference[key] - tight[key], SIXDOF_AGREEMENT_M
        )
        agree(
            f"MLT's {key} against the 6DOF",
            flights[1000.0][key] - reference[key],
            MLT_AGREEMENT_M[key],
        )
    print()
    print("HP at 50 deg, 2022 m/s, 5 m/s cross wind, to impact (density altitude flat)")
    print(
        f"6DOF {best['6DOF'] * 1e3:.0f} ms, apogee {reference['apogee_altitude_m'] / 1e3:.3f} km, "
        f"range {reference['range_m'] / 1e3:.3f} km; against itself at rtol 1e-12: apogee "
        f"{reference['apogee_altitude_m'] - tight['apogee_altitude_m']:+.1e} m, range "
        f"{reference['range_m'] - tight['range_m']:+.1e} m"
    )

    def differences(name):
        return " ".join(
            f"{flights[name][key] - reference[key]:>{width}.1f}"
            for key, width in zip(keys, (18, 17))
        )

    three = flights["3DOF"]
    print(
        f"3DOF (point mass, spherical altitude) {best['3DOF'] * 1e3:.1f} ms; against the 6DOF: "
        f"apogee {three['apogee_altitude_m'] - reference['apogee_altitude_m']:+.1f} m, range "
        f"{three['range_m'] - reference['range_m']:+.1f} m"
    )
    print(
        f"{'MLT segment (m)':>15} {'time (ms)':>10} {'segments':>9} {'/3DOF':>7} {'/6DOF':>7} "
        f"{'apogee - 6DOF (m)':>18} {'range - 6DOF (m)':>17}"
    )
    for length in [name for name in cases if isinstance(name, float)]:
        seconds = best[length]
        print(
            f"{length:>15.0f} {seconds * 1e3:>10.1f} {flights[length]['steps']:>9} "
            f"{seconds / best['3DOF']:>7.2f} {seconds / best['6DOF']:>7.3f} {differences(length)}"
        )


if __name__ == "__main__":
    main(smoke=smoke_requested())
