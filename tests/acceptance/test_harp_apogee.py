"""Acceptance: the HARP apogee statistics of Chapter 6, per model, against the text's numbers.

Thresholds are the text's (Ch. 6 C: Barbados within 0.4 km of the centre, standard deviation
2.25 km; Ch. 6 D: Yuma 0.44 km from the centre, 2.65 km), both sites' centres read alike as the
magnitude of the mean residual (ledger row ch6.barbados.mean). Tolerances come from how the
text prints them: its statistics are Appendix E's own truncated (its errors average 0.447 km,
standard deviation 2.657 km), so a value reproduces in [text - half a unit, text + one unit)
of the last printed digit. The statistics a model does not reproduce are
strict xfails naming their ledger row, where the reason is argued.
"""

import pytest

from harp_analysis.analyses.harp import apogees

TEXT = {  # (site, statistic): (lowest, highest accepted value, km)
    ("barbados", "abs_mean"): (0.35, 0.5),
    ("barbados", "std"): (2.245, 2.26),
    ("yuma", "mean"): (0.435, 0.45),
    ("yuma", "std"): (2.645, 2.66),
}
#: (model, site, statistic) that do not reproduce: the ledger row that says why.
DEVIATIONS = {
    ("dissertation", "barbados", "abs_mean"): "ch6.barbados.mean",
    ("dissertation", "barbados", "std"): "ch6.barbados.std",
    ("consistent", "barbados", "abs_mean"): "ch6.barbados.mean.consistent",
    ("consistent", "barbados", "std"): "ch6.barbados.std.consistent",
    ("consistent", "yuma", "mean"): "ch6.yuma.mean.consistent",
    ("consistent", "yuma", "std"): "ch6.yuma.std.consistent",
    ("printed_columns", "barbados", "abs_mean"): "ch6.barbados.mean.printed_columns",
    ("printed_columns", "barbados", "std"): "ch6.barbados.std.printed_columns",
    ("printed_columns", "yuma", "mean"): "ch6.yuma.mean.printed_columns",
}
CASES = [
    pytest.param(
        model,
        site,
        statistic,
        marks=(
            [
                pytest.mark.xfail(
                    strict=True, reason=f"ledger row {DEVIATIONS[model, site, statistic]}"
                )
            ]
            if (model, site, statistic) in DEVIATIONS
            else []
        ),
    )
    for model in ("dissertation", "consistent", "printed_columns")
    for site, statistic in TEXT
]


@pytest.mark.parametrize("model, site, statistic", CASES)
def test_residual_statistic_matches_the_text(model, site, statistic):
    low, high = TEXT[site, statistic]
    value = apogees.residual_statistic(site, statistic, model=model)
    assert low <= value < high, f"{model} {site} {statistic}: {value:.3f} km, text [{low}, {high})"


def test_dissertation_model_reproduces_every_printed_yuma_error():
    """Issue threshold 0.02 km per round; print rounding alone allows 0.005 km."""
    frame = apogees.predicted_apogees("yuma", "dissertation")
    assert len(frame) == 22
    assert (frame.residual_m - frame.printed_error_m).abs().max() < 20.0


def test_every_printed_row_is_predicted():
    assert len(apogees.predicted_apogees("barbados")) == 23


def test_unknown_names_are_named():
    with pytest.raises(ValueError, match="site"):
        apogees.predicted_apogees("woomera")
    with pytest.raises(ValueError, match="statistic"):
        apogees.residual_statistic("yuma", "median")
    with pytest.raises(ValueError, match="model"):
        apogees.predicted_apogees("yuma", "newtonian")
