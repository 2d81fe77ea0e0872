"""The compiled ECI MKS firing solver (Chapter 7 A): every root of many targets in one call.

For each target (a point fixed to the Earth, the gun at longitude 0 and t = 0) the solver
looks for the gun elevations and bearings whose ECI Modified Kepler trajectory
(:func:`.eci.corrected_launch`, then :class:`.mks.ModifiedKeplerSolution`'s kernels) crosses
the target's radius, on the chosen branch, at the target. The trajectory's crossing point P
(inertial, at its time of flight t by eq 3.32) is turned back by -omega t into the Earth-fixed
frame: Q, the point of the ground (at the target's altitude) the shot meets. Two residuals:

- the along-track excess, a *signed* angle: the angle of Q along the great circle from the gun
  toward the target (atan2, negative behind the gun) less the target's central angle. A shot
  whose inertial velocity tips past the vertical (westward, where the Earth's turn outruns the
  gun's horizontal speed) lands behind, with a negative angle, so the excess is continuous and
  falls on both sides of the maximum range: its zeros are the low and high roots;
- the east and north miss (m) of Q from the target, which the roots zero.

Per target: a grid of elevations at the great-circle bearing, its best point refined by golden
section to the maximum range (so that two roots closer than the grid are not stepped over),
then each side's sign change refined by Newton's method on (elevation, bearing), its first
Jacobian by forward differences and Broyden's updates after, elevation kept on its side of the
maximum range. The differences are two of the handful of trajectories a root's Newton takes,
and the search most of a solve's (``evaluations`` and the counts :func:`solve` returns), so
analytic derivatives of the closed form would not pay; the Jacobian at the root is returned,
and the 3DOF's refinement
(:func:`~harp_analysis.analyses.fire_control.verification.verify_with_3dof`) starts from it instead
of differencing the 3DOF. Every number is SI (m, s, rad); the physics is :mod:`.eci`'s and
:mod:`.mks`'s (their formulas and kernels, compiled in here), not a copy.
"""

from __future__ import annotations

import math

import numpy as np

from ...engines import mks
from ...engines.eci import corrected_launch
from ...foundation import earth
from ...foundation.compiled import jit
from ...models.trajectory import cross, dot, launch_axes, turned_about_axis

__all__ = [
    "GRID_POINTS",
    "LOWEST_ELEVATION_RAD",
    "HIGHEST_ELEVATION_RAD",
    "MAX_DECAY",
    "OK",
    "NOT_USABLE",
    "ESCAPES",
    "BELOW",
    "FOUND",
    "NO_TRAJECTORY",
    "ALL_ESCAPE",
    "BEYOND_RANGE",
    "BELOW_LOWEST",
    "ABOVE_HIGHEST",
    "NOT_CONVERGED",
    "SOLUTION_FIELDS",
    "solve",
    "warm_up",
]

#: The elevations the solver searches (rad): the grid's ends, short of the vertical, where tau
#: of eq 3.27 is infinite, and its count of points at the great-circle bearing.
LOWEST_ELEVATION_RAD = math.radians(0.5)
HIGHEST_ELEVATION_RAD = math.radians(89.9)
GRID_POINTS = 16
#: Elevations whose beta x decay scale exceeds this are not usable: the angular momentum
#: decays to e^-8 of its launch value and the closed form's constants cancel
#: (mks.ModifiedKeplerSolution refuses them) long before beta reaches its validity limit 0.25.
MAX_DECAY = 8.0
#: Eq 3.32's time of flight: Gauss-Legendre points per interval of mks.time_to, within 0.12 us
#: of 4,000 equal intervals (50 um of the target's motion; 8 points: 1 ns, a third more work).
TIME_ORDER = 6
#: The search of the maximum range stops within this of its elevation (rad): the excess is
#: flat there to 1e-15 rad.
_PEAK_WIDTH_RAD = 1e-7
#: The golden section's fraction, of the search of the maximum range (Brent's method).
_GOLDEN = 0.5 * (3.0 - math.sqrt(5.0))
#: Newton's method on (elevation, bearing): the forward-difference step (rad), the miss (m) it
#: stops at, the step (rad) below which it stops and its iterations. The bearing is free: near
#: the vertical the Earth's turn moves the landing point more than the bearing does, and the
#: root's bearing may lie far from the great circle's.
_DIFFERENCE_RAD = 1e-7
_CONVERGED_M = 1e-4
_STALLED_RAD = 1e-13
_ITERATIONS = 40
#: Bearings Newton's method starts from, in turn until it converges: the great circle's, then
#: every 45 deg round.
_BEARING_STARTS = 8
#: The edge of the usable elevations is searched to this width (rad) in at most this many
#: steps (bisection halves a grid step 22 times to it).
_EDGE_WIDTH_RAD = 1e-8
_EDGE_ITERATIONS = 30

#: A shot's status (the first return of ``_shot()``).
OK, NOT_USABLE, ESCAPES, BELOW = 0, 1, 2, 3
#: A root's status in :func:`solve`'s ``status`` (n, 2): found, or why not.
FOUND = 0
NO_TRAJECTORY = 1  # no usable elevation reaches the target's altitude on the branch
ALL_ESCAPE = 2  # every usable elevation escapes
BEYOND_RANGE = 3  # the maximum range falls short of the target
BELOW_LOWEST = 4  # the lowest usable elevation already reaches beyond: the low root is lower
ABOVE_HIGHEST = 5  # the highest usable elevation still reaches beyond: the high root is higher
NOT_CONVERGED = 6  # Newton's method stopped off the target (a lost root: tests keep it at 0)
#: The columns of :func:`solve`'s ``roots`` (n, 2, 12).
SOLUTION_FIELDS = (
    "elevation_rad",
    "bearing_rad",
    "time_of_flight_s",
    "miss_m",
    "beta",
    "apogee_altitude_m",
    "evaluations",
    "d_east_d_elevation",  # the Jacobian (m/rad) of the east and north miss at the root
    "d_east_d_bearing",
    "d_north_d_elevation",
    "d_north_d_bearing",
    "along_slope",  # d(along-track excess)/d(elevation): > 0 on the low side, < 0 on the high
)
_FIELDS = len(SOLUTION_FIELDS)
#: :func:`solve`'s ``search`` (n, 6): the maximum range's elevation and its Earth-fixed ground
#: range along the great circle (m), the lowest and highest usable elevations (rad) and their
#: ground ranges (m), NaN where there are none, and the target's distance (m).
SEARCH_FIELDS = (
    "peak_elevation_rad",
    "peak_range_m",
    "lowest_elevation_rad",
    "lowest_range_m",
    "highest_elevation_rad",
    "highest_range_m",
    "distance_m",  # the target's great-circle distance from the gun along the ground
)
_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(TIME_ORDER)
# gun: speed, latitude, Cd0 A, mass, rho0, k, omega, the flags of eci.corrected_launch
_SPEED, _LATITUDE, _DRAG_AREA, _MASS, _DENSITY, _DECAY_K, _OMEGA = range(7)


@jit
def _shot(gun, flags, elevation, bearing, target, work):
    """The ECI MKS of the gun laid at ``elevation`` and ``bearing`` to the target ``target``
    (its Earth-fixed unit vector, radius, great-circle axis, central angle and branch; see
    :func:`_target_row`). Returns the status, the along-track excess (rad), the east and north
    miss (m), the time of flight (s), beta (eq 6.11) and the apogee's altitude (m)."""
    nan = math.nan
    (_, _, mu, _, _, _, _, velocity, speed, launch_elevation, _, ratio, beta, tau, _) = _corrected(
        gun, flags, elevation, bearing
    )
    drive = math.cos(mu) * ratio
    decay = drive if flags[5] else math.cos(mu)  # the consistent decay, or eq 6.14 as printed
    if not launch_elevation > 0.0 or beta * decay > MAX_DECAY:
        return NOT_USABLE, nan, nan, nan, nan, beta, nan
    table, _, arguments, angles = work
    for row, value in enumerate((speed, launch_elevation, beta, tau, earth.RADIUS_M, drive, decay)):
        arguments[row, 0] = value
    status = _apogee(work)
    if status != OK:
        return status, nan, nan, nan, nan, beta, nan
    apogee_angle, apogee_altitude = angles[0], angles[1]
    radius = target[3]
    if not apogee_altitude + earth.RADIUS_M > radius:
        return BELOW, nan, nan, nan, nan, beta, apogee_altitude
    low, high, sign = _branch(work, target)
    if not high > low > -1.0 or not apogee_angle > 0.0:  # no digits: grazing, or vertical
        return NOT_USABLE, nan, nan, nan, nan, beta, apogee_altitude
    theta = mks.crossing_angle(table, 0, tau, low, high, 1.0 / radius, sign)
    time = mks.time_to(table, 0, tau, beta * decay, theta, _NODES, _WEIGHTS)
    excess, east, north = _landing(
        gun, velocity, mks.u_at(table, 0, tau, theta), theta, time, target
    )
    return OK, excess, east, north, time, beta, apogee_altitude


# _apogee, _branch and _landing are inlined: they run at every shot, where a call passing
# arrays would cost its reference counts
@jit(inline=True)
def _apogee(work):
    """The MKS constants of the launch in ``work``'s arguments and its apogee (polar angle and
    altitude, into its angles): :data:`OK`, :data:`ESCAPES` or :data:`NOT_USABLE`."""
    table, escapes, a, angles = work
    if mks.solve_constants(a[0], a[1], a[2], a[3], a[4], a[5], a[6], table, escapes) >= 0:
        return NOT_USABLE
    if escapes[0]:
        return ESCAPES
    if mks.find_apogees(table, a[3], a[4], escapes, angles[0:1], angles[1:2]) >= 0:
        return NOT_USABLE
    return OK


@jit(inline=True)
def _branch(work, target):
    """The polar angles bounding the target's branch of the trajectory of :func:`_apogee`
    (apogee to impact descending, launch to apogee ascending; NaN where the impact is not
    found) and the sign :func:`.mks.crossing_angle` takes for it."""
    table, escapes, a, angles = work
    if not target[8] > 0:
        return 0.0, angles[0], -1.0
    if mks.find_impacts(table, a[3], a[4], escapes, angles[0:1], angles[2:3]) >= 0:
        return math.nan, math.nan, 1.0
    return angles[0], angles[2], 1.0


@jit(inline=True)
def _landing(gun, velocity, u, theta, time, target):
    """The along-track excess (rad) and the east and north miss (m) of the crossing at polar
    angle ``theta`` (``u`` its 1/r) reached at ``time``, the shot launched at ``velocity``:
    the crossing point in the inertial frame of t = 0, turned back into the Earth's."""
    radius = target[3]
    up = launch_axes(gun[_LATITUDE], 0.0, 0.0)[0]
    climb = dot(velocity, up)
    along = (velocity[0] - climb * up[0], velocity[1] - climb * up[1], velocity[2] - climb * up[2])
    size = math.sqrt(dot(along, along))
    r = 1.0 / u
    c, s = r * math.cos(theta), r * math.sin(theta) / size
    x, y = turned_about_axis(
        c * up[0] + s * along[0], c * up[1] + s * along[1], -gun[_OMEGA] * time
    )
    point = (x, y, c * up[2] + s * along[2])
    axis = (target[4], target[5], target[6])
    excess = math.atan2(dot(point, axis), dot(point, up)) - target[7]
    aim = (target[0] * radius, target[1] * radius, target[2] * radius)
    miss = (point[0] - aim[0], point[1] - aim[1], point[2] - aim[2])
    east = (-target[1], target[0], 0.0)
    east_size = math.hypot(east[0], east[1])
    if east_size == 0.0:  # a target at a pole: east is that of the gun's meridian
        east, east_size = (0.0, 1.0, 0.0), 1.0
    east = (east[0] / east_size, east[1] / east_size, 0.0)
    north = cross((target[0], target[1], target[2]), east)
    return excess, dot(miss, east), dot(miss, north)


@jit
def _corrected(gun, flags, elevation, bearing):
    """:func:`.eci.corrected_launch` of the gun laid at ``elevation`` and ``bearing``."""
    return corrected_launch(
        gun[_SPEED],
        elevation,
        bearing,
        gun[_LATITUDE],
        gun[_DRAG_AREA],
        gun[_MASS],
        gun[_DENSITY],
        gun[_DECAY_K],
        gun[_OMEGA],
        earth.RADIUS_M,
        flags[0],
        flags[1],
        flags[2],
        flags[3],
        flags[4],
    )


@jit
def _excess(gun, flags, elevation, bearing, target, work):
    """The along-track excess (rad) at ``elevation`` and ``bearing``; -inf where the shot does
    not reach the target's altitude on its branch (short of any range), NaN where the MKS has
    no usable solution."""
    status, excess = _shot(gun, flags, elevation, bearing, target, work)[:2]
    if status == OK:
        return excess
    return -math.inf if status == BELOW else math.nan


@jit
def _peak(gun, flags, low, high, bearing, target, work):
    """The elevation in [low, high] of the greatest along-track excess at ``bearing``, its
    excess and the evaluations spent: Brent's method (parabolic steps, golden sections where
    they fail), the excess having one maximum there."""
    a, b = low, high
    x = w = v = a + _GOLDEN * (b - a)
    fx = fw = fv = -_finite(_excess(gun, flags, x, bearing, target, work))
    evaluations = 1
    d = e = 0.0
    tolerance = _PEAK_WIDTH_RAD
    while True:
        middle = 0.5 * (a + b)
        if abs(x - middle) <= 2.0 * tolerance - 0.5 * (b - a):
            break
        d, e = _brent_step(a, b, x, w, v, fx, fw, fv, d, e, middle)
        u = x + (d if abs(d) >= tolerance else (tolerance if d > 0 else -tolerance))
        fu = -_finite(_excess(gun, flags, u, bearing, target, work))
        evaluations += 1
        a, b, v, fv, w, fw, x, fx = _brent_keep(a, b, v, fv, w, fw, x, fx, u, fu)
    return x, -fx, evaluations


@jit
def _brent_step(a, b, x, w, v, fx, fw, fv, d, e, middle):
    """Brent's next step from ``x`` and the last two (``d``, ``e``): the parabola's through
    x, w and v where it falls inside [a, b] and shrinks, else a golden section; returns both."""
    tolerance = _PEAK_WIDTH_RAD
    if abs(e) > tolerance:
        r = (x - w) * (fx - fv)
        q = (x - v) * (fx - fw)
        p = (x - v) * q - (x - w) * r
        q = 2.0 * (q - r)
        if q > 0.0:
            p = -p
        q = abs(q)
        if abs(p) < abs(0.5 * q * e) and q * (a - x) < p < q * (b - x):
            e, d = d, p / q
            if (x + d) - a < 2.0 * tolerance or b - (x + d) < 2.0 * tolerance:
                d = tolerance if middle > x else -tolerance
            return d, e
    e = (b - x) if x < middle else (a - x)
    return _GOLDEN * e, e


@jit
def _brent_keep(a, b, v, fv, w, fw, x, fx, u, fu):
    """Brent's bracket [a, b] and its three best points (x the best, w and v the next) with
    their values, after the trial ``u`` of value ``fu``."""
    if fu <= fx:
        if u < x:
            b = x
        else:
            a = x
        return a, b, w, fw, x, fx, u, fu
    if u < x:
        a = u
    else:
        b = u
    if fu <= fw or w == x:
        return a, b, w, fw, u, fu, x, fx
    if fu <= fv or v == x or v == w:
        return a, b, u, fu, w, fw, x, fx
    return a, b, v, fv, w, fw, x, fx


@jit
def _finite(excess):
    """An excess as the search compares it: NaN (no usable solution) as short of any range."""
    return -math.inf if math.isnan(excess) else excess


@jit
def _residual(gun, flags, elevation, bearing, target, work, f):
    """The east and north miss and the along-track excess into ``f`` (6,), then the time of
    flight, beta and the apogee's altitude, at ``elevation`` and ``bearing``; whether the shot
    is usable (reaches the target's altitude on its branch)."""
    status, excess, east, north, time, beta, apogee = _shot(
        gun, flags, elevation, bearing, target, work
    )
    f[0], f[1], f[2], f[3], f[4], f[5] = east, north, excess, time, beta, apogee
    return status == OK


@jit
def _jacobian(gun, flags, x, f, target, work, out, shifted):
    """Forward differences of the east and north miss and of the along-track excess into
    ``out`` (3, 2) at ``x`` (elevation, bearing) whose residual is ``f``; backward where the
    forward shot is not usable. False if neither is."""
    for k in range(2):
        done = False
        for sign in (1.0, -1.0):
            step = sign * _DIFFERENCE_RAD
            elevation = x[0] + (step if k == 0 else 0.0)
            bearing = x[1] + (step if k == 1 else 0.0)
            if _residual(gun, flags, elevation, bearing, target, work, shifted):
                for row in range(3):
                    out[row, k] = (shifted[row] - f[row]) / step
                done = True
                break
        if not done:
            return False
    return True


@jit
def _newton(gun, flags, start, low, high, bearing, target, work, out):
    """Newton's method on (elevation, bearing) from ``start`` elevation at the great-circle
    ``bearing``, elevation kept in [low, high], the bearing free:
    Broyden's updates of a forward-difference Jacobian, differenced afresh when a step fails
    to halve the miss. Writes the root's :data:`SOLUTION_FIELDS` into ``out`` (the Jacobian
    Broyden's at the root); returns whether it converged and the trajectories it evaluated."""
    x = np.array([start, bearing])
    f, trial, shifted = np.empty(6), np.empty(6), np.empty(6)
    jacobian = np.empty((3, 2))
    evaluations = 3
    if not _linearised(gun, flags, x, target, work, f, jacobian, shifted):
        return False, evaluations
    miss = math.hypot(f[0], f[1])
    for _ in range(_ITERATIONS):
        if miss <= _CONVERGED_M:
            break
        regular, step_e, step_b = _newton_step(jacobian, f)
        if not regular:
            break
        usable, step_e, step_b, spent = _usable_step(
            gun, flags, x, step_e, step_b, low, high, target, work, trial
        )
        evaluations += spent
        if not usable:
            break
        norm = step_e * step_e + step_b * step_b
        _broyden(jacobian, f, trial, step_e, step_b, norm)
        x[0], x[1] = x[0] + step_e, x[1] + step_b
        f[:] = trial
        new_miss = math.hypot(f[0], f[1])
        if new_miss > _CONVERGED_M and new_miss > 0.5 * miss:  # Broyden has drifted
            if not _jacobian(gun, flags, x, f, target, work, jacobian, shifted):
                break
            evaluations += 2
        miss = new_miss
        if math.sqrt(norm) < _STALLED_RAD:
            break
    out[0], out[1], out[2], out[3] = x[0], x[1] % (2 * math.pi), f[3], miss
    out[4], out[5], out[6] = f[4], f[5], evaluations
    out[7], out[8], out[9], out[10] = jacobian[0, 0], jacobian[0, 1], jacobian[1, 0], jacobian[1, 1]
    out[11] = jacobian[2, 0]
    return miss <= _CONVERGED_M, evaluations


@jit
def _linearised(gun, flags, x, target, work, f, jacobian, shifted):
    """The residual at ``x`` into ``f`` and its forward-difference Jacobian into ``jacobian``
    (:func:`_jacobian`); False where a shot is not usable."""
    return _residual(gun, flags, x[0], x[1], target, work, f) and _jacobian(
        gun, flags, x, f, target, work, jacobian, shifted
    )


@jit
def _newton_step(jacobian, f):
    """Newton's step (elevation, bearing) that zeroes the east and north miss of ``f`` by the
    Jacobian's first two rows; False first where they are singular."""
    a, b, c, d = jacobian[0, 0], jacobian[0, 1], jacobian[1, 0], jacobian[1, 1]
    determinant = a * d - b * c
    if determinant == 0.0 or not math.isfinite(determinant):
        return False, math.nan, math.nan
    return True, -(d * f[0] - b * f[1]) / determinant, -(-c * f[0] + a * f[1]) / determinant


@jit
def _usable_step(gun, flags, x, step_e, step_b, low, high, target, work, trial):
    """The step from ``x`` halved (at most 30 times) until its shot is usable and its
    elevation in [low, high], that shot's residual in ``trial``: whether one was, the step and
    the trajectories evaluated."""
    evaluations = 0
    for _ in range(30):
        new_e, new_b = x[0] + step_e, x[1] + step_b
        if low <= new_e <= high:
            evaluations += 1
            if _residual(gun, flags, new_e, new_b, target, work, trial):
                return True, step_e, step_b, evaluations
        step_e, step_b = 0.5 * step_e, 0.5 * step_b
    return False, step_e, step_b, evaluations


@jit
def _broyden(jacobian, f, trial, step_e, step_b, norm):
    """Broyden's (good) update of ``jacobian`` along the step taken (squared length ``norm``)
    from the residual ``f`` to ``trial``."""
    for row in range(3):
        change = trial[row] - f[row]
        predicted = jacobian[row, 0] * step_e + jacobian[row, 1] * step_b
        jacobian[row, 0] += (change - predicted) * step_e / norm
        jacobian[row, 1] += (change - predicted) * step_b / norm


@jit
def _target_row(latitude, longitude, altitude, descending, gun_latitude):
    """A target as ``_shot()`` reads it: its Earth-fixed unit vector (longitude relative to
    the gun's), radius, the great circle's axis at the gun toward it (unit, horizontal), its
    central angle from the gun, its branch (+1 descending, -1 ascending) and its great-circle
    bearing from the gun."""
    row = np.empty(10)
    up = launch_axes(latitude, longitude, 0.0)[0]
    gun_up = launch_axes(gun_latitude, 0.0, 0.0)[0]
    normal = cross(gun_up, up)
    central = math.atan2(math.sqrt(dot(normal, normal)), dot(gun_up, up))
    bearing = math.atan2(
        math.sin(longitude) * math.cos(latitude),
        math.cos(gun_latitude) * math.sin(latitude)
        - math.sin(gun_latitude) * math.cos(latitude) * math.cos(longitude),
    ) % (2 * math.pi)
    axis = launch_axes(gun_latitude, 0.0, bearing)[1]
    row[0], row[1], row[2] = up
    row[3] = earth.RADIUS_M + altitude
    row[4], row[5], row[6] = axis
    row[7] = central
    row[8] = 1.0 if descending else -1.0
    row[9] = bearing
    return row


@jit
def _range_m(excess, target):
    """The Earth-fixed ground range (m) along the great circle of an along-track excess."""
    return (excess + target[7]) * earth.RADIUS_M


@jit
def _edge(gun, flags, outside, inside, inside_excess, inside_apogee, bearing, target, work):
    """The usable elevation nearest the edge between one the MKS cannot fly to the target
    (``outside``) and one it can (``inside``, with its excess and apogee's altitude), its excess
    and the evaluations spent. Where the outside shot's apogee falls short of the target's
    radius, regula falsi (Illinois) on the apogee's height over it, which is smooth across
    the edge; else bisection."""
    status, _, _, _, _, _, apogee = _shot(gun, flags, outside, bearing, target, work)
    evaluations = 1
    height = target[3] - earth.RADIUS_M
    fa = apogee - height if status == BELOW else math.nan
    fb = inside_apogee - height
    a, b, excess = outside, inside, inside_excess
    previous = 0
    for _ in range(_EDGE_ITERATIONS):
        if abs(b - a) <= _EDGE_WIDTH_RAD:
            break
        middle = _edge_trial(a, b, fa, fb)
        status, trial, _, _, _, _, apogee = _shot(gun, flags, middle, bearing, target, work)
        evaluations += 1
        if status == OK:
            b, fb, excess = middle, apogee - height, trial
            if previous == 1:
                fa *= 0.5  # Illinois: the end that stays put is halved
            previous = 1
        else:
            a, fa = middle, (apogee - height if status == BELOW else math.nan)
            if previous == -1:
                fb *= 0.5
            previous = -1
    return b, excess, evaluations


@jit
def _edge_trial(a, b, fa, fb):
    """The next trial elevation between ``a`` (outside) and ``b`` (inside): regula falsi on
    the apogee's heights ``fa`` and ``fb`` where both are known and straddle the target's,
    else (or where it would fall outside) the middle."""
    falsi = math.isfinite(fa) and math.isfinite(fb) and fb > 0.0 > fa
    middle = (a - fa * (b - a) / (fb - fa)) if falsi else 0.5 * (a + b)
    if not min(a, b) < middle < max(a, b):
        middle = 0.5 * (a + b)
    return middle


@jit
def _scan_arrays(n_terms):
    """The scratch the per-target search reuses: the MKS's ``work`` (:func:`_shot`) and the
    ``scan`` of :func:`_usable_points` (the grid, each grid point's status, excess and apogee,
    then the usable points and their excess in order of elevation: the edges and the grid's)."""
    table = np.empty((mks.AMPLITUDES_ROW + n_terms, 1))
    escapes = np.empty(1, dtype=np.bool_)
    arguments = np.empty((7, 1))
    angles = np.empty(3)
    work = (table, escapes, arguments, angles)
    grid = np.linspace(LOWEST_ELEVATION_RAD, HIGHEST_ELEVATION_RAD, GRID_POINTS)
    shots = np.empty(GRID_POINTS, dtype=np.int64)
    excess = np.empty(GRID_POINTS)
    apogees = np.empty(GRID_POINTS)
    points = np.empty(GRID_POINTS + 2)
    values = np.empty(GRID_POINTS + 2)
    return work, (grid, shots, excess, apogees, points, values)


@jit
def _solve_all(
    gun, flags, n_terms, latitude, longitude, altitude, descending, roots, status, search
):
    """Every target's roots (:func:`solve`); returns the MKS trajectories of each."""
    work, scan = _scan_arrays(n_terms)
    counts = np.zeros(latitude.size, dtype=np.int64)
    for i in range(latitude.size):
        target = _target_row(latitude[i], longitude[i], altitude[i], descending[i], gun[_LATITUDE])
        counts[i] = _solve_target(gun, flags, target, work, scan, roots[i], status[i], search[i])
    return counts


@jit
def _solve_target(gun, flags, target, work, scan, roots, status, search):
    """One target's two roots, their status and its search row; returns the MKS trajectories
    evaluated."""
    points, values = scan[4], scan[5]
    roots[:] = math.nan
    search[:] = math.nan
    search[6] = target[7] * earth.RADIUS_M
    size, evaluations = _usable_points(gun, flags, target, work, scan, status)
    if size == 0:
        return evaluations
    search[2], search[3] = points[0], _range_m(values[0], target)
    search[4], search[5] = points[size - 1], _range_m(values[size - 1], target)
    peak, top, spent = _maximum_range(gun, flags, points, values, size, target, work)
    evaluations += spent
    search[0], search[1] = peak, _range_m(top, target)
    if top < 0.0:
        status[0] = status[1] = BEYOND_RANGE
        return evaluations
    for side in range(2):
        a, fa, b, fb = _bracket(points, values, size, peak, top, side)
        if math.isnan(a):
            status[side] = BELOW_LOWEST if side == 0 else ABOVE_HIGHEST
            continue
        converged, spent = _root(
            gun,
            flags,
            a + (b - a) * fa / (fa - fb),
            points[0] if side == 0 else peak,
            peak if side == 0 else points[size - 1],
            target,
            work,
            roots[side],
        )
        evaluations += spent
        status[side] = FOUND if converged else NOT_CONVERGED
    return evaluations


@jit
def _usable_points(gun, flags, target, work, scan, status):
    """The elevation scan at the great-circle bearing: the usable points of ``scan`` in order
    of elevation (the grid's, and the edges of the usable elevations between grid points, found
    by :func:`_edge`: the excess may be greatest there, on the ascending branch of a target
    aloft). Returns their count (0, with both roots' ``status`` saying why, where no grid point
    is usable) and the MKS trajectories evaluated."""
    grid, shots, excess, apogees, points, values = scan
    bearing = target[9]
    first = last = -1
    for j in range(GRID_POINTS):
        shot = _shot(gun, flags, grid[j], bearing, target, work)
        shots[j], excess[j], apogees[j] = shot[0], shot[1], shot[6]
        if shot[0] == OK:
            first = j if first < 0 else first
            last = j
    evaluations = GRID_POINTS
    if first < 0:
        status[0] = status[1] = _unusable(shots)
        return 0, evaluations
    size = 0
    if first > 0:
        points[0], values[0], spent = _edge(
            gun,
            flags,
            grid[first - 1],
            grid[first],
            excess[first],
            apogees[first],
            bearing,
            target,
            work,
        )
        evaluations += spent
        size = 1
    for j in range(first, last + 1):
        if shots[j] == OK:
            points[size], values[size] = grid[j], excess[j]
            size += 1
    if last < GRID_POINTS - 1:
        points[size], values[size], spent = _edge(
            gun,
            flags,
            grid[last + 1],
            grid[last],
            excess[last],
            apogees[last],
            bearing,
            target,
            work,
        )
        evaluations += spent
        size += 1
    return size, evaluations


@jit
def _unusable(shots):
    """Why no shot of the grid (its statuses ``shots``) is usable: :data:`ALL_ESCAPE` where
    some escape and none falls short of the target's altitude, else :data:`NO_TRAJECTORY`."""
    escaping = reaching = False
    for j in range(GRID_POINTS):
        escaping |= shots[j] == ESCAPES
        reaching |= shots[j] == BELOW
    return ALL_ESCAPE if escaping and not reaching else NO_TRAJECTORY


@jit
def _maximum_range(gun, flags, points, values, size, target, work):
    """The elevation of the maximum range and its excess, and the evaluations spent: the best
    usable point, searched further by :func:`_peak` where the points cannot tell: the best
    falls short (beyond the maximum range, or two roots between points) or a neighbour of it
    does (a root within a step of the best point, which must not bound its search)."""
    best = 0
    for k in range(size):
        if values[k] > values[best]:
            best = k
    peak, top = points[best], values[best]
    before = values[best - 1] if best > 0 else math.inf
    after = values[best + 1] if best < size - 1 else math.inf
    if not (top < 0.0 or before < 0.0 or after < 0.0):
        return peak, top, 0
    refined, value, spent = _peak(
        gun,
        flags,
        points[max(best - 1, 0)],
        points[min(best + 1, size - 1)],
        target[9],
        target,
        work,
    )
    if value > top:
        return refined, value, spent
    return peak, top, spent


@jit
def _bracket(points, values, size, peak, top, side):
    """The sign change of the excess nearest the maximum range (``peak``, excess ``top``) on
    the low (``side`` 0) or high (1) side of it, among the usable points and the peak: its
    ends (a, fa, b, fb), ``a`` short of the target; NaN where there is none."""
    a = fa = b = fb = math.nan
    # from the far end toward the peak: up the low side, down the high side (elevations
    # compared by sign * elevation, exactly, as if the high side ran upward too)
    sign = 1 if side == 0 else -1
    for k in range(0, size) if side == 0 else range(size - 1, -1, -1):
        if sign * points[k] >= sign * peak:
            break
        inside = sign * points[k + sign] < sign * peak
        following = values[k + sign] if inside else top
        ending = points[k + sign] if inside else peak
        if values[k] < 0.0 <= following:
            a, fa, b, fb = points[k], values[k], ending, following
    return a, fa, b, fb


@jit
def _root(gun, flags, start, low, high, target, work, out):
    """One root by :func:`_newton` from ``start`` elevation, elevation kept in [low, high]:
    from the great-circle bearing, then from others (near the vertical the Earth's turn
    carries the landing points round a circle about the vertical shot's, and the root's
    bearing can be far from the great circle's). Returns whether it converged and the MKS
    trajectories evaluated."""
    evaluations = 0
    for start_index in range(_BEARING_STARTS):
        converged, spent = _newton(
            gun,
            flags,
            start,
            low,
            high,
            target[9] + 2.0 * math.pi * start_index / _BEARING_STARTS,
            target,
            work,
            out,
        )
        evaluations += spent
        if converged:
            break
    return converged, evaluations


def solve(
    gun: np.ndarray,
    flags: tuple[bool, ...],
    latitude_rad: np.ndarray,
    longitude_rad: np.ndarray,
    altitude_m: np.ndarray,
    descending: np.ndarray,
    *,
    n_terms: int = 3,
):
    """Both roots of every target (arrays (n,): latitude, longitude relative to the gun's,
    altitude above the sphere, branch), for the gun ``gun`` (speed, latitude, Cd0 A, mass, rho0,
    k, omega: :mod:`~harp_analysis.analyses.fire_control` builds it) and :class:`.eci.EciModel`
    ``flags`` with the decay's ("consistent") last. Returns ``roots`` (n, 2,
    :data:`SOLUTION_FIELDS`; low, high), ``status`` (n, 2), ``search`` (n, :data:`SEARCH_FIELDS`)
    and the MKS trajectories evaluated per target (n,). The caller validates; this trusts its
    arrays."""
    count = latitude_rad.size
    roots = np.empty((count, 2, _FIELDS))
    status = np.zeros((count, 2), dtype=np.int64)
    search = np.empty((count, len(SEARCH_FIELDS)))
    counts = _solve_all(
        gun,
        flags,
        n_terms,
        latitude_rad,
        longitude_rad,
        altitude_m,
        descending,
        roots,
        status,
        search,
    )
    return roots, status, search, counts


def warm_up() -> None:
    """Compile the solver now (or load it from the on-disk cache), not at first use."""
    gun = np.array([2000.0, 0.2, 3e-3, 80.0, 1.225, 1.17e-4, 7.29e-5])
    one = np.array([0.21])
    solve(gun, (True, False, True, True, False, True), one, np.array([0.01]), one * 0, one > 0)
