"""Appendix A's own scheme: its artefacts are real, and it converges to the accurate 3DOF."""

import warnings

import numpy as np
import pytest

from harp_analysis.engines import appendix_a, threedof
from harp_analysis.foundation import earth
from harp_analysis.foundation.validation import ModelValidityWarning
from harp_analysis.models import trajectory
from harp_analysis.models.launch import Launch
from harp_analysis.models.projectiles import BASELINE

#: The listing's launch: the baseline cone (eq 4.8) at 45 deg in the three-layer air it
#: hard-codes, 2157 m/s due east from the equator, the Earth's spin off.
LISTING = Launch(BASELINE, 2157.0, 45.0, atmosphere="three_layer")


@pytest.fixture(scope="module")
def accurate():
    return threedof.simulate_3dof(LISTING)


def test_clock_leads_position_by_one_step():
    dt = 0.1
    rows = appendix_a.simulate_appendix_a(LISTING, dt)
    first = rows.iloc[0]
    assert first.time_s == pytest.approx(3 * dt)
    # The first position is two steps out (Euler then one recurrence step), not three.
    two_steps = 2 * dt * 2157.0 * np.sin(np.radians(45.0))
    assert first.altitude_m == pytest.approx(two_steps, rel=0.01)


@pytest.mark.parametrize("dt", [0.1, 0.05])
def test_launch_offset_against_an_accurate_solution(dt):
    """The first printed row carries the clock 3 dt but the position after two steps, so an
    accurate flight at the printed time is one step further on: the gap is the accurate path
    from 2 dt to 3 dt, less the a dt^2 by which the macro's start (an Euler step without forces,
    then the recurrence) runs ahead of the decelerating projectile, a = drag / m + g sin(45 deg)
    at launch. This is the 200 m of Fig 4.11 (ledger row ch4.launch_error.appendix_a_clock)."""
    with pytest.warns(trajectory.TruncatedFlightWarning):
        rows = appendix_a.simulate_appendix_a(LISTING, dt, max_time_s=2.0)
    # the accurate flight, written every 0.01 s so that interpolating it costs under 1 mm
    with pytest.warns(trajectory.TruncatedFlightWarning):
        accurate = threedof.simulate_3dof(LISTING, output_step_s=0.01, max_time_s=2.0)
    columns = ["ground_range_m", "altitude_m"]

    def truth(t):
        return np.array([np.interp(t, accurate.time_s, accurate[c]) for c in columns])

    first = rows.iloc[0]
    gap = np.linalg.norm(truth(first.time_s) - first[columns].to_numpy(float))
    path = np.linalg.norm(truth(3 * dt) - truth(2 * dt))
    gravity = earth.GM_M3_S2 / earth.RADIUS_M**2
    deceleration = gravity * (accurate.drag_to_gravity.iloc[0] + np.sin(np.radians(45.0)))
    ahead = deceleration * dt**2
    # the rest is the change of the deceleration over the first steps: a small part of a dt^2
    assert gap == pytest.approx(path - ahead, abs=0.2 * ahead)
    assert 0.99 * 2157.0 * dt < path < 2157.0 * dt  # one step at a little under V0


def test_converges_to_the_accurate_3dof_at_first_order(accurate):
    """A first-order scheme: halving the step halves the apogee error, and Richardson's
    extrapolation 2 A(dt/2) - A(dt) lands on the accurate apogee. The macro reads its apogee
    off rows 0.5 s apart, up to g (0.25 s)^2 / 2 = 0.3 m low each, so the extrapolation can be
    off by 3 x 0.3 m."""
    apogees = [
        appendix_a.simulate_appendix_a(LISTING, dt).attrs["apogee_altitude_m"] for dt in (0.2, 0.1)
    ]
    truth = accurate.attrs["apogee_altitude_m"]
    sampling_m = 3 * 0.5 * 9.8 * 0.25**2
    assert (apogees[1] - truth) / (apogees[0] - truth) == pytest.approx(0.5, abs=0.01)
    assert 2 * apogees[1] - apogees[0] == pytest.approx(truth, abs=sampling_m)


def test_shared_metadata_and_a_flight_in_the_launch_plane():
    rows = appendix_a.simulate_appendix_a(LISTING, 0.2)
    assert set(trajectory.METADATA_KEYS) <= set(rows.attrs)
    assert rows.attrs["engine"] == "Appendix A macro" and rows.attrs["launch"] is LISTING
    assert rows.attrs["impact"] and rows.attrs["stop_reason"] == "impact"
    assert rows.attrs["apogee_altitude_m"] == rows.altitude_m.max()
    assert rows.attrs["range_m"] == rows.ground_range_m.iloc[-1]
    assert np.abs(rows.cross_range_m).max() < 1e-6  # no wind, no spin: no cross range


def test_the_launch_chooses_the_air(accurate):
    """The air is the launch's: in the two-segment air the macro moves toward the 3DOF flown
    in the two-segment air (by the ~80 m the airs differ), off the three-layer one."""
    launch = LISTING.but(atmosphere="two_segment")
    two = appendix_a.simulate_appendix_a(launch, 0.1).attrs["apogee_altitude_m"]
    three = appendix_a.simulate_appendix_a(LISTING, 0.1).attrs["apogee_altitude_m"]
    truth = threedof.simulate_3dof(launch).attrs["apogee_altitude_m"]
    # a precondition, not a result: the airs must move the apogee by far more than the ~1 m
    # the macro's 0.5 s rows resolve, or the 1 % comparison below would say nothing
    assert abs(truth - accurate.attrs["apogee_altitude_m"]) > 10.0
    assert (two - three) == pytest.approx(truth - accurate.attrs["apogee_altitude_m"], rel=0.01)


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"dt_s": 0.0}, "dt_s"),
        ({"dt_s": np.nan}, "dt_s"),
        ({"elevation_deg": 95.0}, "elevation_deg"),
        ({"site_altitude_m": 1000.0}, "site_altitude_m"),
        ({"max_time_s": 0.0}, "max_time_s"),
    ],
)
def test_bad_input_is_named(kwargs, name):
    arguments = {"elevation_deg": 45.0, "dt_s": 0.1} | kwargs
    options = {key: arguments.pop(key) for key in ("dt_s", "max_time_s") if key in arguments}
    with pytest.raises(ValueError, match=name):
        appendix_a.simulate_appendix_a(LISTING.but(**arguments), **options)


def test_a_projectile_is_not_a_launch_and_wind_is_ignored_aloud():
    with pytest.raises(TypeError, match="Launch"):
        appendix_a.simulate_appendix_a(BASELINE, 0.1)
    with pytest.warns(ModelValidityWarning, match="cross_wind_m_s"):
        windy = appendix_a.simulate_appendix_a(LISTING.but(cross_wind_m_s=5.0), 0.2)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        calm = appendix_a.simulate_appendix_a(LISTING, 0.2)
    assert windy.altitude_m.to_numpy() == pytest.approx(calm.altitude_m.to_numpy(), rel=0)
