"""Argument checks shared by every public function: bad input fails early, naming the argument."""

from __future__ import annotations

import math
import numbers
from collections.abc import Iterable
from dataclasses import dataclass
from typing import TypeVar

import numpy as np

from .compiled import formula

__all__ = [
    "ModelValidityWarning",
    "finite_array",
    "finite_scalar",
    "real_number",
    "real_array",
    "whole_number",
    "probability",
    "positive_scalar",
    "Bounds",
    "inside",
    "check_choice",
]


class ModelValidityWarning(UserWarning):
    """An input is legal but lies outside the range where a model is valid."""


def finite_array(value, name: str) -> np.ndarray:
    """Return ``value`` as a float64 array, or raise naming ``name`` if it is not finite numbers
    (strings and booleans included, which numpy would read as numbers: "1e-9" as 1e-9)."""
    if np.asarray(value).dtype.kind in "bUSc":
        raise TypeError(f"{name} must be a real number or an array of them; got {value!r:.80}")
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name} must be a real number or an array of them; got {value!r}") from exc
    bad = ~np.isfinite(array)
    if bad.any():
        where = "" if array.ndim == 0 else f" at index {tuple(int(i) for i in np.argwhere(bad)[0])}"
        raise ValueError(f"{name} must be finite; got {array[bad].flat[0]}{where}")
    return array


def real_number(value, name: str) -> float:
    """``value`` as a finite float, strictly: TypeError naming ``name`` for anything that is not
    a real number (a string such as "50" or a bool included), ValueError for NaN or infinity."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name} must be a real number; got {value!r}")
    try:
        value = float(value)
    except OverflowError:
        raise ValueError(f"{name} must be finite; got an integer beyond float range") from None
    if not math.isfinite(value):
        raise ValueError(f"{name} must be finite; got {value}")
    return value


def real_array(value, name: str) -> np.ndarray:
    """``value`` as a float64 array, strictly: TypeError naming ``name`` for strings, booleans
    or anything else that is not real numbers (numpy would read "10" as ten), ValueError naming
    the first element that is NaN or infinite."""
    array = np.asarray(value)
    if array.dtype.kind not in "iuf":
        raise TypeError(
            f"{name} must be a real number or an array of them; got {value!r:.80} "
            f"(of dtype {array.dtype.kind!r})"
        )
    return finite_array(array, name)


def whole_number(value, name: str, *, low: int, high: float = math.inf) -> int:
    """``value`` as an int in [low, high], or an error naming ``name``: TypeError for anything
    that is not a real number (a string such as "3" or a bool included), ValueError for a
    number that is not whole (2.5 series terms, round 181.7) or outside the bounds (a count
    bounded so that it cannot allocate until the machine stops)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name} must be a whole number; got {value!r:.60}")
    number = real_number(value, name)
    if number != int(number):
        raise ValueError(f"{name} must be a whole number; got {value!r}")
    return int(Bounds(low, high).check(number, name))


def probability(value, name: str) -> float:
    """``value`` as a number strictly between 0 and 1 (a confidence level, a significance), or
    an error naming ``name``."""
    number = real_number(value, name)
    return Bounds(0.0, 1.0, low_inclusive=False, high_inclusive=False).check(number, name)


def positive_scalar(value, name: str, unit: str = "") -> float:
    """``value`` as one finite float > 0, or an error naming ``name`` (a time span, a step, a
    tolerance: the engines' numerical options)."""
    return Bounds(low=0.0, low_inclusive=False, unit=unit).scalar(value, name)


def finite_scalar(value, name: str) -> float:
    """Return ``value`` as a float, or raise naming ``name`` if it is not one finite number."""
    array = finite_array(value, name)
    if array.ndim != 0:
        raise ValueError(f"{name} must be a single number; got an array of shape {array.shape}")
    return float(array)


Checked = TypeVar("Checked", float, np.ndarray)


@formula
def inside(value, low, high, low_inclusive, high_inclusive):
    """Whether ``value`` (a number, an array of them, or a number in compiled code) lies in the
    interval from ``low`` to ``high``, each end closed where its flag says; NaN never does.
    Kernels call it with a :attr:`Bounds.limits` as constants (mks's domains, per launch)."""
    above = value >= low if low_inclusive else value > low
    below = value <= high if high_inclusive else value < high
    return above & below & (value - value == 0.0)  # the last: finite


@dataclass(frozen=True)
class Bounds:
    """An interval a number must lie in: the one vocabulary of the package's range checks, on a
    number (:meth:`~harp_analysis.foundation.validation.Bounds.number`,
    :meth:`~harp_analysis.foundation.validation.Bounds.scalar`), an array
    (:meth:`~harp_analysis.foundation.validation.Bounds.array`,
    :meth:`~harp_analysis.foundation.validation.Bounds.finite`), a value already converted
    (:meth:`~harp_analysis.foundation.validation.Bounds.check`) or, through
    :attr:`~harp_analysis.foundation.validation.Bounds.limits` and :func:`inside`, in compiled
    code."""

    low: float = -math.inf
    high: float = math.inf
    low_inclusive: bool = True
    high_inclusive: bool = True
    unit: str = ""

    @property
    def limits(self) -> tuple[float, float, bool, bool]:
        """(low, high, low_inclusive, high_inclusive): :func:`inside`'s arguments after the
        value, constants for a kernel."""
        return self.low, self.high, self.low_inclusive, self.high_inclusive

    def inside(self, value):
        """Whether ``value`` (a float, or an array of them) lies inside; NaN never does."""
        return inside(value, *self.limits)

    def number(self, value, name: str) -> float:
        """``value`` as a float inside, or an error naming ``name``: TypeError for anything
        that is not a real number (a string or a bool included)."""
        if type(value) is float and self.inside(value):  # the common case, checked cheaply
            return value
        value = real_number(value, name)
        if not self.inside(value):
            raise ValueError(self.outside(name, value))
        return value

    def array(self, value, name: str) -> np.ndarray:
        """``value`` (a number or a 1-D array of them, real numbers strictly) as a new float
        array inside, or an error naming ``name`` and the index of its first bad element."""
        array = real_array(value, name).copy()
        outside = ~self.inside(array)
        if outside.any():
            index = int(np.flatnonzero(outside)[0])
            raise ValueError(self.outside(f"{name}[{index}]", float(array.flat[index])))
        return array

    def finite(self, value, name: str) -> np.ndarray:
        """``value`` as a float array of finite numbers (:func:`finite_array`; a number gives a
        0-d array) inside, or an error naming ``name``."""
        return self.check(finite_array(value, name), name)

    def scalar(self, value, name: str) -> float:
        """``value`` as one finite float (:func:`finite_scalar`) inside, or an error naming
        ``name``."""
        return self.check(finite_scalar(value, name), name)

    def check(self, value: Checked, name: str) -> Checked:
        """``value`` itself, or a ValueError naming ``name`` and its first element outside
        (NaN passes: refusing it is :func:`finite_array`'s job)."""
        below = value < self.low if self.low_inclusive else value <= self.low
        above = value > self.high if self.high_inclusive else value >= self.high
        bad = np.asarray(below | above)
        if bad.any():
            raise ValueError(self.outside(name, np.asarray(value)[bad].flat[0]))
        return value

    def outside(self, name: str, value: float) -> str:
        """The error message of ``name``'s ``value`` outside."""
        interval = (
            ("[" if self.low_inclusive else "(")
            + f"{self.low:g}, {self.high:g}"
            + ("]" if self.high_inclusive else ")")
        )
        unit = f" {self.unit}" if self.unit else ""
        return f"{name} must lie in {interval}{unit}; got {value:g}{unit}"


def check_choice(value: str, name: str, options: Iterable[str]) -> str:
    """Return ``value`` if it is one of ``options``; otherwise raise naming ``name`` and the
    options."""
    options = list(options)
    if value not in options:
        raise ValueError(
            f"unknown {name} {value!r}; expected one of {', '.join(map(repr, options))}"
        )
    return value
