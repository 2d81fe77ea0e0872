"""The fly-out table (Chapter 7 A's tables of numerical flights, harp_analysis.engines.flyout_table)
and its comparison with the calibrated MKS (harp_analysis.analyses.flyout_comparison).

The table is the gun's 3DOF flights interpolated: at a node of its grid it is the 3DOF there,
but for the spline in time between its time nodes; a launch outside its band or of another gun
is refused by name; on launches drawn at random (never a node) it converges on the 3DOF as its
cells shrink. The comparison builds both tables from the same flights and counts them once.
"""

import math
import warnings

import numpy as np
import pandas as pd
import pytest

from harp_analysis.analyses import flyout_comparison
from harp_analysis.engines import flyout_table, threedof
from harp_analysis.engines.flight_grid import DEFAULT_GRID, TIME_NODES, Grid, Gun, fly_grid
from harp_analysis.foundation.validation import ModelValidityWarning

BARBADOS = flyout_comparison.GUNS["HP, Barbados"]
CONE = flyout_comparison.GUNS["baseline cone, Yuma"]
#: A coarse grid, quick to fly (336 flights): every node is a launch the 3DOF flew.
COARSE = Grid(elevations_deg=(15.0, 40.0, 65.0, 88.0), speed_step=0.35, bearings=4)


@pytest.fixture(scope="module")
def coarse_table():
    return flyout_table.tabulate(Gun.of(BARBADOS), COARSE)


def _quiet(function, *args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelValidityWarning)
        return function(*args, **kwargs)


@pytest.mark.parametrize(
    "elevation_deg, speed_node, bearing_deg, density",
    [(40.0, 0, 90.0, 0.1), (65.0, 4, 270.0, -0.1), (88.0, 6, 0.0, 0.0), (15.0, 3, 180.0, 0.0)],
)
def test_at_its_nodes_the_table_is_the_3dof(
    coarse_table, elevation_deg, speed_node, bearing_deg, density
):
    """At a node the interpolation across the inputs gives the node's flight: its time of
    flight and impact point as the 3DOF's (to the 3DOF's own tolerance, the table's flights
    flown at longitude 0), and along the path the spline in time within metres (the air
    brakes hardest in the last tenth of the flight), its apogee within centimetres, its speed
    within a few m/s."""
    speed = coarse_table.axes[1][speed_node] * BARBADOS.projectile.launch_speed_m_s
    launch = BARBADOS.but(
        elevation_deg=elevation_deg,
        speed_m_s=speed,
        bearing_deg=bearing_deg,
        density_change_fraction=density,
    )
    flight = _quiet(threedof.simulate_3dof, launch, output_step_s=0.5)
    table = flyout_table.simulate_flyout_table(launch, table=coarse_table, n_points=200)
    solution = flyout_table.FlyoutSolution(launch, coarse_table)
    attrs, flown = table.attrs, flight.attrs
    assert attrs["time_of_flight_s"] == pytest.approx(flown["time_of_flight_s"], rel=1e-6)
    assert attrs["range_m"] == pytest.approx(flown["range_m"], abs=0.1)
    assert attrs["cross_range_m"] == pytest.approx(flown["cross_range_m"], abs=0.1)
    assert attrs["apogee_altitude_m"] == pytest.approx(flown["apogee_altitude_m"], abs=0.05)
    assert attrs["apogee_time_s"] == pytest.approx(flown["apogee_time_s"], abs=0.05)
    times = np.minimum(flight.time_s.to_numpy(), solution.time_of_flight_s)  # its last: rtol
    path = solution.positions(times)
    off = np.linalg.norm(path - flight[["x_m", "y_m", "z_m"]].to_numpy(), axis=1)
    assert off.max() < 10.0
    step = float(solution.time_of_flight_s) / 199  # the 3DOF at the table's own times
    flown = _quiet(threedof.simulate_3dof, launch, output_step_s=step).iloc[:199]
    np.testing.assert_allclose(flown.time_s, table.time_s[:199], atol=1e-4)
    assert np.max(np.abs(flown.speed_m_s - table.speed_m_s[:199])) < 3.0
    assert attrs["engine"] == "fly-out table" and attrs["table_flights"] == coarse_table.flights


def test_between_time_nodes_the_spline_keeps_the_apogee_a_line_would_cut(coarse_table):
    """The raw path is curved: a straight line between the time nodes around an apogee (10-17 s
    apart) cuts it by up to hundreds of metres, where the apogee falls between two nodes, while
    the table's spline keeps every apogee within centimetres (the grid's own nodes: nothing
    interpolated across the inputs)."""
    cuts, errors = [], []
    for elevation in COARSE.elevations_deg[1:]:
        launch = BARBADOS.but(
            elevation_deg=elevation,
            speed_m_s=coarse_table.axes[1][4] * BARBADOS.projectile.launch_speed_m_s,
            bearing_deg=0.0,
        )
        apogee = _quiet(threedof.simulate_3dof, launch).attrs["apogee_altitude_m"]
        solution = flyout_table.FlyoutSolution(launch, coarse_table)
        nodes = solution.positions(TIME_NODES * solution.time_of_flight_s)
        launched = np.linalg.norm(nodes[0])
        cuts.append(apogee - (np.linalg.norm(nodes, axis=1).max() - launched))  # a line's, nearly
        errors.append(abs(solution.apogee_altitude_m - apogee))
    assert max(cuts) > 50.0, cuts
    assert max(errors) < 0.05, errors


@pytest.mark.parametrize(
    "change, named",
    [
        ({"speed_m_s": 0.7 * 2022.0}, r"speed_m_s = 1415.4 m/s lies outside the band"),
        ({"elevation_deg": 10.0}, r"elevation_deg = 10 deg lies outside the band"),
        ({"density_change_fraction": 0.2}, r"density_change_fraction = \+0.2 lies outside"),
        ({"latitude_deg": 30.0}, r"learned for another gun: the launch's latitude_deg"),
        ({"rotation_rate_rad_s": 0.0}, r"rotation_rate_rad_s"),
    ],
)
def test_a_launch_outside_the_band_is_refused_by_name(coarse_table, change, named):
    with pytest.raises(ValueError, match=named):
        flyout_table.FlyoutSolution(BARBADOS.but(**change), coarse_table)


def test_the_wind_it_never_flew_is_named():
    with pytest.warns(ModelValidityWarning, match="cross_wind_m_s"):
        flyout_table.FlyoutSolution(
            BARBADOS.but(cross_wind_m_s=5.0), flyout_table.tabulate(Gun.of(BARBADOS), COARSE)
        )


def test_it_converges_on_random_launches_as_its_cells_shrink():
    """The baseline cone (a smooth drag law), judged on launches drawn across the band, none a
    node: every error falls each time the cells shrink, the impact's by more than a decade
    from the coarsest grid to the default."""
    gun = Gun.of(CONE)
    judged = flyout_comparison.judging_launches(CONE, count=100, seed=7)
    reference = _quiet(threedof.fly_3dof, judged)
    errors = []
    for scale in (0.35, 0.7, 1.0):
        table = flyout_table.tabulate(gun, flyout_comparison.grid_at(scale))
        solution = flyout_table.FlyoutSolution(judged, table)
        errors.append(
            [
                np.sqrt(
                    np.mean(np.sum((solution.impact_point_m - reference.end_position_m.T) ** 2, 1))
                ),
                np.sqrt(np.mean((solution.apogee_altitude_m - reference.apogee_altitude_m) ** 2)),
                np.sqrt(np.mean((solution.time_of_flight_s - reference.time_of_flight_s) ** 2)),
            ]
        )
    errors = np.array(errors)
    assert np.all(np.diff(errors, axis=0) < 0), errors
    assert errors[0, 0] > 10 * errors[-1, 0]
    assert errors[-1, 0] < 30.0  # metres, over flights of 100-400 km


def test_tables_from_given_flights_are_those_it_flies(coarse_table):
    flights = fly_grid(Gun.of(BARBADOS), COARSE)
    again = flyout_table.tabulate(Gun.of(BARBADOS), COARSE, flights=flights)
    np.testing.assert_array_equal(again.values, coarse_table.values)
    assert again.seconds >= flights.seconds and again.flights == flights.flights
    with pytest.raises(ValueError, match="flown over other nodes"):
        flyout_table.tabulate(Gun.of(BARBADOS), DEFAULT_GRID, flights=flights)
    with pytest.raises(ValueError, match="do not span the band"):
        flyout_table.tabulate(Gun.of(BARBADOS), Grid(elevations_deg=(20.0, 88.0)))


# --- the comparison -------------------------------------------------------------------------------
def test_the_grids_shrink_to_and_past_the_default():
    assert flyout_comparison.grid_at(1.0) == DEFAULT_GRID
    gun = Gun.of(BARBADOS)
    sizes = [
        math.prod(a.size for a in flyout_comparison.grid_at(s).axes(gun))
        for s in flyout_comparison.SCALES
    ]
    assert sizes == sorted(sizes) and len(set(sizes)) == len(sizes)


def test_judging_launches_span_the_band_and_are_no_grid_s_nodes():
    launches = flyout_comparison.judging_launches(BARBADOS)
    points = flyout_table.BAND.check(launches, Gun.of(BARBADOS), "test")  # in the band
    assert len(launches) == flyout_comparison.JUDGED_LAUNCHES
    assert np.all(launches.longitude_deg == BARBADOS.longitude_deg)
    for scale in flyout_comparison.SCALES:
        axes = flyout_comparison.grid_at(scale).axes(Gun.of(BARBADOS))
        for column, nodes in enumerate(axes):
            assert np.min(np.abs(points[:, column, None] - nodes[None, :])) > 0.0
    spread = points.max(axis=0) - points.min(axis=0)
    assert np.all(spread > 0.9 * np.array([73.0, 0.35, 360.0, 0.2]))
    again = flyout_comparison.judging_launches(BARBADOS)
    assert np.array_equal(again.elevation_deg, launches.elevation_deg)


@pytest.fixture(scope="module")
def comparison():
    return flyout_comparison.comparison()


def test_both_methods_count_the_same_flights(comparison):
    """Both tables of a grid are built from one set of flights: the same flights, evaluations
    and flight time, bytes as many as each keeps a flight; the flights are the grid's nodes,
    and each build took at least the flights' time."""
    assert list(comparison.columns) == list(flyout_comparison.COLUMNS)
    assert len(comparison) == len(flyout_comparison.GUNS) * len(flyout_comparison.SCALES) * 2
    for (gun, scale), rows in comparison.groupby(["gun", "scale"]):
        assert set(rows.method) == set(flyout_comparison.METHODS)
        for column in ("flights", "rhs_evaluations", "flight_s"):
            assert rows[column].nunique() == 1, (gun, scale, column)
        # 8-byte numbers a flight: the time of flight (and the calibrated MKS's two of the
        # apogee), then a position at each time node
        numbers = {
            "flyout_table": 1 + 3 * TIME_NODES.size,
            "calibrated_mks": 3 + 3 * TIME_NODES.size,
        }
        assert np.all(rows.nbytes == 8 * rows.flights * rows.method.map(numbers))
        axes = flyout_comparison.grid_at(scale).axes(Gun.of(flyout_comparison.GUNS[gun]))
        assert rows.flights.iloc[0] == math.prod(a.size for a in axes)
        assert np.all(rows.build_s >= rows.flight_s)
        assert np.all(rows.impact_p95_m >= 0.5 * rows.impact_rms_m)


def test_both_tables_converge_on_the_3dof(comparison):
    for (gun, method), rows in comparison.groupby(["gun", "method"]):
        rows = rows.sort_values("flights")
        assert rows.impact_rms_m.iloc[-1] < rows.impact_rms_m.iloc[0] / 20, (gun, method)
        assert rows.tof_rms_s.iloc[-1] < rows.tof_rms_s.iloc[0] / 10, (gun, method)


def test_the_size_needed_is_read_off_the_measured_curve():
    frame = pd.DataFrame(
        {
            "gun": ["HP, Barbados"] * 6,
            "method": ["flyout_table"] * 3 + ["calibrated_mks"] * 3,
            "flights": [100, 1000, 10000] * 2,
            "nbytes": [8e4, 8e5, 8e6] * 2,
            "build_s": [0.1, 1.0, 10.0] * 2,
            "impact_rms_m": [1000.0, 100.0, 10.0, 100.0, 10.0, 1.0],
        }
    )
    needed = flyout_comparison.size_needed("HP, Barbados", target=300.0, frame=frame)
    assert needed.flights == pytest.approx(1000 / 3)  # a decade of error a decade of flights
    assert needed.nbytes == pytest.approx(8e5 / 3)
    assert needed.other_flights == 100  # the calibrated MKS's coarsest is already there
    assert needed.ratio == pytest.approx(10 / 3)
    beyond = flyout_comparison.size_needed("HP, Barbados", target=5.0, frame=frame)
    assert math.isnan(beyond.flights) and beyond.other_flights == pytest.approx(10**3.30103)
    assert beyond.finest_flights == 10000 and beyond.finest_error == 10.0
    with pytest.raises(ValueError, match="method"):
        flyout_comparison.size_needed(method="table", frame=frame)
