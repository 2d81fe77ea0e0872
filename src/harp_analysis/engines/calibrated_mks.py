"""The calibrated MKS: the ECI MKS corrected by a table learned from 3DOF flights of the same
gun, Chapter 7 C's remedy built ("A set of empirical correction factors may be developed ... or
a look-up table approach may be used to correct for this mismatch").

The MKS (eqs 3.30, 6.6-6.15) gives a launch's whole flight in closed form, the position r(theta)
in its plane and the time t(theta) (eq 3.32), but it misses by kilometres: its angular momentum
is eq 3.22's straight-line guess through eq 3.11's air at the launch Cd0, nothing decays on
re-entry, and on the turning Earth the drag's push across the flight is a guess at launch
(eq 5.8). What it misses varies smoothly with the launch, and a gun's 3DOF flights measure it.
So the calibrated MKS keeps the MKS's flight and adds to it what the 3DOF shows it misses:

- the time, as a factor on the MKS's time of flight, kappa = T_3DOF / T_MKS: the flight at the
  fraction s of its time is the MKS's at s of its own;
- the apogee, as what the 3DOF's altitude and fraction of the flight differ from the MKS's;
- the position, as the 3DOF's displacement from the MKS at each fraction s of the flight, along
  the gun's up, downrange and right at launch (axes that turn smoothly with the launch: the
  MKS's own plane swings fast where the Earth's turn leaves the inertial launch velocity nearly
  vertical, a westward shot at 75 deg), at :data:`.flight_grid.TIME_NODES` and linear between
  them.

Both are learned from the 3DOF flights of a grid of launches of one gun (:func:`calibrate`,
:mod:`.flight_grid`: elevations 15-88 deg, muzzle speeds 0.8-1.15 of the projectile's, every
bearing, the day's density within +-10 %) and interpolated between them (local cubic in each
axis, periodic in bearing). The MKS underneath is the text's ECI MKS (the one door,
:func:`.eci.correction_for_launch`, three terms) with one change: its drag area is the gun's,
at the projectile's own muzzle speed, for every launch of the band. The launch's own Cd0 at its
launch Mach (eqs 3.22, 5.8) follows the drag table's breakpoints, and the MKS with it, so that
what it misses jumps in slope where a launch Mach crosses one (HP's table at Mach 4.9): a
correction learned across such a kink interpolates poorly, one learned on a smooth base does not.
The 3DOF's flights fly the drag table as it is; the table learns the rest.

A launch outside the band, or of another gun, is refused by name (:meth:`.flight_grid.Band.
check`): a table is never extrapolated. A calibration is computed once per gun and version of
the physics, kept in memory and on disk (:mod:`harp_analysis.foundation.stored`), read-only
(:func:`calibration_for`); its cost is reported (:attr:`Calibration.seconds`).

SI inside; degrees only in the names that say so.
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np
import pandas as pd

from ..foundation import earth
from ..foundation.stored import stored_arrays
from ..foundation.validation import ModelValidityWarning, finite_array, whole_number
from ..models.launch import Launch, Launches
from ..models.trajectory import MAX_ROWS, describe, launch_frame, rotate_about_axis, surface_ranges
from . import eci, mks
from .flight_grid import DEFAULT_GRID, TIME_NODES, Band, Grid, Gun, fly_grid, interpolate

__all__ = [
    "Calibration",
    "CalibratedSolution",
    "BAND",
    "calibrate",
    "calibration_for",
    "solution_for_launch",
    "simulate_calibrated_mks",
    "ENGINE",
]

ENGINE = "calibrated MKS"
#: The launches a calibration covers (:class:`.flight_grid.Band`).
BAND = Band()
#: Terms of the MKS underneath: the text's three.
N_TERMS = 3
#: Equal steps of angular range on which the MKS's t(theta) is inverted for a fraction of its
#: flight, by cubic Hermite polynomials through the MKS's own slopes (error as a step's fourth
#: power); the calibration learns its displacements through the same inversion, so what is
#: left is learned with the rest.
_TIME_GRID = 65
_NODES = TIME_NODES.size


@dataclass(frozen=True)
class Calibration:
    """What the calibrated MKS learned of one gun: at each node of the grid's axes (elevation,
    speed factor, bearing, density change), the time factor kappa, the apogee's difference and
    the displacements (m) of the 3DOF from the MKS at :data:`.flight_grid.TIME_NODES`, along
    the gun's up, downrange and right (read-only arrays), and the drag area of the MKS
    underneath."""

    gun: Gun
    band: Band
    axes: tuple[np.ndarray, ...] = field(repr=False)
    speed_breaks: np.ndarray = field(repr=False)  # no interpolation across one
    time_factor: np.ndarray = field(repr=False)  # (*grid,)
    displacement_m: np.ndarray = field(repr=False)  # (*grid, nodes, 3)
    apogee_m: np.ndarray = field(repr=False)  # (*grid, 2): the 3DOF's apogee altitude less
    # the MKS's (m), and its fraction of the flight less the MKS's
    drag_area_m2: float
    flights: int  # 3DOF flights it was learned from
    rhs_evaluations: int  # their right-hand-side evaluations
    seconds: float  # what learning it took (s), measured; 0 where it was loaded from disk
    loaded: bool = False  # from the disk store, not computed in this process
    learned: np.ndarray = field(init=False, repr=False)  # kappa and the displacements, one row

    def __post_init__(self):
        for array in (
            *self.axes,
            self.speed_breaks,
            self.time_factor,
            self.displacement_m,
            self.apogee_m,
        ):
            array.flags.writeable = False  # shared by every caller of calibration_for
        grid = self.time_factor.shape
        learned = np.concatenate(
            [self.time_factor[..., None], self.apogee_m, self.displacement_m.reshape(*grid, -1)],
            axis=-1,
        )
        learned.flags.writeable = False
        object.__setattr__(self, "learned", learned)


def _base_drag_area(gun: Gun) -> float:
    """Cd0 A (m^2) at the projectile's own muzzle speed, from the gun's site in its air."""
    nominal = gun.launches(1.0, 45.0, 0.0, 0.0)
    return float(nominal.launch_drag_coefficient[0]) * gun.projectile.reference_area_m2


@dataclass(frozen=True)
class _Base:
    """The ECI MKS under the calibration for many launches: the solution, its plane (3, n),
    and t(theta) on equal steps of angular range (n, G)."""

    correction: eci.LaunchCorrection
    solution: mks.ModifiedKeplerSolution
    up: np.ndarray
    along: np.ndarray
    theta: np.ndarray
    times: np.ndarray
    rates: np.ndarray  # dtheta/dt = h u^2 at each step (n, G)
    gun_axes: np.ndarray  # (n, 3, 3): up, downrange and right of each gun at longitude 0

    @property
    def time_of_flight_s(self) -> np.ndarray:
        return self.times[:, -1]

    def apogees(self) -> tuple[np.ndarray, np.ndarray]:
        """The MKS's apogee altitude (m) and its fraction of the flight (n,)."""
        angle = np.reshape(self.solution.apogee_angle, (-1, 1))
        time = _hermite(self.theta, self.times, 1.0 / self.rates, angle)[:, 0]
        altitude = np.reshape(self.solution.apogee_altitude(), (-1,))
        return altitude, time / self.time_of_flight_s

    def positions(self, fraction: np.ndarray) -> np.ndarray:
        """The MKS's inertial positions (n, k, 3) at the fractions (n, k) of its time of
        flight, at longitude 0."""
        theta = _hermite(self.times, self.theta, self.rates, fraction * self.times[:, -1:])
        radius = np.reshape(self.solution.radius(theta), theta.shape)
        up, along = self.up.T[:, None, :], self.along.T[:, None, :]
        return radius[..., None] * (
            np.cos(theta)[..., None] * up + np.sin(theta)[..., None] * along
        )


#: Larger than any time or fraction a row holds: rows offset by it search as one sorted array.
_OFFSET = 1e7


def _hermite(t: np.ndarray, theta: np.ndarray, rate: np.ndarray, at: np.ndarray) -> np.ndarray:
    """Row by row, theta at ``at`` (n, k) of the increasing t (n, G), by the cubic Hermite
    polynomial through the steps' values ``theta`` and slopes ``rate`` = dtheta/dt (n, G)
    (clipped to each row's ends): with the MKS's own slopes (dtheta/dt = h u^2, or its inverse
    for t(theta)) good to the fourth power of a step."""
    count, size = t.shape
    shifted = t + np.arange(count)[:, None] * _OFFSET
    index = np.searchsorted(shifted.ravel(), (at + np.arange(count)[:, None] * _OFFSET).ravel())
    index = np.clip(index.reshape(at.shape) - np.arange(count)[:, None] * size, 1, size - 1)
    rows = np.arange(count)[:, None]
    t0, t1 = t[rows, index - 1], t[rows, index]
    step = t1 - t0
    x = np.clip((at - t0) / step, 0.0, 1.0)
    h00, h10, h01, h11 = (2 * x**3 - 3 * x**2 + 1, x**3 - 2 * x**2 + x, -2 * x**3 + 3 * x**2,
                          x**3 - x**2)  # fmt: skip
    return (
        h00 * theta[rows, index - 1]
        + h10 * step * rate[rows, index - 1]
        + h01 * theta[rows, index]
        + h11 * step * rate[rows, index]
    )


def _base(launch: Launch | Launches, drag_area_m2: float) -> _Base:
    correction = eci.correction_for_launch(launch, drag_area_m2=drag_area_m2)
    solution = eci.solution_for(correction, n_terms=N_TERMS, warn=False)
    if np.any(solution.escapes):
        raise ValueError(
            f"the MKS under the {ENGINE} escapes for this launch: no flight to correct"
        )
    impact = np.reshape(solution.impact_angle, (-1, 1))
    theta = impact * np.linspace(0.0, 1.0, _TIME_GRID)
    times = np.reshape(solution.time(theta), theta.shape)
    u = np.reshape(solution.u(theta), theta.shape)
    rates = np.reshape(solution.angular_momentum(theta), theta.shape) * u * u
    up, along = eci.flight_plane(correction, np.ravel(launch.latitude_rad))
    latitude = np.ravel(launch.latitude_rad)
    gun_up, downrange, _ = launch_frame(latitude, 0.0 * latitude, np.ravel(launch.bearing_rad))
    right = np.cross(downrange.T, gun_up.T)
    gun_axes = np.stack([np.broadcast_to(gun_up.T, right.shape), downrange.T, right], axis=1)
    return _Base(correction, solution, up, along, theta, times, rates, gun_axes)


def _displacements(base: _Base, positions_m: np.ndarray) -> np.ndarray:
    """(n, nodes, 3): ``positions_m`` (n, nodes, 3, at longitude 0) minus the MKS's at the same
    fractions of each one's flight, along the gun's up, downrange and right at launch: axes
    that turn smoothly with the launch (the MKS's own plane does not, where the Earth's turn
    leaves the inertial launch velocity nearly vertical)."""
    count = positions_m.shape[0]
    difference = positions_m - base.positions(np.broadcast_to(TIME_NODES, (count, _NODES)))
    return np.einsum("nkj,naj->nka", difference, base.gun_axes)


def calibrate(gun: Gun, grid: Grid = DEFAULT_GRID, band: Band = BAND) -> Calibration:
    """Learn the calibrated MKS of ``gun`` from its 3DOF flights over ``grid``
    (:func:`.flight_grid.fly_grid`): each flight's time of flight over the MKS's and its
    displacement from the MKS at :data:`.flight_grid.TIME_NODES`. No caching (see
    :func:`calibration_for`)."""
    if not grid.covers(band):
        raise ValueError(f"grid: its axes do not span the band {band}")
    if gun.site_altitude_m != 0.0:
        raise ValueError(
            f"the {ENGINE} cannot learn gun.site_altitude_m = {gun.site_altitude_m:g}: the "
            "MKS underneath launches from r0 = R"
        )
    start = time.perf_counter()
    flights = fly_grid(gun, grid)
    shape = flights.time_of_flight_s.shape
    mesh = np.meshgrid(*flights.axes, indexing="ij")
    launches = gun.launches(mesh[1], mesh[0], mesh[2], mesh[3])
    area = _base_drag_area(gun)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelValidityWarning)
        base = _base(launches, area)
    positions = flights.positions_m.reshape(-1, _NODES, 3)
    altitude, fraction = base.apogees()
    apogee = np.stack(
        [
            flights.apogee_altitude_m.ravel() - altitude,
            flights.apogee_time_s.ravel() / flights.time_of_flight_s.ravel() - fraction,
        ],
        axis=-1,
    )
    return Calibration(
        gun,
        band,
        flights.axes,
        grid.speed_breaks(gun),
        (flights.time_of_flight_s.ravel() / base.time_of_flight_s).reshape(shape),
        _displacements(base, positions).reshape(*shape, _NODES, 3),
        apogee.reshape(*shape, 2),
        area,
        flights.flights,
        flights.rhs_evaluations,
        time.perf_counter() - start,
    )


@lru_cache(maxsize=16)
def _calibration(gun: Gun, grid: Grid) -> Calibration:
    def compute() -> dict[str, np.ndarray]:
        calibration = calibrate(gun, grid)
        return {
            "time_factor": calibration.time_factor,
            "displacement_m": calibration.displacement_m,
            "apogee_m": calibration.apogee_m,
            "cost": np.array(
                [
                    calibration.drag_area_m2,
                    calibration.flights,
                    calibration.rhs_evaluations,
                    calibration.seconds,
                ]
            ),  # fmt: skip
        }

    arrays, loaded = stored_arrays(__name__, "calibrations", f"{gun.key} {grid!r}", compute)
    area, flights, evaluations, seconds = arrays["cost"]
    return Calibration(
        gun,
        BAND,
        tuple(np.array(a) for a in grid.axes(gun)),
        grid.speed_breaks(gun),
        arrays["time_factor"],
        arrays["displacement_m"],
        arrays["apogee_m"],
        float(area),
        int(flights),
        int(evaluations),
        0.0 if loaded else float(seconds),
        loaded,
    )


def calibration_for(launch: Launch | Launches, grid: Grid = DEFAULT_GRID) -> Calibration:
    """The calibration of ``launch``'s gun (:meth:`.flight_grid.Gun.of`) over ``grid``: learned
    from its 3DOF flights the first time (a few seconds, :attr:`Calibration.seconds`), then
    kept in memory and on disk for every later call and process (read-only arrays).

    Parameters
    ----------
    launch : Launch or Launches
        A launch of the gun (its projectile, site, air model and Earth rotation).
    grid : Grid
        The training launches (:class:`.flight_grid.Grid`): the table's resolution.

    Returns
    -------
    Calibration
        What the calibrated MKS learned of the gun, and what learning it cost.
    """
    if not isinstance(launch, Launch | Launches):
        raise TypeError(f"launch must be a Launch or Launches; got {type(launch).__name__}")
    if not isinstance(grid, Grid):
        raise TypeError(f"grid must be a flight_grid.Grid; got {type(grid).__name__}")
    return _calibration(Gun.of(launch), grid)


class CalibratedSolution:
    """The calibrated MKS of one launch or many (:class:`~harp_analysis.models.launch.Launches`):
    the ECI MKS underneath with the calibration's time factor and displacements interpolated
    at each launch. Numbers for a single Launch, arrays (n,) for many; positions in the 3DOF's
    frame (inertial, the axes the Earth has at launch, the launch's longitude included)."""

    def __init__(self, launch: Launch | Launches, calibration: Calibration | None = None):
        self.launch = launch
        if calibration is None:  # the band first: a launch outside it learns no table
            BAND.check(launch, Gun.of(launch), ENGINE)
            calibration = calibration_for(launch)
        self.calibration = calibration
        self.single = isinstance(launch, Launch)
        points = self.calibration.band.check(launch, self.calibration.gun, ENGINE)
        self._base = _base(launch, self.calibration.drag_area_m2)
        learned = interpolate(
            self.calibration.axes, self.calibration.learned, points, self.calibration.speed_breaks
        )
        self._time_factor = learned[:, 0]
        self._apogee = learned[:, 1:3]
        self._displacement = learned[:, 3:].reshape(-1, _NODES, 3)
        self._longitude = np.radians(np.ravel(launch.longitude_deg))
        self._rotation = float(self.calibration.gun.rotation_rate_rad_s)

    def _out(self, values: np.ndarray):
        return float(values[0]) if self.single else values

    @property
    def time_of_flight_s(self):
        """Time of flight (s)."""
        return self._out(self._time_factor * self._base.time_of_flight_s)

    def _at_fractions(self, fraction: np.ndarray) -> np.ndarray:
        """Inertial positions (n, k, 3) at fractions (n, k) of each flight, at longitude 0."""
        index = np.clip(np.searchsorted(TIME_NODES, fraction), 1, _NODES - 1)
        share = (fraction - TIME_NODES[index - 1]) / (TIME_NODES[index] - TIME_NODES[index - 1])
        rows = np.arange(fraction.shape[0])[:, None]
        parts = (1 - share)[..., None] * self._displacement[rows, index - 1] + share[
            ..., None
        ] * self._displacement[rows, index]
        return self._base.positions(fraction) + np.einsum(
            "nka,naj->nkj", parts, self._base.gun_axes
        )

    def _state(self, fraction: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Inertial positions and velocities (n, k, 3) at fractions (n, k) of each flight, at
        longitude 0: the MKS's (V = h (u onward - u' outward), eq 4.2's speed) on its time
        stretched by kappa, plus the displacements and their rate between nodes."""
        base = self._base
        theta = _hermite(base.times, base.theta, base.rates, fraction * base.times[:, -1:])
        u = np.reshape(base.solution.u(theta), theta.shape)
        slope = np.reshape(base.solution.du_dtheta(theta), theta.shape)
        h = np.reshape(base.solution.angular_momentum(theta), theta.shape)
        up, along = base.up.T[:, None, :], base.along.T[:, None, :]
        outward = np.cos(theta)[..., None] * up + np.sin(theta)[..., None] * along
        onward = -np.sin(theta)[..., None] * up + np.cos(theta)[..., None] * along
        index = np.clip(np.searchsorted(TIME_NODES, fraction), 1, _NODES - 1)
        rows = np.arange(fraction.shape[0])[:, None]
        before, after = self._displacement[rows, index - 1], self._displacement[rows, index]
        width = (TIME_NODES[index] - TIME_NODES[index - 1])[..., None]
        share = (fraction[..., None] - TIME_NODES[index - 1][..., None]) / width
        tof = (self._time_factor * base.time_of_flight_s)[:, None, None]
        displacement = before + share * (after - before)
        rate = (after - before) / width / tof
        position = outward / u[..., None] + np.einsum("nka,naj->nkj", displacement, base.gun_axes)
        mks = (h * u)[..., None] * onward - (h * slope)[..., None] * outward
        velocity = mks / self._time_factor[:, None, None] + np.einsum(
            "nka,naj->nkj", rate, base.gun_axes
        )
        return position, velocity

    def _turned(self, inertial: np.ndarray, times: np.ndarray) -> np.ndarray:
        """Positions (n, k, 3) at longitude 0 turned to the launch's longitude, less the Earth's
        turn by ``times`` (n, k) where ``times`` is given (Earth-fixed), in the Earth's axes at
        launch."""
        angle = self._longitude[:, None] - self._rotation * times
        flat = rotate_about_axis(inertial.reshape(-1, 3).T, angle.ravel())
        return flat.T.reshape(inertial.shape)

    @property
    def impact_point_m(self) -> np.ndarray:
        """The impact point fixed to the Earth (3,) or (n, 3), in the Earth's axes at launch."""
        ends = self._at_fractions(np.ones((self._displacement.shape[0], 1)))
        tof = self._time_factor * self._base.time_of_flight_s
        fixed = self._turned(ends, tof[:, None])[:, 0]
        return fixed[0] if self.single else fixed

    @property
    def impact_range_m(self):
        """(ground range, cross range) of the impact on the turning Earth (m)."""
        latitude = np.ravel(self.launch.latitude_rad)
        up, downrange, _ = launch_frame(
            latitude, self._longitude, np.ravel(self.launch.bearing_rad)
        )
        points = np.reshape(self.impact_point_m, (-1, 3))
        ground, cross = surface_ranges(points, up.T, downrange.T)
        return (self._out(np.atleast_1d(ground)), self._out(np.atleast_1d(cross)))

    def _apogees(self) -> tuple[np.ndarray, np.ndarray]:
        """Apogee altitude (m) and its fraction of the flight: the MKS's, moved by what the
        3DOF's apogees differ from it by (learned as the rest is)."""
        altitude, fraction = self._base.apogees()
        return altitude + self._apogee[:, 0], fraction + self._apogee[:, 1]

    @property
    def apogee_altitude_m(self):
        """Apogee altitude (m)."""
        return self._out(self._apogees()[0])

    @property
    def apogee_time_s(self):
        """Time of the apogee (s)."""
        return self._out(self._apogees()[1] * self._time_factor * self._base.time_of_flight_s)

    def positions(self, time_s) -> np.ndarray:
        """Inertial positions (k, 3) of a single launch at ``time_s`` (k,) within the flight, in
        the 3DOF's frame (the launch's longitude included)."""
        if not self.single:
            raise TypeError("positions: a single launch's; index the launches for one")
        times = np.atleast_1d(finite_array(time_s, "time_s"))
        tof = float(self.time_of_flight_s)
        if np.any(times < 0) or np.any(times > tof * (1 + 1e-12)):
            raise ValueError(f"time_s must lie within the flight, 0 to {tof:.6g} s")
        inertial = self._at_fractions((times / tof)[None, :])
        return self._turned(inertial, np.zeros((1, times.size)))[0]


def solution_for_launch(
    launch: Launch | Launches, calibration: Calibration | None = None
) -> CalibratedSolution:
    """The calibrated MKS of a launch, or of every launch of a Launches at once.

    Parameters
    ----------
    launch : Launch or Launches
        Launches of one gun (projectile, site, air model and Earth rotation), within the band
        the calibration covers (:data:`BAND`).
    calibration : Calibration, optional
        What to correct the MKS with; by default the gun's (:func:`calibration_for`, learned
        on first use).

    Returns
    -------
    CalibratedSolution
        Time of flight, apogee, impact point and range, and (for one launch) positions.
    """
    return CalibratedSolution(launch, calibration)


def simulate_calibrated_mks(
    launch: Launch,
    *,
    grid: Grid = DEFAULT_GRID,
    calibration: Calibration | None = None,
    n_points: int = 400,
) -> pd.DataFrame:
    """The calibrated MKS of ``launch`` as the engines' trajectory table
    (:mod:`harp_analysis.models.trajectory`), launch to impact at ``n_points`` equal steps of
    time, in the 3DOF's frame on the rotating Earth (as :func:`.eci.simulate_eci_mks`). The
    velocity is the path's derivative, the MKS's own (eq 4.2) with the displacements' rate;
    Mach is the speed relative to the air, which turns with the Earth; the drag coefficient
    the projectile's at that Mach, and drag/gravity in the launch's day air. No right-hand
    side is evaluated.

    Parameters
    ----------
    launch : Launch
        A launch of a gun within the band of :data:`BAND`.
    grid : Grid
        The training launches of the gun's calibration (its resolution: the engine's
        tolerance option), when ``calibration`` is not given.
    calibration : Calibration, optional
        What corrects the MKS; by default the gun's over ``grid`` (:func:`calibration_for`).
    n_points : int
        Rows, at equal steps of time from launch to impact.

    Returns
    -------
    pandas.DataFrame
        The trajectory table, one row per output time in SI units, with the shared metadata in
        ``frame.attrs`` (and ``time_factor``, the calibration's kappa at the launch).
    """
    count = whole_number(n_points, "n_points", low=3, high=MAX_ROWS)
    if not isinstance(launch, Launch):
        raise TypeError(
            f"launch must be a Launch; got {type(launch).__name__} (solution_for_launch solves "
            "Launches together)"
        )
    solution = CalibratedSolution(launch, calibration or calibration_for(launch, grid))
    tof = float(solution.time_of_flight_s)
    times = np.linspace(0.0, tof, count)
    inertial, velocity = (
        state[0] for state in solution._state(np.linspace(0.0, 1.0, count)[None, :])
    )
    turned = solution._turned(inertial[None], np.zeros((1, count)))[0]
    fixed = solution._turned(inertial[None], times[None])[0]
    radius = np.linalg.norm(inertial, axis=1)
    altitude = radius - earth.RADIUS_M
    omega = solution._rotation
    air_velocity = velocity - omega * np.stack(
        [-inertial[:, 1], inertial[:, 0], 0.0 * inertial[:, 2]], axis=1
    )
    air_speed = np.linalg.norm(air_velocity, axis=1)
    speed = np.linalg.norm(velocity, axis=1)
    density, sound = launch.air(np.maximum(altitude, 0.0))
    mach = air_speed / sound
    projectile = launch.projectile
    cd = projectile.drag_law(mach)
    drag = 0.5 * density * cd * projectile.reference_area_m2 * air_speed**2
    up, downrange, _ = launch_frame(
        launch.latitude_rad, math.radians(launch.longitude_deg), launch.bearing_rad
    )
    ground, cross = surface_ranges(fixed, np.ravel(up), np.ravel(downrange))
    momentum = np.linalg.norm(np.cross(inertial, velocity), axis=1)
    frame = pd.DataFrame(
        {
            "time_s": times,
            "x_m": turned[:, 0],
            "y_m": turned[:, 1],
            "z_m": turned[:, 2],
            "altitude_m": altitude,
            "ground_range_m": ground,
            "cross_range_m": cross,
            "speed_m_s": speed,
            "mach": mach,
            "drag_coefficient": cd,
            "drag_to_gravity": drag / (projectile.mass_kg * earth.GM_M3_S2 / radius**2),
            "specific_angular_momentum_m2_s": momentum,
            "flight_path_angle_rad": np.arcsin(
                np.clip(np.sum(velocity * inertial, axis=1) / (speed * radius), -1.0, 1.0)
            ),
        }
    )
    apogee_altitude = float(solution.apogee_altitude_m)
    apogee_time = float(solution.apogee_time_s)
    apogee_ground = float(np.interp(apogee_time, times, ground))
    return describe(
        frame,
        engine=ENGINE,
        launch=launch,
        apogee=(apogee_time, apogee_altitude, apogee_ground),
        impact=True,
        rhs_evaluations=0,
        steps=0,
        max_time_s=math.inf,
        time_factor=float(solution._time_factor[0]),
        calibration_flights=solution.calibration.flights,
    )
