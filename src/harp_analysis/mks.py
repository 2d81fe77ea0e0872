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
import pandas as pd

from . import earth
from .atmosphere import SEA_LEVEL_DENSITY_KG_M3, TEXT_DECAY_CONSTANT_PER_M, get_atmosphere
from .launch import Launch
from .trajectory import describe, launch_frame
from .validation import ModelValidityWarning, check_range, finite_array, finite_scalar

__all__ = [
    "ModifiedKeplerSolution",
    "decay_factor_beta",
    "decay_rate_tau",
    "check_n_terms",
    "for_launch",
    "gun_density_kg_m3",
    "simulate_mks",
    "BETA_VALIDITY_LIMIT",
    "SENSIBLE_ATMOSPHERE_M",
]

#: Chapter 4 B: "a beta value of less than 0.25 is required for a reasonably accurate MKS".
BETA_VALIDITY_LIMIT = 0.25
#: Chapter 3: the Kepler solution "is reasonably valid above 30 km".
SENSIBLE_ATMOSPHERE_M = 30_000.0
#: The radius of the Earth's sphere of influence against the Sun, a (m_earth/m_sun)^(2/5)
#: = 9.25e5 km: beyond it the Sun's pull dominates and no Kepler orbit about the Earth holds.
EARTH_SPHERE_OF_INFLUENCE_M = 9.25e8
#: How closely the closed form's constants must reproduce the launch conditions u(0) = 1/r0 and
#: u'(0) = -tan(phi0)/r0 (relative to 1/r0): at a very low elevation beta (eq 3.22) is so large
#: that the constants cancel to no significant digit, or overflow.
_LAUNCH_CONDITION_TOLERANCE = 1e-6


def check_n_terms(n_terms) -> int:
    """``n_terms``, a count of series terms, as an int >= 1; ValueError naming it otherwise
    (2.5 is refused, not truncated)."""
    value = finite_scalar(n_terms, "n_terms")
    if isinstance(n_terms, bool) or value != int(value):
        raise ValueError(f"n_terms must be a whole number of series terms; got {n_terms!r}")
    return int(check_range(value, "n_terms", low=1))


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
    ``asymptotic_eccentricity`` (m,) is that of the conic the solution ends on, and
    ``escapes`` (m,) marks launches that leave on an open one: their apogee and impact are NaN.
    Constants that cannot reproduce the launch conditions (a grazing elevation) raise.
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
        n_terms = check_n_terms(n_terms)
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
        n = np.arange(n_terms)
        factorial = np.array([math.factorial(i) for i in n], dtype=float)
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            self.h_inf = self.h0 * np.exp(-self.beta * self.decay_scale)  # eq 3.23
            self.c3 = earth.GM_M3_S2 / self.h_inf**2  # eq 6.8
            self.amplitudes = (
                self.c3
                * (-2 * self.beta * self.drive_scale) ** n
                / (factorial * (1 + (n * self.tau) ** 2))
            )  # (m, N)
            self.rates = n * self.tau  # (m, N)
            self.c2 = 1 / self.radius_m - self.amplitudes.sum(axis=1, keepdims=True)
            self.c1 = -np.tan(self.elevation_rad) / self.radius_m + (
                self.rates * self.amplitudes
            ).sum(axis=1, keepdims=True)
        self._check_launch_conditions()
        self.asymptotic_eccentricity, self.escapes = self._asymptotic_conic()
        if warn:
            self._warn_outside_validity()

    def _check_launch_conditions(self):
        """ValueError naming the elevation if the constants do not reproduce u(0) = 1/r0 and
        u'(0) = -tan(phi0)/r0: at a very low elevation beta (eq 3.22, proportional to
        1/sin(phi0)) makes h_inf = h0 exp(-beta) underflow, or c3 and the amplitudes so large
        that they cancel to no significant digit; a NaN would otherwise surface deep inside."""
        scale = 1 / self.radius_m[:, 0]
        with np.errstate(invalid="ignore", over="ignore"):
            u0 = self.c2[:, 0] + self.amplitudes.sum(axis=1)
            slope0 = self.c1[:, 0] - (self.rates * self.amplitudes).sum(axis=1)
            error = np.maximum(
                np.abs(u0 - scale),
                np.abs(slope0 + np.tan(self.elevation_rad[:, 0]) * scale),
            )
            bad = ~(error <= _LAUNCH_CONDITION_TOLERANCE * scale)
        if np.any(bad):
            i = int(np.argmax(bad))
            raise ValueError(
                f"the MKS has no usable closed form at elevation_rad = "
                f"{self.elevation_rad[i, 0]:.6g} ({math.degrees(self.elevation_rad[i, 0]):.6g} "
                f"deg): beta = {self.beta[i, 0]:.4g} (eq 3.22, which grows as 1/sin of the "
                "elevation) makes h_inf = h0 exp(-beta) underflow or its constants cancel "
                "to no significant digit; raise the elevation"
            )

    def _asymptotic_conic(self):
        """The eccentricity of the conic u = K + c1 sin(theta) + c2 cos(theta) that the solution
        becomes once the driving terms have died out (K = c3 = GM/h_inf^2, the asymptotic
        angular momentum's; the whole series if tau = 0), and whether the launch escapes:
        that conic is open (e >= 1) and the flight is still aloft and climbing when the
        driving terms have died (e^{-tau theta} = e^-20), so it never comes back."""
        constant = np.where(self.rates == 0, self.amplitudes, 0.0).sum(axis=1)
        eccentricity = np.hypot(self.c1, self.c2)[:, 0] / constant
        tau = self.tau[:, 0]
        late = np.where(tau > 0, 20 / np.where(tau > 0, tau, 1.0), 0.0)[:, None]
        u, slope, _ = self._solution(late)
        aloft = u[:, 0] <= 1 / self.radius_m[:, 0]
        return eccentricity, (eccentricity >= 1.0) & aloft & (slope[:, 0] < 0)

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

        Taken on the branch where c1 sin(theta) + c2 cos(theta) is least, atan2(-c1, -c2):
        on a suborbital flight c2 < 0 (c3 = GM/h^2 exceeds 1/r0) and this is the printed
        principal branch; a launch whose horizontal speed exceeds the circular speed has
        c2 > 0 and its apogee beyond a quarter of the way round, where the principal branch
        would give the perigee's direction instead."""
        return self._out(np.arctan2(-self.c1, -self.c2)[:, 0])

    @cached_property
    def apogee_angle(self):
        """The first zero of du/dtheta (rad), by Newton iteration from eq 6.4; NaN for a launch
        that escapes (:attr:`escapes`)."""
        flying = ~self.escapes[:, None]
        theta = np.where(flying, np.atleast_1d(self.apogee_angle_eq_6_4)[:, None], 0.0)
        for _ in range(50):
            step = self._rows(self.du_dtheta, theta) / self._rows(self.d2u_dtheta2, theta)
            theta = self._newton(theta, np.where(flying, step, 0.0), "apogee")
            if np.all(np.abs(step[flying]) < 1e-15):
                break
        return self._out(np.where(flying, theta, np.nan)[:, 0])

    def _newton(self, theta, step, what):
        """``theta - step``, or ValueError naming the elevation if Newton's iteration for
        ``what`` has left the finite numbers."""
        theta = theta - step
        if not np.all(np.isfinite(theta)):
            i = int(np.argmax(~np.isfinite(theta[:, 0])))
            raise ValueError(
                f"the MKS {what} could not be found at elevation_rad = "
                f"{self.elevation_rad[i, 0]:.6g}, beta = {self.beta[i, 0]:.4g}"
            )
        return theta

    def _rows(self, function, theta_column):
        value = function(theta_column)
        return np.atleast_2d(value).reshape(theta_column.shape)

    def apogee_altitude(self, method: str = "first_zero"):
        """Apogee height (m): at the first zero of du/dtheta, or at eq 6.4's angle (eq 6.5);
        NaN for a launch that escapes (:attr:`escapes`)."""
        if method not in ("first_zero", "eq_6_4"):
            raise ValueError(f"unknown method {method!r}; expected 'first_zero' or 'eq_6_4'")
        angle = self.apogee_angle if method == "first_zero" else self.apogee_angle_eq_6_4
        flying = ~self.escapes[:, None]
        theta = np.where(flying, np.atleast_1d(angle)[:, None], 0.0)
        height = 1 / self._rows(self.u, theta) - self.radius_m
        return self._out(np.where(flying, height, np.nan)[:, 0])

    @cached_property
    def impact_angle(self):
        """Angular range (rad) where the descending solution returns to the launch radius; NaN
        for a launch that escapes (:attr:`escapes`)."""
        flying = ~self.escapes[:, None]
        # a symmetric conic's return; Newton refines it
        theta = np.where(flying, 2 * np.atleast_1d(self.apogee_angle)[:, None], 0.0)
        for _ in range(50):
            u = self._rows(self.u, theta) - 1 / self.radius_m
            step = np.where(flying, u / self._rows(self.du_dtheta, theta), 0.0)
            theta = self._newton(theta, step, "impact")
            if np.all(np.abs(step[flying]) < 1e-15):
                break
        return self._out(np.where(flying, theta, np.nan)[:, 0])

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
        if np.any(self.escapes):
            i = int(np.argmax(self.escapes))
            warnings.warn(
                f"MKS launch at {self.speed_m_s[i, 0]:.6g} m/s escapes: the asymptotic angular "
                f"momentum h_inf = {self.h_inf[i, 0]:.4g} m^2/s gives an escape orbit "
                f"(eccentricity {self.asymptotic_eccentricity[i]:.4g} >= 1), with no apogee "
                "or impact (apogee and impact are NaN)",
                ModelValidityWarning,
                stacklevel=3,
            )
        if np.any(self.beta > BETA_VALIDITY_LIMIT):
            warnings.warn(
                f"MKS beta = {self.beta.max():.3g} > {BETA_VALIDITY_LIMIT}: the text finds "
                "the solution inaccurate for such high-drag projectiles (Ch. 4 B)",
                ModelValidityWarning,
                stacklevel=3,
            )
        apogee = np.atleast_1d(self.apogee_altitude())[~self.escapes]
        beyond = apogee + self.radius_m[~self.escapes, 0] > EARTH_SPHERE_OF_INFLUENCE_M
        if np.any(beyond):
            warnings.warn(
                f"MKS apogee {apogee[beyond].max() / 1e3:.4g} km lies beyond the Earth's sphere "
                f"of influence ({EARTH_SPHERE_OF_INFLUENCE_M / 1e3:.4g} km from its centre): "
                "a near-escape launch (eccentricity "
                f"{self.asymptotic_eccentricity[~self.escapes][beyond].max():.4g}) that the "
                "Sun and Moon perturb, which no Kepler orbit about the Earth describes",
                ModelValidityWarning,
                stacklevel=3,
            )
        if np.any(~(apogee > SENSIBLE_ATMOSPHERE_M)):
            warnings.warn(
                f"MKS apogee {np.nanmin(apogee) / 1e3:.1f} km does not leave the "
                f"sensible atmosphere (below {SENSIBLE_ATMOSPHERE_M / 1e3:g} km), where "
                "the straight-line drag assumption fails (Ch. 3)",
                ModelValidityWarning,
                stacklevel=3,
            )


def gun_density_kg_m3(launch: Launch) -> float:
    """rho0 of the MKS for ``launch``: its air is eq 3.11's, rho0 exp(-k a) with rho0 =
    1.225 kg/m^3 (Chapter 3 B's fit to the 1976 standard atmosphere), taken at the site's
    altitude, whatever air the simulations fly; none in a vacuum launch."""
    if get_atmosphere(launch.atmosphere).density(0.0) == 0.0:
        return 0.0
    return SEA_LEVEL_DENSITY_KG_M3 * math.exp(-TEXT_DECAY_CONSTANT_PER_M * launch.site_altitude_m)


def _launches(launches) -> list[Launch]:
    if isinstance(launches, Launch):
        return [launches]
    if isinstance(launches, (str, bytes)) or not hasattr(launches, "__iter__"):
        raise TypeError(
            "launch must be a Launch or a non-empty sequence of them; "
            f"got {type(launches).__name__} {launches!r:.80}"
        )
    launches = list(launches)
    if not launches or not all(isinstance(launch, Launch) for launch in launches):
        raise TypeError(
            f"launch must be a Launch or a non-empty sequence of them; got {launches!r:.80}"
        )
    return launches


def for_launch(
    launch,
    *,
    n_terms: int = 3,
    decay_constant_per_m: float = TEXT_DECAY_CONSTANT_PER_M,
    warn: bool = True,
) -> ModifiedKeplerSolution:
    """The non-rotating MKS of ``launch`` (a :class:`~harp_analysis.launch.Launch`, or a
    sequence of them, solved together): Cd0 of the projectile's drag law at the launch Mach
    number, rho0 of the launch's air at the gun, k of eq 3.11 (Chapter 3 B), r0 = R + the
    site's altitude. The MKS is planar and drag-only: a wind is ignored with a warning, and a
    rotating Earth is :func:`harp_analysis.eci.solution_for_launch`'s."""
    launches = _launches(launch)
    for one in launches:
        one.require_zero(
            "MKS",
            "rotation_rate_rad_s",
            reason="the MKS is non-rotating; eci.solution_for_launch corrects it",
        )
        if one.elevation_deg >= 90.0:
            raise ValueError(
                f"the MKS cannot fly launch.elevation_deg = {one.elevation_deg:g}: a vertical "
                "shot has no angular momentum and tau = k r0 tan(phi0) (eq 3.27) is infinite"
            )
        if warn:
            one.warn_ignored(
                "MKS", "cross_wind_m_s", "head_wind_m_s", reason="the MKS has no wind (Chapter 3)"
            )
    speed, elevation, cd0, density, area, mass, radius = (
        np.array(
            [getattr(one, name) if isinstance(name, str) else name(one) for one in launches],
            dtype=float,
        )
        for name in (
            "speed_m_s",
            "elevation_rad",
            "launch_drag_coefficient",
            gun_density_kg_m3,
            lambda one: one.projectile.reference_area_m2,
            lambda one: one.projectile.mass_kg,
            lambda one: earth.RADIUS_M + one.site_altitude_m,
        )
    )
    beta = decay_factor_beta(cd0, density, area, mass, elevation, decay_constant_per_m)
    single = isinstance(launch, Launch)
    pick = (lambda a: a[0]) if single else (lambda a: a)
    return ModifiedKeplerSolution(
        pick(speed),
        pick(elevation),
        pick(beta),
        pick(decay_rate_tau(elevation, decay_constant_per_m, radius)),
        n_terms=n_terms,
        radius_m=pick(radius),
        warn=warn,
    )


def simulate_mks(
    launch: Launch,
    *,
    n_terms: int = 3,
    n_points: int = 400,
    decay_constant_per_m: float = TEXT_DECAY_CONSTANT_PER_M,
    warn: bool = True,
) -> pd.DataFrame:
    """The MKS of ``launch`` (:func:`for_launch`) as the engines' trajectory table, launch to
    impact at ``n_points`` equal steps of angular range plus the apogee, with the shared
    metadata (no right-hand side is evaluated: ``rhs_evaluations = steps = 0``).

    Positions are Earth-centred (z north, x toward longitude 0) in the launch plane; Mach is
    the speed over the launch atmosphere's speed of sound; the drag coefficient is the MKS's
    constant Cd0 and drag/gravity is its drag in eq 3.11's air, rho0 exp(-k a)."""
    count = int(check_range(finite_scalar(n_points, "n_points"), "n_points", low=2))
    if not isinstance(launch, Launch):
        raise TypeError(f"launch must be a Launch; got {type(launch).__name__}")
    solution = for_launch(
        launch, n_terms=n_terms, decay_constant_per_m=decay_constant_per_m, warn=warn
    )
    if solution.escapes[0]:
        raise ValueError(
            f"the MKS of launch.speed_m_s = {launch.speed_m_s:g} escapes (its asymptotic "
            "conic is an escape orbit): there is no apogee or impact to tabulate"
        )
    apogee_angle = float(solution.apogee_angle)
    theta = np.union1d(np.linspace(0.0, float(solution.impact_angle), count), [apogee_angle])
    sample = solution.sample(theta)
    radius = sample["altitude_m"] + float(solution.radius_m[0, 0])
    up, downrange, _ = launch_frame(
        launch.latitude_rad, math.radians(launch.longitude_deg), launch.bearing_rad
    )
    position = radius[:, None] * (
        np.cos(theta)[:, None] * np.ravel(up) + np.sin(theta)[:, None] * np.ravel(downrange)
    )
    altitude = radius - earth.RADIUS_M
    cd0, projectile = launch.launch_drag_coefficient, launch.projectile
    density = gun_density_kg_m3(launch) * np.exp(
        -decay_constant_per_m * (altitude - launch.site_altitude_m)
    )
    drag = 0.5 * density * cd0 * projectile.reference_area_m2 * sample["speed_m_s"] ** 2
    sound = get_atmosphere(launch.atmosphere).speed_of_sound(np.maximum(altitude, 0.0))
    frame = pd.DataFrame(
        {
            "time_s": sample["time_s"],
            "x_m": position[:, 0],
            "y_m": position[:, 1],
            "z_m": position[:, 2],
            "altitude_m": altitude,
            "ground_range_m": earth.RADIUS_M * theta,
            "cross_range_m": np.zeros_like(theta),
            "speed_m_s": sample["speed_m_s"],
            "mach": sample["speed_m_s"] / sound,
            "drag_coefficient": np.full_like(theta, cd0),
            "drag_to_gravity": drag / (projectile.mass_kg * earth.GM_M3_S2 / radius**2),
            "specific_angular_momentum_m2_s": solution.angular_momentum(theta),
            "flight_path_angle_rad": sample["flight_path_angle_rad"],
        }
    )
    top = frame.iloc[int(np.searchsorted(theta, apogee_angle))]
    return describe(
        frame,
        engine="MKS",
        launch=launch,
        apogee=(top.time_s, top.altitude_m, top.ground_range_m),
        impact=True,
        rhs_evaluations=0,
        steps=0,
        max_time_s=math.inf,
        n_terms=n_terms,
    )
