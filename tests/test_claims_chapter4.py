"""The quantities of harp_analysis.analyses.claims.chapter4, checked against eq 3.22, the flown
launches, bounds and Chapter 4's own errors."""

import math

import pytest

from harp_analysis.analyses import comparisons, rotating
from harp_analysis.analyses.claims import chapter4
from harp_analysis.engines import mks
from harp_analysis.models.launch import baseline_chapter_4


def test_beta_limit_elevation_solves_eq_3_22():
    elevation = chapter4.beta_limit_elevation_deg("baseline", 0.25)
    cd0 = baseline_chapter_4(elevation).launch_drag_coefficient  # eq 4.8 at the launch Mach
    beta = mks.decay_factor_beta(cd0, 1.225, 0.008, 11.6, math.radians(elevation), 0.117e-3)
    assert float(beta) == pytest.approx(0.25, rel=1e-9)
    assert math.isnan(chapter4.beta_limit_elevation_deg("LP", 0.25))  # 0.39 even at 90 deg


def test_beta_accuracy_limit_grows_with_the_allowed_error_and_brackets_hp():
    one, two = chapter4.beta_accuracy_limit(1.0), chapter4.beta_accuracy_limit(2.0)
    assert 0 < one < two
    # HP itself (beta 0.2745) errs by 2.21 km at apogee, more than 2 km
    assert two < 0.2745


def test_min_mach_is_below_the_launch_mach_and_the_whole_flight_is_slower():
    ascent = chapter4.min_mach_below(40.0, "ascent")
    flight = chapter4.min_mach_below(40.0, "flight")
    assert 1 < flight <= ascent < 2157.0 / 340.0


def test_variant_speed_increase_is_the_flown_launches_and_about_a_fifth():
    """The increase is that of the launches Fig 4.17's comparison flies (the 3DOF's first
    speed), and Ch. 4 C's "20 % increase" to the printed 2.59 km/s's rounding."""
    faster = comparisons.case("baseline", 45.0, **comparisons.VARIANTS["speed_plus_20pct"])[0]
    baseline = comparisons.case("baseline", 45.0)[0]
    flown = faster.speed_m_s.iloc[0] / baseline.speed_m_s.iloc[0] - 1
    assert chapter4.variant_speed_increase() == pytest.approx(flown, rel=1e-9)
    assert chapter4.variant_speed_increase() == pytest.approx(0.20, abs=0.005 / 2.157)


def test_the_clock_s_launch_error_shrinks_as_the_speed_does():
    """Appendix A's clock leads its positions by one step, so the MKS is V dt ahead: below 30 km
    on the way up that part has fallen with the speed, while the MKS's own error (zero at
    launch) has grown, so the error left lies between the speed ratio and 1."""
    rows, _ = rotating.appendix_a_errors(0.1, 45.0)
    climbing = rows[(rows.time_s <= rows.attrs["apogee_time_s"]) & (rows.altitude_m < 30e3)]
    speed_ratio = climbing.speed_m_s.min() / rows.speed_m_s.iloc[0]
    assert speed_ratio < chapter4.launch_error_left_below(30.0, 0.1, 45.0) < 1.0
    assert rotating.appendix_a_errors(0.1, 45.0)[1].total_geometric_m.iloc[0] == pytest.approx(
        rotating.appendix_a_launch_error_m(0.1, 45.0)
    )


@pytest.mark.parametrize("engine", ["6DOF", "MLT", "3DOF"])
def test_the_descent_s_fastest_point_is_slower_than_the_gun_and_faster_than_impact(engine):
    """Drag takes energy all the way: the fastest point on the way down is slower than the
    launch (2022 m/s, Chapter 2 A) and faster than the apogee's speed and the impact."""
    loss = chapter4.reentry_speed_loss(engine, "HP")
    assert loss.impact_speed_m_s < loss.peak_speed_m_s < 2022.0
    assert 0.0 < loss.loss < 1.0 and 0.0 < loss.flight_share < 0.5


def test_off_design_error_at_the_design_launch_is_chapter_4_s():
    design = chapter4.off_design_error(45.0, 2157.0)
    assert design.error_km == pytest.approx(comparisons.error_at_apogee_km("baseline", 45.0))
    assert design.share_of_apogee == pytest.approx(
        comparisons.error_at_apogee_km("baseline", 45.0, relative=True)
    )
