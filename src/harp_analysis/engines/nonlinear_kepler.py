"""The Modified Kepler equation before linearisation (Chapter 3 C), solved numerically, and the
natural frequency and frequency response of Fig 3.4 (Assumption 6).

With u = 1/r, theta the angular range, gamma = e^{-tau theta} and L = L_inf e^{beta gamma}
(eq 3.23), eq 3.9 reads

    u'' + (1/L)(dL/dtheta) u' + u = c3 exp(-2 beta gamma),   (1/L)(dL/dtheta) = -tau beta gamma,

which is eq 3.25 with the series of eq 3.24 summed: eq 3.26 differentiates eq 3.23 exactly, so
"eq 3.9 with the exact L(theta)" and eq 3.25 are one equation, and the printed signs of eqs
3.25, 3.26 and 3.29 all follow from eq 3.9 (checked: the "nonlinear term" of the text is
-tau beta gamma u', its "(tau beta e^{-tau theta} du/dtheta)" drops the minus). Substituting
u' = -u tan(phi) (eq 3.28; the middle member there lacks the factor 1/r) gives eq 3.29,

    u'' + omega_n^2(theta) u = c3 exp(-2 beta gamma),  omega_n^2 = 1 + tau beta tan(phi) gamma,

again the same equation while tan(phi) = -u'/u; with tan(phi) frozen at its launch value it
becomes a different equation (a stiffness instead of the u' term), the one whose "initial
natural frequency" the text quotes. Eq 3.30 sets omega_n = 1 (:mod:`.mks` solves it in closed form).

The term is linear in u; only eq 3.29's rewriting makes it look nonlinear. It comes from eq
3.1, whose radial equation has no drag, so eq 3.9 is exact for a purely transverse force. For
drag along the velocity (eq 3.10's drag) the radial drag -D sin(phi) cancels it exactly, and
u'' + u = GM/h^2 holds for any h(theta): eq 3.30 is then exact given h(theta), and Assumption 6
costs nothing. The differences computed here are therefore those between a transverse and an
along-velocity drag with the same angular-momentum decay (tests/test_nonlinear_kepler.py
checks both against time-domain integrations). They are tens of km (HP at 50 deg: apogee
+50 km on 76.7 km), and the 3DOF in the exponential atmosphere sides with eq 3.30.

SI units; the ODE is integrated in w = u r0 (w(0) = 1) by DOP853 at rtol 1e-12.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from scipy.integrate import solve_ivp

from ..foundation.validation import Bounds, check_choice, finite_array, finite_scalar
from ..models.launch import Launch
from . import mks

__all__ = [
    "FORMS",
    "TEXT_INITIAL_NATURAL_FREQUENCY",
    "NumericalKeplerSolution",
    "solve",
    "solve_for_launch",
    "driving_function",
    "natural_frequency",
    "initial_natural_frequency",
    "frequency_response",
    "driving_rates",
    "LinearisationError",
    "linearisation_error",
]

#: The equations solved: eq 3.25 (= eq 3.9 with L of eq 3.23), eq 3.29 with tan(phi) = -u'/u
#: (the same equation), eq 3.29 with tan(phi) frozen at launch, and eq 3.30 (omega_n = 1).
FORMS = ("eq_3_25", "eq_3_29", "eq_3_29_frozen", "eq_3_30")
#: Chapter 3 C: "the initial natural frequency of the system is 27 rad/rad" (HP, 50 deg).
TEXT_INITIAL_NATURAL_FREQUENCY = 27.0


@dataclass(frozen=True)
class _Launch:
    """The scalars of one launch of a :class:`mks.ModifiedKeplerSolution`."""

    radius_m: float
    tan_phi0: float
    tau: float
    beta_drive: float  # beta in the driving function (times drive_scale, eqs 6.9-6.10)
    beta_decay: float  # beta in L = L_inf exp(beta gamma) (times decay_scale, eq 6.14)
    c3: float

    @classmethod
    def of(cls, solution: mks.ModifiedKeplerSolution) -> _Launch:
        if not isinstance(solution, mks.ModifiedKeplerSolution):
            raise TypeError("solution must be an mks.ModifiedKeplerSolution")
        if not solution.single:
            raise ValueError("solution must describe a single launch")
        return cls(
            float(solution.radius_m[0, 0]),
            float(np.tan(solution.elevation_rad[0, 0])),
            float(solution.tau[0, 0]),
            float(solution.beta[0, 0] * solution.drive_scale[0, 0]),
            float(solution.beta[0, 0] * solution.decay_scale[0, 0]),
            float(solution.c3[0, 0]),
        )


def _n_terms(n_terms):
    if n_terms is None:
        return None
    return mks.check_n_terms(n_terms)


def driving_function(solution: mks.ModifiedKeplerSolution, theta_rad, n_terms=None):
    """Right-hand side of eqs 3.25, 3.29 and 3.30 (1/m): c3 exp(-2 beta gamma), or its series
    (eq 3.24) truncated to ``n_terms`` terms, gamma = e^{-tau theta}."""
    launch = _Launch.of(solution)
    n_terms = _n_terms(n_terms)
    x = -2 * launch.beta_drive * np.exp(-launch.tau * finite_array(theta_rad, "theta_rad"))
    if n_terms is None:
        return launch.c3 * np.exp(x)
    return launch.c3 * sum(x**n / math.factorial(n) for n in range(n_terms))


def natural_frequency(solution: mks.ModifiedKeplerSolution, theta_rad, tan_phi=None):
    """Eq 3.29: omega_n = sqrt(1 + tau beta tan(phi) e^{-tau theta}) (rad/rad) at ``theta_rad``;
    ``tan_phi`` is the local flight-path slope, by default frozen at its launch value."""
    launch = _Launch.of(solution)
    slope = launch.tan_phi0 if tan_phi is None else finite_array(tan_phi, "tan_phi")
    theta = Bounds(low=0.0, unit="rad").finite(theta_rad, "theta_rad")
    square = 1 + launch.tau * launch.beta_decay * slope * np.exp(-launch.tau * theta)
    return np.sqrt(
        Bounds(low=0.0).check(square, "tan_phi (omega_n^2 = 1 + tau beta tan(phi) gamma)")
    )


def initial_natural_frequency(solution: mks.ModifiedKeplerSolution) -> float:
    """Eq 3.29's natural frequency at launch, sqrt(1 + tau beta tan(phi0)) (rad/rad); the text
    quotes 27 for HP at 50 deg (:data:`TEXT_INITIAL_NATURAL_FREQUENCY`)."""
    return float(natural_frequency(solution, 0.0))


def frequency_response(omega, natural_frequency):
    """|1/(omega_n^2 - omega^2)|: the magnitude response of u'' + omega_n^2 u = f to a driving
    component of angular-range frequency ``omega`` (rad/rad), as read from Fig 3.4 (infinite at
    the undamped resonance omega = omega_n). The driving terms are decaying exponentials
    e^{-s theta}, whose particular solutions scale as 1/(omega_n^2 + s^2) instead; either way
    omega_n barely matters at s = tau, 2 tau. The large effect of eq 3.29's u-coefficient is on
    the homogeneous (ballistic) part of u, which this response does not show."""
    omega = Bounds(low=0.0).finite(omega, "omega")
    omega_n = Bounds(low=0.0, low_inclusive=False).finite(natural_frequency, "natural_frequency")
    with np.errstate(divide="ignore"):
        return 1 / np.abs(omega_n**2 - omega**2)


def driving_rates(solution: mks.ModifiedKeplerSolution, n_terms: int = 3):
    """The decay rates n tau (rad/rad), n = 1..``n_terms``, of the exponentials e^{-n tau theta}
    that make up the driving function (eq 3.24): the frequencies to mark on Fig 3.4."""
    return _Launch.of(solution).tau * np.arange(1, _n_terms(n_terms) + 1)


def _second_derivative(launch: _Launch, form: str, n_terms):
    """w'' (w = u r0) as a function of (theta, w, w') for each of :data:`FORMS`."""
    tau, beta, c3r0 = launch.tau, launch.beta_decay, launch.c3 * launch.radius_m
    factorials = None if n_terms is None else [math.factorial(n) for n in range(n_terms)]

    def drive(theta):
        x = -2 * launch.beta_drive * math.exp(-tau * theta)
        return c3r0 * (
            math.exp(x) if factorials is None else sum(x**n / f for n, f in enumerate(factorials))
        )

    if form == "eq_3_25":
        return lambda theta, w, dw: drive(theta) - w + tau * beta * math.exp(-tau * theta) * dw
    if form == "eq_3_29":
        return lambda theta, w, dw: (
            drive(theta) - w * (1 + tau * beta * (-dw / w) * math.exp(-tau * theta))
        )
    if form == "eq_3_29_frozen":
        return lambda theta, w, dw: (
            drive(theta) - w * (1 + tau * beta * launch.tan_phi0 * math.exp(-tau * theta))
        )
    return lambda theta, w, dw: drive(theta) - w


@dataclass(frozen=True)
class NumericalKeplerSolution:
    """A numerical solution u(theta) of one of :data:`FORMS`, from launch to impact."""

    form: str
    radius_m: float
    apogee_angle: float  # rad, first zero of du/dtheta
    impact_angle: float  # rad, return to the launch radius (nan if not within theta_max)
    _dense: object

    def _w(self, theta_rad):
        theta = Bounds(low=0.0, high=self._dense.t_max, unit="rad").finite(theta_rad, "theta_rad")
        return self._dense(theta)

    def u(self, theta_rad):
        """u = 1/r (1/m)."""
        return self._w(theta_rad)[0] / self.radius_m

    def du_dtheta(self, theta_rad):
        """du/dtheta (1/m per rad)."""
        return self._w(theta_rad)[1] / self.radius_m

    def altitude(self, theta_rad):
        """Height above the spherical Earth (m)."""
        return 1 / self.u(theta_rad) - self.radius_m

    def apogee_altitude(self) -> float:
        """Apogee height (m)."""
        return float(self.altitude(self.apogee_angle))

    @property
    def impact_range_m(self) -> float:
        """Ground range (arc on the launch sphere) from launch to impact (m)."""
        return self.radius_m * self.impact_angle


def solve(
    solution: mks.ModifiedKeplerSolution,
    form: str = "eq_3_25",
    *,
    n_terms=None,
    theta_max_rad: float = 2 * math.pi,
) -> NumericalKeplerSolution:
    """Integrate ``form`` (one of :data:`FORMS`) for the launch of ``solution`` (its beta, tau,
    c3 and r0, u(0) = 1/r0, u'(0) = -tan(phi0)/r0, eq 3.28) up to impact or ``theta_max_rad``;
    ``n_terms`` truncates the series of eq 3.24 in the driving function only (None: the
    double exponential itself)."""
    launch = _Launch.of(solution)
    check_choice(form, "form", FORMS)
    theta_max = finite_scalar(theta_max_rad, "theta_max_rad")
    Bounds(low=0.0, low_inclusive=False, unit="rad").check(theta_max, "theta_max_rad")
    second = _second_derivative(launch, form, _n_terms(n_terms))

    def apogee(theta, y):
        return y[1]

    def impact(theta, y):
        return y[0] - 1.0

    # (solve_ivp reads an event's options from attributes of the function)
    apogee.direction = impact.direction = 1.0  # type: ignore[attr-defined]
    impact.terminal = True  # type: ignore[attr-defined]
    result = solve_ivp(
        lambda theta, y: (y[1], second(theta, y[0], y[1])),
        (0.0, theta_max),
        (1.0, -launch.tan_phi0),
        method="DOP853",
        rtol=1e-12,
        atol=1e-14,
        dense_output=True,
        events=(apogee, impact),
    )
    if not result.success:
        raise RuntimeError(f"integration of {form} failed: {result.message}")
    first = [float(t[0]) if t.size else math.nan for t in result.t_events]
    return NumericalKeplerSolution(form, launch.radius_m, first[0], first[1], result.sol)


def solve_for_launch(
    launch: Launch, form: str = "eq_3_25", *, n_terms=None, **mks_options
) -> NumericalKeplerSolution:
    """:func:`solve` for ``launch`` (beta, tau from :func:`~harp_analysis.engines.mks.for_launch`,
    which ``mks_options`` are passed to)."""
    if not isinstance(launch, Launch):
        raise TypeError(f"launch must be a Launch; got {type(launch).__name__}")
    return solve(mks.for_launch(launch, warn=False, **mks_options), form, n_terms=n_terms)


class LinearisationError(NamedTuple):
    """A numerical form minus the closed-form eq 3.30 (m)."""

    apogee_m: float
    range_m: float


def linearisation_error(
    solution: mks.ModifiedKeplerSolution,
    form: str = "eq_3_25",
    *,
    n_terms=None,
    linear_terms: int = 30,
) -> LinearisationError:
    """Apogee and impact-range differences between ``form`` and eq 3.30 in closed form with
    ``linear_terms`` series terms (the size of Assumption 6 for that form)."""
    numerical = solve(solution, form, n_terms=n_terms)
    linear = mks.ModifiedKeplerSolution(
        solution.speed_m_s[0, 0],
        solution.elevation_rad[0, 0],
        solution.beta[0, 0],
        solution.tau[0, 0],
        n_terms=linear_terms,
        radius_m=solution.radius_m[0, 0],
        drive_scale=solution.drive_scale[0, 0],
        decay_scale=solution.decay_scale[0, 0],
        warn=False,
    )
    return LinearisationError(
        numerical.apogee_altitude() - float(linear.apogee_altitude()),
        numerical.impact_range_m - float(linear.impact_angle * linear.radius_m[0, 0]),
    )
