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
statistic of data printed in coarse steps) reproduces only if it does so across the margin,
and fails only if it fails across it: a value within ``margin`` of a tolerance's edge is
``close``, whichever side it falls.

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
    "range_problem",
    "printed_digits",
    "Claim",
    "ClaimResult",
    "load_claims",
    "evaluate",
    "evaluate_all",
    "verdict_problems",
    "render_claims",
    "VERDICTS",
]

VERDICTS = ("reproduces", "recovered", "close", "does not reproduce")
_REQUIRED = (
    "id",
    "source",
    "statement",
    "text_value",
    "unit",
    "compute",
    "tolerance",
    "verdict",
    "explanation",
    "figures",
)


@dataclass(frozen=True)
class Claim:
    id: str
    source: str
    statement: str
    text_value: float
    unit: str
    compute: str
    tolerance: float
    verdict: str
    explanation: str
    figures: tuple[str, ...]  # the figures and tables it is about (see the module docstring)
    tolerance_kind: str = "absolute"
    close_tolerance: float | None = None
    kwargs: dict = field(default_factory=dict, hash=False)
    field: str | None = None
    scale: float = 1.0
    bound: str | None = None
    fitted_to: str | None = None  # what the project fitted to the number scored (recovered)
    margin: float = 0.0  # how far the computed value is known, in the tolerance's terms
    digits: int | None = None  # significant digits CLAIMS.md prints; default: what the
    # tolerance resolves, 3 to 6 (see printed_digits)
    expected: tuple[float, float] | None = None  # the range the computed value must stay in
    quote: str | None = None  # verbatim words of the text's paragraph, where the statement
    # does not quote it (see the module docstring)


_QUOTE = re.compile(r"<<([A-Za-z_][\w.]*)(?::([^>]*))?>>")


@dataclass(frozen=True)
class ClaimResult:
    claim: Claim
    computed: float
    details: object = None  # what the compute returned, whose attributes explanations quote

    @property
    def explanation(self) -> str:
        """The claim's explanation with every ``<<name:format>>`` quoted from :attr:`details`
        (``<<value>>``: the computed value); a name it lacks is a ValueError naming the row."""

        def quote(match: re.Match) -> str:
            name, spec = match.group(1), match.group(2) or ""
            value: object = self.computed if name == "value" else self.details
            if name != "value":
                for part in name.split("."):
                    if not hasattr(value, part):
                        raise ValueError(
                            f"claim {self.claim.id!r}: its explanation quotes <<{name}>>, "
                            f"which {self.claim.compute} does not return"
                        )
                    value = getattr(value, part)
            return format(value, spec)

        return _QUOTE.sub(quote, self.claim.explanation)

    @property
    def deviation(self) -> float:
        """|computed - text| (for a bound, only past it), relative to the text's value when
        the tolerance is relative."""
        difference = self.computed - self.claim.text_value
        difference = {"upper": max(difference, 0.0), "lower": max(-difference, 0.0)}.get(
            self.claim.bound or "", abs(difference)
        )
        if self.claim.tolerance_kind == "relative":
            return difference / abs(self.claim.text_value)
        return difference

    @property
    def within_tolerance(self) -> bool:
        return self.deviation <= self.claim.tolerance


def _claim(raw: dict, position: int, source: Path) -> Claim:
    where = f"{source.name} claim {raw.get('id', '?')!r}"
    missing = [name for name in _REQUIRED if name not in raw]
    if missing:
        raise ValueError(f"{where}: missing field(s) {', '.join(missing)}")
    unknown = set(raw) - set(Claim.__dataclass_fields__)
    if unknown:
        raise ValueError(f"{where}: unknown field(s) {', '.join(sorted(unknown))}")
    if raw["verdict"] not in VERDICTS:
        raise ValueError(f"{where}: verdict {raw['verdict']!r} is not one of {VERDICTS}")
    if raw.get("tolerance_kind", "absolute") not in ("absolute", "relative"):
        raise ValueError(f"{where}: tolerance_kind must be 'absolute' or 'relative'")
    if raw.get("bound") not in (None, "upper", "lower"):
        raise ValueError(f"{where}: bound must be 'upper' or 'lower'")
    if ":" not in raw["compute"]:
        raise ValueError(f"{where}: compute must read 'module:function', got {raw['compute']!r}")
    figures = raw["figures"]
    if not isinstance(figures, list) or not all(isinstance(f, str) for f in figures):
        raise ValueError(f'{where}: figures must be a list of figure numbers such as "4.7"')
    raw = {**raw, "figures": tuple(figures)}
    if "quote" in raw and (
        not isinstance(raw["quote"], str) or len(re.findall(r"\w+", raw["quote"])) < 5
    ):
        raise ValueError(f"{where}: quote must be at least five words of the text")
    if "expected" in raw:
        low_high = raw["expected"]
        if (
            not isinstance(low_high, list)
            or len(low_high) != 2
            or not all(isinstance(v, int | float) for v in low_high)
            or not low_high[0] < low_high[1]
        ):
            raise ValueError(f"{where}: expected must be [low, high] with low < high")
        raw = {**raw, "expected": (float(low_high[0]), float(low_high[1]))}
    return Claim(**raw)


@cached_copies
def load_claims(path: Path | None = None) -> tuple[Claim, ...]:
    """Every claim of the ledger, in file order; ids must be unique."""
    path = Path(path) if path else paths.REGISTRY_DIR / "claims.toml"
    return load_toml_rows(path, "claim", _claim, "id")


def evaluate(claim: Claim) -> ClaimResult:
    """Compute the project's value of ``claim`` by calling the package."""
    module_name, _, attribute = claim.compute.partition(":")
    details = result = getattr(importlib.import_module(module_name), attribute)(**claim.kwargs)
    for name in claim.field.split(".") if claim.field else ():
        result = getattr(result, name)
    return ClaimResult(claim, float(result) * claim.scale, details)


def evaluate_all(prefix: str | tuple[str, ...] = "") -> list[ClaimResult]:
    """Evaluate every claim, or only those whose id starts with ``prefix`` (a notebook's own)."""
    return [evaluate(claim) for claim in load_claims() if claim.id.startswith(prefix)]


def range_problem(result: ClaimResult) -> str | None:
    """Why ``result``'s computed value is outside its row's expected range (a regression guard
    that holds whatever the verdict), or None."""
    expected = result.claim.expected
    if expected is None:
        return "no expected range"
    low, high = expected
    if not low <= result.computed <= high:
        return f"computed {result.computed:.6g} is outside the expected range [{low:g}, {high:g}]"
    return None


def verdict_problems(result: ClaimResult) -> list[str]:
    """Why ``result``'s verdict does not match its numbers (empty when it does)."""
    claim, problems = result.claim, []
    if not math.isfinite(result.computed):
        return [f"computed value is {result.computed}"]
    low, high = result.deviation - claim.margin, result.deviation + claim.margin
    close = claim.tolerance if claim.close_tolerance is None else claim.close_tolerance
    if claim.fitted_to and claim.verdict == "reproduces":
        problems.append(f"fitted to {claim.fitted_to}: a value fitted to its target is 'recovered'")
    if claim.verdict == "recovered" and not claim.fitted_to:
        problems.append("verdict 'recovered' needs fitted_to: what was fitted to the number")
    if claim.verdict in ("reproduces", "recovered"):
        if high > claim.tolerance:
            margin = f" (with its margin {claim.margin:g})" if claim.margin else ""
            problems.append(
                f"marked {claim.verdict!r} but deviates by {result.deviation:.4g}{margin} "
                f"> tolerance {claim.tolerance:g}"
            )
        return problems
    if not claim.explanation.strip():
        problems.append(f"verdict {claim.verdict!r} needs an explanation")
    if high <= claim.tolerance:
        problems.append(
            f"marked {claim.verdict!r} but is within tolerance "
            f"({result.deviation:.4g} <= {claim.tolerance:g}): it reproduces"
        )
    if claim.verdict == "close":
        if claim.close_tolerance is None and not claim.margin:
            problems.append("verdict 'close' needs a close_tolerance or a margin")
        elif low > close:
            problems.append(
                f"marked 'close' but deviates by {result.deviation:.4g} > close tolerance {close:g}"
            )
    elif (claim.close_tolerance is not None or claim.margin) and low <= close:
        problems.append(
            f"marked 'does not reproduce' but is within close tolerance {close:g}"
            + (f" of its margin {claim.margin:g}" if claim.margin else "")
            + ": it is close"
        )
    return problems


def printed_digits(result: ClaimResult) -> int:
    """Significant digits of the computed value in CLAIMS.md: the row's ``digits``, or enough
    to resolve its tolerance (3 to 6). More would print the last bits, which differ between
    machines."""
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
    "A value known only to within a margin (listed in its explanation) counts as close where the "
    "margin straddles a tolerance's edge.",
)


_TABLE_HEAD = (
    "| id | source | statement | text | computed | unit | tolerance | close tolerance "
    "| expected range | verdict | explanation |",
    "|---|---|---|---|---|---|---|---|---|---|---|",
)


def _table_row(r: ClaimResult) -> str:
    c = r.claim

    def tolerance(value):
        if value is None:
            return "-"
        return f"{value:g}" if c.tolerance_kind == "absolute" else f"{value:.2%} rel."

    text = {"upper": "< ", "lower": "> "}.get(c.bound or "", "") + _number(c.text_value)
    expected = f"[{c.expected[0]:g}, {c.expected[1]:g}]" if c.expected else "-"
    margin = f" (margin {c.margin:g})" if c.margin else ""
    fitted = f"Fitted to {c.fitted_to}. " if c.fitted_to else ""
    return (
        f'| <a id="{c.id}"></a>`{c.id}` | {_cell(c.source)} | {_cell(c.statement)} | '
        f"{text} | {_number(r.computed, printed_digits(r))}{margin} | {_cell(c.unit)} | "
        f"{tolerance(c.tolerance)} | {tolerance(c.close_tolerance)} | {expected} | "
        f"**{c.verdict}** | {_cell(fitted + r.explanation)} |"
    )


def render_claims(target: Path | None = None) -> Path:
    """Write ``figures/CLAIMS.md``: the ledger evaluated now, as readable tables, the recovered
    rows apart from the rest. Computed values are printed to the digits they can defend
    (:func:`printed_digits`)."""
    target = Path(target) if target else paths.FIGURES_DIR / "CLAIMS.md"
    results = evaluate_all()
    counts = {v: sum(r.claim.verdict == v for r in results) for v in VERDICTS}
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
        f"{len(scored)} rows scored against the text: "
        + ", ".join(f"{counts[v]} {v}" for v in VERDICTS if v != "recovered")
        + f"; {counts['recovered']} recovered, apart below ({len(results)} in all).",
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
    ]
    text = "\n".join(lines) + "\n"
    return paths.write_atomically(target, lambda path: path.write_text(text))


def claims_by_figure() -> dict[str, list[ClaimResult]]:
    """Every evaluated claim under each figure or table it is about."""
    tied: dict[str, list[ClaimResult]] = {}
    for result in evaluate_all():
        for number in result.claim.figures:
            tied.setdefault(number, []).append(result)
    return tied
