"""The 6DOF simulation of Appendix B (Dr. Slegers' MATLAB), ported and made fast.

Appendix B integrates the rigid finned projectile of Chapter 2 A (M829 aerodynamics) in a flat
launch frame: x downrange, y cross range, z down, the Earth's centre at (0, 0, +R), the frame
non-rotating. The 12 states are ``[x y z phi theta psi u v w p q r]``: position in the flat
frame, 3-2-1 Euler angles of the body from it, and body-axis velocity and angular velocity.
RK4 with h = 0.0005 s runs to 270 s from theta = 50 deg, u = 2022 m/s, p = 10 rad/s.

:func:`appendix_b_derivatives` is a line-by-line port of ``PROJ6DOF_M829_DERV``. What the
printed code does that we keep (each faithfully ported):

- gravity: the ``Weight`` line's magnitude is m GM / ((6378 - z/1000)^2 + (x/1000)^2) (km),
  i.e. m GM / ((R - z)^2 + x^2): it omits y^2, while its direction (-x, -y, R - z)/|r| includes
  y. The relative error is y^2 / r^2, a few 1e-9 for these flights;
- the atmosphere (density and speed of sound) is evaluated at the flat-frame altitude -z, not
  at the spherical altitude |r| - R, the default ``density_altitude="flat"``. Downrange the
  Earth's surface falls x^2 / (2R) below the flat plane (4.6 km at HP's 241 km range), so on
  the way down the code flies through air that is too dense: 1.6 times too dense at 10 km
  (true) altitude, and at impact -z = -4.6 km, where the fit 1.22581 (1 + 0.00002257 z)^4.256
  extrapolates to 1.5 times sea level. HP lands at 807 m/s instead of 1094 m/s.
  ``density_altitude="spherical"`` evaluates the atmosphere at |r| - R instead;
- ``thetacorrect`` (pitch above the local horizontal) and ``TIB2`` built from it are computed
  but unused (they fed a commented-out Weight line), as is a commented-out flat-Earth weight
  ``mass*9.81*TIB*[0;0;1]`` and a commented-out ``rho=0`` (vacuum);
- CYPA and SLMAG are zero in the table, so the Magnus force and moment are inert.

What we change, each stated again in :func:`appendix_b_derivatives`:

- density, speed of sound and the nine coefficients are evaluated at the state passed; the
  code evaluates them once per RK4 step, at the step's start, outside the derivative function
  (which makes its RK4 formally first-order in the aerodynamic terms);
- wind: the text says the projectiles fly "with a 5 m/s cross wind", but the code has no wind
  term at all. We subtract a constant wind (flat-frame components) from the velocity to get the
  air-relative velocity used in every aerodynamic force and moment and in the Mach number;
- the Mach interpolation holds the table's end values outside Mach 0-8, where MATLAB's
  ``interp1`` returns NaN (see :mod:`.drag`).

Oddities of the printed code with no effect on the physics: the ``FSA`` line opens its vector
with ``(`` instead of ``[`` and the ``Weight`` line has one ``)`` too many, so the code as
printed does not run; the comment calls GM (km^3/s^2) a "gravitational acceleration km^2/s^2";
the initial theta is 0.872665 rad (50.00002 deg); the RK4 loop runs to 270 s without an impact
test; its output column 6, the "angle of attack", is sqrt(v^2 + w^2)/u in degrees (the small
angle tangent, inertial velocity), meaningless at the large angles reached above the
atmosphere; rows are written at the first step after each 0.5 s mark.

The no-roll formulation (used by :func:`simulate_6dof`)
-------------------------------------------------------
The fins spin the projectile from 10 rad/s to the roll equilibrium p d / (2V) = -CLDD/CLP
(about 300 rad/s for HP, 445 for LP) within a second, so body-axis v, w, q, r oscillate at the
spin rate and an adaptive integrator needs ~1e5+ steps. The projectile is axisymmetric in the
code (Iy = Iz, one CNA for pitch and yaw) and every force and moment term is covariant under a
rotation about the body x axis, so the same equations can be written exactly in the no-roll
frame N, reached from the flat frame by psi then theta only (the body frame is N turned by phi
about x). Velocity and body angular velocity are resolved in N: ``[u v w]`` and ``[p q r]``
(u and p are unchanged; v, w and q, r are the body's rotated back by phi).

1. N turns relative to the flat frame at Omega = psi' k + theta' j', i.e. in N components
   Omega = [-psi' sin(theta), theta', psi' cos(theta)]; the body at Omega + phi' i. Hence
   theta' = q, psi' = r / cos(theta), phi' = p + r tan(theta), and Omega = [-r tan(theta), q, r].
2. Position: [x y z]' = T_N^T [u v w], T_N = Appendix B's TIB with phi = 0.
3. Translation: [u v w]' = (F_aero + Weight)/m - Omega x [u v w]: the body equation with the
   frame rate Omega in place of the body rate (p replaced by -r tan(theta) in the cross product).
4. Rotation: the angular momentum is H = [Ix p, Iy q, Iy r] in N too, because Iy = Iz makes the
   inertia invariant under the phi rotation. H' = M - Omega x H gives
   p' = Mx / Ix,  q' = (My - Ix p r - Iy tan(theta) r^2) / Iy,
   r' = (Mz + Ix p q + Iy tan(theta) q r) / Iy.
5. Forces and moments keep their Appendix B expressions with v, w, q, r read in N: v^2 + w^2
   and p are invariant, [v, w], [w, -v] and [q, r] rotate with the frame; the weight direction
   is resolved with T_N. phi enters nothing: it is integrated only for output.

Nothing in N oscillates at the spin rate: what remains is the pitch/yaw oscillation (9 Hz
for HP, 17 Hz for LP at launch, slowing as the air thins) and, above the atmosphere, the
gyroscopic nutation at Ix p / Iy (below 1 rad/s), so DOP853 at rtol 1e-9 takes about 1500
steps (25000 evaluations) for a whole flight. ``tests/test_sixdof.py`` checks that the two
derivatives agree at random states (transformed between the frames) and that the adaptive
no-roll solution agrees with Appendix B's own fixed-step RK4 on the body-frame port.

The no-roll derivatives (:func:`right_hand_side`) and the table's aerodynamics are compiled
(:mod:`.compiled`; :func:`warm_up`): about 1 us an evaluation, so a flight takes about 0.13 s,
four fifths of it scipy's own stepping, events and dense output. Appendix B's port stays numpy
(it verifies).

The Euler angles are Appendix B's and share its singularity at theta = +-90 deg.

The projectile itself (its constants and M829 table, the aerodynamic force and moment, the launch
state and the table of no-roll states) is :mod:`harp_analysis.models.rigid_body`, which Modified
Linear Theory (:mod:`.mlt`) flies too; this module holds the 6DOF's equations of motion and their
integration.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pandas as pd
from scipy.integrate import solve_ivp

from ..foundation import earth
from ..foundation.compiled import jit
from ..foundation.counting import Counted
from ..foundation.validation import Bounds, check_choice, finite_array, positive_scalar
from ..models.atmosphere import get_atmosphere
from ..models.launch import HP_CHAPTER_2, Launch
from ..models.projectiles import Projectile
from ..models.rigid_body import (
    SINGULAR_PITCH_COSINE,
    STATE_NAMES,
    RigidBodyKernel,
    RigidBodyModel,
    aerodynamics,
    flat_velocity,
    flight_table,
    launch_state,
    rigid_body_launch,
    rigid_body_model,
)
from ..models.trajectory import TruncatedFlightWarning

__all__ = [
    "appendix_b_derivatives",
    "right_hand_side",
    "counted_functions",
    "simulate_6dof",
    "integrate_fixed_step",
    "warm_up",
]

_R = earth.RADIUS_M
_GM = earth.GM_M3_S2
#: The frames :func:`appendix_b_derivatives` resolves the velocities in.
_FRAMES = ("body", "no_roll")

# Absolute error floors per state for solve_ivp: micrometre positions, 1e-10 rad attitudes,
# 1e-7 m/s velocities and 1e-10 rad/s pitch/yaw rates (q, r are ~1e-3 rad/s in vacuum).
_ATOL = np.array([1e-6] * 3 + [1e-10] * 3 + [1e-7] * 3 + [1e-8, 1e-10, 1e-10])


@jit
def right_hand_side(t, state, kernel):
    """The no-roll right-hand side (module docstring, steps 1-5) of the model whose
    :attr:`~harp_analysis.models.rigid_body.RigidBodyModel.kernel` is ``kernel``, compiled: what
    DOP853 calls in :func:`simulate_6dof` (unchecked; the checked form is
    :func:`appendix_b_derivatives` with ``frame="no_roll"``). ``state`` holds the 12 no-roll states
    (:data:`~harp_analysis.models.rigid_body.STATE_NAMES`)."""
    model = RigidBodyKernel(*kernel)
    x, y, z, _, theta, psi, u, v, w, p, q, r = state
    c_theta, s_theta = math.cos(theta), math.sin(theta)
    t_theta = s_theta / c_theta
    c_psi, s_psi = math.cos(psi), math.sin(psi)
    force, moment, _, _, _ = aerodynamics(
        model, x, y, z, c_theta, s_theta, c_psi, s_psi, u, v, w, p, q, r
    )
    fx, fy, fz = force
    mx, my, mz = moment
    # Weight per unit mass, Appendix B's magnitude (no y^2), resolved in N.
    radius = math.sqrt(x * x + y * y + (_R - z) ** 2)
    g = _GM / (((_R - z) ** 2 + x * x) * radius)
    gx, gy, gz = -g * x, -g * y, g * (_R - z)
    g_u = c_theta * c_psi * gx + c_theta * s_psi * gy - s_theta * gz
    g_v = -s_psi * gx + c_psi * gy
    g_w = s_theta * c_psi * gx + s_theta * s_psi * gy + c_theta * gz
    frame_roll = -r * t_theta  # x component of the frame rate Omega
    m, ix, iy = model.mass, model.ix, model.iy
    return np.array(
        (
            c_theta * c_psi * u - s_psi * v + s_theta * c_psi * w,
            c_theta * s_psi * u + c_psi * v + s_theta * s_psi * w,
            -s_theta * u + c_theta * w,
            p - frame_roll,
            q,
            r / c_theta,
            fx / m + g_u - (q * w - r * v),
            fy / m + g_v - (r * u - frame_roll * w),
            fz / m + g_w - (frame_roll * v - q * u),
            mx / ix,
            (my - ix * p * r + iy * frame_roll * r) / iy,
            (mz + ix * p * q - iy * frame_roll * q) / iy,
        )
    )


def counted_functions(launch: Launch) -> tuple[Counted, ...]:
    """The functions one evaluation of the no-roll right-hand side runs for ``launch``, each
    once: :func:`right_hand_side`, the rigid body's aerodynamics, where it reads the air, its
    coefficient table, and the launch's atmosphere's density and speed of sound
    (:mod:`harp_analysis.analyses.effort` counts their operations per evaluation, Fig 4.7)."""
    air = get_atmosphere(launch.atmosphere)
    return tuple(
        Counted(function)
        for function in (
            right_hand_side,
            aerodynamics,
            RigidBodyModel.air_altitude,
            RigidBodyModel.coefficients,
            air.density_kernel,
            air.sound_kernel,
        )
    )


def _appendix_b(model: RigidBodyModel, state) -> np.ndarray:
    """PROJ6DOF_M829_DERV line by line (matrix form), with wind and the per-state air."""
    x, y, z, phi, theta, psi, u, v, w, p, q, r = state
    c_theta, s_theta, t_theta = math.cos(theta), math.sin(theta), math.tan(theta)
    c_phi, s_phi = math.cos(phi), math.sin(phi)
    c_psi, s_psi = math.cos(psi), math.sin(psi)
    tib = np.array(
        [
            [c_theta * c_psi, c_theta * s_psi, -s_theta],
            [
                s_phi * s_theta * c_psi - c_phi * s_psi,
                s_phi * s_theta * s_psi + c_phi * c_psi,
                s_phi * c_theta,
            ],
            [
                c_phi * s_theta * c_psi + s_phi * s_psi,
                c_phi * s_theta * s_psi - s_phi * c_psi,
                c_phi * c_theta,
            ],
        ]
    )
    kinematic = np.array(
        [
            [1.0, s_phi * t_theta, c_phi * t_theta],
            [0.0, c_phi, -s_phi],
            [0.0, s_phi / c_theta, c_phi / c_theta],
        ]
    )
    # (6378 - z/1000)^2 + (x/1000)^2 km^2 with GM*1000 km^3/s^2 is this in SI; no y^2.
    weight = (
        (model.mass * _GM / ((_R - z) ** 2 + x**2))
        * tib
        @ (np.array([-x, -y, _R - z]) / math.sqrt(x * x + y * y + (_R - z) ** 2))
    )
    sw = np.array([[0.0, -r, q], [r, 0.0, -p], [-q, p, 0.0]])
    inertia = np.diag([model.ix, model.iy, model.iy])
    velocity, rates = np.array([u, v, w]), np.array([p, q, r])

    ua, va, wa = velocity - tib @ np.asarray(model.wind)
    big_v = math.sqrt(ua * ua + va * va + wa * wa)
    rho, sound = model.air(x, y, z)
    cx0, cx2, cna, cypa, cmq, clp, cldd, dx, dxmag = model.coefficients(big_v / sound)
    d = model.d
    qa = 0.125 * math.pi * rho * big_v**2 * d**2
    fsa = qa * np.array(
        [cx0 + cx2 * (va**2 + wa**2) / big_v**2, -cna * va / big_v, -cna * wa / big_v]
    )
    fmag = 0.0625 * rho * math.pi * d**3 * p * cypa * np.array([0.0, wa, -va])
    msa = qa * cna * dx * np.array([0.0, wa / big_v, -va / big_v])
    mua = (
        qa
        * d
        * np.array(
            [
                cldd + p * clp * d / (2 * big_v),
                q * cmq * d / (2 * big_v),
                r * cmq * d / (2 * big_v),
            ]
        )
    )
    mmag = 0.0625 * rho * math.pi * d**3 * p * cypa * dxmag * np.array([0.0, va, wa])
    return np.concatenate(
        [
            tib.T @ velocity,
            kinematic @ rates,
            (fsa + fmag + weight) / model.mass - sw @ velocity,
            np.linalg.solve(inertia, msa + mua + mmag - sw @ inertia @ rates),
        ]
    )


def warm_up() -> None:
    """Compile the 6DOF's kernels now (or load them from the on-disk cache), not at first use."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", TruncatedFlightWarning)  # a short flight compiles all
        simulate_6dof(HP_CHAPTER_2, max_time_s=0.1, output_step_s=0.1)


def _checked_state(state) -> np.ndarray:
    state = finite_array(state, "state")
    if state.shape != (12,):
        raise ValueError(f"state must hold the 12 states {STATE_NAMES}; got shape {state.shape}")
    return state


def appendix_b_derivatives(
    state,
    projectile: Projectile,
    *,
    frame: str = "body",
    atmosphere="two_segment",
    wind_m_s=(0.0, 0.0, 0.0),
    density_altitude: str = "flat",
) -> np.ndarray:
    """Time derivative of Appendix B's 12 states: a port of ``PROJ6DOF_M829_DERV`` (App. B),
    in the body frame as printed (``frame="body"``) or, exactly the same equations, in the
    no-roll frame :func:`simulate_6dof` integrates (``frame="no_roll"``; derivation in the
    module docstring).

    ``state`` is ``[x y z phi theta psi u v w p q r]`` (flat frame, z down; 3-2-1 Euler angles;
    velocity and angular velocity along the body's axes, or in the no-roll frame the body's v,
    w and q, r rotated back by phi, phi then carried for output only). Forces, moments, the
    kinematic matrix K, TIB and the weight expression (including its omitted y^2, see the
    module docstring) are the code's. Differences from the printed code:

    - density, speed of sound and the aero coefficients are evaluated at ``state`` (the code
      evaluates them once per RK4 step at the step's start, outside this function);
    - ``wind_m_s`` (flat-frame components, constant) is subtracted from the velocity to give
      the air-relative velocity of every aerodynamic force and moment and of the Mach number;
      the printed code has no wind although the text flies a 5 m/s cross wind;
    - the Mach interpolation holds the table's end values outside Mach 0-8 (interp1: NaN);
    - ``density_altitude="spherical"`` evaluates the atmosphere at |r| - R instead of the
      code's flat-frame -z (the default, ``"flat"``).

    ``atmosphere`` is a name of :data:`harp_analysis.models.atmosphere.ATMOSPHERE_NAMES` or an
    :class:`~harp_analysis.models.atmosphere.AtmosphereModel`.
    """
    check_choice(frame, "frame", _FRAMES)
    model = rigid_body_model(projectile, atmosphere, wind_m_s, density_altitude)
    state = _checked_state(state)
    if frame == "body":
        return _appendix_b(model, state)
    return np.array(right_hand_side(0.0, state, model.kernel))


def integrate_fixed_step(
    derivatives, state0, h_s: float, t_end_s: float
) -> tuple[np.ndarray, np.ndarray]:
    """Appendix B's classical RK4 with a fixed step ``h_s`` from t = 0 to ``t_end_s``.

    ``derivatives(t, state)`` returns the state's time derivative. Returns the times (n + 1,)
    and the states (n + 1, len(state0)); ``t_end_s`` must be a whole number of steps. Used to
    verify :func:`simulate_6dof` against the dissertation's own integration scheme.
    """
    y = finite_array(state0, "state0").copy()
    if y.ndim != 1:
        raise ValueError(f"state0 must be one state vector; got shape {y.shape}")
    h = float(Bounds(low=0.0, low_inclusive=False, unit="s").scalar(h_s, "h_s"))
    t_end = float(Bounds(low=h, unit="s").scalar(t_end_s, "t_end_s"))
    n = round(t_end / h)
    if abs(n * h - t_end) > 1e-9 * t_end:
        raise ValueError(f"t_end_s must be a whole number of steps h_s = {h:g} s; got {t_end:g} s")
    states = np.empty((n + 1, y.size))
    states[0] = y
    for i in range(n):
        t = i * h
        k1 = np.asarray(derivatives(t, y))
        k2 = np.asarray(derivatives(t + 0.5 * h, y + 0.5 * h * k1))
        k3 = np.asarray(derivatives(t + 0.5 * h, y + 0.5 * h * k2))
        k4 = np.asarray(derivatives(t + h, y + h * k3))
        y = y + (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
        states[i + 1] = y
    return np.arange(n + 1) * h, states


@jit
def _radial_velocity(state):
    """r . dr/dt of a no-roll state up to the factor 1/|r|: the apogee event."""
    x, y, z, _, theta, psi, u, v, w, _, _, _ = state
    vx, vy, vz = flat_velocity(theta, psi, u, v, w)
    return x * vx + y * vy + (z - _R) * vz


def simulate_6dof(
    launch: Launch,
    *,
    density_altitude: str = "flat",
    rtol: float = 1e-9,
    max_time_s: float = 400.0,
    output_step_s: float = 0.5,
) -> pd.DataFrame:
    """One 6DOF flight of Appendix B from launch to impact, as the tidy trajectory table.

    Launch from the flat frame's origin with psi = phi = 0, theta = the launch elevation, body
    velocity [speed, 0, 0] and roll rate ``launch.spin_rad_s``; the launch's cross wind blows
    along +y (toward positive cross range), its head wind along -x. The equations are Appendix
    B's (:func:`appendix_b_derivatives`) integrated in the no-roll frame (its
    ``frame="no_roll"``) by scipy's DOP853 with relative tolerance ``rtol``; air
    density at the flat-frame altitude as Appendix B takes it, or ``density_altitude=
    "spherical"``.

    Rows every ``output_step_s`` (dense output) and at the end: the impact, where the spherical
    altitude |r| - R returns to zero, or ``max_time_s`` if it comes first (a
    TruncatedFlightWarning). Columns: :data:`harp_analysis.models.trajectory.BASE_COLUMNS` (x_m,
    y_m, z_m in the flat frame, z down; speed relative to the non-rotating frame; Mach and angle of
    attack air-relative; ``drag_coefficient`` the applied axial coefficient -CX0 - CX2 (v^2 +
    w^2)/V^2; ``drag_to_gravity`` the aerodynamic force component opposing the air-relative
    velocity over m GM / |r|^2) and :data:`harp_analysis.models.rigid_body.EXTRA_COLUMNS`;
    ``frame.attrs`` the shared metadata
    (:func:`harp_analysis.models.trajectory.describe`).

    Parameters
    ----------
    launch : Launch
        The launch to fly (its projectile needs Appendix B's aerodynamic tables: HP or LP).
    density_altitude : str
        ``"flat"`` (the air at the flat frame's altitude, as Appendix B) or ``"spherical"``.
    rtol : float
        DOP853's relative tolerance.
    max_time_s : float
        The longest flight (s); one cut off here warns (TruncatedFlightWarning).
    output_step_s : float
        Seconds between rows.

    Returns
    -------
    pandas.DataFrame
        The 6DOF's flight as the engines' trajectory table
        (:mod:`harp_analysis.models.trajectory`), rows ``output_step_s`` apart, with what every
        engine records in ``frame.attrs``.
    """
    model = rigid_body_launch(launch, "6DOF", density_altitude)
    projectile = launch.projectile
    rtol = Bounds(low=1e-13, high=1e-3).scalar(rtol, "rtol")
    max_time = positive_scalar(max_time_s, "max_time_s", "s")
    step = positive_scalar(output_step_s, "output_step_s", "s")

    def impact(t, y):
        return math.sqrt(y[0] ** 2 + y[1] ** 2 + (_R - y[2]) ** 2) - _R

    def apogee(t, y):
        return _radial_velocity(y)

    def singular_pitch(t, y):
        return math.cos(y[4]) - SINGULAR_PITCH_COSINE

    # The launch is upward, so the altitude leaves zero increasing: only a downward crossing
    # (direction -1) is an impact and the launch point is not one.
    # (solve_ivp reads an event's options from attributes of the function)
    impact.terminal, impact.direction = True, -1  # type: ignore[attr-defined]
    apogee.direction = -1  # type: ignore[attr-defined]
    singular_pitch.terminal, singular_pitch.direction = True, -1  # type: ignore[attr-defined]
    y0 = launch_state(launch)
    kernel = model.kernel
    try:
        solution = solve_ivp(
            lambda t, y: right_hand_side(t, y, kernel),
            (0.0, max_time),
            y0,
            method="DOP853",
            rtol=rtol,
            atol=_ATOL,
            dense_output=True,
            events=(impact, apogee, singular_pitch),
        )
    except (ArithmeticError, ValueError) as exc:
        raise RuntimeError(f"6DOF integration of {projectile.name} failed: {exc}") from exc
    if solution.status < 0:
        raise RuntimeError(
            f"6DOF integration of {projectile.name} failed at "
            f"t = {solution.t[-1]:.3f} s: {solution.message}"
        )
    if solution.t_events[2].size:
        raise RuntimeError(
            f"6DOF flight of {projectile.name} stopped at t = "
            f"{solution.t[-1]:.3f} s: the pitch reached +-90 deg, the singularity "
            "of Appendix B's Euler angles"
        )

    return flight_table(
        model,
        solution,
        launch,
        "6DOF",
        output_step_s=step,
        max_time_s=max_time,
        rtol=rtol,
        density_altitude=density_altitude,
    )
