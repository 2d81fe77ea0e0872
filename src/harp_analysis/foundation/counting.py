"""What an engine declares of its own code for counting its operations (Fig 4.7).

:mod:`harp_analysis.analyses.effort` counts floating-point operations from the source, by one rule
for every method. It reads each function's own body; which functions one unit of an engine's work
runs, whether a function computes in complex numbers and how long its loops over unsized
iterables are, only the engine knows: it says so as a tuple of :class:`Counted` (the engines'
``counted_functions(launch)``, carried by their records in
:mod:`harp_analysis.engines.catalogue`).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from types import MappingProxyType
from typing import Any, NamedTuple

__all__ = ["Counted"]


class Counted(NamedTuple):
    """A function whose own body is counted (the functions it calls are counted as their own
    entries), whether it computes in complex numbers (each of its operations then counts
    :data:`harp_analysis.analyses.effort.COMPLEX_WEIGHT` real ones) and the number of items of
    each loop whose iterable its code does not size, keyed by the iterable's source text."""

    function: Callable[..., Any]
    complex_numbers: bool = False
    trips: Mapping[str, int] = MappingProxyType({})
