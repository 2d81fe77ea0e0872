"""Launches from arrays: validated once, naming the field and the index; flown by the MKS, the
ECI MKS and the 3DOF exactly as the list of Launch it stands for."""

import math
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from harp_analysis.engines import eci, mks, threedof
from harp_analysis.foundation.validation import ModelValidityWarning
from harp_analysis.models.launch import BOUNDS, Launch, Launches, baseline_chapter_4
from harp_analysis.models.projectiles import BASELINE, HP

ELEVATIONS = np.array([30.0, 45.0, 65.0, 85.0])
BEARINGS = np.array([0.0, 90.0, 200.0, 300.0])


def rotating(elevations=ELEVATIONS, bearings=BEARINGS) -> Launches:
    return Launches(
        BASELINE,
        2157.0,
        elevations,
        bearing_deg=bearings,
        latitude_deg=13.1,
        rotation_rate_rad_s=7.292e-5,
    )


# --- one Launch: the fast path refuses what the strict path refuses --------------------------
@pytest.mark.parametrize(
    "changes, error, match",
    [
        ({"elevation_deg": 95.0}, ValueError, r"elevation_deg must lie in \(0, 90\] deg; got 95"),
        ({"elevation_deg": 0.0}, ValueError, "elevation_deg must lie in"),
        ({"speed_m_s": math.nan}, ValueError, "speed_m_s must be finite"),
        ({"spin_rad_s": math.inf}, ValueError, "spin_rad_s must be finite"),
        ({"speed_m_s": 1e9}, ValueError, r"speed_m_s must lie in \(0, 100000\] m/s; got 1e\+09"),
        ({"spin_rad_s": -1e300}, ValueError, r"spin_rad_s must lie in \[-100000, 100000\]"),
        ({"speed_m_s": "2157"}, TypeError, "speed_m_s must be a real number"),
        ({"bearing_deg": True}, TypeError, "bearing_deg must be a real number"),
        ({"bearing_deg": 360.0}, ValueError, r"bearing_deg must lie in \[0, 360\)"),
        ({"atmosphere": "mars"}, ValueError, "unknown atmosphere 'mars'"),
        ({"atmosphere": ["two_segment"]}, TypeError, "atmosphere must be a name"),
    ],
)
def test_a_launch_names_the_field_it_refuses(changes, error, match):
    with pytest.raises(error, match=match):
        baseline_chapter_4(45.0).but(**changes)


@settings(max_examples=200, deadline=None)
@given(name=st.sampled_from(sorted(BOUNDS)), value=st.floats(allow_nan=True, width=64))
def test_a_launch_accepts_exactly_the_values_inside_its_bounds(name, value):
    bounds = BOUNDS[name]
    low_ok = value >= bounds.low if bounds.low_inclusive else value > bounds.low
    high_ok = value <= bounds.high if bounds.high_inclusive else value < bounds.high
    inside = math.isfinite(value) and low_ok and high_ok
    try:
        launch = baseline_chapter_4(45.0).but(**{name: value})
    except ValueError as error:
        assert not inside
        assert name in str(error)
    else:
        assert inside
        assert getattr(launch, name) == value


# --- many launches: validated once, read-only, the same launches as a list --------------------
def test_fields_broadcast_to_one_length_and_index_to_launches():
    launches = rotating()
    assert len(launches) == 4
    assert launches.latitude_deg.tolist() == [13.1] * 4
    assert launches[1] == Launch(
        BASELINE, 2157.0, 45.0, bearing_deg=90.0, latitude_deg=13.1, rotation_rate_rad_s=7.292e-5
    )
    assert list(launches) == [launches[i] for i in range(4)]
    assert launches[-1] == launches[3]
    assert len(launches[1:3]) == 2
    assert launches[ELEVATIONS > 40].elevation_deg.tolist() == [45.0, 65.0, 85.0]
    assert Launches.from_launches(list(launches))[2] == launches[2]
    assert launches.but(elevation_deg=50.0).elevation_deg.tolist() == [50.0] * 4


def test_fields_are_read_only_and_the_callers_arrays_are_copied():
    elevations = ELEVATIONS.copy()
    launches = rotating(elevations)
    elevations[0] = 89.0
    assert launches.elevation_deg[0] == 30.0
    with pytest.raises(ValueError, match="read-only"):
        launches.elevation_deg[0] = 10.0
    with pytest.raises(ValueError, match="read-only"):
        launches.latitude_deg[0] = 10.0


@pytest.mark.parametrize(
    "fields, error, match",
    [
        ({"elevation_deg": [30.0, 95.0]}, ValueError, r"elevation_deg\[1\] must lie in"),
        ({"speed_m_s": [2000.0, math.nan]}, ValueError, r"speed_m_s must be finite.*index \(1,\)"),
        ({"speed_m_s": ["2157", "2000"]}, TypeError, "speed_m_s must be a real number"),
        ({"speed_m_s": [True, False]}, TypeError, "speed_m_s must be a real number"),
        ({"elevation_deg": [30.0, 40.0], "bearing_deg": [1.0, 2.0, 3.0]}, ValueError, "one length"),
        ({"elevation_deg": [[30.0, 40.0]]}, ValueError, "1-D"),
        ({"elevation_deg": []}, ValueError, "at least one launch"),
        ({"atmosphere": "mars"}, ValueError, "unknown atmosphere"),
        ({"projectile": "HP"}, TypeError, "projectile must be a Projectile"),
    ],
)
def test_launches_name_the_field_and_index_they_refuse(fields, error, match):
    with pytest.raises(error, match=match):
        Launches(**{"projectile": BASELINE, "speed_m_s": 2157.0, "elevation_deg": 45.0, **fields})


def test_a_list_of_launches_must_share_projectile_and_atmosphere():
    with pytest.raises(ValueError, match=r"launches\[1\]\.projectile differs"):
        Launches.from_launches([baseline_chapter_4(45.0), Launch(HP, 2022.0, 45.0)])
    with pytest.raises(TypeError, match=r"launches\[1\] must be a Launch"):
        Launches.from_launches([baseline_chapter_4(45.0), 45.0])
    with pytest.raises(ValueError, match=r"launches\[1\]\.elevation_deg = 45 differs"):
        rotating().shared("elevation_deg")


@settings(max_examples=30, deadline=None)
@given(
    st.lists(
        st.tuples(
            st.floats(1.0, 90.0), st.floats(0.0, 359.0), st.floats(-90.0, 90.0), st.floats(-1, 1)
        ),
        min_size=1,
        max_size=6,
    )
)
def test_launches_hold_exactly_the_launches_of_their_rows(rows):
    elevation, bearing, latitude, wind = (np.array(column) for column in zip(*rows))
    launches = Launches(
        HP, 2022.0, elevation, bearing_deg=bearing, latitude_deg=latitude, cross_wind_m_s=wind
    )
    for i, row in enumerate(rows):
        assert launches[i] == Launch(
            HP, 2022.0, row[0], bearing_deg=row[1], latitude_deg=row[2], cross_wind_m_s=row[3]
        )


# --- every engine that flies many launches flies Launches as the list ------------------------
def test_the_mks_of_launches_is_the_mks_of_each_launch():
    launches = Launches(BASELINE, np.array([2000.0, 2157.0, 2300.0, 2157.0]), ELEVATIONS)
    together = mks.for_launch(launches)
    assert together.apogee_altitude().shape == (4,)
    for i, launch in enumerate(launches):
        alone = mks.for_launch(launch)
        assert together.apogee_altitude()[i] == alone.apogee_altitude()
        assert together.impact_angle[i] == alone.impact_angle
    assert np.array_equal(mks.for_launch(list(launches)).impact_angle, together.impact_angle)


def test_the_eci_mks_of_launches_is_the_eci_mks_of_each_launch():
    launches = rotating()
    together = eci.correction_for_launch(launches).solution(warn=False)
    for i, launch in enumerate(launches):
        alone = eci.correction_for_launch(launch).solution(warn=False)
        assert np.ravel(together.apogee_altitude())[i] == pytest.approx(
            float(np.ravel(alone.apogee_altitude())[0]), rel=1e-14
        )


def test_the_3dof_flies_launches_as_the_list_of_them():
    launches = rotating()
    together = threedof.fly_3dof(launches)
    listed = threedof.fly_3dof(list(launches))
    for name in ("apogee_altitude_m", "range_m", "cross_range_m", "time_of_flight_s"):
        assert np.array_equal(getattr(together, name), getattr(listed, name))
    single = threedof.simulate_3dof(launches[2]).attrs
    assert together.range_m[2] == pytest.approx(single["range_m"], abs=1e-6)
    table = threedof.simulate_3dof_batch(launches)
    assert table.bearing_deg.tolist() == BEARINGS.tolist()
    assert np.array_equal(table.apogee_altitude_m, together.apogee_altitude_m)


def test_a_3dof_batch_needs_one_rotation_and_site():
    with pytest.raises(ValueError, match=r"launches\[1\]\.site_altitude_m"):
        threedof.fly_3dof(Launches(BASELINE, 2157.0, 45.0, site_altitude_m=[0.0, 100.0]))


def test_engines_refuse_or_warn_per_launch_and_say_which():
    with pytest.raises(ValueError, match=r"rotation_rate_rad_s\[0\]"):
        mks.for_launch(rotating())
    with pytest.raises(ValueError, match=r"site_altitude_m\[1\]"):
        eci.correction_for_launch(Launches(BASELINE, 2157.0, 45.0, site_altitude_m=[0.0, 10.0]))
    windy = Launches(BASELINE, 2157.0, 45.0, cross_wind_m_s=[0.0, 5.0, 0.0])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        mks.for_launch(windy)
    messages = [str(w.message) for w in caught if issubclass(w.category, ModelValidityWarning)]
    assert any("cross_wind_m_s in 1 of 3 launches (first [1] = 5)" in m for m in messages)


def test_the_improved_mks_of_launches_is_that_of_each_launch():
    from harp_analysis.engines import mks_improved

    launches = rotating(ELEVATIONS[:2], BEARINGS[:2])
    together = mks_improved.solve(launches)
    assert len(together) == 2
    for solution, launch in zip(together, launches):
        alone = mks_improved.solve(launch)
        assert solution.impact_range_m == alone.impact_range_m
        assert solution.impact_time_s == alone.impact_time_s
