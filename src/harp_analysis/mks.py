"""The Modified Kepler Solution (Chapter 3): Kepler's orbit equation driven by the decay of the
angular momentum in the atmosphere, solved in closed form.

With u = 1/r and theta the angular range, the linearised Modified Kepler equation (eq 3.30) is

    u'' + u = c3 sum_{n=0}^{N-1} (-2 beta e^{-tau theta})^n / n!,     c3 = GM / h_inf^2,

where h is the specific angular momentum, h = h_inf exp(beta gamma) with gamma = e^{-tau theta}
(eqs 3.20-3.23), beta = Cd0 rho0 A / (2 k m sin phi0) (eq 3.22) and tau = k r0 tan phi0
(eq 3.27). Each term of the series is an exponential, so the particular solution is term by
term, and the constants follow from the launch conditions u(0) = 1/r0 and
u'(0) = -tan(phi0)/r0 (eq 3.28):

    u(theta) = c1 sin(theta) + c2 cos(theta) + sum_n A_n e^{-n tau theta},
    A_n = c3 (-2 beta)^n / (n! (1 + n^2 tau^2)),
    c2 = 1/r0 - sum_n A_n,      c1 = -tan(phi0)/r0 + tau sum_n n A_n,

which for N = 3 are eqs 6.6-6.10 (c4 = A_1, c5 = A_2) without the rotating-Earth factors. Those
factors of Chapter 5 enter as two scales: the driving function's beta is multiplied by
``drive_scale`` (cos mu (Vrel/V)^2, eqs 6.9-6.10) and the decay h_inf = h0 exp(-beta
``decay_scale``) by ``decay_scale`` (cos mu, eq 6.14); both are 1 on a non-rotating Earth.

SI units: r in m, u in 1/m, h in m^2/s, k in 1/m (the text's 0.117 /km is 1.17e-4 /m; beta
and tau are dimensionless only if k and r0, m and A share units).
"""

from __future__ import annotations

import math
import warnings
from functools import cache, cached_property

import numpy as np

from . import earth
from .atmosphere import SEA_LEVEL_DENSITY_KG_M3, TEXT_DECAY_CONSTANT_PER_M, get_atmosphere
from .projectiles import Projectile
from .validation import ModelValidityWarning, check_range, finite_array, finite_scalar

__all__ = [
    "ModifiedKeplerSolution",
    "decay_factor_beta",
    "decay_rate_tau",
    "for_projectile",
    "BETA_VALIDITY_LIMIT",
    "SENSIBLE_ATMOSPHERE_M",
]

#: Chapter 4 B: "a beta value of less than 0.25 is required for a reasonably accurate MKS".
BETA_VALIDITY_LIMIT = 0.25
#: Chapter 3: the Kepler solution "is reasonably valid above 30 km".
SENSIBLE_ATMOSPHERE_M = 30_000.0


@cache
def _gauss_legendre(order: int):
    return np.polynomial.legendre.leggauss(order)


def decay_factor_beta(
    drag_coefficient,
    surface_density_kg_m3,
    area_m2,
    mass_kg,
    elevation_rad,
    decay_constant_per_m=TEXT_DECAY_CONSTANT_PER_M,
):
    """Eq 3.22: beta = Cd0 rho0 A / (2 k m sin phi0), the MKS ballistic coefficient."""
    return (
        np.asarray(drag_coefficient)
        * surface_density_kg_m3
        * area_m2
        / (2 * decay_constant_per_m * mass_kg * np.sin(elevation_rad))
    )


def decay_rate_tau(
    elevation_rad, decay_constant_per_m=TEXT_DECAY_CONSTANT_PER_M, radius_m=earth.RADIUS_M
):
    """Eq 3.27: tau = k r0 tan phi0, the decay rate of the density along the angular range."""
    return decay_constant_per_m * radius_m * np.tan(elevation_rad)


class ModifiedKeplerSolution:
    """The MKS of one or many launches (arguments broadcast to shape (m,)).

    Functions of the angular range take ``theta_rad`` of shape (k,) and return (k,) for a
    single launch or (m, k) for many; ``theta_rad`` may also be (m, k), one row per launch.
    """

    def __init__(
        self,
        speed_m_s,
        elevation_rad,
        beta,
        tau,
        *,
        n_terms: int = 3,
        radius_m=earth.RADIUS_M,
        drive_scale=1.0,
        decay_scale=1.0,
        warn: bool = True,
    ):
        speed = check_range(
            finite_array(speed_m_s, "speed_m_s"),
            "speed_m_s",
            low=0.0,
            low_inclusive=False,
            unit="m/s",
        )
        elevation = check_range(
            finite_array(elevation_rad, "elevation_rad"),
            "elevation_rad",
            low=0.0,
            low_inclusive=False,
            high=math.pi / 2,
            high_inclusive=False,
            unit="rad",
        )
        beta = check_range(finite_array(beta, "beta"), "beta", low=0.0)
        tau = check_range(finite_array(tau, "tau"), "tau", low=0.0)
        radius = check_range(
            finite_array(radius_m, "radius_m"), "radius_m", low=0.0, low_inclusive=False, unit="m"
        )
        n_terms = int(check_range(finite_scalar(n_terms, "n_terms"), "n_terms", low=1))
        arrays = np.broadcast_arrays(
            speed,
            elevation,
            beta,
            tau,
            radius,
            finite_array(drive_scale, "drive_scale"),
            finite_array(decay_scale, "decay_scale"),
        )
        self.single = arrays[0].ndim == 0
        (
            self.speed_m_s,
            self.elevation_rad,
            self.beta,
            self.tau,
            self.radius_m,
            self.drive_scale,
            self.decay_scale,
        ) = (np.atleast_1d(a).astype(float)[:, None] for a in arrays)
        self.n_terms = n_terms
        self.h0 = self.speed_m_s * self.radius_m * np.cos(self.elevation_rad)  # eq 6.13
        self.h_inf = self.h0 * np.exp(-self.beta * self.decay_scale)  # eq 3.23
        self.c3 = earth.GM_M3_S2 / self.h_inf**2  # eq 6.8
        n = np.arange(n_terms)
        factorial = np.array([math.factorial(i) for i in n], dtype=float)
        self.amplitudes = (
            self.c3
            * (-2 * self.beta * self.drive_scale) ** n
            / (factorial * (1 + (n * self.tau) ** 2))
        )  # (m, N)
        self.rates = n * self.tau  # (m, N)
        self.c2 = 1 / self.radius_m - self.amplitudes.sum(axis=1, keepdims=True)
        self.c1 = -np.tan(self.elevation_rad) / self.radius_m + (self.rates * self.amplitudes).sum(
            axis=1, keepdims=True
        )
        if warn:
            self._warn_outside_validity()

    # --- the solution and its derivatives ----------------------------------------------------
    def _out(self, value):
        return value[0] if self.single else value

    def _theta(self, theta_rad):
        theta = finite_array(theta_rad, "theta_rad")
        return theta if theta.ndim == 2 else np.atleast_1d(theta)[None, :]

    def _terms(self, theta):
        """sum_n A_n e^{-n tau theta} and its first two derivatives, shapes (m, k)."""
        decay = np.exp(-self.rates[:, :, None] * theta[:, None, :])  # (m, N, k)
        a = self.amplitudes[:, :, None]
        r = self.rates[:, :, None]
        return (
            np.sum(a * decay, axis=1),
            np.sum(-r * a * decay, axis=1),
            np.sum(r * r * a * decay, axis=1),
        )

    def _solution(self, theta_rad):
        """u, du/dtheta and d2u/dtheta2 at ``theta_rad``, shapes (m, k), from one evaluation."""
        theta = self._theta(theta_rad)
        sin, cos = np.sin(theta), np.cos(theta)
        terms, slope, curvature = self._terms(theta)
        return (
            self.c1 * sin + self.c2 * cos + terms,
            self.c1 * cos - self.c2 * sin + slope,
            -self.c1 * sin - self.c2 * cos + curvature,
        )

    def u(self, theta_rad):
        """u = 1/r (1/m) at angular range ``theta_rad`` (eq 3.30's solution)."""
        return self._out(self._solution(theta_rad)[0])

    def du_dtheta(self, theta_rad):
        """du/dtheta (1/m per rad), eq 6.1 for three terms."""
        return self._out(self._solution(theta_rad)[1])

    def d2u_dtheta2(self, theta_rad):
        return self._out(self._solution(theta_rad)[2])

    def radius(self, theta_rad):
        """Distance from the Earth's centre (m)."""
        return 1.0 / self.u(theta_rad)

    def altitude(self, theta_rad):
        """Height above the spherical Earth (m)."""
        return self.radius(theta_rad) - self._out(self.radius_m)

    def angular_momentum(self, theta_rad):
        """Specific angular momentum h = h_inf exp(beta gamma), gamma = e^{-tau theta} (eq 3.23)."""
        theta = self._theta(theta_rad)
        return self._out(
            self.h_inf * np.exp(self.beta * self.decay_scale * np.exp(-self.tau * theta))
        )

    def speed(self, theta_rad):
        """Speed (m/s) from eq 4.2: V = h sqrt(u^2 + (du/dtheta)^2)."""
        u, slope, _ = self._solution(theta_rad)
        return self.angular_momentum(theta_rad) * self._out(np.hypot(u, slope))

    def flight_path_angle(self, theta_rad):
        """Angle of the velocity above the horizontal, tan(phi) = -u'/u (eq 3.28)."""
        u, slope, _ = self._solution(theta_rad)
        return self._out(np.arctan2(-slope, u))

    # --- apogee, impact, time ----------------------------------------------------------------
    @cached_property
    def apogee_angle_eq_6_4(self):
        """Eq 6.4: theta_apogee = atan(c1/c2), the apogee with the driving terms dropped.

        The principal branch is the right one: on a suborbital flight c1 and c2 are both
        negative (c3 = GM/h^2 exceeds 1/r0), so atan2 would pick the wrong quadrant."""
        return self._out(np.arctan(self.c1 / self.c2)[:, 0])

    @cached_property
    def apogee_angle(self):
        """The first zero of du/dtheta (rad), by Newton iteration from eq 6.4."""
        theta = np.atleast_1d(self.apogee_angle_eq_6_4)[:, None].copy()
        for _ in range(50):
            step = self._rows(self.du_dtheta, theta) / self._rows(self.d2u_dtheta2, theta)
            theta -= step
            if np.all(np.abs(step) < 1e-15):
                break
        return self._out(theta[:, 0])

    def _rows(self, function, theta_column):
        value = function(theta_column)
        return np.atleast_2d(value).reshape(theta_column.shape)

    def apogee_altitude(self, method: str = "first_zero"):
        """Apogee height (m): at the first zero of du/dtheta, or at eq 6.4's angle (eq 6.5)."""
        angles = {"first_zero": self.apogee_angle, "eq_6_4": self.apogee_angle_eq_6_4}
        if method not in angles:
            raise ValueError(f"unknown method {method!r}; expected 'first_zero' or 'eq_6_4'")
        theta = np.atleast_1d(angles[method])[:, None]
        return self._out(1 / self._rows(self.u, theta)[:, 0] - self.radius_m[:, 0])

    @cached_property
    def impact_angle(self):
        """Angular range (rad) where the descending solution returns to the launch radius."""
        apogee = np.atleast_1d(self.apogee_angle)[:, None]
        theta = 2 * apogee  # a symmetric conic's return; Newton refines it
        for _ in range(50):
            u = self._rows(self.u, theta) - 1 / self.radius_m
            step = u / self._rows(self.du_dtheta, theta)
            theta -= step
            if np.all(np.abs(step) < 1e-15):
                break
        return self._out(theta[:, 0])

    def sample(self, theta_rad, order: int = 3) -> dict:
        """A whole trajectory at the (sorted) angles ``theta_rad`` in one pass: arrays of
        ``theta_rad``, ``ground_range_m``, ``altitude_m``, ``speed_m_s``,
        ``flight_path_angle_rad`` and ``time_s`` (named as in :mod:`.trajectory`)."""
        u, slope, _ = self._solution(theta_rad)
        h = self.angular_momentum(theta_rad)
        theta = self._out(self._theta(theta_rad))
        return {
            "theta_rad": theta,
            "ground_range_m": theta * self._out(self.radius_m),
            "altitude_m": self._out(1 / u - self.radius_m),
            "speed_m_s": h * self._out(np.hypot(u, slope)),
            "flight_path_angle_rad": self._out(np.arctan2(-slope, u)),
            "time_s": self.time(theta_rad, order),
        }

    def time(self, theta_rad, order: int = 3):
        """Time of flight (s) from launch to each ``theta_rad`` (sorted, starting anywhere >= 0),
        eq 3.32: t = integral of dtheta / (u^2 h), by ``order``-point Gauss-Legendre on every
        interval between consecutive angles (and from 0 to the first). On a grid of a few
        hundred angles three points per interval are converged to nanoseconds (tests); ask for
        the time at a single far angle and one three-point interval spans the whole flight:
        pass the grid and read its last value instead."""
        theta = self._theta(theta_rad)
        theta = np.broadcast_to(theta, (self.h0.shape[0], theta.shape[1]))
        edges = np.concatenate([np.zeros((theta.shape[0], 1)), theta], axis=1)
        if np.any(np.diff(edges, axis=1) < 0):
            raise ValueError("theta_rad must be sorted and non-negative")
        nodes, weights = _gauss_legendre(int(order))
        low, high = edges[:, :-1], edges[:, 1:]
        points = (0.5 * (high - low))[:, :, None] * (nodes + 1) + low[:, :, None]
        flat = points.reshape(points.shape[0], -1)
        integrand = 1 / (self._rows(self.u, flat) ** 2 * self._rows(self.angular_momentum, flat))
        pieces = 0.5 * (high - low) * (integrand.reshape(points.shape) @ weights)
        return self._out(np.cumsum(pieces, axis=1))

    # --- validity ------------------------------------------------------------------------------
    def _warn_outside_validity(self):
        if np.any(self.beta > BETA_VALIDITY_LIMIT):
            warnings.warn(
                f"MKS beta = {self.beta.max():.3g} > {BETA_VALIDITY_LIMIT}: the text finds "
                "the solution inaccurate for such high-drag projectiles (Ch. 4 B)",
                ModelValidityWarning,
                stacklevel=3,
            )
        apogee = np.atleast_1d(self.apogee_altitude())
        if np.any(~(apogee > SENSIBLE_ATMOSPHERE_M)):
            warnings.warn(
                f"MKS apogee {np.nanmin(apogee) / 1e3:.1f} km does not leave the "
                f"sensible atmosphere (below {SENSIBLE_ATMOSPHERE_M / 1e3:g} km), where "
                "the straight-line drag assumption fails (Ch. 3)",
                ModelValidityWarning,
                stacklevel=3,
            )


def for_projectile(
    projectile: Projectile,
    elevation_deg,
    *,
    speed_m_s=None,
    n_terms: int = 3,
    decay_constant_per_m: float = TEXT_DECAY_CONSTANT_PER_M,
    surface_density_kg_m3: float = SEA_LEVEL_DENSITY_KG_M3,
    sound_atmosphere: str = "two_segment",
    warn: bool = True,
) -> ModifiedKeplerSolution:
    """The non-rotating MKS of ``projectile`` fired at ``elevation_deg``: Cd0 from its drag law
    at the launch Mach number (speed of sound of ``sound_atmosphere`` at sea level), rho0 and
    k of eq 3.11 (Chapter 3 B)."""
    elevation = np.radians(
        check_range(
            finite_array(elevation_deg, "elevation_deg"),
            "elevation_deg",
            low=0.0,
            low_inclusive=False,
            high=90.0,
            high_inclusive=False,
            unit="deg",
        )
    )
    speed = finite_array(
        projectile.launch_speed_m_s if speed_m_s is None else speed_m_s, "speed_m_s"
    )
    cd0 = projectile.drag_law(speed / get_atmosphere(sound_atmosphere).speed_of_sound(0.0))
    beta = decay_factor_beta(
        cd0,
        surface_density_kg_m3,
        projectile.reference_area_m2,
        projectile.mass_kg,
        elevation,
        decay_constant_per_m,
    )
    return ModifiedKeplerSolution(
        speed,
        elevation,
        beta,
        decay_rate_tau(elevation, decay_constant_per_m),
        n_terms=n_terms,
        warn=warn,
    )
