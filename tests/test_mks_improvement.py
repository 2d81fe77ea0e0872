"""The improved MKS judged broadly (issue 26): the broad set holds what it says (every
projectile, speed, elevation, Earth and day's air; none of it a training launch or an error-map
point), its batch errors are those of the tables' route, telling the MKS the day's air helps
the MKS that integrates through the air, and the statistics are those of the rows. A small
subset is flown here; the ledger flies the whole set."""

import math
import warnings

import numpy as np
import pandas as pd
import pytest

from harp_analysis.analyses import mks_improvement
from harp_analysis.engines import mks, mks_improved, threedof
from harp_analysis.foundation.validation import ModelValidityWarning

SUBSET = {"speeds_m_s": (1500.0, 3000.0), "elevations_deg": (35.0, 65.0)}


@pytest.fixture(scope="module")
def subset():
    return mks_improvement.broad_judgement(**SUBSET)


def test_the_broad_set_spans_what_it_is_judged_on():
    launches = mks_improvement.broad_launches()
    flown = [entry.flown for entry in launches]
    assert {entry.projectile for entry in launches} == {"HP", "LP", "baseline", "Martlet"}
    assert {launch.speed_m_s for launch in flown} == {1500.0, 2000.0, 2500.0, 3000.0, 3500.0}
    assert {launch.elevation_deg for launch in flown} == {20.0, 35.0, 50.0, 65.0, 85.0}
    assert {entry.earth for entry in launches} == {"still", "turning"}
    assert {entry.air for entry in launches} == {"standard", "told", "untold"}
    for entry in launches:
        turning = entry.flown.rotation_rate_rad_s != 0.0
        assert turning == (entry.earth == "turning")
        assert entry.flown.has_day_air == (entry.air != "standard")
        if entry.air != "untold":
            assert entry.told == entry.flown
        else:  # the same day flown, the standard air told
            assert not entry.told.has_day_air
            assert entry.told == entry.flown.but(
                density_change_fraction=0.0, temperature_change_k=0.0
            )


def test_the_broad_set_is_neither_fitted_nor_mapped():
    """No broad launch is a training launch, and none lies on the error map the validity band
    was drawn from (the map flies the baseline at its 2157 m/s on a grid of bearings and
    latitudes; the broad set draws them off it)."""
    launches = {entry.flown for entry in mks_improvement.broad_launches()}
    launches |= {entry.told for entry in mks_improvement.broad_launches()}
    assert not launches & set(mks_improvement.TRAINING)
    mapped = {
        mks_improvement._rotating(e, lat, b)
        for b in mks_improvement.MAP_BEARINGS_DEG
        for e in mks_improvement.MAP_ELEVATIONS_DEG
        for lat in mks_improvement.MAP_LATITUDES_DEG
    }
    assert not launches & mapped
    turning = [launch for launch in launches if launch.rotation_rate_rad_s != 0.0]
    assert not {launch.bearing_deg for launch in turning} & set(mks_improvement.MAP_BEARINGS_DEG)


def test_batch_errors_are_those_of_the_3dof_tables(subset):
    """The broad set flies the 3DOF in compiled batches without tables; launch_errors takes the
    tabled flight of one launch (an independent route through simulate_3dof)."""
    launches = mks_improvement.broad_launches(**SUBSET)
    for index in (0, 7, 17, len(launches) - 1):
        entry = launches[index]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ModelValidityWarning)
            solution = mks_improved.solve(entry.told, mks_improvement.calibration())
        errors = mks_improvement.launch_errors(
            entry.flown, solution, threedof.simulate_3dof(entry.flown, output_step_s=1.0)
        )
        row = subset.iloc[index]
        # the two routes integrate the same equations to rtol 1e-9: metres, milliseconds
        assert row.improved_impact_range_error_m == pytest.approx(
            errors.impact_range_error_m, abs=1.0
        )
        assert row.improved_impact_time_error_s == pytest.approx(
            errors.impact_time_error_s, abs=1e-3
        )
        assert row.improved_impact_miss_m == pytest.approx(errors.impact_miss_m, abs=1.0)


def test_the_text_validity_split_is_eq_3_22s_beta(subset):
    inside = subset.beta <= mks.BETA_VALIDITY_LIMIT
    assert (subset.validity == np.where(inside, "inside", "outside")).all()
    assert (subset.warning == "warned").equals(subset.beta > mks_improved.MAX_JUDGED_BETA)
    assert inside.any() and (~inside).any()


def test_telling_the_improved_mks_the_days_air_helps(subset):
    """The improved MKS integrates its loss through the launch's air, so the day's density and
    temperature, told, move it with the 3DOF; untold, its apogee error is about the day's own
    effect on the 3DOF's apogee. Over the subset's pairs the told apogee errors are smaller."""
    told, untold = (subset[subset.air == air].reset_index(drop=True) for air in ("told", "untold"))
    both = told.improved_apogee_error_m.notna() & untold.improved_apogee_error_m.notna()
    told_error = np.abs(told.improved_apogee_error_m[both])
    untold_error = np.abs(untold.improved_apogee_error_m[both])
    assert np.median(told_error) < np.median(untold_error)


def test_statistics_are_those_of_the_rows():
    """Three launches, one the improved MKS cannot solve (left out of both variants)."""
    frame = pd.DataFrame(
        {
            "validity": ["inside", "inside", "outside"],
            "earth": ["still", "turning", "turning"],
            "air": ["standard", "told", "untold"],
            "air_momentum_share": [0.0, 0.1, 2.0],
            **{
                f"{variant}_{measure}": values
                for measure in mks_improvement.BROAD_MEASURES
                for variant, values in (
                    ("dissertation", [-3.0, 4.0, 10.0]),
                    ("improved", [1.0, -1.0, np.nan]),
                )
            },
        }
    )
    result = mks_improvement.broad_improvement("apogee_error_m", judged=frame)
    assert result.launches == 2 and result.unsolved == 1
    assert result.dissertation == pytest.approx(math.sqrt(12.5))
    assert result.improved == 1.0 and result.better_share == 1.0
    median = mks_improvement.broad_improvement("impact_time_error_s", "median", judged=frame)
    assert (median.improved, median.dissertation) == (1.0, 3.5)
    turning = mks_improvement.broad_improvement("impact_miss_m", earth="turning", judged=frame)
    assert (turning.launches, turning.unsolved, turning.ratio) == (1, 1, 0.25)
    table = mks_improvement.broad_errors("validity", frame)
    assert table.loc[("inside", "improved"), "apogee_error_m_rms"] == 1.0
    assert table.loc[("outside", "improved"), "unsolved"] == 1
    shares = mks_improvement.map_shares(frame, ("impact_miss_m",))
    assert (shares.inside, shares.better_impact_miss_m_inside) == (2, 1.0)
    assert shares.better_impact_miss_m_outside == 0.0  # unsolved counts as not better


def test_bad_choices_are_named():
    for call, name in (
        (lambda: mks_improvement.broad_errors("bearing"), "split"),
        (lambda: mks_improvement.broad_improvement("range_m"), "measure"),
        (lambda: mks_improvement.broad_improvement(statistic="mean"), "statistic"),
        (lambda: mks_improvement.broad_improvement(air="humid"), "air"),
    ):
        with pytest.raises(ValueError, match=name):
            call()
