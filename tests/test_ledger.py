"""Every row of the claims ledger is recomputed by the package and its verdict checked."""

import pytest

from harp_analysis import ledger

CLAIMS = ledger.load_claims()


@pytest.mark.parametrize("claim", CLAIMS, ids=lambda claim: claim.id)
def test_claim_verdict_matches_computed_value(claim):
    result = ledger.evaluate(claim)
    problems = ledger.verdict_problems(result)
    assert not problems, (
        f"{claim.id} ({claim.source}): text {claim.text_value} {claim.unit}, "
        f"computed {result.computed:.6g}: " + "; ".join(problems)
    )


def test_ledger_rows_are_complete():
    assert CLAIMS, "the ledger is empty"
    for claim in CLAIMS:
        assert claim.statement.strip() and claim.source.strip() and claim.unit.strip()
        assert claim.tolerance >= 0


def _write(tmp_path, body):
    path = tmp_path / "claims.toml"
    path.write_text(body)
    return path


ROW = """[[claim]]
id = "x"
source = "eq 1"
statement = "one"
text_value = 1.0
unit = "-"
compute = "numpy:asarray"
kwargs = {{ a = {x} }}
tolerance = 0.01
verdict = "{verdict}"
explanation = "{explanation}"
{extra}
"""


@pytest.mark.parametrize(
    "x, verdict, explanation, extra, ok",
    [
        (1.0, "reproduces", "", "", True),
        (1.1, "reproduces", "", "", False),
        (1.1, "close", "because", "close_tolerance = 0.2", True),
        (1.1, "close", "", "close_tolerance = 0.2", False),  # no explanation
        (1.0, "close", "because", "close_tolerance = 0.2", False),  # actually reproduces
        (2.0, "close", "because", "close_tolerance = 0.2", False),  # further than close
        (2.0, "does not reproduce", "because", "", True),
        (1.0, "does not reproduce", "because", "", False),  # stale verdict
    ],
)
def test_verdict_rules(tmp_path, x, verdict, explanation, extra, ok):
    path = _write(tmp_path, ROW.format(x=x, verdict=verdict, explanation=explanation, extra=extra))
    (claim,) = ledger.load_claims(path)
    assert (not ledger.verdict_problems(ledger.evaluate(claim))) is ok


@pytest.mark.parametrize(
    "x, bound, ok",
    [(0.5, "upper", True), (1.5, "upper", False), (1.5, "lower", True), (0.5, "lower", False)],
)
def test_bounds_count_only_the_wrong_side(tmp_path, x, bound, ok):
    path = _write(
        tmp_path, ROW.format(x=x, verdict="reproduces", explanation="", extra=f'bound = "{bound}"')
    )
    (claim,) = ledger.load_claims(path)
    assert ledger.evaluate(claim).within_tolerance is ok


def test_relative_tolerance(tmp_path):
    path = _write(
        tmp_path,
        ROW.format(
            x=1.01, verdict="reproduces", explanation="", extra='tolerance_kind = "relative"'
        ),
    )
    (claim,) = ledger.load_claims(path)
    assert ledger.evaluate(claim).deviation == pytest.approx(0.01)


@pytest.mark.parametrize(
    "edit, message",
    [
        (('verdict = "reproduces"', 'verdict = "maybe"'), "verdict"),
        (('compute = "numpy:asarray"', 'compute = "numpy.asarray"'), "module:function"),
        (('unit = "-"', ""), "missing field"),
        (("tolerance = 0.01", "tolerance = 0.01\ncolour = 1"), "unknown field"),
    ],
)
def test_malformed_ledger_rows_are_named(tmp_path, edit, message):
    body = ROW.format(x=1.0, verdict="reproduces", explanation="", extra="").replace(*edit)
    with pytest.raises(ValueError, match=f"claim 'x'.*{message}"):
        ledger.load_claims(_write(tmp_path, body))


def test_render_claims(tmp_path):
    text = ledger.render_claims(tmp_path / "CLAIMS.md").read_text()
    for claim in CLAIMS:
        assert f"`{claim.id}`" in text
