"""The claims ledger: the dissertation's checkable statements, recomputed by the package.

The ledger is ``registry/claims.toml``. Each ``[[claim]]`` names the package callable that
computes the project's value (``compute = "module:function"``, with optional ``kwargs``, an
optional ``field`` to read from the result, dotted for a field of a field, and an optional
``scale`` to the row's unit), so the value is recomputed on every evaluation and never typed
in. Verdicts are checked against the
numbers (:func:`verdict_problems`), so a verdict cannot silently go stale:

- ``reproduces``: the computed value is within ``tolerance`` of the text's;
- ``close``: outside ``tolerance`` but within ``close_tolerance``, with an explanation;
- ``does not reproduce``: outside ``close_tolerance`` (or ``tolerance`` if none), with an
  explanation;
- ``recovered``: within ``tolerance``, but of a value the project fitted to the very number it
  is scored against (a drag area fitted to Appendix E's Error column, then Appendix E's mean
  error; a speed of sound fitted to a Mach column, then that column): the row says what was
  fitted in ``fitted_to``, and such a row can never read ``reproduces``. A fit that misses its
  own target reads ``close`` or ``does not reproduce`` as any row.

A value known only to within ``margin`` (a count that rounding moves by a few per cent, a
statistic of data printed in coarse steps), or to an ``interval`` its computation returns (the
dotted attribute of what ``compute`` returns holding ``.low`` and ``.high``, ``"."`` for what it
returns itself: the confidence interval of a statistic of 22 rounds), reproduces only if it
does so across all of it, and fails only if it fails across all of it: a value whose margin or
interval straddles a tolerance's edge is ``close``, whichever side it falls
(:func:`deviation_range`, the one rule :func:`earned_verdict` applies to every row).

Tolerances are absolute in the row's unit, or relative when ``tolerance_kind = "relative"``.
An explanation may quote the computation's own numbers instead of typing them: ``<<name>>`` or
``<<name:format>>`` (a format spec, as ``<<apogee_km:.1f>>``) is replaced by the attribute
``name`` (dotted for an attribute of an attribute) of what ``compute`` returned, before
``field`` picks the value; ``<<value>>`` is the computed value itself. A number so quoted
cannot drift from the computation (:func:`ClaimResult.explanation`).

A claim that is a bound ("less than 1 %", "over 4 degrees") sets ``bound = "upper"`` or
``"lower"``: only a computed value on the wrong side of the text's counts as a deviation.

Every row names the figures and tables it speaks about, ``figures = ["4.7", "Table 4.1",
"X.5"]`` (required; empty for a row no figure draws): those its ``source`` cites and those the
text's paragraph it comes from discusses (tests/test_ledger.py checks both), so a figure's
status answers to every row about it, unfavourable ones included.

A row locates the text it scores: its ``statement`` quotes the paragraph (or the table or
equation line) verbatim over at least eight words, or it sets ``quote``, a short verbatim
excerpt of it of at least five words (optional otherwise). tests/test_ledger.py finds every
row's paragraph in the text by one or the other, and checks that each figure the paragraph cites
is among the row's ``figures``.
A row tied to a figure by its paragraph but about something the figure cannot draw (the
3DOF's integrator, of a figure of the 6DOF's angle of attack) is exempted from that figure's
status with the reason: ``exempt = { "2.5" = "why" }``.

Extension results, ``[[extension]]`` rows, are the project's own measurements beyond the text
(its improved MKS, readings resting on input sizes or hypotheses the text does not give): the
same fields but no ``text_value``, tolerance or verdict, and shown apart in CLAIMS.md. A row
that scores the project's own extension against a suggestion of the text ("may give a slight
improvement") is one of these, not a claim.

Every row also carries ``expected = [low, high]``, the range its computed value is expected to
stay in whatever the verdict (:func:`range_problem`): a regression guard, so a change that moves
a value that does not reproduce is caught too. Optional: ``digits`` (significant digits
CLAIMS.md prints, :func:`printed_digits`).
"""

from __future__ import annotations

import importlib
import math
import re
from dataclasses import dataclass, field
from pathlib import Path

from ..foundation import paths
from ..foundation.caching import cached_copies
from .registry import load_toml_rows

__all__ = [
    "claims_by_figure",
    "measurements_by_figure",
    "bearing_on",
    "known_to",
    "headline",
    "quote_rows",
    "range_problem",
    "printed_digits",
    "Row",
    "Claim",
    "Measurement",
    "ClaimResult",
    "MeasuredResult",
    "load_claims",
    "load_measurements",
    "evaluate",
    "evaluate_all",
    "evaluate_measurements",
    "deviation_range",
    "earned_verdict",
    "verdict_problems",
    "render_claims",
    "VERDICTS",
]

VERDICTS = ("reproduces", "recovered", "close", "does not reproduce")
_ROW_FIELDS = ("id", "source", "statement", "unit", "compute", "explanation", "figures")
_REQUIRED = {
    "claim": (*_ROW_FIELDS, "text_value", "tolerance", "verdict"),
    "extension": (*_ROW_FIELDS, "expected"),
}


@dataclass(frozen=True, kw_only=True)
class Row:
    """What every row of the ledger has: what it measures, how the package computes it, and
    the range its value must stay in (see the module docstring)."""

    id: str
    source: str
    statement: str
    unit: str
    compute: str
    explanation: str
    figures: tuple[str, ...]  # the figures and tables it is about (see the module docstring)
    kwargs: dict = field(default_factory=dict, hash=False)
    field: str | None = None
    scale: float = 1.0
    digits: int | None = None  # significant digits CLAIMS.md prints; default: what the
    # tolerance resolves, 3 to 6 (see printed_digits)
    expected: tuple[float, float] | None = None  # the range the computed value must stay in
    quote: str | None = None  # verbatim words of the text's paragraph, where the statement
    # does not quote it (see the module docstring)


@dataclass(frozen=True, kw_only=True)
class Claim(Row):
    """A statement of the text, scored: its value, tolerance and the verdict it earns."""

    text_value: float
    tolerance: float
    verdict: str
    tolerance_kind: str = "absolute"
    close_tolerance: float | None = None
    bound: str | None = None
    fitted_to: str | None = None  # what the project fitted to the number scored (recovered)
    margin: float = 0.0  # how far the computed value is known, in the tolerance's terms
    interval: str | None = None  # the attribute of what compute returns (dotted) holding the
    # interval (.low, .high) the computed value is known to
    exempt: dict[str, str] = field(default_factory=dict, hash=False)  # figure: why this row,
    # tied to it by its paragraph, does not bear on what the figure draws


@dataclass(frozen=True, kw_only=True)
class Measurement(Row):
    """An extension result: a value the project measures of its own work, beyond what the text
    states (the project's improved MKS, a reading of its own). It has no text value and no
    verdict: nothing in the text to score it against; ``expected`` guards it."""


_QUOTE = re.compile(r"<<([A-Za-z_][\w.]*)(?::([^>]*))?>>")


def _attribute(details: object, name: str, row: Row, what: str) -> object:
    """The dotted attribute ``name`` of ``details``; one it lacks is a ValueError naming the
    row and what asked for it."""
    value = details
    for part in name.split("."):
        if not hasattr(value, part):
            raise ValueError(
                f"ledger row {row.id!r}: its {what} names {name!r}, which {row.compute} "
                "does not return"
            )
        value = getattr(value, part)
    return value


def _quoted(row: Row, computed: float, details: object) -> str:
    """``row``'s explanation with every ``<<name:format>>`` quoted from ``details``
    (``<<value>>``: the computed value)."""

    def quote(match: re.Match) -> str:
        name, spec = match.group(1), match.group(2) or ""
        value = computed if name == "value" else _attribute(details, name, row, "explanation")
        return format(value, spec)

    return _QUOTE.sub(quote, row.explanation)


def _deviation(claim: Claim, value: float) -> float:
    """|value - text| (for a bound, only past it), relative to the text's value when the
    tolerance is relative."""
    difference = value - claim.text_value
    difference = {"upper": max(difference, 0.0), "lower": max(-difference, 0.0)}.get(
        claim.bound or "", abs(difference)
    )
    if claim.tolerance_kind == "relative":
        return difference / abs(claim.text_value)
    return difference


@dataclass(frozen=True)
class ClaimResult:
    claim: Claim
    computed: float
    details: object = None  # what the compute returned, whose attributes explanations quote
    interval: tuple[float, float] | None = None  # the claim's interval, in the row's unit

    @property
    def explanation(self) -> str:
        """The claim's explanation with every ``<<name:format>>`` quoted from :attr:`details`
        (``<<value>>``: the computed value); a name it lacks is a ValueError naming the row."""
        return _quoted(self.claim, self.computed, self.details)

    @property
    def deviation(self) -> float:
        """|computed - text| (for a bound, only past it), relative to the text's value when
        the tolerance is relative."""
        return _deviation(self.claim, self.computed)

    @property
    def within_tolerance(self) -> bool:
        return self.deviation <= self.claim.tolerance


@dataclass(frozen=True)
class MeasuredResult:
    """An extension result evaluated: the measured value, no verdict."""

    row: Measurement
    computed: float
    details: object = None

    @property
    def explanation(self) -> str:
        return _quoted(self.row, self.computed, self.details)


def _row(table: str, raw: dict, source: Path) -> Claim | Measurement:
    """A ``[[claim]]`` or ``[[extension]]`` row of ``source``, checked field by field."""
    kind = Claim if table == "claim" else Measurement
    where = f"{source.name} {table} {raw.get('id', '?')!r}"
    _check_names(raw, table, kind, where)
    _check_values(raw, where)
    raw = {**raw, "figures": tuple(raw["figures"])}
    if "expected" in raw:
        raw = {**raw, "expected": _expected_range(raw["expected"], where)}
    if kind is Claim:
        _check_claim(raw, where)
    return kind(**raw)


def _check_names(raw: dict, table: str, kind: type[Claim | Measurement], where: str) -> None:
    """Every field ``table`` requires is there, and none that ``kind`` lacks."""
    missing = [name for name in _REQUIRED[table] if name not in raw]
    if missing:
        raise ValueError(f"{where}: missing field(s) {', '.join(missing)}")
    unknown = set(raw) - set(kind.__dataclass_fields__)
    if unknown:
        raise ValueError(f"{where}: unknown field(s) {', '.join(sorted(unknown))}")


def _check_values(raw: dict, where: str) -> None:
    """The values of the fields of either kind of row: compute, figures and quote (if any)."""
    if ":" not in raw["compute"]:
        raise ValueError(f"{where}: compute must read 'module:function', got {raw['compute']!r}")
    figures = raw["figures"]
    if not isinstance(figures, list) or not all(isinstance(f, str) for f in figures):
        raise ValueError(f'{where}: figures must be a list of figure numbers such as "4.7"')
    if "quote" in raw and (
        not isinstance(raw["quote"], str) or len(re.findall(r"\w+", raw["quote"])) < 5
    ):
        raise ValueError(f"{where}: quote must be at least five words of the text")


def _expected_range(low_high, where: str) -> tuple[float, float]:
    """A row's ``expected`` range, checked: [low, high] with low < high."""
    if (
        not isinstance(low_high, list)
        or len(low_high) != 2
        or not all(isinstance(v, int | float) for v in low_high)
        or not low_high[0] < low_high[1]
    ):
        raise ValueError(f"{where}: expected must be [low, high] with low < high")
    return float(low_high[0]), float(low_high[1])


def _check_claim(raw: dict, where: str) -> None:
    """The fields only a scored row has: its verdict, tolerance, bound and exemptions."""
    if raw["verdict"] not in VERDICTS:
        raise ValueError(f"{where}: verdict {raw['verdict']!r} is not one of {VERDICTS}")
    if raw.get("tolerance_kind", "absolute") not in ("absolute", "relative"):
        raise ValueError(f"{where}: tolerance_kind must be 'absolute' or 'relative'")
    if raw.get("bound") not in (None, "upper", "lower"):
        raise ValueError(f"{where}: bound must be 'upper' or 'lower'")
    exempt = raw.get("exempt", {})
    if not isinstance(exempt, dict) or not all(
        isinstance(reason, str) and reason.strip() for reason in exempt.values()
    ):
        raise ValueError(f"{where}: exempt must map figure numbers to the reason for each")
    if not set(exempt) <= set(raw["figures"]):
        raise ValueError(
            f"{where}: exempt names {sorted(set(exempt) - set(raw['figures']))}, which are not "
            "among its figures (a row is exempted only from a figure it is tied to)"
        )


@cached_copies
def load_claims(path: Path | None = None) -> tuple[Claim, ...]:
    """Every claim of the ledger (its ``[[claim]]`` rows), in file order; ids must be unique
    across the ledger."""
    return _load(path)[0]


@cached_copies
def load_measurements(path: Path | None = None) -> tuple[Measurement, ...]:
    """Every extension result of the ledger (its ``[[extension]]`` rows), in file order."""
    return _load(path)[1]


def _load(path: Path | None) -> tuple[tuple[Claim, ...], tuple[Measurement, ...]]:
    path = Path(path) if path else paths.REGISTRY_DIR / "claims.toml"
    tables = tuple(
        load_toml_rows(path, table, lambda raw, _, source, t=table: _row(t, raw, source), "id")
        for table in ("claim", "extension")
    )
    ids = [row.id for rows in tables for row in rows]
    shared = sorted({i for i in ids if ids.count(i) > 1})
    if shared:
        raise ValueError(f"{path.name}: ids {shared} name both a claim and an extension result")
    return tables  # type: ignore[return-value]  # (claims, extension results), as built


def _computed(row: Row) -> tuple[float, object]:
    """The value the package computes for ``row`` now (its unit), and what compute returned."""
    module_name, _, attribute = row.compute.partition(":")
    details = getattr(importlib.import_module(module_name), attribute)(**row.kwargs)
    result = _attribute(details, row.field, row, "field") if row.field else details
    return float(result) * row.scale, details  # type: ignore[arg-type]  # a number, by contract


def evaluate(claim: Claim) -> ClaimResult:
    """Compute the project's value of ``claim`` by calling the package."""
    computed, details = _computed(claim)
    interval = None
    if claim.interval:
        known = (
            details
            if claim.interval == "."
            else _attribute(details, claim.interval, claim, "interval")
        )
        interval = (
            float(known.low) * claim.scale,  # type: ignore[attr-defined]
            float(known.high) * claim.scale,  # type: ignore[attr-defined]
        )
        if not interval[0] <= computed <= interval[1]:
            raise ValueError(
                f"claim {claim.id!r}: its value {computed:.6g} lies outside its interval "
                f"[{interval[0]:.6g}, {interval[1]:.6g}]"
            )
    return ClaimResult(claim, computed, details, interval)


def evaluate_all(prefix: str | tuple[str, ...] = "") -> list[ClaimResult]:
    """Evaluate every claim, or only those whose id starts with ``prefix`` (a notebook's own)."""
    return [evaluate(claim) for claim in load_claims() if claim.id.startswith(prefix)]


def evaluate_measurements() -> list[MeasuredResult]:
    """Measure every extension result of the ledger."""
    return [MeasuredResult(row, *_computed(row)) for row in load_measurements()]


def range_problem(result: ClaimResult | MeasuredResult) -> str | None:
    """Why ``result``'s computed value is outside its row's expected range (a regression guard
    that holds whatever the verdict), or None."""
    row = result.claim if isinstance(result, ClaimResult) else result.row
    if row.expected is None:
        return "no expected range"
    low, high = row.expected
    if not low <= result.computed <= high:
        return f"computed {result.computed:.6g} is outside the expected range [{low:g}, {high:g}]"
    return None


def deviation_range(result: ClaimResult) -> tuple[float, float]:
    """The least and the greatest deviation the claim's value may have: its deviation, widened
    by its ``margin`` both ways and, where the row names an ``interval``, over every value of
    the interval. The one rule every verdict answers to: a value reproduces only if it does so
    across what it is known to, and fails only if it fails across it."""
    claim = result.claim
    low_value, high_value = result.interval or (result.computed, result.computed)
    ends = [_deviation(claim, value) for value in (low_value, high_value)]
    inside = claim.bound is None and low_value <= claim.text_value <= high_value
    least = 0.0 if inside else min(ends)
    return least - claim.margin, max(ends) + claim.margin


def earned_verdict(result: ClaimResult) -> str:
    """The verdict ``result``'s numbers earn (:func:`deviation_range` against the tolerances):
    "reproduces" (or "recovered", for a value fitted to its target) if every value it may have
    is within the tolerance, "close" if some value is within the close tolerance (or the
    tolerance, where there is none), else "does not reproduce"."""
    claim = result.claim
    least, greatest = deviation_range(result)
    if greatest <= claim.tolerance:
        return "recovered" if claim.fitted_to else "reproduces"
    close = claim.tolerance if claim.close_tolerance is None else claim.close_tolerance
    return "close" if least <= close else "does not reproduce"


def verdict_problems(result: ClaimResult) -> list[str]:
    """Why ``result``'s verdict does not match its numbers (empty when it does)."""
    claim = result.claim
    if not math.isfinite(result.computed):
        return [f"computed value is {result.computed}"]
    problems = []
    if claim.verdict == "recovered" and not claim.fitted_to:
        problems.append("verdict 'recovered' needs fitted_to: what was fitted to the number")
    if claim.verdict in ("close", "does not reproduce") and not claim.explanation.strip():
        problems.append(f"verdict {claim.verdict!r} needs an explanation")
    earned = earned_verdict(result)
    if claim.verdict != earned and (claim.verdict, earned) != ("recovered", "reproduces"):
        problems.append(_unearned(result, earned))
    return problems


def _unearned(result: ClaimResult, earned: str) -> str:
    """Why ``result``'s verdict is not the one its numbers earn (``earned``): its deviation
    (and the range it is known to) against its tolerances."""
    claim = result.claim
    least, greatest = deviation_range(result)
    known = (
        f", known to {max(least, 0.0):.4g}-{greatest:.4g}"
        if claim.margin or result.interval
        else ""
    )
    close = "" if claim.close_tolerance is None else f", close tolerance {claim.close_tolerance:g}"
    fitted = f" (fitted to {claim.fitted_to})" if claim.fitted_to else ""
    return (
        f"marked {claim.verdict!r} but its numbers earn {earned!r}{fitted}: deviation "
        f"{result.deviation:.4g}{known}, tolerance {claim.tolerance:g}{close}"
    )


def printed_digits(result: ClaimResult | MeasuredResult) -> int:
    """Significant digits of the computed value in CLAIMS.md: the row's ``digits``, or enough
    to resolve its tolerance (3 to 6; 3 for an extension result, which has none). More would
    print the last bits, which differ between machines."""
    if isinstance(result, MeasuredResult):
        return result.row.digits or 3
    claim = result.claim
    if claim.digits is not None:
        return claim.digits
    scale = 1.0 if claim.tolerance_kind == "relative" else abs(result.computed)
    if claim.tolerance <= 0 or scale == 0:
        return 3
    return int(min(max(math.ceil(math.log10(scale / claim.tolerance)) + 1, 3), 6))


def _number(value: float, digits: int = 6) -> str:
    return f"{value:.{digits}g}"


def _cell(text: str) -> str:
    """Text safe inside a Markdown table cell: a literal | would end the cell."""
    return text.replace("|", "\\|").replace("\n", " ")


_VERDICT_DEFINITIONS = (
    "- **reproduces**: the computed value lies within the tolerance of the text's (for a bound "
    'such as "less than 2 km", on the stated side of it).',
    "- **close**: outside the tolerance but within the close tolerance; the explanation says "
    "why it differs.",
    "- **does not reproduce**: outside the close tolerance (or the tolerance, where there is "
    "none); the explanation gives the best reason found.",
    "- **recovered**: within the tolerance, of a value fitted to the very number it is scored "
    "against (shown apart, below): evidence that the fit holds, not that the text reproduces.",
    "",
    "A value known only to within a margin or an interval (printed beside it) reproduces only if "
    "it does so across all of it and fails only if it fails across all of it; where it "
    "straddles a tolerance's edge it is close.",
)


_TABLE_HEAD = (
    "| id | source | statement | text | computed | unit | tolerance | close tolerance "
    "| expected range | verdict | explanation |",
    "|---|---|---|---|---|---|---|---|---|---|---|",
)
_EXTENSION_HEAD = (
    "| id | answers | what is measured | measured | unit | expected range | explanation |",
    "|---|---|---|---|---|---|---|",
)


def _expected(row: Row) -> str:
    return f"[{row.expected[0]:g}, {row.expected[1]:g}]" if row.expected else "-"


def known_to(result: ClaimResult) -> str:
    """How far the claim's computed value is known, as CLAIMS.md prints it beside the value:
    " (margin 22)", " [1.95, 2.9]" or ""."""
    if result.interval:
        digits = printed_digits(result)
        return f" [{_number(result.interval[0], digits)}, {_number(result.interval[1], digits)}]"
    return f" (margin {result.claim.margin:g})" if result.claim.margin else ""


def _table_row(r: ClaimResult) -> str:
    c = r.claim

    def tolerance(value):
        if value is None:
            return "-"
        return f"{value:g}" if c.tolerance_kind == "absolute" else f"{value:.2%} rel."

    text = {"upper": "< ", "lower": "> "}.get(c.bound or "", "") + _number(c.text_value)
    fitted = f"Fitted to {c.fitted_to}. " if c.fitted_to else ""
    return (
        f'| <a id="{c.id}"></a>`{c.id}` | {_cell(c.source)} | {_cell(c.statement)} | '
        f"{text} | {_number(r.computed, printed_digits(r))}{known_to(r)} | {_cell(c.unit)} | "
        f"{tolerance(c.tolerance)} | {tolerance(c.close_tolerance)} | {_expected(c)} | "
        f"**{c.verdict}** | {_cell(fitted + r.explanation)} |"
    )


def _extension_row(r: MeasuredResult) -> str:
    m = r.row
    return (
        f'| <a id="{m.id}"></a>`{m.id}` | {_cell(m.source)} | {_cell(m.statement)} | '
        f"{_number(r.computed, printed_digits(r))} | {_cell(m.unit)} | {_expected(m)} | "
        f"{_cell(r.explanation)} |"
    )


def headline() -> str:
    """The ledger in one sentence: how many rows, scored how, and how many extension results
    (README.md's and CLAIMS.md's, generated, never typed)."""
    results = evaluate_all()
    counts = {v: sum(r.claim.verdict == v for r in results) for v in VERDICTS}
    scored = len(results) - counts["recovered"]
    return (
        f"{scored} rows scored against the text: "
        + ", ".join(f"{counts[v]} {v}" for v in VERDICTS if v != "recovered")
        + f"; {counts['recovered']} recovered (fitted to the number scored); "
        f"{len(load_measurements())} extension results measured, not scored"
    )


def render_claims(target: Path | None = None) -> Path:
    """Write ``figures/CLAIMS.md``: the ledger evaluated now, as readable tables, the recovered
    rows and the extension results apart from the rest. Computed values are printed to the
    digits they can defend (:func:`printed_digits`), and no row is a wall time, so the file
    is the same on every machine (tests/test_ledger.py regenerates it)."""
    target = Path(target) if target else paths.FIGURES_DIR / "CLAIMS.md"
    results = evaluate_all()
    scored = [r for r in results if r.claim.verdict != "recovered"]
    recovered = [r for r in results if r.claim.verdict == "recovered"]
    lines = [
        "# Claims ledger: the dissertation's numbers, recomputed",
        "",
        "Generated by `make figures` from `registry/claims.toml`; do not edit by hand. Every "
        "computed value comes from the package at generation time; `tests/test_ledger.py` "
        "checks every verdict against it. Verdicts:",
        "",
        *_VERDICT_DEFINITIONS,
        "",
        headline() + ", apart below.",
        "",
        *_TABLE_HEAD,
        *map(_table_row, scored),
        "",
        "## Recovered: values fitted to the number they are scored against",
        "",
        "Each of these agrees with the text because the project fitted one of its inputs to it; "
        "they show the fit holds, not that the text reproduces.",
        "",
        *_TABLE_HEAD,
        *map(_table_row, recovered),
        "",
        "## Extension results: the project's own measurements, not scored",
        "",
        "What the project measures of its own work beyond the text (its improved MKS, readings "
        "that rest on sizes or hypotheses the text does not give): each answers a passage of "
        "the text (the 'answers' column) but states nothing the text claims, so it carries no "
        "verdict, only its measured value and the range that value must stay in.",
        "",
        *_EXTENSION_HEAD,
        *map(_extension_row, evaluate_measurements()),
    ]
    text = "\n".join(lines) + "\n"
    return paths.write_atomically(target, lambda path: path.write_text(text))


_ROW_QUOTE = re.compile(r"<<([A-Za-z][\w.]*)(?:\|([A-Za-z_][\w.]*))?(?::([^>]*))?>>")


def quote_rows(text: str) -> str:
    """``text`` (a figure's reason or caption in the registry) with every ``<<row>>`` replaced
    by that ledger row's computed value as CLAIMS.md prints it, ``<<row:format>>`` formatted,
    and ``<<row|name:format>>`` by the attribute ``name`` of what its computation returned: a
    number a reason quotes then comes from the ledger, never typed. An unknown row is a
    ValueError naming it."""
    rows: dict[str, Claim | Measurement] = {claim.id: claim for claim in load_claims()}
    rows.update({measurement.id: measurement for measurement in load_measurements()})

    def quote(match: re.Match) -> str:
        row_id, name, spec = match.group(1), match.group(2), match.group(3)
        if row_id not in rows:
            raise ValueError(f"{row_id!r}, quoted as {match.group(0)}, is no row of the ledger")
        row = rows[row_id]
        result = evaluate(row) if isinstance(row, Claim) else MeasuredResult(row, *_computed(row))
        if name:
            return format(_attribute(result.details, name, row, "quote"), spec or "")
        return (
            format(result.computed, spec)
            if spec
            else _number(result.computed, printed_digits(result))
        )

    return _ROW_QUOTE.sub(quote, text)


def claims_by_figure() -> dict[str, list[ClaimResult]]:
    """Every evaluated claim under each figure or table it is about (those exempted from a
    figure included: :func:`bearing_on` tells them apart)."""
    tied: dict[str, list[ClaimResult]] = {}
    for result in evaluate_all():
        for number in result.claim.figures:
            tied.setdefault(number, []).append(result)
    return tied


def bearing_on(number: str, results: list[ClaimResult]) -> list[ClaimResult]:
    """The rows of ``results`` that bear on figure ``number``'s status: all but those exempted
    from it (a row tied to the figure by its paragraph about what the figure cannot draw)."""
    return [r for r in results if number not in r.claim.exempt]


def measurements_by_figure() -> dict[str, list[MeasuredResult]]:
    """Every extension result under each figure it is about."""
    tied: dict[str, list[MeasuredResult]] = {}
    for result in evaluate_measurements():
        for number in result.row.figures:
            tied.setdefault(number, []).append(result)
    return tied
