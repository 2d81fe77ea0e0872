"""The calibrated MKS (issue 35): the ECI MKS corrected by a table learned from the gun's 3DOF
flights, held to the 3DOF it learned from (exactly at its grid's nodes, closely between them),
to the interpolation's own algebra, and to its band."""

import dataclasses
import math
import warnings

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from harp_analysis.engines import calibrated_mks, eci, flight_grid, threedof
from harp_analysis.engines.flight_grid import Band, Grid, Gun
from harp_analysis.foundation import earth
from harp_analysis.foundation.validation import ModelValidityWarning
from harp_analysis.models import sites
from harp_analysis.models.launch import Launch
from harp_analysis.models.projectiles import BASELINE, HP, LP
from harp_analysis.models.trajectory import rotate_about_axis

#: A still-Earth gun learns fast (one bearing: 315 flights).
STILL_CONE = Gun(BASELINE)
COARSE = Grid(elevations_deg=(15.0, 30.0, 50.0, 70.0, 88.0), speed_step=0.2)


# --- the interpolation ------------------------------------------------------------------------
def test_interpolation_is_exact_for_cubics_in_each_axis():
    """Local cubic Lagrange reproduces any polynomial of degree three in elevation and speed
    (on uneven nodes, across a break), quadratic in density, and a constant in bearing."""
    axes = (
        np.array([15.0, 17.0, 22.0, 30.0, 41.0, 55.0, 70.0, 88.0]),
        np.array([0.8, 0.84, 0.87, 0.9, 0.95, 1.0, 1.07, 1.15]),
        np.arange(12) * 30.0,
        np.array([-0.1, 0.0, 0.1]),
    )
    breaks = np.array([0.8, 0.9, 1.15])

    def polynomial(e, s, d):
        return 1e-4 * e**3 - 0.02 * e**2 + e * s**3 + 5 * s - 3 * d**2 + 2 * d * e

    e, s, b, d = np.meshgrid(*axes, indexing="ij")
    values = polynomial(e, s, d)[..., None] * np.array([1.0, -2.0])
    rng = np.random.default_rng(5)
    points = np.column_stack(
        [rng.uniform(15, 88, 200), rng.uniform(0.8, 1.15, 200), rng.uniform(0, 360, 200),
         rng.uniform(-0.1, 0.1, 200)]
    )  # fmt: skip
    found = flight_grid.interpolate(axes, values, points, breaks)
    expected = polynomial(points[:, 0], points[:, 1], points[:, 3])
    assert found[:, 0] == pytest.approx(expected, rel=1e-10, abs=1e-9)
    assert found[:, 1] == pytest.approx(-2 * expected, rel=1e-10, abs=1e-9)


def test_a_stencil_never_straddles_a_break_and_wraps_in_bearing():
    nodes = np.array([0.8, 0.82, 0.84, 0.86, 0.9, 0.95, 1.0, 1.05])
    breaks = np.array([0.8, 0.86, 1.05])
    indices, weights = flight_grid._stencil(nodes, np.array([0.855, 0.865]), False, breaks)
    assert set(nodes[indices[0]]) <= {0.8, 0.82, 0.84, 0.86}  # just below the break
    assert set(nodes[indices[1]]) <= {0.86, 0.9, 0.95, 1.0, 1.05}  # just above it
    assert weights.sum(axis=1) == pytest.approx(1.0)
    indices, _ = flight_grid._stencil(np.arange(12) * 30.0, np.array([355.0]), True)
    assert set(indices[0]) == {10, 11, 0, 1}  # 300, 330, 0 (360) and 30 deg


def test_speed_nodes_hold_the_drag_tables_breakpoints():
    """HP's drag table kinks at Mach 5.0; the launch Mach crosses it at 1700 m/s from a sea-level
    gun, 0.84 of HP's muzzle speed: a node of the speed axis and a break of the stencils."""
    gun = Gun(HP)
    sound = float(np.ravel(gun.launches(1.0, 45.0, 0.0, 0.0).air(0.0)[1])[0])
    kink = 5.0 * sound / HP.launch_speed_m_s
    breaks = flight_grid.DEFAULT_GRID.speed_breaks(gun)
    assert breaks == pytest.approx([0.8, kink, 1.15])
    speeds = flight_grid.DEFAULT_GRID.axes(gun)[1]
    assert np.min(np.abs(speeds - kink)) < 1e-12
    assert np.max(np.diff(speeds)) <= flight_grid.DEFAULT_GRID.speed_step + 1e-12
    assert len(flight_grid.DEFAULT_GRID.speed_breaks(STILL_CONE)) == 2  # eq 4.8 has no kinks


# --- what it learned: the 3DOF -----------------------------------------------------------------
@pytest.fixture(scope="module")
def coarse():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelValidityWarning)
        return calibrated_mks.calibrate(STILL_CONE, COARSE)


def test_at_a_node_it_flies_the_flight_it_learned(coarse):
    """At a node of its grid the calibrated MKS is the 3DOF's own flight: the time of flight,
    the apogee and every position at the table's fractions of the flight."""
    launch = Launch(BASELINE, 0.8 * BASELINE.launch_speed_m_s, 50.0, density_change_fraction=0.1)
    flight = threedof.simulate_3dof(launch, output_step_s=0.05)
    solution = calibrated_mks.CalibratedSolution(launch, coarse)
    assert solution.time_of_flight_s == pytest.approx(flight.attrs["time_of_flight_s"], rel=1e-12)
    assert solution.apogee_altitude_m == pytest.approx(flight.attrs["apogee_altitude_m"], abs=1e-6)
    times = flight_grid.TIME_NODES[1:-1] * flight.attrs["time_of_flight_s"]
    inside = times[(times > 1.0) & (times < flight.time_s.iloc[-1] - 1.0)]
    found = solution.positions(inside)
    table = flight[["x_m", "y_m", "z_m"]].to_numpy()
    expected = np.stack([np.interp(inside, flight.time_s, table[:, k]) for k in range(3)], axis=1)
    assert np.max(np.linalg.norm(found - expected, axis=1)) < 0.02  # 0.05 s rows, linear


def test_a_node_the_turning_earth_leaves_vertical_is_learned():
    """A westward shot whose horizontal speed the Earth's surface speed cancels is vertical in
    the inertial frame, where the MKS's angular momentum vanishes and its constants cancel. A
    gun with such a node on its grid (LP at 80 deg, at the latitude that cancels it exactly) is
    still learned, and at that node flies the 3DOF's flight."""
    grid = Grid(elevations_deg=(15.0, 30.0, 50.0, 80.0, 88.0), speed_step=0.2)
    turning = Gun(LP, rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S)
    speed = LP.launch_speed_m_s * grid.axes(turning)[1][-1]  # a node of the speeds

    def westward(latitude_deg):
        return Launch(
            LP,
            speed,
            80.0,
            bearing_deg=270.0,
            latitude_deg=latitude_deg,
            rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S,
        )

    area = calibrated_mks._base_drag_area(turning)  # the MKS underneath flies the gun's

    def off_vertical(latitude_deg):
        correction = eci.correction_for_launch(westward(latitude_deg), drag_area_m2=area)
        elevation = correction.elevation_rad
        return math.pi / 2 - float(np.ravel(elevation)[0])

    latitude = minimize_scalar(
        off_vertical, bounds=(0.0, 60.0), method="bounded", options={"xatol": 1e-9}
    ).x
    assert math.degrees(off_vertical(latitude)) < 1e-4  # where the ECI MKS has no closed form
    gun, launch = dataclasses.replace(turning, latitude_deg=latitude), westward(latitude)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelValidityWarning)
        learned = calibrated_mks.calibrate(gun, grid)
        solution = calibrated_mks.CalibratedSolution(launch, learned)
    flight = threedof.simulate_3dof(launch)
    assert np.ravel(solution.apogee_altitude_m)[0] == pytest.approx(
        flight.attrs["apogee_altitude_m"], abs=1e-6
    )


def test_between_the_nodes_it_is_far_closer_to_the_3dof_than_the_eci_mks():
    """Launches drawn off the grid (the default grid of a still-Earth cone gun): the impact
    point, apogee and time of flight within a fiftieth of the text's ECI MKS's misses (RMS)."""
    rng = np.random.default_rng(17)
    ours, theirs = [], []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelValidityWarning)
        for _ in range(8):
            launch = Launch(
                BASELINE,
                rng.uniform(0.8, 1.15) * BASELINE.launch_speed_m_s,
                rng.uniform(15.0, 88.0),
                density_change_fraction=rng.uniform(-0.1, 0.1),
            )
            flight = threedof.simulate_3dof(launch)
            text = eci.simulate_eci_mks(launch, warn=False).attrs
            solution = calibrated_mks.CalibratedSolution(launch)
            truth = flight.attrs
            ours.append(
                [abs(solution.impact_range_m[0] - truth["range_m"]),
                 abs(solution.apogee_altitude_m - truth["apogee_altitude_m"]),
                 abs(solution.time_of_flight_s - truth["time_of_flight_s"])]
            )  # fmt: skip
            theirs.append(
                [abs(text["range_m"] - truth["range_m"]),
                 abs(text["apogee_altitude_m"] - truth["apogee_altitude_m"]),
                 abs(text["time_of_flight_s"] - truth["time_of_flight_s"])]
            )  # fmt: skip
    rms = lambda rows: np.sqrt(np.mean(np.square(rows), axis=0))  # noqa: E731
    assert np.all(rms(ours) < 0.02 * rms(theirs)), (rms(ours), rms(theirs))


def test_on_the_turning_earth_its_impact_is_fixed_to_the_earth():
    """The impact point is the inertial one turned back by the Earth's rotation over the time
    of flight (the gun turns with the Earth), and lies on the surface."""
    launch = Launch(
        HP, HP.launch_speed_m_s, 60.0, bearing_deg=200.0, latitude_deg=13.08,
        longitude_deg=-59.6, rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S,
    )  # fmt: skip
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelValidityWarning)
        solution = calibrated_mks.CalibratedSolution(launch)
        flight = threedof.simulate_3dof(launch)
    tof = solution.time_of_flight_s
    inertial = solution.positions([tof])[0]
    turned = rotate_about_axis(inertial[:, None], np.array([-launch.rotation_rate_rad_s * tof]))
    assert solution.impact_point_m == pytest.approx(turned[:, 0], abs=1e-6)
    assert np.linalg.norm(solution.impact_point_m) == pytest.approx(earth.RADIUS_M, abs=5.0)
    fixed = rotate_about_axis(
        flight[["x_m", "y_m", "z_m"]].to_numpy()[-1][:, None],
        np.array([-launch.rotation_rate_rad_s * flight.attrs["time_of_flight_s"]]),
    )[:, 0]
    assert np.linalg.norm(solution.impact_point_m - fixed) < 500.0  # the 3DOF's, off the grid


# --- where it crosses an altitude ---------------------------------------------------------------
#: HP from Barbados on the turning Earth, the gun fire control aims (its calibration shared).
BARBADOS = Gun(
    HP, latitude_deg=math.degrees(sites.BARBADOS.latitude_rad),
    rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S,
)  # fmt: skip


@pytest.fixture(scope="module")
def launches_between_nodes():
    """Launches of the gun drawn at random within the calibrated band (none a grid node), each
    with an altitude below its calibrated apogee and a branch."""
    draws = np.random.default_rng(35)
    count = 120
    launches = BARBADOS.launches(
        draws.uniform(0.8, 1.15, count),
        draws.uniform(15.0, 88.0, count),
        draws.uniform(0.0, 360.0, count),
        draws.uniform(-0.1, 0.1, count),
    )
    solution = calibrated_mks.CalibratedSolution(launches)
    altitude = draws.uniform(0.0, 0.9, count) * solution.apogee_altitude_m
    rising = draws.uniform(size=count) < 0.5
    return launches, solution, altitude, rising


def test_the_crossing_of_an_altitude_is_the_3dof_s(launches_between_nodes):
    """Where the calibrated MKS crosses an altitude on its way up or down, at random off the
    grid: on the altitude, on the branch's side of the apogee, and at the 3DOF's own crossing
    (fly_3dof to that altitude) to what the table holds (a median of metres to tens of metres,
    the worst a few hundred, descending high up), where the other branch's lies kilometres off."""
    launches, solution, altitude, rising = launches_between_nodes
    time, point = solution.crossing(altitude, rising)
    radius = np.linalg.norm(point, axis=1)
    assert np.max(np.abs(radius - earth.RADIUS_M - altitude)) < 1e-3
    before = time < solution.apogee_time_s
    assert np.array_equal(before, rising)
    flight = threedof.fly_3dof(launches, end_altitude_m=altitude, rising=rising)
    assert flight.impact.all()
    distance = np.linalg.norm(point - flight.end_position_m.T, axis=1)
    assert np.median(distance) < 50.0 and np.max(distance) < 1e3
    assert np.median(np.abs(time - flight.time_of_flight_s)) < 0.1
    other = solution.crossing(altitude, ~rising)[1]
    assert np.median(np.linalg.norm(other - flight.end_position_m.T, axis=1)) > 10e3


def test_the_crossing_ends_at_the_impact_and_is_nan_above_the_apogee(launches_between_nodes):
    launches, solution, _, rising = launches_between_nodes
    time, point = solution.crossing(0.0)
    assert np.array_equal(point, solution.impact_point_m)
    assert np.array_equal(time, solution.time_of_flight_s)
    # the path's top lies within metres of the apogee, which is learned apart
    time, point = solution.crossing(solution.apogee_altitude_m + 100.0, rising)
    assert np.isnan(time).all() and np.isnan(point).all()
    time, point = solution.crossing(solution.apogee_altitude_m - 100.0, rising)
    assert np.isfinite(time).all() and np.isfinite(point).all()
    one = calibrated_mks.CalibratedSolution(launches[3])
    halfway = 0.5 * one.apogee_altitude_m
    single = one.crossing(halfway, True)
    assert isinstance(single[0], float) and single[1].shape == (3,)
    assert single[1] == pytest.approx(solution.crossing(halfway, True)[1][3], abs=1e-6)
    with pytest.raises(ValueError, match="altitude_m must be >= 0"):
        one.crossing(-1.0)
    with pytest.raises(TypeError, match="rising must be True, False"):
        one.crossing(10e3, "up")


# --- its band --------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "change, message",
    [
        ({"speed_m_s": 0.7 * BASELINE.launch_speed_m_s}, "speed_m_s = .* outside the band"),
        ({"speed_m_s": 1.2 * BASELINE.launch_speed_m_s}, "speed_m_s = .* outside the band"),
        ({"elevation_deg": 10.0}, "elevation_deg = 10 deg lies outside"),
        ({"density_change_fraction": 0.2}, "density_change_fraction = \\+0.2 lies outside"),
        ({"projectile": LP, "speed_m_s": LP.launch_speed_m_s}, "another gun.*projectile"),
        ({"latitude_deg": 30.0}, "another gun.*latitude_deg"),
    ],
)
def test_a_launch_outside_its_band_or_gun_is_refused_by_name(coarse, change, message):
    launch = Launch(BASELINE, BASELINE.launch_speed_m_s, 45.0).but(**change)
    with pytest.raises(ValueError, match=message):
        calibrated_mks.CalibratedSolution(launch, coarse)


def test_a_wind_is_left_out_with_a_warning(coarse):
    with pytest.warns(ModelValidityWarning, match="cross_wind_m_s"):
        calibrated_mks.CalibratedSolution(
            Launch(BASELINE, BASELINE.launch_speed_m_s, 45.0, cross_wind_m_s=5.0), coarse
        )


def test_a_gun_above_sea_level_cannot_be_learned():
    with pytest.raises(ValueError, match="site_altitude_m"):
        calibrated_mks.calibrate(Gun(BASELINE, site_altitude_m=100.0), COARSE)


def test_the_band_names_its_field_for_a_batch(coarse):
    launches = Gun(BASELINE).launches([1.0, 1.0, 1.0], [30.0, 10.0, 40.0], 0.0, 0.0)
    with pytest.raises(ValueError, match=r"elevation_deg\[1\] = 10 deg"):
        Band().check(launches, Gun(BASELINE), "calibrated MKS")


# --- kept once per gun -------------------------------------------------------------------------
def test_a_calibration_is_learned_once_kept_on_disk_and_read_only(monkeypatch, tmp_path):
    monkeypatch.setenv("HARP_ANALYSIS_KERNEL_CACHE", str(tmp_path))
    monkeypatch.delenv("HARP_ANALYSIS_STORE", raising=False)
    calibrated_mks._calibration.cache_clear()
    launch = Launch(BASELINE, BASELINE.launch_speed_m_s, 45.0)
    try:
        first = calibrated_mks.calibration_for(launch, COARSE)
        assert (
            not first.loaded and first.seconds > 0 and first.flights == 5 * 4 * 3
        )  # elevations, speeds, days
        assert calibrated_mks.calibration_for(launch, COARSE) is first  # memory
        calibrated_mks._calibration.cache_clear()
        second = calibrated_mks.calibration_for(launch, COARSE)  # disk
        assert second.loaded and second.seconds == 0.0
        assert np.array_equal(second.values, first.values)
        for array in (second.time_factor, second.displacement_m, *second.axes):
            assert not array.flags.writeable
        with pytest.raises(ValueError, match="read-only"):
            second.time_factor[0, 0, 0, 0] = 1.0
        assert len(list(tmp_path.rglob("tables/*.npz"))) == 1
    finally:
        calibrated_mks._calibration.cache_clear()


def test_the_trajectory_table_meets_its_own_numbers():
    launch = Launch(BASELINE, BASELINE.launch_speed_m_s, 45.0)
    table = calibrated_mks.simulate_calibrated_mks(launch, n_points=200)
    solution = calibrated_mks.CalibratedSolution(launch)
    attrs = table.attrs
    assert attrs["time_of_flight_s"] == pytest.approx(solution.time_of_flight_s, rel=1e-12)
    assert attrs["range_m"] == pytest.approx(solution.impact_range_m[0], abs=1e-6)
    assert table.altitude_m.iloc[0] == pytest.approx(0.0, abs=1e-6)
    assert table.altitude_m.max() <= attrs["apogee_altitude_m"] + 5.0  # the rows straddle it
    # the speed is the path's derivative: the displacement between rows over their time
    step = np.diff(table[["x_m", "y_m", "z_m"]].to_numpy(), axis=0)
    mean_speed = np.linalg.norm(step, axis=1) / np.diff(table.time_s)
    middle = 0.5 * (table.speed_m_s.to_numpy()[1:] + table.speed_m_s.to_numpy()[:-1])
    assert mean_speed == pytest.approx(middle, rel=1e-2)  # the displacements: linear in time
    assert math.isfinite(attrs["time_factor"])


def test_a_launch_outside_the_band_learns_no_table(monkeypatch):
    """The band is checked before the gun's table is looked up or learned (seconds)."""

    def refuse(*args, **kwargs):
        raise AssertionError("a table was looked up for a launch outside the band")

    monkeypatch.setattr(calibrated_mks, "_calibration", refuse)
    with pytest.raises(ValueError, match="elevation_deg = 10 deg"):
        calibrated_mks.CalibratedSolution(Launch(BASELINE, BASELINE.launch_speed_m_s, 10.0))


def test_a_gun_whose_flights_do_not_land_cannot_be_learned():
    """A table is learned from flights that land: one cut off by the 3DOF's flight time (a
    round so fast it leaves the Earth) refuses the gun, naming the launch."""
    fast = dataclasses.replace(BASELINE, name="fast cone", launch_speed_m_s=9000.0)
    with pytest.raises(ValueError, match="does not land within the 3DOF's flight time"):
        calibrated_mks.calibrate(Gun(fast), COARSE)
