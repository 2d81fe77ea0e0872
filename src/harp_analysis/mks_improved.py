"""A better MKS (Chapter 7 C: "more work on accurately predicting the asymptotic angular momentum
and decay of angular momentum during reentry"): the dissertation's closed form with a
self-consistent drag decay on the way up and a re-entry decay on the way down. A named variant;
:mod:`.mks` and :mod:`.eci` stay as the text has them.

Why h(theta) is what matters. For drag along the velocity the Binet equation u'' + u =
GM/h(theta)^2 is exact: the drag's radial part and the term -(h'/h) u' that a varying h adds
cancel. The MKS's errors on a non-rotating Earth therefore come from its model of h(theta) (and
the series' truncation): eq 3.22's beta is the loss integral ln(h0/h_inf) = int (A/2m) rho Cd ds
taken along a straight line through eq 3.11's air at the launch Cd0 (Assumptions 2-4), and
nothing decays on the way down, so the flight ends early.

Ascent, self-consistent. Along any flight, d(-ln h)/dtheta = (A/2m) rho Cd(M) |Vrel|
(1 - omega n_z r^2/h) r^2/h exactly (in-plane part): |Vrel|^2 = V^2 - 2 omega h n_z + omega^2
r^2 cos^2(latitude), since V.(omega x r) = omega.(r x V) = omega h n_z with n the flight plane's
normal, and r x Vrel = h - r x (omega x r) has the in-plane part h - omega n_z r^2. Evaluated
along the MKS's own path with its own speed, through the launch's air and drag law, it gives the
loss L = int rate dtheta and the shape of h = h_inf exp(beta e^{-tau theta}) by the first moment,
tau = 1/<theta> (the exponential's loss density beta tau e^{-tau theta} has mean 1/tau). The MKS
flown with these is evaluated again, to a fixed point: the path curves as the solution does
(Fig 4.14's straight-line error), and the air and Cd(Mach) are the launch's own. Drive and decay
take one beta (eq 3.23's h = h_inf exp(beta gamma) needs the same one in both).

On a rotating Earth the drag along Vrel also pushes across the inertial velocity. Chapter 5 gives
that push to the launch as V_tangent (eq 6.15), from eq 5.8's straight line through eq 3.11's
air; here V_tangent is its integral along the same path, int (A/2m) rho Cd |Vrel| |(omega x
r) across V| dt, in eq 6.15's direction. V_tangent raises h0 above that of the gun's Vrel +
omega x r0, which is what the loss decays: h_inf = h_gun e^{-L}, so beta = L + ln(h0/h_gun).

Re-entry. The same form mirrored about the impact, h = h_inf exp(-beta_re e^{-tau_re (theta_imp -
theta)}): GM/h^2 = c3 sum_n (2 beta_re e^{tau_re (theta - theta_imp)})^n / n!, and each term
e^{+n tau_re theta} has the particular solution B_n e^{n tau_re (theta - theta_imp)}, B_n = c3
(2 beta_re)^n / (n! (1 + n^2 tau_re^2)) (mks's A_n with tau -> -tau). A conic absorbs the
terms' (vanishing) value and slope at launch, so u(0) and u'(0) stay the launch's; at the impact
the terms are sum B_n whatever theta_imp, so u = 1/r0 is one equation in it. beta_re and tau_re
are the loss along the ascent solution's descent from the top of the air to its impact,
integrated forward with the speed it loses (h = h_inf e^{-L}), and 1 / the loss's mean distance
before the impact. h(theta) is the product of the two branches: continuous and non-increasing
from launch to impact. Time is t = int dtheta / (h u^2) with it.

The re-entry terms hardly move the path (B_n ~ c3 beta_re / tau_re^2: metres at the impact):
drag along the path bends it only by slowing it. What they change is the time of flight, and so
the position at a given time.

The one fitted number (:class:`Calibration`): ``reentry_scale`` on beta_re. The descent loss is
taken along the drag-free conic's path, shallower and faster than the real one, and spread as
an exponential only roughly; one factor absorbs both, fitted by
:func:`harp_analysis.mks_improvement.fit` on training launches only (1 is the physics alone).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from . import earth, eci, mks
from .launch import Launch
from .trajectory import launch_frame, rotate_about_axis, surface_ranges
from .validation import ModelValidityWarning, check_range, finite_array, finite_scalar

__all__ = [
    "Calibration",
    "UNCALIBRATED",
    "VARIANTS",
    "ImprovedSolution",
    "solve",
    "dissertation",
    "flight",
    "TOP_OF_ATMOSPHERE_M",
    "AIR_MOMENTUM_SHARE_RANGE",
    "air_momentum_share",
]

#: Outside this band of the air's share in the launch's angular momentum
#: (:func:`air_momentum_share`) the improved MKS warns: on the error map (bearing x elevation x
#: latitude, :func:`harp_analysis.mks_improvement.error_map`) it misses the impact by more than
#: the dissertation's at every point outside it. The band was drawn from that same map, so the
#: map's share of better points inside it is not an independent test.
AIR_MOMENTUM_SHARE_RANGE = (-0.5, 1.0)
#: Where the loss integrals stop: above 100 km eqs 2.1-2.2's density is 3e-7 kg/m^3 and what
#: is left of the loss, rho H Cd A/(2m), is below 1e-8 of h.
TOP_OF_ATMOSPHERE_M = 100_000.0
#: Points of the loss quadratures, spaced geometrically from the dense end (the air's scale
#: height is a few thousandths of a flight's angular range).
_QUADRATURE_POINTS = 1500
#: The self-consistent ascent stops when beta and tau change by less than this (relative).
_FIXED_POINT_TOLERANCE = 1e-10
_FIXED_POINT_ITERATIONS = 30
#: Points of the time grid from launch to impact (3-point Gauss-Legendre on each interval).
_TIME_POINTS = 4001

VARIANTS = ("dissertation", "improved")


@dataclass(frozen=True)
class Calibration:
    """The fitted part of the improved MKS: ``reentry_scale`` multiplies the re-entry loss
    beta_re (1: the loss along the drag-free conic as it is)."""

    reentry_scale: float = 1.0

    def __post_init__(self):
        value = check_range(
            finite_scalar(self.reentry_scale, "reentry_scale"), "reentry_scale", low=0.0
        )
        object.__setattr__(self, "reentry_scale", value)


#: The physics alone, nothing fitted.
UNCALIBRATED = Calibration()


@dataclass(frozen=True)
class _Plane:
    """The inertial flight plane (longitude 0 at t = 0): unit vectors up (the launch point) and
    along (the launch velocity's horizontal part), and the z component of their normal."""

    up: np.ndarray
    along: np.ndarray

    @property
    def normal_z(self) -> float:
        return float(np.cross(self.up, self.along)[2])

    def directions(self, theta_rad) -> np.ndarray:
        """Unit vectors (n, 3) at angular ranges ``theta_rad`` (n,)."""
        theta = np.asarray(theta_rad, dtype=float)[:, None]
        return np.cos(theta) * self.up + np.sin(theta) * self.along


def _plane(ascent: mks.ModifiedKeplerSolution, correction, latitude_rad) -> _Plane:
    """Chapter 5's plane of ``correction`` as :func:`eci.inertial_positions` places the MKS."""
    apogee = float(ascent.apogee_angle)
    points = eci.inertial_positions(ascent, correction, latitude_rad, [0.0, apogee])
    up = points[0] / np.linalg.norm(points[0])
    along = points[1] / np.linalg.norm(points[1]) - math.cos(apogee) * up
    return _Plane(up, along / np.linalg.norm(along))


class _Air:
    """What the loss rate needs of a launch: drag per density, the launch's air on its day,
    drag law, Earth rotation."""

    def __init__(self, launch: Launch, plane: _Plane):
        self.latitude_rad = launch.latitude_rad
        projectile = launch.projectile
        self.per_density = projectile.reference_area_m2 / (2 * projectile.mass_kg)
        self.air = launch.air
        self.drag_law = projectile.drag_law
        self.omega = launch.rotation_rate_rad_s
        self.plane = plane

    def rates(self, theta, u, slope, h):
        """d(-ln h)/dtheta (per rad) at angular ranges ``theta`` of a path u(theta) with
        du/dtheta ``slope`` flown with angular momentum ``h`` (module docstring), and the
        drag's acceleration across the inertial velocity per rad, dV_tangent/dtheta (m/s)."""
        r = 1 / u
        altitude = np.maximum(r - earth.RADIUS_M, 0.0)
        speed_squared = h**2 * (u**2 + slope**2)
        omega, n_z = self.omega, self.plane.normal_z
        cos_latitude_squared = 1 - self.plane.directions(theta)[:, 2] ** 2
        # the air's velocity omega x r: its square, and its part along the inertial velocity
        air_squared = (omega * r) ** 2 * cos_latitude_squared
        along = omega * h * n_z
        air_speed = np.sqrt(np.maximum(speed_squared - 2 * along + air_squared, 0.0))
        across = np.sqrt(np.maximum(air_squared - along**2 / speed_squared, 0.0))
        density, sound = self.air(altitude)
        mach = air_speed / sound
        per_time = self.per_density * density * self.drag_law(mach)
        per_time *= air_speed * r**2 / h  # times dt/dtheta
        return per_time * (1 - omega * n_z * r**2 / h), per_time * across


def _loss_and_rate(rate, theta) -> tuple[float, float]:
    """int rate dtheta, and 1 / the mean |theta| weighted by |rate| (the exponential's tau;
    |rate|, because on a rotating Earth the air can add angular momentum as well as take it)."""
    size = np.abs(rate)
    mean = float(np.trapezoid(size * np.abs(theta), theta) / np.trapezoid(size, theta))
    return float(np.trapezoid(rate, theta)), 1 / mean


def _scalar(value) -> float:
    """The one number of a single launch's (1,) or () result."""
    return float(np.ravel(value)[0])


def _ascent_grid(top_rad: float) -> np.ndarray:
    return np.concatenate([[0.0], np.geomspace(top_rad * 1e-7, top_rad, _QUADRATURE_POINTS)])


def _top_angle(solution: mks.ModifiedKeplerSolution, low: float, high: float, rising: bool):
    """Angular range in [low, high] where ``solution`` passes TOP_OF_ATMOSPHERE_M going up
    (``rising``) or down; ``high`` (the apogee) or ``low`` if it never gets that high."""
    grid = np.linspace(low, high, 2001)
    altitude = np.ravel(solution.altitude(grid))
    if altitude.max() <= TOP_OF_ATMOSPHERE_M:
        return high if rising else low
    if rising:
        above = np.argmax(altitude >= TOP_OF_ATMOSPHERE_M)
        return float(
            np.interp(
                TOP_OF_ATMOSPHERE_M, altitude[above - 1 : above + 1], grid[above - 1 : above + 1]
            )
        )
    below = np.argmax(altitude <= TOP_OF_ATMOSPHERE_M)
    return float(
        np.interp(
            -TOP_OF_ATMOSPHERE_M, -altitude[below - 1 : below + 1], grid[below - 1 : below + 1]
        )
    )


def _with_tangent(correction, tangent_speed_m_s: float, latitude_rad: float):
    """``correction`` launched with V_tangent = ``tangent_speed_m_s`` along eq 6.15's direction."""
    direction = eci.tangent_direction(
        correction.relative_m_s, correction.relative_m_s + correction.surface_m_s
    )
    velocity = correction.relative_m_s + correction.surface_m_s + tangent_speed_m_s * direction
    speed = np.linalg.norm(velocity)
    elevation, azimuth = eci.elevation_azimuth(velocity, latitude_rad)
    return replace(
        correction,
        tangent_speed_m_s=np.asarray(tangent_speed_m_s),
        velocity_m_s=velocity,
        speed_m_s=speed,
        elevation_rad=elevation,
        azimuth_rad=azimuth,
        initial_angular_momentum_m2_s=eci.initial_angular_momentum(speed, elevation),
    )


def _ascent_decay(correction, air: _Air, n_terms: int):
    """(corrected launch, MKS) whose beta and tau are the loss and first moment along the MKS's
    own ascent, and whose V_tangent is the cross-track drag's impulse along it."""
    solution = eci.solution_for(correction, n_terms=n_terms, warn=False)
    beta, tau = float(solution.beta[0, 0] * solution.decay_scale[0, 0]), float(solution.tau[0, 0])
    radius = float(solution.radius_m[0, 0])
    # The loss decays the angular momentum the gun gives, that of Vrel + omega x r0.
    h_gun = float(
        eci.initial_angular_momentum(
            correction.corrected_speed_m_s, correction.corrected_elevation_rad, radius
        )
    )
    for _ in range(_FIXED_POINT_ITERATIONS):
        top = _top_angle(solution, 0.0, float(solution.apogee_angle), rising=True)
        theta = _ascent_grid(top)
        rate, cross_rate = air.rates(
            theta, solution.u(theta), solution.du_dtheta(theta), solution.angular_momentum(theta)
        )
        if not np.any(rate):  # no air: beta = 0 and the MKS is the conic, whatever tau
            break
        loss, new_tau = _loss_and_rate(rate, theta)
        cross_impulse = float(np.trapezoid(cross_rate, theta))
        correction = _with_tangent(correction, cross_impulse, air.latitude_rad)
        air.plane = _plane(solution, correction, air.latitude_rad)  # V_tangent may tilt it
        h0 = float(correction.initial_angular_momentum_m2_s)
        new_beta = loss + math.log(h0 / h_gun)
        converged = (
            abs(new_beta - beta) <= _FIXED_POINT_TOLERANCE * abs(beta)
            and abs(new_tau - tau) <= _FIXED_POINT_TOLERANCE * tau
        )
        beta, tau = new_beta, new_tau
        # mks takes beta >= 0; a gain (beta < 0) is its size with both scales -1
        sign = 1.0 if beta >= 0 else -1.0
        solution = mks.ModifiedKeplerSolution(
            float(correction.speed_m_s),
            float(correction.elevation_rad),
            abs(beta),
            tau,
            n_terms=n_terms,
            radius_m=radius,
            drive_scale=sign,
            decay_scale=sign,
            warn=False,
        )
        if converged:
            break
    return correction, solution


def _reentry_decay(ascent: mks.ModifiedKeplerSolution, air: _Air) -> tuple[float, float]:
    """(beta_re, tau_re): the loss along ``ascent``'s descent from the top of the atmosphere to
    its impact, integrated forward with the speed it loses, and 1 / its mean distance before
    the impact (rad)."""
    impact, apogee = float(ascent.impact_angle), float(ascent.apogee_angle)
    top = _top_angle(ascent, apogee, impact, rising=False)
    before = np.geomspace(impact - top, (impact - top) * 1e-7, _QUADRATURE_POINTS)
    theta = np.concatenate([impact - before, [impact]])
    h_inf = float(ascent.h_inf[0, 0])

    def rate(angle, loss):  # dL/dtheta with the speed lost so far, h = h_inf e^-L
        point = np.atleast_1d(angle)
        return air.rates(point, ascent.u(point), ascent.du_dtheta(point), h_inf * np.exp(-loss))[0]

    # 1e-8 moves the impact point by 0.1 mm against 1e-10, in two thirds of the time
    marched = solve_ivp(
        rate, (theta[0], theta[-1]), [0.0], method="DOP853", t_eval=theta, rtol=1e-8, atol=1e-11
    )
    loss = marched.y[0] if marched.success else np.full_like(theta, np.nan)
    if not np.all(np.isfinite(loss)):
        raise ValueError(
            "the improved MKS's re-entry decay has no finite solution for this launch: near a "
            "vertical in the inertial frame the air's angular momentum omega n_z r^2 rivals h"
        )
    total = float(loss[-1])
    if total == 0.0:
        return 0.0, math.inf
    slope = air.rates(theta, ascent.u(theta), ascent.du_dtheta(theta), h_inf * np.exp(-loss))[0]
    return total, _loss_and_rate(slope, impact - theta)[1]


def _cumulative_time(theta, integrand_of):
    """t(theta) on the sorted grid ``theta`` (starting at 0): 3-point Gauss-Legendre of
    ``integrand_of`` (vectorised) on every interval, summed."""
    nodes, weights = np.polynomial.legendre.leggauss(3)
    low, high = theta[:-1], theta[1:]
    half = 0.5 * (high - low)
    points = half[:, None] * (nodes + 1) + low[:, None]
    pieces = half * (integrand_of(points.ravel()).reshape(points.shape) @ weights)
    return np.concatenate([[0.0], np.cumsum(pieces)])


class ImprovedSolution:
    """An MKS of one launch: the closed-form ascent (a :class:`mks.ModifiedKeplerSolution`)
    with, for the improved variant, the re-entry branch (module docstring). Angles in rad,
    SI otherwise; positions are inertial (x toward longitude 0 at t = 0, z north) as the 3DOF's
    table has them, Earth-fixed ones where said."""

    def __init__(
        self,
        launch: Launch,
        correction,
        ascent: mks.ModifiedKeplerSolution,
        beta_reentry: float = 0.0,
        tau_reentry: float = math.inf,
        variant: str = "improved",
    ):
        self.launch, self.correction, self.ascent, self.variant = (
            launch,
            correction,
            ascent,
            variant,
        )
        self.beta_reentry, self.tau_reentry = float(beta_reentry), float(tau_reentry)
        self.radius_m = float(ascent.radius_m[0, 0])
        self.plane = _plane(ascent, correction, launch.latitude_rad)
        rates = np.arange(1, ascent.n_terms) * self.tau_reentry
        powers = (2 * self.beta_reentry) ** np.arange(1, ascent.n_terms)
        factorials = np.cumprod(np.arange(1, ascent.n_terms, dtype=float))
        self._rates = rates if self.beta_reentry != 0 else np.zeros(0)
        self._amplitudes = (
            float(ascent.c3[0, 0]) * powers / (factorials * (1 + rates**2))
            if self.beta_reentry != 0
            else np.zeros(0)
        )
        self.impact_angle = self._impact_angle()

    # --- the re-entry terms and the solution ---------------------------------------------------
    def _reentry_terms(self, theta, impact):
        """u_re, du_re/dtheta, d2u_re/dtheta2 of the re-entry terms plus the conic that keeps
        u(0) and u'(0) the launch's, for an impact at ``impact``."""
        theta = np.asarray(theta, dtype=float)
        value = slope = curvature = np.zeros_like(theta)
        at_launch = self._amplitudes * np.exp(-self._rates * impact)
        cos_shift, sin_shift = -at_launch.sum(), -(self._rates * at_launch).sum()
        for rate, amplitude in zip(self._rates, self._amplitudes):
            term = amplitude * np.exp(rate * (theta - impact))
            value, slope, curvature = value + term, slope + rate * term, curvature + rate**2 * term
        sin, cos = np.sin(theta), np.cos(theta)
        return (
            value + sin_shift * sin + cos_shift * cos,
            slope + sin_shift * cos - cos_shift * sin,
            curvature - sin_shift * sin - cos_shift * cos,
        )

    def _impact_angle(self) -> float:
        """Where u returns to 1/r0 descending; the re-entry terms equal sum B_n there, so
        u_ascent(theta) + sum B_n (+ the conic shift) = 1/r0 is one equation in theta."""
        low, high = float(self.ascent.apogee_angle), float(self.ascent.impact_angle)
        if self._amplitudes.size == 0:
            return high
        high += 0.05 * (high - low)  # a re-entry gain (beta_re < 0) lands a little further

        def excess(theta):
            return (
                _scalar(self.ascent.u(theta) + self._reentry_terms(theta, theta)[0])
                - 1 / self.radius_m
            )

        return float(brentq(excess, low, high, xtol=1e-15, rtol=4 * np.finfo(float).eps))

    # Functions of the angular range return the shape of ``theta_rad``.
    def u(self, theta_rad):
        """u = 1/r (1/m) at ``theta_rad``."""
        theta = np.asarray(theta_rad, dtype=float)
        ascent = np.reshape(self.ascent.u(theta), theta.shape)
        return ascent + self._reentry_terms(theta, self.impact_angle)[0]

    def du_dtheta(self, theta_rad):
        theta = np.asarray(theta_rad, dtype=float)
        ascent = np.reshape(self.ascent.du_dtheta(theta), theta.shape)
        return ascent + self._reentry_terms(theta, self.impact_angle)[1]

    def radius(self, theta_rad):
        return 1 / self.u(theta_rad)

    def altitude(self, theta_rad):
        return self.radius(theta_rad) - self.radius_m

    def angular_momentum(self, theta_rad):
        """h(theta) (m^2/s): the ascent's decay times the re-entry's."""
        theta = np.asarray(theta_rad, dtype=float)
        reentry = np.exp(
            -self.beta_reentry * np.exp(-self.tau_reentry * (self.impact_angle - theta))
        )
        ascent = np.reshape(self.ascent.angular_momentum(theta), theta.shape)
        return ascent * (reentry if self.beta_reentry != 0 else 1.0)

    def speed(self, theta_rad):
        """Inertial speed (m/s), V = h sqrt(u^2 + u'^2)."""
        return self.angular_momentum(theta_rad) * np.hypot(
            self.u(theta_rad), self.du_dtheta(theta_rad)
        )

    # --- apogee, impact, time ------------------------------------------------------------------
    @cached_property
    def apogee_angle(self) -> float:
        """The zero of du/dtheta: Newton's iteration from the ascent's own apogee."""
        theta = float(self.ascent.apogee_angle)
        for _ in range(5):
            extra = self._reentry_terms(theta, self.impact_angle)
            slope = _scalar(self.ascent.du_dtheta(theta) + extra[1])
            curvature = _scalar(self.ascent.d2u_dtheta2(theta) + extra[2])
            theta -= slope / curvature
        return theta

    @property
    def apogee_altitude_m(self) -> float:
        return float(self.altitude(self.apogee_angle))

    @cached_property
    def _time_grid(self):
        theta = np.union1d(np.linspace(0.0, self.impact_angle, _TIME_POINTS), [self.apogee_angle])
        times = _cumulative_time(theta, lambda x: 1 / (self.u(x) ** 2 * self.angular_momentum(x)))
        return theta, times

    def time(self, theta_rad):
        """Time of flight (s) to ``theta_rad`` (within the flight), t = int dtheta / (h u^2)."""
        theta, times = self._time_grid
        return np.interp(theta_rad, theta, times)

    @property
    def apogee_time_s(self) -> float:
        return float(self.time(self.apogee_angle))

    @property
    def impact_time_s(self) -> float:
        return float(self._time_grid[1][-1])

    @property
    def impact_flight_path_angle_rad(self) -> float:
        """The angle of the velocity below the horizontal at impact (positive)."""
        return float(np.arctan2(self.du_dtheta(self.impact_angle), self.u(self.impact_angle)))

    def angle_at(self, time_s):
        """Angular range (rad) at ``time_s`` (clipped to the flight)."""
        theta, times = self._time_grid
        return np.interp(time_s, times, theta)

    # --- positions -----------------------------------------------------------------------------
    def positions(self, time_s) -> np.ndarray:
        """Inertial positions (n, 3) at ``time_s`` (n,), in the 3DOF's frame (longitude of the
        launch included); after the impact, the impact point."""
        time = finite_array(time_s, "time_s").reshape(-1)
        theta = self.angle_at(time)
        inertial = self.radius(theta)[:, None] * self.plane.directions(theta)
        return rotate_about_axis(
            inertial.T, np.full(theta.size, math.radians(self.launch.longitude_deg))
        ).T

    @property
    def impact_point_m(self) -> np.ndarray:
        """The impact point (3,) fixed to the Earth (the inertial frame at t = 0)."""
        inertial = self.positions([self.impact_time_s])[0]
        turned = rotate_about_axis(
            inertial[:, None], np.array([-self.launch.rotation_rate_rad_s * self.impact_time_s])
        )
        return turned[:, 0]

    @property
    def impact_range_m(self) -> tuple[float, float]:
        """(ground range, cross range) of the impact point on the turning Earth (m)."""
        launch = self.launch
        up, downrange, _ = launch_frame(
            launch.latitude_rad, math.radians(launch.longitude_deg), launch.bearing_rad
        )
        ground, cross = surface_ranges(self.impact_point_m, np.ravel(up), np.ravel(downrange))
        return float(ground), float(cross)


def _correction(launch: Launch):
    if not isinstance(launch, Launch):
        raise TypeError(f"launch must be a Launch; got {type(launch).__name__}")
    if launch.elevation_deg >= 90.0:
        raise ValueError(
            f"the MKS cannot fly launch.elevation_deg = {launch.elevation_deg:g}: a vertical "
            "shot has no angular momentum"
        )
    return eci.correction_for_launch(launch)


def dissertation(launch: Launch, *, n_terms: int = 3) -> ImprovedSolution:
    """The dissertation's MKS of ``launch`` (Chapter 5's ECI MKS, :func:`eci.solution_for_launch`
    with the consistent decay; on a non-rotating Earth it is :func:`mks.for_launch`) behind the
    same interface, with no re-entry decay."""
    correction = _correction(launch)
    ascent = eci.solution_for(correction, n_terms=n_terms, warn=False)
    return ImprovedSolution(launch, correction, ascent, variant="dissertation")


def air_momentum_share(launch: Launch) -> float:
    """omega n_z r0^2 / h0: the angular momentum the turning air has about the Earth's centre in
    the flight plane over the launch's (gun velocity Vrel + omega x r0). It sets the in-plane
    loss factor 1 - omega n_z r^2/h; outside :data:`AIR_MOMENTUM_SHARE_RANGE` the air adds
    or takes a large share of h and the improved MKS is worse than the text's."""
    correction = _correction(launch)
    velocity = np.ravel(correction.relative_m_s + correction.surface_m_s)
    up = np.ravel(launch_frame(launch.latitude_rad, 0.0, 0.0)[0]) * earth.RADIUS_M
    momentum = np.cross(up, velocity)
    return float(
        launch.rotation_rate_rad_s * momentum[2] * earth.RADIUS_M**2 / (momentum @ momentum)
    )


def solve(
    launch: Launch, calibration: Calibration = UNCALIBRATED, *, n_terms: int = 3
) -> ImprovedSolution:
    """The improved MKS of ``launch``: the self-consistent ascent decay and the re-entry decay
    (module docstring), beta_re scaled by ``calibration``."""
    if not isinstance(calibration, Calibration):
        raise TypeError(f"calibration must be a Calibration; got {type(calibration).__name__}")
    correction = _correction(launch)
    first = eci.solution_for(correction, n_terms=n_terms, warn=False)
    air = _Air(launch, _plane(first, correction, launch.latitude_rad))
    share = air_momentum_share(launch)
    low, high = AIR_MOMENTUM_SHARE_RANGE
    if not low < share <= high:
        warnings.warn(
            f"the air carries {share:.2f} of the launch's angular momentum (omega n_z r0^2 / "
            f"h0, outside ({low:g}, {high:g}]): a near-vertical shot in the inertial frame, "
            "where the improved MKS's exponential decay does not hold (mks_improvement's maps)",
            ModelValidityWarning,
            stacklevel=2,
        )
    correction, ascent = _ascent_decay(correction, air, n_terms)
    beta_re, tau_re = _reentry_decay(ascent, air)
    return ImprovedSolution(launch, correction, ascent, calibration.reentry_scale * beta_re, tau_re)


def flight(
    launch: Launch, variant: str = "improved", calibration: Calibration = UNCALIBRATED
) -> ImprovedSolution:
    """The ``variant`` (one of :data:`VARIANTS`) MKS of ``launch``."""
    if variant == "dissertation":
        return dissertation(launch)
    if variant == "improved":
        return solve(launch, calibration)
    raise ValueError(
        f"unknown variant {variant!r}; expected one of {', '.join(map(repr, VARIANTS))}"
    )
