"""Time per trajectory of Modified Linear Theory against the 3DOF and the 6DOF, from one run.

HP at 50 deg, 2022 m/s, 5 m/s cross wind, to impact: MLT with 2000, 1000, 500 and 100 m
segments (coefficients at each segment's middle) against one 3DOF and one 6DOF trajectory,
each the best of several runs (``effort.best_time``), with every MLT run's apogee and range
minus the 6DOF's. MLT and the 6DOF share the density altitude, "flat" (-z, the figures'
setting); the 3DOF is the point mass on its spherical altitude. Every time includes the
method's trajectory table (a row every 0.5 s). Run: `make benchmark`.
"""

from harp_analysis import effort, mlt, sixdof, threedof
from harp_analysis.launch import HP_CHAPTER_2

SEGMENTS_M = (2000.0, 1000.0, 500.0, 100.0)


def main():
    hp = HP_CHAPTER_2
    three = effort.best_time(lambda: threedof.simulate_3dof(hp))
    six = effort.best_time(lambda: sixdof.simulate_6dof(hp, density_altitude="flat"), repeat=2)
    reference = sixdof.simulate_6dof(hp, density_altitude="flat").attrs
    print("HP at 50 deg, 2022 m/s, 5 m/s cross wind, to impact (density altitude flat)")
    print(
        f"3DOF {three * 1e3:.1f} ms; 6DOF {six * 1e3:.0f} ms, apogee "
        f"{reference['apogee_altitude_m'] / 1e3:.3f} km, "
        f"range {reference['range_m'] / 1e3:.3f} km"
    )
    print(
        f"{'MLT segment (m)':>15} {'time (ms)':>10} {'segments':>9} {'/3DOF':>7} {'/6DOF':>7} "
        f"{'apogee - 6DOF (m)':>18} {'range - 6DOF (m)':>17}"
    )
    for length in SEGMENTS_M:

        def run(length=length):
            return mlt.simulate_mlt(
                hp, segment_length_m=length, coefficients_at="middle", density_altitude="flat"
            )

        seconds = effort.best_time(run, repeat=3)
        flight = run().attrs
        print(
            f"{length:>15.0f} {seconds * 1e3:>10.1f} {flight['steps']:>9} "
            f"{seconds / three:>7.2f} {seconds / six:>7.3f} "
            f"{flight['apogee_altitude_m'] - reference['apogee_altitude_m']:>18.1f} "
            f"{flight['range_m'] - reference['range_m']:>17.1f}"
        )


if __name__ == "__main__":
    main()
