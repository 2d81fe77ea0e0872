"""Taylor-Maccoll flow over the baseline cone and its drag law, eq 4.8 (Chapter 4 B, Appendix C).

Chapter 4 B models the baseline projectile as a right cone of 4 deg half angle, solves the
Taylor-Maccoll equations by Anderson's method [49] for the cone surface pressure, assumes a
base pressure of 75 % of free stream and fits Cd = a exp(b Ma) + c to the drag so found
(eq 4.8: a = 0.077, b = -0.38, c = 0.014, R^2 = 0.999; Fig 4.9).

:func:`cone_flow` is Anderson's method (Modern Compressible Flow, 3rd ed., Sec 10.4): for a
trial shock angle the oblique-shock relations give the velocity just behind the shock, the
Taylor-Maccoll equation is integrated inward in the ray angle until the normal velocity
vanishes, and that ray is the cone surface; the shock angle is adjusted until the surface is at
the requested half angle. The surface pressure follows isentropically from the total pressure
behind the shock. Appendix C does the same with a fixed-step Taylor series in the ray angle and
a shock angle stepped down from 70 deg; here the ODE is integrated adaptively (``solve_ivp``)
and the shock angle is found by ``brentq`` on the weak (attached) branch. (Appendix C's step
drops the 1/2 of the second-order Taylor term, an error that vanishes with the step: emulated
line by line with a 0.01 deg step, it agrees with this module to 0.5 % in Cd from Mach 2.5 to
12, 1.6 % at Mach 2.)

:func:`cone_drag_coefficient` is pressure drag only (no skin friction, as in Appendix C). The
surface pressure acts on the conical face, whose axial projection is the base area, so with Cd
referred to the base area

    Cd = (p_c - p_base) / q_ref,    p_base = base_pressure_ratio * p_inf.

Reading of Appendix C's last formula, ``2000 (ps - p1 * Cells(4,12)) / (Vmax^2 * Cells(2,12))``:
``p1`` and ``ps`` are in kPa (hence the 1000 in 2000 = 2 x 1000), ``Cells(4,12)`` is the base
pressure ratio 0.75 and ``Cells(2,12)`` the free-stream density in kg/m^3. The reference
pressure is therefore rho Vmax^2 / 2 with Vmax the limiting (maximum adiabatic) speed, not the
free-stream dynamic pressure rho V^2 / 2. The printed Vmax line has one closing parenthesis too
many; dropping the one after ``(Gamma - 1)`` gives Vmax^2 = 2 a^2 / (gamma - 1) + V^2, the
limiting speed that the Taylor-Maccoll terms of the same macro (``alpha``, ``a3``) require, and
that is the reading taken here. With rho consistent with p1 and T1 (p = rho R T), Appendix C's
Cd is the physical Cd times M^2 / (M^2 + 2 / (gamma - 1)):

``normalisation="free_stream"`` (default)
    q_ref = gamma / 2 p_inf M^2, the physical drag coefficient for the drag equation.
``normalisation="appendix_c"``
    q_ref = gamma / 2 p_inf (M^2 + 2 / (gamma - 1)), Appendix C's rho Vmax^2 / 2.

(With the other reading, Vmax^2 = 2 a^2 / (gamma - 1) + V^2 / 2, a line-by-line emulation of
the macro fails on a negative square root at Mach 1.5, 2, 4 and 6 and returns a negative Cd
at Mach 3: it cannot have produced Fig 4.9.)

Eq 4.8 is reproduced by the ``appendix_c`` normalisation, not by the physical one: Appendix C's
Cd lies within 2 % of eq 4.8 from Mach 1.5 to 10 (3 % low at Mach 11, 6 % at 12.5), while
the physical Cd is 1 + 5 / M^2 times Appendix C's (12 % above eq 4.8 at the launch Mach 6.3,
54 % at Mach 3). The text does not print its Mach grid. Fitting Appendix C's Cd on 22 Mach
numbers (its spreadsheet rows 7 to 28) 0.5 apart reproduces a, b, c and R^2 to the printed
digits when the first Mach number is 1.1 to 1.25 or 1.75 to 2.0, and to within one unit of
the last digit of a in between; :data:`EQ_4_8_MACH_GRID`, Mach 1.5 to 12, is the middle one
(a = 0.0777, b = -0.383, c = 0.0138, R^2 = 0.9996).
Grids confined to the trajectories' own range (about Mach 3 to 7) give b near -0.41 instead.
The physical Cd fitted on any of these grids gives a = 0.19 to 1.2 and b = -0.53 to -1.26.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq, curve_fit, minimize_scalar

from ..foundation.validation import Bounds, check_choice, finite_array, finite_scalar
from .drag import BASELINE_CONE as BASELINE_CONE_LAW
from .drag import ExponentialDragLaw

__all__ = [
    "ConeFlow",
    "cone_flow",
    "cone_drag_coefficient",
    "NORMALISATIONS",
    "DragFit",
    "fit_eq_4_8",
    "BASELINE_HALF_ANGLE_RAD",
    "BASE_PRESSURE_RATIO",
    "TRAJECTORY_MACH_RANGE",
    "EQ_4_8_MACH_GRID",
    "baseline_fit",
    "physical_over_eq_4_8",
]

BASELINE_HALF_ANGLE_RAD = math.radians(4.0)  # Chapter 4 B
BASE_PRESSURE_RATIO = 0.75  # Chapter 4 B: base pressure 75 % of free stream
NORMALISATIONS = ("free_stream", "appendix_c")

#: Mach range of the baseline trajectories (3DOF, elevations 30 to 60 deg, launch 2157 m/s =
#: Mach 6.3 at sea level): about 3.3 to 6.7. Near-vertical shots fall lower at apogee.
TRAJECTORY_MACH_RANGE = (3.0, 7.0)
#: 22 Mach numbers (Appendix C's rows 7 to 28), 0.5 apart from Mach 1.5 to 12: the middle of
#: the grids on which Appendix C's Cd reproduces eq 4.8 (inferred; the text prints no grid).
EQ_4_8_MACH_GRID = 1.5 + 0.5 * np.arange(22)

_ODE_RTOL = 1e-10
_ODE_ATOL = 1e-12
_BRACKET_STEPS = 32
_MIN_SHOCK_STRENGTH_RAD = 1e-6  # shock angle minus Mach angle


@dataclass(frozen=True)
class ConeFlow:
    """Conical flow at zero incidence: arrays shaped like the broadcast ``mach`` and half angle."""

    mach: np.ndarray | float
    half_angle_rad: np.ndarray | float
    shock_angle_rad: np.ndarray | float
    surface_mach: np.ndarray | float
    surface_pressure_ratio: np.ndarray | float  # p_c / p_inf
    gamma: float

    @property
    def pressure_coefficient(self):
        """Surface pressure coefficient Cp = (p_c - p_inf) / (gamma / 2 p_inf M^2)."""
        return (self.surface_pressure_ratio - 1.0) / (0.5 * self.gamma * self.mach**2)


def _taylor_maccoll(theta, y, gamma):
    """Anderson's eq 10.15 as a first-order system in (V_r, V_theta), speeds over V_max."""
    v_r, v_t = y
    a2 = 0.5 * (gamma - 1.0) * (1.0 - v_r * v_r - v_t * v_t)  # (a / V_max)^2
    dv_t = (v_t * v_t * v_r - a2 * (2.0 * v_r + v_t / math.tan(theta))) / (a2 - v_t * v_t)
    return [v_t, dv_t]


def _normal_velocity_zero(theta, y, gamma):
    return y[1]


# scipy's solve_ivp reads an event's options from attributes of the function
_normal_velocity_zero.terminal = True  # type: ignore[attr-defined]
_normal_velocity_zero.direction = 1.0  # type: ignore[attr-defined]


def _cone_angle(shock_rad, mach, gamma, theta_stop):
    """Ray angle where V_theta = 0 behind a shock at ``shock_rad``; ``theta_stop`` if none."""
    mach_n = mach * math.sin(shock_rad)
    density_ratio = (gamma + 1.0) * mach_n**2 / ((gamma - 1.0) * mach_n**2 + 2.0)
    speed = (1.0 + 2.0 / ((gamma - 1.0) * mach**2)) ** -0.5  # V_inf / V_max
    start = [speed * math.cos(shock_rad), -speed * math.sin(shock_rad) / density_ratio]
    sol = solve_ivp(
        _taylor_maccoll,
        (shock_rad, theta_stop),
        start,
        args=(gamma,),
        events=_normal_velocity_zero,
        rtol=_ODE_RTOL,
        atol=_ODE_ATOL,
    )
    if sol.t_events[0].size:
        return float(sol.t_events[0][0]), float(sol.y_events[0][0][0])
    return theta_stop, float("nan")


def _weak_shock_angle(mach, half_angle, gamma):
    """Shock angle of the attached (weak) solution; ValueError naming ``mach`` if detached."""
    theta_stop = 0.5 * half_angle
    mach_angle = math.asin(1.0 / mach)

    def excess(shock_rad):
        if shock_rad <= mach_angle:  # a Mach wave turns nothing
            return -half_angle
        return _cone_angle(shock_rad, mach, gamma, theta_stop)[0] - half_angle

    steps = np.linspace(mach_angle, 0.5 * math.pi, _BRACKET_STEPS + 1)[:-1]
    values = [excess(mach_angle)]
    for k in range(1, steps.size):
        values.append(excess(steps[k]))
        if values[-1] >= 0.0:
            return _checked(
                brentq(excess, steps[k - 1], steps[k], xtol=1e-13, rtol=1e-13),
                mach,
                half_angle,
                mach_angle,
            )
        if values[-1] < values[-2]:  # passed the largest cone angle: find it
            peak = minimize_scalar(
                lambda shock: -excess(shock),
                method="bounded",
                bounds=(steps[k - 2], steps[k]),
                options={"xatol": 1e-10},
            )
            if -peak.fun >= 0.0:
                return brentq(excess, steps[k - 2], peak.x, xtol=1e-13, rtol=1e-13)
            values.append(-peak.fun)
            break
    largest = math.degrees(half_angle + max(values))
    raise ValueError(
        f"mach {mach:g} is too low for a {math.degrees(half_angle):g} deg cone: the "
        f"shock detaches (largest attached half angle about {largest:.2f} deg)"
    )


def _checked(shock_rad, mach, half_angle, mach_angle):
    """Refuse shocks so close to the Mach angle that the shooting loses accuracy.

    There the flow behind the shock differs from the free stream by ~(shock - Mach angle),
    which the ODE tolerance no longer resolves; slender-body theory applies instead.
    """
    if shock_rad - mach_angle < _MIN_SHOCK_STRENGTH_RAD:
        raise ValueError(
            f"half_angle_rad {half_angle:g} is too slender for the Taylor-Maccoll "
            f"shooting at mach {mach:g} (shock within "
            f"{_MIN_SHOCK_STRENGTH_RAD:g} rad of the Mach angle)"
        )
    return shock_rad


def _cone_flow_point(mach, half_angle, gamma):
    shock = _weak_shock_angle(mach, half_angle, gamma)
    _, v_c = _cone_angle(shock, mach, gamma, 0.5 * half_angle)
    g1 = gamma - 1.0
    surface_mach = math.sqrt(2.0 / g1 * v_c**2 / (1.0 - v_c**2))
    mn2 = (mach * math.sin(shock)) ** 2
    total_pressure_ratio = ((gamma + 1.0) * mn2 / (g1 * mn2 + 2.0)) ** (gamma / g1) * (
        (gamma + 1.0) / (2.0 * gamma * mn2 - g1)
    ) ** (1.0 / g1)
    pressure_ratio = total_pressure_ratio * (
        (1.0 + 0.5 * g1 * mach**2) / (1.0 + 0.5 * g1 * surface_mach**2)
    ) ** (gamma / g1)
    return shock, surface_mach, pressure_ratio


def _gamma(gamma) -> float:
    gamma = finite_scalar(gamma, "gamma")
    Bounds(low=1.0, low_inclusive=False).check(gamma, "gamma")
    return gamma


def cone_flow(mach, half_angle_rad, gamma=1.4) -> ConeFlow:
    """Taylor-Maccoll solution for a right cone at zero incidence (Ch. 4 B, Appendix C).

    ``mach`` (> 1) and ``half_angle_rad`` (0 to pi/2) broadcast against each other; the
    attached-shock (weak) solution only, with a ValueError naming ``mach`` if the shock
    detaches, and one naming ``half_angle_rad`` for cones so slender (below 0.5 to 1 deg)
    that the shock lies within 1e-6 rad of the Mach angle and the shooting cannot resolve it.
    Anderson, Modern Compressible Flow, 3rd ed., Sec 10.4 (pp 366-372).
    """
    mach = Bounds(low=1.0, low_inclusive=False).finite(mach, "mach")
    half_angle = Bounds(
        low=0.0, high=0.5 * math.pi, low_inclusive=False, high_inclusive=False, unit="rad"
    ).finite(half_angle_rad, "half_angle_rad")
    gamma = _gamma(gamma)
    mach, half_angle = np.broadcast_arrays(mach, half_angle)
    points = [
        _cone_flow_point(float(m), float(t), gamma) for m, t in zip(mach.flat, half_angle.flat)
    ]
    shock, surface, pressure = (np.reshape(column, mach.shape) for column in zip(*points))
    if mach.ndim == 0:
        return ConeFlow(
            float(mach), float(half_angle), float(shock), float(surface), float(pressure), gamma
        )
    return ConeFlow(mach.copy(), half_angle.copy(), shock, surface, pressure, gamma)


def cone_drag_coefficient(
    mach,
    half_angle_rad=BASELINE_HALF_ANGLE_RAD,
    base_pressure_ratio=BASE_PRESSURE_RATIO,
    gamma=1.4,
    normalisation="free_stream",
):
    """Pressure drag coefficient of a right cone on its base area (Ch. 4 B, Appendix C).

    Cd = (p_c - base_pressure_ratio p_inf) / q_ref, no skin friction. ``normalisation`` picks
    q_ref: ``"free_stream"`` (gamma/2 p_inf M^2, the physical Cd) or ``"appendix_c"`` (Appendix
    C's rho Vmax^2 / 2 = gamma/2 p_inf (M^2 + 2/(gamma-1))); see the module notes.
    """
    check_choice(normalisation, "normalisation", NORMALISATIONS)
    base = finite_scalar(base_pressure_ratio, "base_pressure_ratio")
    Bounds(low=0.0).check(base, "base_pressure_ratio")
    flow = cone_flow(mach, half_angle_rad, gamma)
    speed_term = flow.mach**2
    if normalisation == "appendix_c":
        speed_term = speed_term + 2.0 / (flow.gamma - 1.0)
    return (flow.surface_pressure_ratio - base) / (0.5 * flow.gamma * speed_term)


@dataclass(frozen=True)
class DragFit:
    """Least-squares Cd = a exp(b Ma) + c with its coefficient of determination."""

    a: float
    b: float
    c: float
    r_squared: float

    @property
    def law(self) -> ExponentialDragLaw:
        """The fit as a drag law usable by the simulations."""
        return ExponentialDragLaw(self.a, self.b, self.c)


def fit_eq_4_8(mach_grid, cd) -> DragFit:
    """Fit eq 4.8's form, Cd = a exp(b Ma) + c, to ``cd`` on ``mach_grid`` (Ch. 4 B, Fig 4.9)."""
    mach = finite_array(mach_grid, "mach_grid")
    cd = finite_array(cd, "cd")
    if mach.ndim != 1 or mach.size < 4:
        raise ValueError("mach_grid must be a 1-D array of at least 4 Mach numbers")
    if cd.shape != mach.shape:
        raise ValueError(f"cd must have one value per Mach number; got shape {cd.shape}")
    c0 = cd.min() - 0.1 * np.ptp(cd)  # a data-driven start: decay rate 0.5 per unit Mach
    p0 = ((cd[0] - c0) * np.exp(0.5 * mach[0]), -0.5, c0)
    (a, b, c), _ = curve_fit(
        lambda m, a, b, c: a * np.exp(b * m) + c, mach, cd, p0=p0, maxfev=20000
    )
    residual = cd - (a * np.exp(b * mach) + c)
    r_squared = 1.0 - np.sum(residual**2) / np.sum((cd - cd.mean()) ** 2)
    return DragFit(float(a), float(b), float(c), float(r_squared))


@cache
def baseline_fit(normalisation: str = "appendix_c") -> DragFit:
    """Eq 4.8's fit to the 4 deg cone's Cd on :data:`EQ_4_8_MACH_GRID` (Fig 4.9)."""
    cd = cone_drag_coefficient(EQ_4_8_MACH_GRID, normalisation=normalisation)
    return fit_eq_4_8(EQ_4_8_MACH_GRID, cd)


def physical_over_eq_4_8(mach: float = 2157.0 / 340.137) -> float:
    """The cone's pressure drag referred to the free-stream dynamic pressure over eq 4.8's
    Cd at ``mach`` (default: the baseline's launch Mach number)."""
    return float(cone_drag_coefficient(mach) / BASELINE_CONE_LAW(mach))
