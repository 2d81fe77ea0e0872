"""The figures of Chapter 3's Modified Kepler equation (notebook 03): the polar coordinates of a
trajectory (Fig 3.1), the straight line of eq 3.16 (Fig 3.3) and the open-loop frequency response
of eqs 3.29-3.30 (Fig 3.4), with the sampling that draws Fig 3.4's undamped resonances."""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import Rectangle

from ...analyses import comparisons, scenarios
from ...engines import mks, nonlinear_kepler
from ...foundation import earth
from ...models.launch import Launch
from .. import plotting
from ..plotting import FULL_WIDTH_IN, new_figure

__all__ = [
    "draw_polar_coordinates",
    "draw_straight_line",
    "draw_frequency_response",
    "resonance_grid",
]

_RADIUS_KM = earth.RADIUS_M / 1e3
_RADIUS_LOOK: dict[str, Any] = {"color": "k", "lw": 0.8, "ls": "--"}
_ARROW: dict[str, Any] = {"arrowstyle": "->", "lw": 0.8}
#: Fig 3.1 (a): the Earth's surface drawn from and to these angles (rad) about its centre.
_SURFACE_RAD = (np.radians(-16), np.radians(22))
#: Fig 3.1 (b)'s window in (a), (x, y, width, height) in km.
_WINDOW_KM = (-30.0, _RADIUS_KM - 70, 470.0, 220.0)


def _xy(angle, r):
    """Axes in the plane of flight about the Earth's centre O, y through the launch point."""
    return np.sin(angle) * r, np.cos(angle) * r


def draw_polar_coordinates(launch: Launch) -> Figure:
    """Fig 3.1: the MKS of ``launch`` (:func:`~harp_analysis.analyses.comparisons.fly`) in the plane
    of flight about the Earth's centre O, with r and theta marked at the apogee; both panels at true
    scale with equal axes: (a) the whole sector, (b) the window marked in (a), near the surface."""
    solution = comparisons.fly(launch)[1]
    angles = np.linspace(0, solution.impact_angle, 300)
    radius_km = _RADIUS_KM + solution.altitude(angles) / 1e3
    apogee = solution.apogee_angle
    apogee_km = solution.altitude(apogee).item() / 1e3
    theta_label = rf"$\theta$ = {np.degrees(apogee):.2f}°"
    fig, (whole, near) = new_figure(1, 2, figsize=(FULL_WIDTH_IN, 2.9), layout="constrained",
                                    gridspec_kw={"width_ratios": [1, 3.2]})  # fmt: skip
    # (a) the sector about the Earth's centre
    ground = np.linspace(*_SURFACE_RAD, 200)
    gx, gy = _xy(ground, _RADIUS_KM)
    whole.fill(np.r_[0, gx, 0], np.r_[0, gy, 0], color="0.9", lw=0)
    whole.plot(gx, gy, "k", lw=1)
    whole.plot(*_xy(angles, radius_km), color=plotting.ENGINE_STYLES["MKS"]["color"], lw=1.5)
    whole.plot([0, 0], [0, _RADIUS_KM], **_RADIUS_LOOK)
    whole.plot(*zip((0, 0), _xy(apogee, _RADIUS_KM + apogee_km)), **_RADIUS_LOOK)
    whole.plot(0, 0, "ko", ms=4)
    whole.annotate("$R$", (0, 0.7 * _RADIUS_KM), xytext=(-4, 0), textcoords="offset points",
                   ha="right", va="center", fontsize=8)  # fmt: skip
    whole.annotate("O", (0, 0), xytext=(0, -5), textcoords="offset points", ha="center",
                   va="top", fontsize=8)  # fmt: skip
    whole.annotate(theta_label, _xy(apogee / 2, 0.45 * _RADIUS_KM), xytext=(22, -10),
                   textcoords="offset points", ha="left", va="center", fontsize=8,
                   arrowprops=_ARROW)  # fmt: skip
    x0, y0, width, height = _WINDOW_KM
    whole.add_patch(Rectangle((x0, y0), width, height, fill=False, lw=0.8, color="k"))
    whole.annotate("(b)", (x0 + width, y0 + height), xytext=(2, 2), textcoords="offset points",
                   fontsize=8)  # fmt: skip
    whole.set_aspect("equal")
    whole.set_xlim(-1700, 2500)
    whole.set_ylim(-800, _RADIUS_KM + 500)
    whole.set_xlabel("$x$ (km)")
    whole.set_ylabel("$y$ (km)")
    whole.set_title("(a) about the Earth's centre O", fontsize=9)

    # (b) the flight, near the surface
    bottom, top = y0 - _RADIUS_KM, y0 + height - _RADIUS_KM
    near.plot(gx, gy - _RADIUS_KM, "k", lw=1)
    near.plot(*np.array(_xy(angles, radius_km)) - [[0], [_RADIUS_KM]],
              **plotting.style("MKS", "baseline") | {"lw": 1.8},
              label=f"MKS, baseline at {launch.elevation_deg:g}°")  # fmt: skip
    apogee_x, apogee_y = _xy(apogee, _RADIUS_KM + apogee_km)
    foot_x, foot_y = _xy(apogee, y0)
    near.plot([0, 0], [bottom, apogee_y - _RADIUS_KM], **_RADIUS_LOOK)
    near.plot([foot_x, apogee_x], [foot_y - _RADIUS_KM, apogee_y - _RADIUS_KM], **_RADIUS_LOOK)
    for x in (0.0, foot_x):  # both radii run down to O
        near.annotate("", (x, bottom), xytext=(x, bottom + 22), arrowprops=_ARROW)
    near.plot(apogee_x, apogee_y - _RADIUS_KM, "ko", ms=3)
    near.annotate(rf"$r = R$ + {apogee_km:.0f} km at the apogee",
                  (apogee_x, apogee_y - _RADIUS_KM), xytext=(22, 12), textcoords="offset points",
                  fontsize=8, va="bottom", arrowprops=_ARROW)  # fmt: skip
    near.annotate(f"{theta_label} between\nthe radii, which meet\nat O, {_RADIUS_KM:.0f} km below",
                  (foot_x, bottom + 4), xytext=(8, 0), textcoords="offset points", ha="left",
                  va="bottom", fontsize=8)  # fmt: skip
    near.set_aspect("equal")
    near.set_xlim(x0, x0 + width)
    near.set_ylim(bottom, top)
    near.set_xlabel("$x$ (km)")
    near.set_ylabel("$y - R$ (km)")
    near.set_title("(b) near the surface; both panels true scale, equal axes", fontsize=9)
    near.legend(loc="upper left")
    return fig


#: Fig 3.3's lower atmosphere.
_STRAIGHT_LINE_TOP_M = 40e3


def draw_straight_line(launch: Launch) -> Figure:
    """Fig 3.3: altitude against angular range on the way up below 40 km, the 3DOF's and the
    MKS's flight of ``launch`` (:func:`~harp_analysis.analyses.comparisons.fly`) and eq 3.16's
    straight line a = theta r0 tan(phi0)
    (:func:`~harp_analysis.analyses.scenarios.straight_line_altitude_m`)."""
    flight, solution, _ = comparisons.fly(launch)
    low = scenarios.ascent_below(flight, _STRAIGHT_LINE_TOP_M)
    angle = low.ground_range_m / earth.RADIUS_M
    line_m = scenarios.straight_line_altitude_m(low.ground_range_m, launch.elevation_rad)
    fig, ax = new_figure(figsize=(FULL_WIDTH_IN, 3.6), layout="constrained")
    ax.plot(angle * 1e3, low.altitude_m / 1e3, **plotting.style("3DOF", "baseline"), label="3DOF")
    ax.plot(angle * 1e3, solution.altitude(angle.to_numpy()) / 1e3,
            **plotting.style("MKS", "baseline") | {"markevery": (0.04, 0.08)},
            label="MKS")  # fmt: skip
    ax.plot(angle * 1e3, line_m / 1e3, color="k", lw=0.9, ls=(0, (6, 3)),
            label=r"$a = \theta\, r_0 \tan\phi_0$ (eq 3.16)")  # fmt: skip
    ax.set_xlabel(r"angular range $\theta$ (mrad)")
    ax.set_ylabel("altitude $a$ (km)")
    ax.legend()
    return fig


#: Fig 3.4's axis top: each curve reaches it at its resonance, where it is unbounded.
_RESPONSE_TOP = 1e2
#: Fig 3.4's frequencies (rad/rad) before the resonances are added (:func:`resonance_grid`).
_FREQUENCIES = np.logspace(-1, 4, 600)


def draw_frequency_response(launch: Launch) -> Figure:
    """Fig 3.4: the magnitude response of the MKS equation of ``launch``, linearised (eq 3.30,
    omega_n = 1) and nonlinear at launch (eq 3.29, omega_n(0)), with the driving function's rates
    n tau, n = 1, 2, 3 (thin vertical lines); the resonances sampled exactly
    (:func:`resonance_grid`), so each peak runs off the axis."""
    solution = mks.for_launch(launch)
    initial = nonlinear_kepler.initial_natural_frequency(solution)
    fig, ax = new_figure(figsize=(FULL_WIDTH_IN, 3.8), layout="constrained")
    for omega_n, look, label in (
        (1.0, {"lw": 2.0}, r"linearised (eq 3.30), $\omega_n = 1$"),
        (initial, {"linestyle": "--"},
         rf"nonlinear at launch (eq 3.29), $\omega_n(0)$ = {initial:.1f}"),
    ):  # fmt: skip
        omega = resonance_grid(_FREQUENCIES, omega_n, _RESPONSE_TOP)
        ax.loglog(omega, nonlinear_kepler.frequency_response(omega, omega_n),
                  **plotting.style("MKS") | look, label=label)  # fmt: skip
    for n, rate in enumerate(nonlinear_kepler.driving_rates(solution), start=1):
        ax.axvline(rate, color="0.45", lw=0.8, ls=(0, (1, 2)))
        ax.annotate(rf"${n if n > 1 else ''}\tau$", (rate, 3e1 / 10 ** (n - 1)), xytext=(2, 0),
                    textcoords="offset points", fontsize=8, ha="left", va="center")  # fmt: skip
    ax.set_xlabel(r"frequency along the angular range $\omega$ (rad/rad)")
    ax.set_ylabel(r"$|$response$|$ (per unit forcing)")
    ax.set_ylim(1e-8, _RESPONSE_TOP)
    ax.legend(loc="lower left")
    return fig


def resonance_grid(omega, natural_frequencies, level: float) -> np.ndarray:
    """The frequencies ``omega`` (rad/rad) with, for each of ``natural_frequencies``, the two
    where the undamped response |1/(omega_n^2 - omega^2)| equals ``level`` and the two where it
    is a million times more: a curve drawn through them reaches an axis topped at ``level`` at
    every resonance, whatever the spacing of ``omega``, and leaves it there (the response is
    unbounded at omega_n), instead of peaking at whatever height the nearest sample has."""
    extra = []
    for omega_n in np.atleast_1d(natural_frequencies):
        for height in (level, 1e6 * level):
            for sign in (-1.0, 1.0):
                squared = omega_n**2 + sign / height
                if squared > 0:
                    extra.append(np.sqrt(squared))
    return np.unique(np.concatenate([np.asarray(omega, dtype=float), extra]))
