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
The 3DOF's flights fly the drag table as it is; the table learns the rest. And where the Earth's
turn leaves a steep shot against it all but vertical in the inertial frame, the MKS has no
closed form (its angular momentum so small that eq 3.30's constants cancel): it is flown there
at the steepest elevation whose constants hold (``_steepest_elevation()``), a few thousandths
of a degree off, and the table learns that difference too.

A launch outside the band, or of another gun, is refused by name (:meth:`.flight_grid.Band.check`):
a table is never extrapolated. A calibration is computed once per gun and version of
the physics, kept in memory and on disk (:mod:`harp_analysis.foundation.stored`), read-only
(:func:`calibration_for`); its cost is reported (:attr:`Calibration.seconds`).

SI inside; degrees only in the names that say so.
"""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass, replace
from functools import cached_property, lru_cache

import numpy as np
import pandas as pd

from ..foundation import earth
from ..foundation.validation import ModelValidityWarning
from ..models.launch import Launch, Launches
from . import eci, mks
from .flight_grid import DEFAULT_GRID, TIME_NODES, Band, Grid, GridFlights, Gun
from .learned import (
    LearnedSolution,
    LearnedTable,
    gun_axes,
    gun_of,
    joined,
    learned_flights,
    split,
    stored_table,
)

__all__ = [
    "Calibration",
    "CalibratedSolution",
    "BAND",
    "calibrate",
    "calibration_for",
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
#: Numbers a calibration learns per flight before its displacements: kappa and the apogee's two.
_NUMBERS = 3


@dataclass(frozen=True, kw_only=True)
class Calibration(LearnedTable):
    """What the calibrated MKS learned of one gun: at each node of the grid's axes (elevation,
    speed factor, bearing, density change), the time factor kappa, the apogee's difference and
    the displacements (m) of the 3DOF from the MKS at :data:`.flight_grid.TIME_NODES`, along
    the gun's up, downrange and right (``values``, one row per node: kappa, the apogee's
    altitude and fraction of the flight less the MKS's, then the displacements), and the drag
    area of the MKS underneath."""

    drag_area_m2: float

    @property
    def time_factor(self) -> np.ndarray:
        """kappa = T_3DOF / T_MKS at each node, ``(*grid,)``."""
        return split(self.values, _NUMBERS)[0][..., 0]

    @property
    def apogee_m(self) -> np.ndarray:
        """The 3DOF's apogee altitude less the MKS's (m), and its fraction of the flight less
        the MKS's, at each node, ``(*grid, 2)``."""
        return split(self.values, _NUMBERS)[0][..., 1:]

    @property
    def displacement_m(self) -> np.ndarray:
        """The 3DOF's displacement from the MKS at each node, ``(*grid, nodes, 3)``."""
        return split(self.values, _NUMBERS)[1]


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

    def apogees(self) -> np.ndarray:
        """The MKS's apogee altitude (m) and its fraction of the flight (n, 2)."""
        angle = np.reshape(self.solution.apogee_angle, (-1, 1))
        time = _hermite(self.theta, self.times, 1.0 / self.rates, angle)[:, 0]
        altitude = np.reshape(self.solution.apogee_altitude(), (-1,))
        return np.stack([altitude, time / self.time_of_flight_s], axis=-1)

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


#: The largest c3 r0 = G M r0 / h_inf^2 (eq 6.8) the MKS underneath is flown with: its
#: constants cancel to the last of their digits near 1e10 (measured over betas 0.05-1.5 and
#: speeds 1-3.6 km/s), so this keeps a hundredfold margin.
_LARGEST_C3_R0 = 1e8


def _steepest_elevation(correction: eci.LaunchCorrection) -> np.ndarray:
    """Each corrected launch's inertial elevation (rad), but no steeper than the elevation at
    which h_inf = V r0 cos(elevation) exp(-beta x decay scale) (eqs 6.13, 6.14) gives
    c3 r0 = :data:`_LARGEST_C3_R0`. The turning Earth makes a steep shot against its turn all
    but vertical (a westward shot at 75-85 deg, where the Earth's surface speed cancels the
    muzzle velocity's horizontal part)."""
    speed = np.asarray(correction.speed_m_s, dtype=float)
    smallest_cosine = np.sqrt(earth.GM_M3_S2 / (_LARGEST_C3_R0 * earth.RADIUS_M)) / speed
    smallest_cosine = smallest_cosine * np.exp(correction.beta * correction.decay_scale)
    return np.minimum(correction.elevation_rad, np.arccos(np.minimum(smallest_cosine, 1.0)))


def _base(launch: Launch | Launches, drag_area_m2: float) -> _Base:
    correction = eci.correction_for_launch(launch, drag_area_m2=drag_area_m2)
    flown = replace(correction, elevation_rad=_steepest_elevation(correction))
    solution = flown.solution(n_terms=N_TERMS, warn=False)
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
    return _Base(correction, solution, up, along, theta, times, rates, gun_axes(launch))


def _displacements(base: _Base, positions_m: np.ndarray) -> np.ndarray:
    """(n, nodes, 3): ``positions_m`` (n, nodes, 3, at longitude 0) minus the MKS's at the same
    fractions of each one's flight, along the gun's up, downrange and right at launch: axes
    that turn smoothly with the launch (the MKS's own plane does not, where the Earth's turn
    leaves the inertial launch velocity nearly vertical)."""
    count = positions_m.shape[0]
    difference = positions_m - base.positions(np.broadcast_to(TIME_NODES, (count, _NODES)))
    return np.einsum("nkj,naj->nka", difference, base.gun_axes)


def calibrate(
    gun: Gun, grid: Grid = DEFAULT_GRID, band: Band = BAND, flights: GridFlights | None = None
) -> Calibration:
    """Learn the calibrated MKS of ``gun`` from its 3DOF flights over ``grid``
    (:func:`.flight_grid.fly_grid`, or ``flights`` where they were flown already): each
    flight's time of flight over the MKS's, its apogee's difference from the MKS's and its
    displacement from the MKS at :data:`.flight_grid.TIME_NODES`. Its ``seconds``: the
    flights' and its own. No caching (see :func:`calibration_for`)."""
    if gun.site_altitude_m != 0.0:
        raise ValueError(
            f"the {ENGINE} cannot learn gun.site_altitude_m = {gun.site_altitude_m:g}: the "
            "MKS underneath launches from r0 = R"
        )
    flights = learned_flights(gun, grid, band, flights)
    start = time.perf_counter()
    shape = flights.time_of_flight_s.shape
    launches = gun.at_nodes(flights.axes)
    area = _base_drag_area(gun)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelValidityWarning)
        base = _base(launches, area)
    positions = flights.positions_m.reshape(-1, _NODES, 3)
    time_factor = flights.time_of_flight_s.ravel() / base.time_of_flight_s
    apogee = (
        np.stack(
            [
                flights.apogee_altitude_m.ravel(),
                (flights.apogee_time_s / flights.time_of_flight_s).ravel(),
            ],
            axis=-1,
        )
        - base.apogees()
    )
    displacement = _displacements(base, positions)
    return Calibration(
        gun=gun,
        band=band,
        grid=grid,
        values=joined(np.column_stack([time_factor, apogee]), displacement).reshape(*shape, -1),
        drag_area_m2=area,
        flights=flights.flights,
        rhs_evaluations=flights.rhs_evaluations,
        seconds=flights.seconds + time.perf_counter() - start,
    )


@lru_cache(maxsize=16)
def _calibration(gun: Gun, grid: Grid) -> Calibration:
    return stored_table(Calibration, __name__, gun, grid, BAND, lambda: calibrate(gun, grid))


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
    gun = gun_of(launch, grid)
    BAND.check(launch, gun, ENGINE)  # before a table is learned for a launch it cannot serve
    return _calibration(gun, grid)


class CalibratedSolution(LearnedSolution):
    """The calibrated MKS of one launch or many (:class:`~harp_analysis.models.launch.Launches`):
    the ECI MKS underneath with the calibration's time factor and displacements interpolated
    at each launch (:class:`.learned.LearnedSolution`: numbers for a single Launch, arrays (n,)
    for many; positions in the 3DOF's frame).

    Parameters
    ----------
    launch : Launch or Launches
        Launches of one gun (projectile, site, air model and Earth rotation), within the band
        the calibration covers (:data:`BAND`).
    calibration : Calibration, optional
        What to correct the MKS with; by default the gun's (:func:`calibration_for`, learned
        on first use).
    """

    ENGINE = ENGINE

    def __init__(self, launch: Launch | Launches, calibration: Calibration | None = None):
        table = calibration_for(launch) if calibration is None else calibration
        super().__init__(launch, table)
        self._base = _base(launch, table.drag_area_m2)
        numbers, self._displacement = split(self._learned, _NUMBERS)
        self._time_factor, self._apogee = numbers[:, 0], numbers[:, 1:]
        self._time_of_flight = self._time_factor * self._base.time_of_flight_s

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

    def _velocities(self, fraction: np.ndarray) -> np.ndarray:
        """Inertial velocities (n, k, 3) at fractions (n, k) of each flight, at longitude 0: the
        MKS's (V = h (u onward - u' outward), eq 4.2's speed) on its time stretched by kappa,
        plus the displacements' rate between their nodes."""
        base = self._base
        theta = _hermite(base.times, base.theta, base.rates, fraction * base.times[:, -1:])
        h = np.reshape(base.solution.angular_momentum(theta), theta.shape)
        u = np.reshape(base.solution.u(theta), theta.shape)
        slope = np.reshape(base.solution.du_dtheta(theta), theta.shape)
        up, along = base.up.T[:, None, :], base.along.T[:, None, :]
        outward = np.cos(theta)[..., None] * up + np.sin(theta)[..., None] * along
        onward = -np.sin(theta)[..., None] * up + np.cos(theta)[..., None] * along
        mks = (h * u)[..., None] * onward - (h * slope)[..., None] * outward
        index = np.clip(np.searchsorted(TIME_NODES, fraction), 1, _NODES - 1)
        rows = np.arange(fraction.shape[0])[:, None]
        rate = (self._displacement[rows, index] - self._displacement[rows, index - 1]) / (
            TIME_NODES[index] - TIME_NODES[index - 1]
        )[..., None]
        tof = (self._time_factor * base.time_of_flight_s)[:, None, None]
        return mks / self._time_factor[:, None, None] + np.einsum(
            "nka,naj->nkj", rate / tof, base.gun_axes
        )

    @cached_property
    def _apogees(self) -> tuple[np.ndarray, np.ndarray]:
        """Apogee altitude (m) and its fraction of the flight: the MKS's, moved by what the
        3DOF's apogees differ from it by (learned as the rest is)."""
        altitude, fraction = (self._base.apogees() + self._apogee).T
        return altitude, fraction


def simulate_calibrated_mks(
    launch: Launch,
    *,
    grid: Grid = DEFAULT_GRID,
    calibration: Calibration | None = None,
    n_points: int = 400,
) -> pd.DataFrame:
    """The calibrated MKS of ``launch`` as the engines' trajectory table
    (:meth:`.learned.LearnedSolution.trajectory`), launch to impact at ``n_points`` equal
    steps of time, in the 3DOF's frame on the rotating Earth. The velocity is the path's
    derivative, the MKS's own (eq 4.2) with the displacements' rate. No right-hand side is
    evaluated.

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
    solution = CalibratedSolution(launch, calibration or calibration_for(launch, grid))
    return solution.trajectory(
        n_points,
        time_factor=float(solution._time_factor[0]),
        calibration_flights=solution.table.flights,
    )
