"""Intercepts of ballistic targets and raids (Chapter 7 A): the firing solutions of
:mod:`.firing` whose MKS projectile meets a target flying its drag-free Kepler conic at a
given time, over its flight
(:func:`~harp_analysis.analyses.fire_control.intercepts.intercept_window`) and for every target of a
raid at once (:func:`~harp_analysis.analyses.fire_control.intercepts.raid_windows`, one call of the
compiled solver); :func:`~harp_analysis.analyses.fire_control.intercepts.raid` is Chapter 7's
count's raid.

SI inside (m, s, rad); degrees only in the arguments and fields named ``_deg``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import partial

import numpy as np

from ...foundation import earth
from ...foundation.sweeps import client_shares, sweep
from ...foundation.validation import Bounds, check_choice, finite_array, finite_scalar
from ...models.launch import Launch
from ...models.trajectory import launch_frame, rotate_about_axis
from .firing import (
    BARBADOS_HP,
    BRANCHES,
    MODELS,
    FiringSolution,
    TargetPoint,
    check_bearing_limits,
    check_gun,
    firing_solutions,
)

__all__ = [
    "KeplerTarget",
    "Intercept",
    "InterceptWindow",
    "intercept",
    "intercept_window",
    "raid_windows",
    "raid_roots",
    "raid",
]

_KEPLER_ITERATIONS = 60
_KEPLER_TOLERANCE_RAD = 1e-14  # 64 nm along a 6,400 km orbit: past it, rounding oscillates


@dataclass(frozen=True, eq=False)
class KeplerTarget:
    """A ballistic target after burnout: its position (m) and velocity (m/s) at ``epoch_s`` in
    the inertial frame of the gun at t = 0 (x toward the gun's longitude on the equator, z
    north), flying the drag-free Kepler conic (an ellipse: a ballistic target does not escape)."""

    position_m: np.ndarray
    velocity_m_s: np.ndarray
    epoch_s: float = 0.0

    def __post_init__(self):
        for name in ("position_m", "velocity_m_s"):
            vector = finite_array(getattr(self, name), name).astype(float)
            if vector.shape != (3,):
                raise ValueError(f"{name} must be a vector (3,); got shape {vector.shape}")
            vector.flags.writeable = False
            object.__setattr__(self, name, vector)
        object.__setattr__(self, "epoch_s", finite_scalar(self.epoch_s, "epoch_s"))
        radius = float(np.linalg.norm(self.position_m))
        if radius < earth.RADIUS_M:
            raise ValueError(
                f"position_m lies {(earth.RADIUS_M - radius) / 1e3:.3f} km below the ground"
            )
        energy = 0.5 * float(self.velocity_m_s @ self.velocity_m_s) - earth.GM_M3_S2 / radius
        if energy >= 0:
            raise ValueError(
                "velocity_m_s reaches escape speed: a ballistic target flies an ellipse"
            )

    @property
    def semi_major_axis_m(self) -> float:
        radius = float(np.linalg.norm(self.position_m))
        speed2 = float(self.velocity_m_s @ self.velocity_m_s)
        return 1.0 / (2.0 / radius - speed2 / earth.GM_M3_S2)

    def _constants(self):
        """a, sqrt(a), r0, sigma0 / sqrt(a), 1 - r0 / a and the mean motion of the Kepler
        equation in the difference of eccentric anomaly from the epoch."""
        a = self.semi_major_axis_m
        r0 = float(np.linalg.norm(self.position_m))
        sigma0 = float(self.position_m @ self.velocity_m_s) / math.sqrt(earth.GM_M3_S2)
        return a, r0, sigma0 / math.sqrt(a), 1.0 - r0 / a, math.sqrt(earth.GM_M3_S2 / a**3)

    def _anomaly(self, mean_rad: np.ndarray) -> np.ndarray:
        """The change of eccentric anomaly dE solving n dt = dE + s (1 - cos dE) - c sin dE:
        monotonic in dE (its slope is r/a > 0) and within 2 of n dt, so Newton's iteration
        kept inside that bracket by bisection converges."""
        _, _, s, c, _ = self._constants()
        low, high = mean_rad - 2.0, mean_rad + 2.0
        x = mean_rad.copy()
        for _ in range(_KEPLER_ITERATIONS):
            excess = x + s * (1 - np.cos(x)) - c * np.sin(x) - mean_rad
            slope = 1 + s * np.sin(x) - c * np.cos(x)
            high = np.where(excess > 0, x, high)
            low = np.where(excess > 0, low, x)
            step = x - excess / slope
            new = np.where((step >= low) & (step <= high), step, 0.5 * (low + high))
            done = np.max(np.abs(new - x), initial=0.0) <= _KEPLER_TOLERANCE_RAD * max(
                1.0, float(np.max(np.abs(x), initial=0.0))
            )
            x = new
            if done:
                break
        return x

    def position_at(self, time_s) -> np.ndarray:
        """Inertial position (m) at ``time_s`` (s, the gun's clock): (3,) for one time, (3, n)
        for n; by Kepler's equation and the f and g functions."""
        time = finite_array(time_s, "time_s")
        dt = np.atleast_1d(time - self.epoch_s).astype(float)
        a, r0, _, _, mean_motion = self._constants()
        de = self._anomaly(mean_motion * dt)
        f = 1 - a / r0 * (1 - np.cos(de))
        g = dt - (de - np.sin(de)) / mean_motion
        position = f * self.position_m[:, None] + g * self.velocity_m_s[:, None]
        return position[:, 0] if time.ndim == 0 else position

    @property
    def ground_time_s(self) -> float:
        """When (s, the gun's clock) it falls back to the ground (radius R) after the epoch;
        inf if its perigee is above the ground. r(dE) = a + (r0 - a) cos dE + sigma0 sqrt(a)
        sin dE falls through R where dE - psi = arccos((R - a) / (a e))."""
        a, r0, s, _, mean_motion = self._constants()
        amplitude = math.hypot(r0 - a, s * a)  # a e
        if amplitude == 0 or (earth.RADIUS_M - a) / amplitude < -1:
            return math.inf
        psi = math.atan2(s * a, r0 - a)
        de = (psi + math.acos(min((earth.RADIUS_M - a) / amplitude, 1.0))) % (2 * math.pi)
        c = 1 - r0 / a
        return self.epoch_s + (de + s * (1 - math.cos(de)) - c * math.sin(de)) / mean_motion


@dataclass(frozen=True)
class Intercept:
    """The firing solutions that meet a Kepler target at ``intercept_time_s``: ``aim`` is its
    point then, fixed to the Earth, with that arrival time (None if it has already landed)."""

    intercept_time_s: float
    aim: TargetPoint | None
    low: FiringSolution | None
    high: FiringSolution | None
    reason: str | None
    mks_solves: int

    @property
    def roots(self) -> list[FiringSolution]:
        return [root for root in (self.low, self.high) if root is not None]


def _check_kepler_target(target) -> KeplerTarget:
    if not isinstance(target, KeplerTarget):
        raise TypeError(f"target must be a KeplerTarget; got {type(target).__name__}")
    return target


def _check_kepler_targets(targets) -> list[KeplerTarget]:
    """A raid's ``targets`` as a list, checked to be a sequence of KeplerTarget."""
    if isinstance(targets, KeplerTarget | str | bytes) or not isinstance(targets, Sequence):
        raise TypeError(f"targets must be a sequence of KeplerTarget; got {type(targets).__name__}")
    for index, target in enumerate(targets):
        if not isinstance(target, KeplerTarget):
            raise TypeError(f"targets[{index}] must be a KeplerTarget; got {type(target).__name__}")
    return list(targets)


def _aims(gun: Launch, target: KeplerTarget, times_s: np.ndarray) -> list[TargetPoint | None]:
    """The target's points at ``times_s`` (n,) fixed to the Earth (None below the ground), each
    with its time as the arrival time: a gun fired at t_f launches from the frame at t = 0
    turned by omega t_f, so meeting the inertial point P at T is reaching the Earth-fixed point
    P turned back by omega T, at T."""
    fixed = rotate_about_axis(
        target.position_at(times_s).reshape(3, -1), -gun.rotation_rate_rad_s * times_s
    )
    return TargetPoint.from_earth_fixed(fixed, times_s, gun.longitude_deg)


def _check_intercept_times(times_s, target: KeplerTarget) -> np.ndarray:
    times = np.atleast_1d(finite_array(times_s, "intercept_time_s")).astype(float)
    if times.ndim != 1:
        raise ValueError(f"intercept times must be a sequence (n,); got shape {times.shape}")
    passed = times[times < 0.0]
    if passed.size:
        raise ValueError(
            f"intercept_time_s = {passed[0]:g} s has already passed: it must be >= 0 "
            "(seconds after t = 0, now)"
        )
    early = times[times < target.epoch_s]
    if early.size:
        raise ValueError(
            f"intercept_time_s = {early[0]:g} s is before the target's epoch_s "
            f"{target.epoch_s:g} s (burnout): its conic starts there"
        )
    return times


def _intercepts(gun, targets, times, branch, limits, model) -> list[list[Intercept]]:
    """The intercepts of every target at its times (a list of (n_i,) arrays), all solved in
    one call of the compiled solver (and, for the calibrated ``model``, moved onto its roots
    at once)."""
    aims = [_aims(gun, target, own) for target, own in zip(targets, times, strict=True)]
    reachable = [aim for row in aims for aim in row if aim is not None]
    solved = iter(
        firing_solutions(gun, reachable, bearing_limits_deg=limits, branch=branch, model=model)
        if reachable
        else []
    )
    result = []
    for target, own, row in zip(targets, times, aims, strict=True):
        items = []
        for when, aim in zip(own, row, strict=True):
            if aim is None:
                reason = f"the target has hit the ground at {target.ground_time_s:.1f} s"
                items.append(Intercept(float(when), None, None, None, reason, 0))
                continue
            found = next(solved)
            items.append(
                Intercept(float(when), aim, found.low, found.high, found.reason, found.mks_solves)
            )
        result.append(items)
    return result


def intercept(
    gun: Launch,
    target: KeplerTarget,
    intercept_time_s: float,
    *,
    branch: str = "ascending",
    bearing_limits_deg: tuple[float, float] | None = None,
    model: str = "eci",
) -> Intercept:
    """The firing solutions (fire time, elevation, bearing, time of flight by eq 3.32) whose
    MKS projectile meets ``target`` at ``intercept_time_s`` on the trajectory's ``branch``:
    :func:`.firing.firing_solutions` to the target's point then, turned back to the Earth-fixed
    frame, with that time as the arrival time, by ``model`` (:data:`.firing.MODELS`). A
    solution that would have to be fired before t = 0, or a target already landed, is no
    solution, with the reason."""
    gun = check_gun(gun)
    target = _check_kepler_target(target)
    branch = check_choice(branch, "branch", BRANCHES)
    limits = check_bearing_limits(bearing_limits_deg)
    model = check_choice(model, "model", MODELS)
    time = _check_intercept_times(intercept_time_s, target)
    if np.ndim(intercept_time_s) != 0:
        raise TypeError("intercept_time_s must be one time (s); intercept_window takes many")
    return _intercepts(gun, [target], [time], branch, limits, model)[0][0]


@dataclass(frozen=True)
class InterceptWindow:
    """The feasible intercepts over a target's flight: every intercept time's result, the
    earliest and latest feasible intercept and the span of feasible fire times (s; NaN if no
    intercept is feasible, then ``reason`` says why not at the first time)."""

    intercepts: tuple[Intercept, ...]
    earliest_intercept_s: float
    latest_intercept_s: float
    first_fire_s: float
    last_fire_s: float
    reason: str | None

    @property
    def intercept_times_s(self) -> np.ndarray:
        return np.array([item.intercept_time_s for item in self.intercepts])

    @property
    def feasible(self) -> np.ndarray:
        return np.array([bool(item.roots) for item in self.intercepts])

    @property
    def time_to_fire_s(self) -> float:
        """The time available to fire: the span of the feasible fire times (s)."""
        return self.last_fire_s - self.first_fire_s

    @property
    def mks_solves(self) -> int:
        return sum(item.mks_solves for item in self.intercepts)


def _window(intercepts: list[Intercept]) -> InterceptWindow:
    feasible = [item for item in intercepts if item.roots]
    fires = [
        root.fire_time_s for item in feasible for root in item.roots if root.fire_time_s is not None
    ]
    if not feasible:
        first = intercepts[0].reason if intercepts else "no intercept times"
        nan = math.nan
        return InterceptWindow(
            tuple(intercepts), nan, nan, nan, nan, f"no feasible intercept: {first}"
        )
    return InterceptWindow(
        tuple(intercepts),
        feasible[0].intercept_time_s,
        feasible[-1].intercept_time_s,
        min(fires),
        max(fires),
        None,
    )


def _window_times(target: KeplerTarget, times_s, count: int) -> np.ndarray:
    if times_s is None:
        end = target.ground_time_s
        if not math.isfinite(end):
            raise ValueError("the target never falls back to the ground: pass times_s")
        times_s = np.linspace(max(target.epoch_s, 0.0), end, count + 2)[1:-1]
    return _check_intercept_times(times_s, target)


def intercept_window(
    gun: Launch,
    target: KeplerTarget,
    *,
    times_s=None,
    count: int = 50,
    branch: str = "ascending",
    bearing_limits_deg: tuple[float, float] | None = None,
    model: str = "eci",
) -> InterceptWindow:
    """:func:`intercept` at every time of ``times_s`` (s), or by default at ``count`` times
    spread over the target's flight from its epoch (or t = 0, if later) until it falls back to
    the ground (ends excluded), solved together by ``model``: which are feasible, the earliest
    and latest feasible intercept and the feasible fire times."""
    return raid_windows(
        gun,
        [target],
        times_s=times_s,
        count=count,
        branch=branch,
        bearing_limits_deg=bearing_limits_deg,
        model=model,
    )[0]


def raid_windows(
    gun: Launch,
    targets: Sequence[KeplerTarget],
    *,
    times_s=None,
    count: int = 50,
    branch: str = "ascending",
    bearing_limits_deg: tuple[float, float] | None = None,
    model: str = "eci",
    client=None,
) -> list[InterceptWindow]:
    """:func:`~harp_analysis.analyses.fire_control.intercepts.intercept_window` of every target of a
    raid, every intercept of every target solved in one call of the compiled solver: at ``times_s``
    (s, the same for every target) or at ``count`` times over each target's flight. Given a Dask
    ``client``, the targets are shared out in chunks among its workers (:func:`.sweeps.sweep`).

    Parameters
    ----------
    gun : Launch
        The gun (its elevation and bearing are what is solved).
    targets : sequence of KeplerTarget
        The raid (:func:`~harp_analysis.analyses.fire_control.intercepts.raid`).
    times_s : array_like, optional
        The intercept times (s), the same for every target; None for ``count`` times over
        each target's flight.
    count : int
        Intercept times per target when ``times_s`` is None.
    branch : str
        ``"ascending"`` or ``"descending"``: where the projectile meets the target.
    bearing_limits_deg : (float, float), optional
        The arc of bearings the gun may take (deg from true north, clockwise from the first to
        the second); None for any.
    model : str
        ``"eci"`` (the text's ECI MKS) or ``"calibrated"`` (the calibrated MKS, from the ECI
        MKS's roots; :func:`.firing.firing_solutions`).
    client : dask.distributed.Client, optional
        Shares the targets out among its workers; None solves them in this process.

    Returns
    -------
    list of InterceptWindow
        One per target, in order: every intercept time's roots (or why none), the earliest
        and latest feasible intercept and the feasible fire times.
    """
    gun = check_gun(gun)
    targets = _check_kepler_targets(targets)
    branch = check_choice(branch, "branch", BRANCHES)
    limits = check_bearing_limits(bearing_limits_deg)
    model = check_choice(model, "model", MODELS)
    if times_s is None:
        count = int(Bounds(low=1).number(count, "count"))
    times = [_window_times(target, times_s, count) for target in targets]
    if client is not None:
        solve = partial(_raid_chunk, gun=gun, branch=branch, limits=limits, model=model)
        chunks = sweep(solve, client_shares(list(zip(targets, times)), client), client=client)
        return [window for chunk in chunks for window in chunk]
    return [_window(items) for items in _intercepts(gun, targets, times, branch, limits, model)]


def _raid_chunk(chunk, gun, branch, limits, model) -> list[InterceptWindow]:
    """The windows of a chunk of (target, times) pairs (a Dask worker's share of a raid)."""
    targets, times = zip(*chunk, strict=True)
    return [_window(items) for items in _intercepts(gun, targets, times, branch, limits, model)]


def raid_roots(windows: Sequence[InterceptWindow]) -> list[tuple[Intercept, FiringSolution]]:
    """Every root of every feasible intercept of ``windows``, with its intercept: what
    :func:`.verification.verify_with_3dof` refines (``[item.aim for item, _ in pairs]``,
    ``[root for _, root in pairs]``).

    Parameters
    ----------
    windows : sequence of InterceptWindow
        The windows of a raid
        (:func:`~harp_analysis.analyses.fire_control.intercepts.raid_windows`).

    Returns
    -------
    list of (Intercept, FiringSolution)
        Each feasible intercept with each of its roots (low and high), in the windows' order.
    """
    return [(item, root) for window in windows for item in window.intercepts for root in item.roots]


def raid(gun: Launch = BARBADOS_HP, count: int = 100) -> list[KeplerTarget]:
    """``count`` re-entering ballistic targets: at t = 0 each is 250 km from the gun at 120 km
    altitude, on bearings spread over 60-160 deg, diving at 3 km/s and 25 deg back toward a
    point up to 30 km beside the gun (deterministic: the Chapter 7 count's raid).

    Parameters
    ----------
    gun : Launch
        The gun the raid comes at (its latitude places the targets).
    count : int
        How many targets.

    Returns
    -------
    list of KeplerTarget
        The targets, by bearing from 60 to 160 deg.
    """
    count = int(Bounds(low=1).number(count, "count"))
    targets = []
    for i in range(count):
        fraction = (i + 0.5) / count
        up, downrange, right = (
            np.ravel(v)
            for v in launch_frame(gun.latitude_rad, 0.0, math.radians(60 + 100 * fraction))
        )
        angle = 250e3 / earth.RADIUS_M
        position = (earth.RADIUS_M + 120e3) * (math.cos(angle) * up + math.sin(angle) * downrange)
        local_up = position / np.linalg.norm(position)
        home = -downrange + 0.12 * math.sin(7.0 * fraction * math.pi) * right  # beside the gun
        inward = home - (home @ local_up) * local_up
        inward /= np.linalg.norm(inward)
        dive = math.radians(-25.0)
        velocity = 3e3 * (math.cos(dive) * inward + math.sin(dive) * local_up)
        targets.append(KeplerTarget(position, velocity, 0.0))
    return targets
