"""Envelope maps: the destination against the great-circle inverse, and each map point's miss
against a 3DOF flight fired directly at fire_control's MKS solution."""

import logging
import math

import distributed
import numpy as np
import pytest

from harp_analysis.analyses.fire_control import envelope, firing
from harp_analysis.analyses.fire_control.firing import firing_solutions, great_circle
from harp_analysis.analyses.fire_control.verification import verify_with_3dof
from harp_analysis.engines import threedof
from harp_analysis.foundation import earth
from harp_analysis.models.sites import BARBADOS, YUMA

GUN = firing.BARBADOS_HP


SITES = [
    (math.degrees(BARBADOS.latitude_rad), -59.6),
    (math.degrees(YUMA.latitude_rad), -114.4),
    (-40.0, 179.5),  # across the date line
    (0.0, 0.0),
    (75.0, 20.0),
]


@pytest.mark.parametrize("latitude_deg, longitude_deg", SITES)
@pytest.mark.parametrize("bearing_deg", [0.0, 37.0, 90.0, 163.0, 270.0, 329.0])
@pytest.mark.parametrize("downrange_m", [1e3, 250e3, 3000e3])
def test_destination_inverts_the_great_circle(
    latitude_deg, longitude_deg, bearing_deg, downrange_m
):
    gun = GUN.but(latitude_deg=latitude_deg, longitude_deg=longitude_deg)
    target = firing.destination(gun, bearing_deg, downrange_m, 12e3)
    angle, bearing = great_circle(gun, target)
    assert angle * earth.RADIUS_M == pytest.approx(downrange_m, rel=1e-9)
    turn = (math.degrees(bearing) - bearing_deg + 180.0) % 360.0 - 180.0
    assert abs(turn) < 1e-7
    assert target.altitude_m == 12e3 and -180.0 <= target.longitude_deg < 180.0


def test_destination_at_no_distance_is_the_gun_and_refuses_the_far_side():
    target = firing.destination(GUN, 123.0, 0.0)
    assert target.latitude_deg == pytest.approx(GUN.latitude_deg, abs=1e-12)
    assert target.longitude_deg == pytest.approx(GUN.longitude_deg, abs=1e-12)
    with pytest.raises(ValueError, match="antipode"):
        firing.destination(GUN, 90.0, 2.1e7)
    with pytest.raises(ValueError, match="downrange_m"):
        firing.destination(GUN, 90.0, -1.0)


def _direct_miss(gun, target, solution):
    """The 3DOF fired straight from the engine at the solution: its Earth-fixed end point
    where it falls through the target's altitude, against the target's position."""
    flight = threedof.fly_3dof(
        gun.but(elevation_deg=solution.elevation_deg, bearing_deg=solution.bearing_deg),
        end_altitude_m=target.altitude_m,
    )
    assert flight.impact[0]
    return float(np.linalg.norm(flight.end_position_m[:, 0] - target.earth_fixed_m()))


@pytest.fixture(scope="module")
def east_map():
    return envelope.miss_map(GUN, 90.0, [60e3, 180e3, 500e3], [0.0, 40e3], root="both")


def test_map_is_tidy_one_row_per_point_and_root(east_map):
    assert list(east_map.columns) == list(envelope.MAP_COLUMNS)
    assert len(east_map) == 3 * 2 * 2
    assert set(east_map.root) == {"low", "high"}
    assert east_map.attrs["bearing_deg"] == 90.0 and east_map.attrs["root"] == "both"
    # every row has a miss or a reason, never both missing
    has_miss = np.isfinite(east_map.miss_3dof_m)
    assert (has_miss ^ east_map.reason.notna()).all()


def test_map_miss_is_the_3dof_fired_at_the_mks_solution(east_map):
    solved = east_map[np.isfinite(east_map.miss_3dof_m)]
    assert len(solved) >= 4
    for row in solved.itertuples():
        target = firing.destination(GUN, 90.0, row.downrange_m, row.altitude_m)
        solutions = firing_solutions(GUN, target)
        solution = solutions.low if row.root == "low" else solutions.high
        assert row.elevation_deg == pytest.approx(solution.elevation_deg, abs=1e-9)
        assert row.miss_3dof_m == pytest.approx(_direct_miss(GUN, target, solution), rel=1e-9)
    low = solved[solved.root == "low"].set_index(["downrange_m", "altitude_m"])
    high = solved[solved.root == "high"].set_index(["downrange_m", "altitude_m"])
    both = low.index.intersection(high.index)
    assert len(both) and (low.loc[both].elevation_deg < high.loc[both].elevation_deg).all()


def test_map_miss_agrees_with_the_verification(east_map):
    """verification.verify_with_3dof measures the same flight's miss at the MKS solution (its
    east and north components); the straight-line distance differs by the vertical part only."""
    row = east_map[(east_map.root == "low") & np.isfinite(east_map.miss_3dof_m)].iloc[0]
    target = firing.destination(GUN, 90.0, row.downrange_m, row.altitude_m)
    verification = verify_with_3dof(GUN, target, firing_solutions(GUN, target).low)
    assert row.miss_3dof_m == pytest.approx(verification.mks_miss_m, abs=1.0)


def test_unreachable_points_keep_their_reason(east_map):
    far = east_map[east_map.downrange_m == 500e3]
    assert far.miss_3dof_m.isna().all() and far.elevation_deg.isna().all()
    assert far.reason.str.contains("beyond the maximum range").all()


def test_each_point_has_one_outcome(east_map):
    """A measured miss where the 3DOF gets there, no solution where the MKS has none; the map
    east has no third kind (test_a_root_the_3dof_never_reaches_is_told_apart)."""
    measured = east_map.outcome == envelope.MEASURED
    assert set(east_map.outcome) <= set(envelope.OUTCOMES)
    assert (measured == np.isfinite(east_map.miss_3dof_m)).all()
    assert ((east_map.outcome == envelope.NO_SOLUTION) == east_map.elevation_deg.isna()).all()
    assert (east_map.apogee_3dof_m[measured] > east_map.altitude_m[measured]).all()


def test_a_root_the_3dof_never_reaches_is_told_apart():
    """Due west, 100 km out at 20 km, the MKS has a low root whose 3DOF flight peaks below the
    target (Fig X.1's stars): not 'no solution' but a root the 3DOF cannot reach. Checked by
    another flight: the 3DOF's trajectory table to the ground, its highest row against the
    target's altitude; at sea level the 3DOF gets there and its miss is measured."""
    west = envelope.miss_map(GUN, 270.0, [60e3, 100e3], [0.0, 20e3], progress=False)
    assert list(west.outcome.value_counts().sort_index().items()) == [
        (envelope.MEASURED, 2),
        (envelope.NEVER_THERE, 1),
        (envelope.NO_SOLUTION, 1),
    ]
    for row in west[west.outcome != envelope.NO_SOLUTION].itertuples():
        flown = GUN.but(elevation_deg=row.elevation_deg, bearing_deg=row.bearing_deg)
        top = threedof.simulate_3dof(flown, output_step_s=0.1).altitude_m.max()
        assert row.apogee_3dof_m == pytest.approx(top, abs=5.0)
        expected = envelope.NEVER_THERE if top < row.altitude_m else envelope.MEASURED
        assert row.outcome == expected, (row.downrange_m, row.altitude_m)
    (never,) = west[west.outcome == envelope.NEVER_THERE].itertuples()
    assert (never.downrange_m, never.altitude_m) == (100e3, 20e3)
    assert math.isnan(never.miss_3dof_m) and never.reason.startswith(
        "the 3DOF fired at the MKS solution never reaches the target's altitude: its apogee"
    )


def test_map_runs_on_a_client_with_the_same_result(east_map):
    with distributed.Client(
        processes=False,
        n_workers=1,
        threads_per_worker=2,
        dashboard_address=":0",
        silence_logs=logging.CRITICAL,
    ) as client:
        frame = envelope.miss_map(GUN, 90.0, [60e3, 180e3, 500e3], [0.0, 40e3], root="both",
                                  client=client)  # fmt: skip
    assert frame.drop(columns="reason").equals(east_map.drop(columns="reason"))
    assert list(frame.reason.fillna("")) == list(east_map.reason.fillna(""))


def test_bad_map_input_is_named():
    with pytest.raises(ValueError, match="root"):
        envelope.miss_map(GUN, 90.0, [1e5], [0.0], root="middle")
    with pytest.raises(ValueError, match="ranges_m"):
        envelope.miss_map(GUN, 90.0, [0.0], [0.0])
    with pytest.raises(ValueError, match="altitudes_m"):
        envelope.miss_map(GUN, 90.0, [1e5], [-5.0])
    with pytest.raises(TypeError, match="gun must be"):
        envelope.miss_map("gun", 90.0, [1e5], [0.0])
