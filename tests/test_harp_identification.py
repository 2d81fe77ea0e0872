"""What Appendix E identifies of the HARP model: every combination of the open choices fitted
to the Error column, the noise its print step allows, and the verdict that follows."""

import itertools

import numpy as np
import pytest

from harp_analysis.analyses.harp import apogees, identification
from harp_analysis.analyses.harp import rounds as harp_rounds
from harp_analysis.engines import eci

OPEN = identification.OPEN_CHOICES


@pytest.fixture(scope="module")
def table():
    return identification.identification_table()


def test_the_table_has_every_combination_once(table):
    readings = sorted(tuple(row) for row in table[list(OPEN)].itertuples(index=False))
    assert readings == sorted(itertools.product(*OPEN.values()))
    # the readings are those eci.EciModel accepts, and the other choices the dissertation's
    for model in identification.combinations():
        for field in ("include_tangent", "beta_elevation", "decay", "beta_column"):
            assert getattr(model, field) == getattr(eci.DISSERTATION, field)
    marked = table[table.dissertation]
    assert len(marked) == 1
    assert all(marked[choice].iloc[0] == getattr(eci.DISSERTATION, choice) for choice in OPEN)


def test_the_dissertation_combination_is_the_dissertation_model(table):
    """Identity: with its own readings a combination fits and predicts what the model does."""
    row = table[table.dissertation].iloc[0]
    assert row.drag_area_m2 == apogees.drag_area_m2("dissertation")
    yuma = apogees.predicted_apogees("yuma")
    misfit = (yuma.residual_m - yuma.printed_error_m).to_numpy() / 1e3
    assert row.error_rms_km == pytest.approx(np.sqrt(np.mean(misfit**2)), rel=1e-12)
    assert row.error_max_km == pytest.approx(apogees.error_column_misfit_km(), rel=1e-12)
    assert row.barbados_mean_km == pytest.approx(apogees.residual_statistic("barbados"), rel=1e-12)
    assert row.barbados_std_km == pytest.approx(
        apogees.residual_statistic("barbados", "std"), rel=1e-12
    )
    assert row.round181_range_km == pytest.approx(harp_rounds.splash_range_km(), rel=1e-12)


def test_each_combination_s_drag_area_is_its_least_squares_fit(table):
    """A 0.05 % step of Cd0 A either way fits Appendix E's Error column worse."""
    for model, row in zip(identification.combinations(), _rows_in_order(table)):
        squares = []
        for factor in (1 - 5e-4, 1.0, 1 + 5e-4):
            yuma = apogees.predicted_apogees("yuma", model, row.drag_area_m2 * factor)
            squares.append(np.sum((yuma.residual_m - yuma.printed_error_m) ** 2))
        assert squares[1] < min(squares[0], squares[2]), model.name


def _rows_in_order(table):
    """The table's rows in the order of :func:`combinations`."""
    by_readings = {tuple(row[c] for c in OPEN): row for _, row in table.iterrows()}
    return [by_readings[tuple(getattr(m, c) for c in OPEN)] for m in identification.combinations()]


def test_the_noise_is_the_error_column_s_print_step():
    """Every printed Error is a whole number of 10 m steps (and not all of 20 m): the column's
    resolution, from the data."""
    steps = (
        apogees.appendix_rounds("yuma").apogee_error_m / identification.ERROR_COLUMN_RESOLUTION_M
    )
    assert np.allclose(steps, np.round(steps), atol=1e-6)
    assert not np.allclose(steps / 2, np.round(steps / 2), atol=1e-6)
    assert identification.rounding_rms_km() == pytest.approx(0.01 / np.sqrt(12))


def test_the_noise_threshold_is_rounding_s_quantile():
    """Independent reference: 22 rounding errors drawn uniformly within half a step, 200,000
    times; the RMS that 1 % of draws exceed is the threshold (to the central limit's 2 %)."""
    rng = np.random.default_rng(26)
    half_km = identification.ERROR_COLUMN_RESOLUTION_M / 2e3
    errors = rng.uniform(-half_km, half_km, size=(200_000, 22))
    quantile = np.quantile(np.sqrt(np.mean(errors**2, axis=1)), 0.99)
    assert identification.noise_threshold_km(22, 0.01) == pytest.approx(quantile, rel=0.02)


def test_the_verdict_follows_from_the_noise(table):
    threshold = identification.noise_threshold_km()
    assert (table.within_noise == (table.error_rms_km <= threshold)).all()
    for resolution_m in (10.0, 30.0):
        fits = identification.identification_table(resolution_m)
        choices = identification.choice_table(resolution_m)
        for choice in OPEN:
            readings = set(fits[choice][fits.within_noise])
            assert choices.loc[choice, "identified"] == (len(readings) == 1)


def test_appendix_e_identifies_every_open_choice(table):
    """Only the dissertation model's readings fit the Error column within its print rounding;
    the next best combination misses by over twice the noise, whatever significance is asked
    down to 1e-15. Printed to 0.03 km, the column could not tell it from the dissertation's."""
    assert table.within_noise.sum() == 1 and table.dissertation[table.within_noise].all()
    choices = identification.choice_table()
    assert choices.identified.all()
    for choice in OPEN:
        assert choices.loc[choice, "readings_within_noise"] == getattr(eci.DISSERTATION, choice)
    runner_up = table.error_rms_km[~table.within_noise].min()
    assert runner_up > 2 * identification.noise_threshold_km()
    assert runner_up > identification.noise_threshold_km(significance=1e-15)
    assert not identification.choice_table(30.0).identified.any()


def test_the_spread_is_over_the_combinations_within_noise(table):
    spread = identification.appendix_e_spread("round181_range_km", nearest_to=0.0)
    fitting = table.round181_range_km[table.within_noise]
    assert (spread.low, spread.high) == (fitting.min(), fitting.max())
    assert spread.nearest == fitting.min()
    assert spread.all_low == table.round181_range_km.min()
    runner_up = table[~table.within_noise].iloc[0]
    assert spread.runner_up == runner_up.round181_range_km
    magnitude = identification.appendix_e_spread("barbados_mean_km", magnitude=True)
    assert magnitude.dissertation == abs(apogees.residual_statistic("barbados"))


def test_a_reading_fit_is_its_best_combination(table):
    fit = identification.reading_fit("tangent_sine", "gun")
    assert fit.error_rms_km == table.error_rms_km[table.tangent_sine == "gun"].min()
    assert not fit.within_noise


@pytest.mark.parametrize(
    "call, error, message",
    [
        (lambda: identification.appendix_e_spread("apogee"), ValueError, "unknown quantity"),
        (lambda: identification.reading_fit("decay", "printed"), ValueError, "choice"),
        (lambda: identification.reading_fit("tangent_sine", "launch"), ValueError, "reading"),
        (
            lambda: identification.noise_threshold_km(significance=0.0),
            ValueError,
            "significance",
        ),
        (lambda: identification.noise_threshold_km(rounds=0), ValueError, "rounds"),
        (lambda: identification.rounding_rms_km("10"), TypeError, "resolution_m"),
    ],
)
def test_bad_arguments_are_named(call, error, message):
    with pytest.raises(error, match=message):
        call()
