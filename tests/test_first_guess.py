"""The improved MKS as the fire-control solver's first guess: against the ECI MKS where both are
exact (the vacuum conic), against the improved MKS's own impact point, against the 3DOF, and
bad input."""

import math
import warnings
from dataclasses import replace

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import pytest

from harp_analysis.analyses.fire_control import firing
from harp_analysis.analyses.fire_control.firing import TargetPoint, destination, firing_solutions
from harp_analysis.analyses.fire_control.studies import first_guess
from harp_analysis.analyses.fire_control.verification import verify_with_3dof
from harp_analysis.engines import mks_improved
from harp_analysis.foundation import earth
from harp_analysis.foundation.validation import ModelValidityWarning
from harp_analysis.models.launch import Launch
from harp_analysis.models.projectiles import HP
from harp_analysis.reporting.figures import first_guess as first_guess_figures

GUN = firing.BARBADOS_HP


def _vacuum(rotation_rate_rad_s):
    return Launch(
        HP,
        HP.launch_speed_m_s,
        45.0,
        latitude_deg=20.0,
        longitude_deg=-30.0,
        atmosphere="vacuum",
        rotation_rate_rad_s=rotation_rate_rad_s,
    )


def _improved(gun, target, root, **options):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelValidityWarning)
        return first_guess.improved_solution(gun, target, root, **options)


# --- vacuum: both models are the exact conic ----------------------------------------------------
@pytest.mark.parametrize("rotation", [0.0, earth.ROTATION_RATE_RAD_S], ids=["still", "rotating"])
@pytest.mark.parametrize("altitude_m", [0.0, 30e3])
def test_in_a_vacuum_the_improved_mks_lands_where_the_eci_mks_does(rotation, altitude_m):
    """Without air both are the drag-free conic (the improved MKS has no loss to model): flown
    at the ECI MKS's root, the improved MKS passes the target within centimetres, its own
    crossing and time of flight turned into the Earth-fixed frame; and Newton's method started
    half a degree off comes back to the ECI MKS's root."""
    gun = _vacuum(rotation)
    target = destination(gun, 60.0, 300e3, altitude_m)
    result = firing_solutions(gun, target)
    assert len(result.roots) == 2
    for root in result.roots:
        assert first_guess.improved_miss(gun, target, root) < 0.01
        same = first_guess.improved_solution(gun, target, root)
        assert same is not None
        assert same.elevation_deg == pytest.approx(root.elevation_deg, abs=1e-9)
        assert same.time_of_flight_s == pytest.approx(root.time_of_flight_s, abs=1e-3)
        off = replace(root, elevation_deg=root.elevation_deg + 0.5)
        back = first_guess.improved_solution(gun, target, off)
        assert back is not None and back.miss_m < 1.0 and back.mks_solves > 1
        # 1 m at a few hundred km per rad of elevation: within 1e-3 deg of the conic's root
        assert back.elevation_deg == pytest.approx(root.elevation_deg, abs=1e-3)
        assert back.bearing_deg == pytest.approx(root.bearing_deg, abs=1e-3)


# --- in the air: the improved MKS's own root ----------------------------------------------------
@pytest.mark.parametrize("bearing_deg", [90.0, 150.0])
def test_the_improved_root_lands_the_improved_mks_on_the_target(bearing_deg):
    """The improved solution's impact point (mks_improved's own, Earth-fixed) is within 1 m of
    the sea-level target, on both roots, though the ECI MKS's root misses by kilometres in the
    improved model."""
    target = destination(GUN, bearing_deg, 150e3)
    for root in firing_solutions(GUN, target).roots:
        assert first_guess.improved_miss(GUN, target, root) > 100.0
        better = _improved(GUN, target, root)
        assert better is not None and better.miss_m < 1.0 and better.branch == root.branch
        laid = GUN.but(elevation_deg=better.elevation_deg, bearing_deg=better.bearing_deg)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ModelValidityWarning)
            flight = mks_improved.solve(laid)
        impact = flight.impact_point_m
        assert np.linalg.norm(impact - target.earth_fixed_m()) < 1.0
        assert better.time_of_flight_s == pytest.approx(flight.impact_time_s, abs=1e-6)


def test_the_improved_mks_moves_a_long_low_shot_toward_the_3dof():
    """The ECI MKS takes no drag on the way down, so its long low-angle shot falls short in
    the 3DOF; the improved MKS's re-entry decay raises the elevation, nearer the 3DOF's root, and
    its first guess lands closer."""
    target = destination(GUN, 90.0, 180e3)
    root = firing_solutions(GUN, target).low
    better = _improved(GUN, target, root)
    check_mks, check_improved = verify_with_3dof(
        GUN, [target, target], [root, better], tolerance_m=1.0
    )
    assert root.elevation_deg < check_mks.elevation_deg  # the MKS's shot falls short
    assert abs(better.elevation_deg - check_mks.elevation_deg) < abs(
        root.elevation_deg - check_mks.elevation_deg
    )
    assert check_improved.mks_miss_m < check_mks.mks_miss_m


# --- the comparison -----------------------------------------------------------------------------
@pytest.fixture(scope="module")
def small_frame():
    return first_guess.compare_first_guesses(
        {"Barbados": GUN},
        bearings_deg=(90.0, 270.0),
        downranges_m=(120e3,),
        altitudes_m=(0.0, 30e3),
    )


def test_the_comparison_refines_both_models_to_the_same_3dof_root(small_frame):
    frame = small_frame
    assert set(frame.model) == {"mks", "improved"}
    assert set(frame.columns) >= set(first_guess.COLUMNS)
    mks = frame[frame.model == "mks"]
    assert mks.converged.all() and (mks.flights >= 1).all() and (mks.miss_m <= 1.0).all()
    found = frame[frame.elevation_deg.notna()]
    assert (found.flights >= 1).all()
    assert not (found.first_guess_miss_m <= 0).any()  # NaN: that shot never got there
    keys = ["bearing_deg", "downrange_m", "altitude_m", "root"]
    for _, pair in found[found.converged].groupby(keys):
        if len(pair) == 2:  # from either start the 3DOF lands on one root (1 m: ~1e-3 deg)
            assert np.ptp(pair.refined_elevation_deg) < 0.01
            assert np.ptp(pair.refined_bearing_deg) < 0.01
    # where the improved MKS has no root its row says why and took no flight
    none = frame[(frame.model == "improved") & frame.elevation_deg.isna()]
    assert none.reason.notna().all() and (none.flights == 0).all()
    assert math.isfinite(frame.attrs["seconds_per_3dof_flight"])


def test_the_summary_has_both_models_over_the_same_shots(small_frame):
    table = first_guess.summary(small_frame)
    assert list(table.index) == ["mks", "improved"]
    for name in ("median_miss_m", "p95_miss_m", "max_miss_m", "mean_flights"):
        assert name in table.columns
    assert table.points["mks"] == table.points["improved"] > 0
    for model in first_guess.MODELS:
        row = table.loc[model]
        assert row.median_miss_m <= row.p95_miss_m <= row.max_miss_m
        assert row.mean_flights >= 1 and row.mean_total_time_s >= row.mean_model_time_s
    assert table.no_root["mks"] == 0
    by_root = first_guess.summary(small_frame, by=("root",))
    assert set(by_root.index.get_level_values("root")) <= set(first_guess.ROOTS)


def test_the_figure_draws_both_panels(small_frame):
    fig = first_guess_figures.draw_first_guess_comparison(small_frame)
    try:
        left, right = fig.axes
        assert left.get_xscale() == "log"
        assert "Barbados" in fig._suptitle.get_text()
        assert "descending" in fig._suptitle.get_text()
    finally:
        plt.close(fig)


# --- bad input ----------------------------------------------------------------------------------
def test_bad_input_is_refused_by_name():
    target = destination(GUN, 90.0, 120e3)
    root = firing_solutions(GUN, target).low
    with pytest.raises(TypeError, match="gun"):
        first_guess.improved_solution("gun", target, root)
    with pytest.raises(TypeError, match="target"):
        first_guess.improved_solution(GUN, (13.0, -58.0), root)
    with pytest.raises(TypeError, match="solution"):
        first_guess.improved_solution(GUN, target, None)
    with pytest.raises(ValueError, match="jacobian_m_rad"):
        first_guess.improved_solution(GUN, target, replace(root, jacobian_m_rad=None))
    with pytest.raises(ValueError, match="iterations"):
        first_guess.improved_solution(GUN, target, root, iterations=0)
    with pytest.raises(TypeError, match="iterations"):
        first_guess.improved_solution(GUN, target, root, iterations=2.5)
    with pytest.raises(TypeError, match="calibration"):
        first_guess.improved_solution(GUN, target, root, calibration=1.0)
    ascending = replace(root, branch="ascending")
    with pytest.raises(ValueError, match="branch"):
        first_guess.improved_solution(GUN, TargetPoint(13.0, -58.0, 0.0), ascending)
    with pytest.raises(TypeError, match="guns"):
        first_guess.compare_first_guesses([GUN])
    with pytest.raises(TypeError, match="bearings_deg"):
        first_guess.compare_first_guesses(bearings_deg="90")
    with pytest.raises(ValueError, match="downranges_m"):
        first_guess.compare_first_guesses(downranges_m=(-1.0,))
    with pytest.raises(ValueError, match="branch"):
        first_guess.compare_first_guesses(branch="sideways")
    with pytest.raises(TypeError, match="frame"):
        first_guess.summary({"model": []})
    with pytest.raises(ValueError, match="columns"):
        first_guess.summary(pd.DataFrame({"model": ["mks"]}))
    with pytest.raises(TypeError, match="frame"):
        first_guess_figures.draw_first_guess_comparison(None)
