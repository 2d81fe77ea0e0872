"""Drag laws Cd(Mach): the baseline cone of eq 4.8 and the M829 tables of Appendix B.

Every law is a callable ``law(mach) -> Cd``, vectorised and checked; the simulations call the
unchecked ``law.evaluate`` inside their integration loops. The tables of Appendix B are kept
whole (:data:`M829`) because the 6DOF needs all of them; their zero-yaw drag is ``-CX0``.

Outside its table a tabulated law holds the end values (``outside="hold"``, the default) or
raises (``outside="raise"``). Appendix B calls MATLAB's ``interp1``, which returns NaN there and
would silently poison a trajectory; holding the end value is the usual ballistics practice
(the coefficients flatten at high Mach), and the trajectories of the dissertation stay inside
the M829 table (Mach 0 to 8) anyway.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, fields
from typing import Any, Protocol

import numpy as np

from ..foundation.compiled import formula, jit
from ..foundation.validation import Bounds, check_choice, finite_array

__all__ = [
    "DragLaw",
    "ExponentialDragLaw",
    "TabulatedDragLaw",
    "AeroTables",
    "M829",
    "BASELINE_CONE",
    "get_drag_law",
    "drag_coefficient",
    "DRAG_LAW_NAMES",
]


class DragLaw(Protocol):
    """What a projectile's drag law offers: ``law(mach)``, checked, ``law.evaluate(mach)``,
    unchecked, for the integration loops, and its number, ``kernel_parameters()`` and
    ``kernel`` for compiled ones (:func:`drag_coefficient`)."""

    code: int  # its number in compiled loops (drag_coefficient)
    #: The unchecked formula that ``evaluate`` and compiled loops run: Cd of the Mach number and
    #: the law's parameters (``kernel_parameters()``), for counting its operations (Fig 4.7).
    kernel: Callable[..., Any]

    def __call__(self, mach) -> np.ndarray: ...

    def evaluate(self, mach): ...

    def kernel_parameters(self) -> tuple[int, np.ndarray, np.ndarray, np.ndarray]: ...


def _mach(mach) -> np.ndarray:
    return Bounds(low=0.0).finite(mach, "mach")


@formula
def _exponential(mach, a, b, c):
    return a * np.exp(b * mach) + c


@formula
def _tabulated(mach, table_mach, table_cd):
    return np.interp(mach, table_mach, table_cd)


#: The laws' numbers in compiled loops (:func:`drag_coefficient`).
EXPONENTIAL_LAW, TABULATED_LAW = 0, 1


@jit(inline=True)
def drag_coefficient(code, mach, parameters, table_mach, table_cd):
    """Cd at ``mach`` (one number) of the law given by its ``kernel_parameters()``, for
    compiled loops (unchecked, like ``evaluate``)."""
    if code == EXPONENTIAL_LAW:
        return _exponential(mach, parameters[0], parameters[1], parameters[2])
    if code == TABULATED_LAW:
        return _tabulated(mach, table_mach, table_cd)
    raise ValueError("unknown drag law code: only ExponentialDragLaw and TabulatedDragLaw compile")


@dataclass(frozen=True)
class ExponentialDragLaw:
    """Cd = a exp(b Ma) + c, the form of eq 4.8."""

    a: float
    b: float
    c: float

    code = EXPONENTIAL_LAW
    kernel = staticmethod(_exponential)

    def evaluate(self, mach):
        return _exponential(mach, self.a, self.b, self.c)

    def kernel_parameters(self) -> tuple[int, np.ndarray, np.ndarray, np.ndarray]:
        """The law as :func:`drag_coefficient` takes it: code, (a, b, c), and no table."""
        return self.code, np.array([self.a, self.b, self.c]), np.zeros(2), np.zeros(2)

    def __call__(self, mach) -> np.ndarray:
        return self.evaluate(_mach(mach))


@dataclass(frozen=True)
class TabulatedDragLaw:
    """Cd interpolated linearly in a table of Mach numbers (as MATLAB's interp1 'linear')."""

    mach: tuple[float, ...]
    cd: tuple[float, ...]
    outside: str = "hold"

    def __post_init__(self):
        check_choice(self.outside, "outside", ("hold", "raise"))
        mach = finite_array(self.mach, "mach table")
        if mach.ndim != 1 or mach.size < 2 or np.any(np.diff(mach) <= 0):
            raise ValueError("mach table must be at least two strictly increasing numbers")
        if finite_array(self.cd, "cd table").shape != mach.shape:
            raise ValueError("cd table must have one value per Mach number")

    code = TABULATED_LAW
    kernel = staticmethod(_tabulated)

    def evaluate(self, mach):
        return _tabulated(mach, self.mach, self.cd)

    def kernel_parameters(self) -> tuple[int, np.ndarray, np.ndarray, np.ndarray]:
        """The law as :func:`drag_coefficient` takes it: code, no parameters, and its table
        (held at its ends, as ``outside="hold"``: compiled loops do not raise)."""
        return self.code, np.zeros(3), np.array(self.mach), np.array(self.cd)

    def __call__(self, mach) -> np.ndarray:
        mach = _mach(mach)
        if self.outside == "raise":
            Bounds(low=self.mach[0], high=self.mach[-1]).check(mach, "mach")
        return self.evaluate(mach)


@dataclass(frozen=True)
class AeroTables:
    """Aerodynamic coefficient tables against Mach, named and ordered as in Appendix B."""

    mach: tuple[float, ...]
    cx0: tuple[float, ...]  # axial force, zero yaw (negative: drag)
    cx2: tuple[float, ...]  # axial force, yaw-squared term
    cna: tuple[float, ...]  # normal force slope
    cypa: tuple[float, ...]  # Magnus force
    cmq: tuple[float, ...]  # pitch damping
    clp: tuple[float, ...]  # roll damping
    cldd: tuple[float, ...]  # roll driving (fin cant)
    sldel: tuple[float, ...]  # centre-of-pressure offset of the normal force (m)
    slmag: tuple[float, ...]  # centre-of-pressure offset of the Magnus force (m)

    def table(self) -> np.ndarray:
        """All coefficients except Mach, one row per Mach number (Appendix B's Coeff_Table)."""
        return np.column_stack([getattr(self, f.name) for f in fields(self)[1:]])

    def zero_yaw_drag(self, outside: str = "hold") -> TabulatedDragLaw:
        """The point-mass drag law Cd(Mach) = -CX0(Mach)."""
        return TabulatedDragLaw(self.mach, tuple(-c for c in self.cx0), outside)


#: Appendix B's M829 tables, as printed.
M829 = AeroTables(
    mach=(0.00, 1.00, 1.50, 2.00, 2.50, 3.00, 4.00, 5.00, 8.00),
    cx0=(-0.60, -1.00, -1.35, -1.22, -1.04, -0.91, -0.69, -0.543, -0.449),
    cx2=(-8.35, -11.53, -17.21, -16.29, -15.73, -13.91, -12.18, -10.41, -9.08),
    cna=(17.94, 22.37, 21.09, 19.97, 18.77, 17.63, 15.36, 13.15, 9.92),
    cypa=(0.0,) * 9,
    cmq=(-7288, -8697, -9064, -8000, -7523, -7047, -6091, -5129, -4224),
    clp=(-21.46, -27.47, -25.0, -23.6, -22.3, -20.2, -16.1, -13.4, -11.4),
    cldd=(0.084, 0.084, 0.076, 0.072, 0.068, 0.062, 0.049, 0.041, 0.035),
    sldel=(-0.2615, -0.2615, -0.2615, -0.2615, -0.2314, -0.2000, -0.1661, -0.1512, -0.1507),
    slmag=(0.0,) * 9,
)

#: Eq 4.8: the Taylor-Maccoll drag of the 4 deg baseline cone, fitted (Chapter 4 B).
BASELINE_CONE = ExponentialDragLaw(0.077, -0.38, 0.014)

_LAWS = {"baseline_cone": BASELINE_CONE, "m829": M829.zero_yaw_drag()}
DRAG_LAW_NAMES = tuple(_LAWS)


def get_drag_law(name: str):
    """The drag law called ``name`` (one of :data:`DRAG_LAW_NAMES`)."""
    return _LAWS[check_choice(name, "drag_law", _LAWS)]
