"""The figures of the atmosphere (notebook 01): the models against the 1976 US Standard
Atmosphere (Fig 2.1), eq 3.11's exponential (Fig 3.2), and how flat the exponential's R^2 is in
its decay constant, reporting on :mod:`harp_analysis.models.atmosphere`.

One look per curve, the same in every figure: the 1976 standard is the black reference line;
each atmosphere model has the colour of the engine whose air it is (the two-segment model the
6DOF's, Appendix A's three layers the 3DOF's, the exponential the MKS's), told apart by line
style and marker too; the text's exponential is grey like every value the text states.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.figure import Figure

from ...models import atmosphere as atm
from ..plotting import ENGINE_STYLES, FULL_WIDTH_IN, OKABE_ITO, new_figure

__all__ = ["draw_density_models", "draw_exponential_model", "draw_r_squared_flatness"]

_STANDARD: dict[str, Any] = {"color": OKABE_ITO["black"], "linewidth": 2.2}
_STANDARD_LABEL = "US Standard Atmosphere 1976"
_MARKS: dict[str, Any] = {"markersize": 4, "markevery": 0.08, "markerfacecolor": "none"}
#: Markers between those of a curve drawn with :data:`_MARKS` over the same altitudes.
_MARKS_BETWEEN = _MARKS | {"markevery": (0.04, 0.08)}
_MKS_AIR = ENGINE_STYLES["MKS"]["color"]
#: Fig 2.1's models: their labels and looks.
_MODELS: dict[str, tuple[str, dict[str, Any]]] = {
    "two_segment": (
        "multi-stage model, eqs 2.1-2.2 (App. B)",
        {"color": ENGINE_STYLES["6DOF"]["color"], "linestyle": "--", "marker": "D", **_MARKS},
    ),
    "three_layer": (
        "three-layer model (App. A)",
        {"color": ENGINE_STYLES["3DOF"]["color"], "linestyle": ":", "linewidth": 2.0,
         "marker": "v", **_MARKS_BETWEEN},
    ),
}  # fmt: skip
#: The points of each density curve from the ground to the figure's top.
_ALTITUDE_POINTS = 1001


def _altitudes_m(top_altitude_km: float) -> np.ndarray:
    return np.linspace(0.0, top_altitude_km * 1e3, _ALTITUDE_POINTS)


def draw_density_models(top_altitude_km: float = 100.0) -> Figure:
    """Fig 2.1: the density of eqs 2.1-2.2's multi-stage model (as Appendix B codes it) and of
    Appendix A's three layers against the 1976 standard up to ``top_altitude_km``, above; each
    model's error against the standard (%) below, linear within +-1 % and logarithmic beyond."""
    altitude_m = _altitudes_m(top_altitude_km)
    standard = atm.standard_density(altitude_m)
    fig, (top, bottom) = new_figure(2, 1, sharex=True, figsize=(FULL_WIDTH_IN, 5.6),
                                    gridspec_kw={"height_ratios": [3, 2]},
                                    layout="constrained")  # fmt: skip
    top.semilogy(altitude_m / 1e3, standard, **_STANDARD, label=_STANDARD_LABEL)
    for name, (label, look) in _MODELS.items():
        density = atm.get_atmosphere(name).density(altitude_m)
        top.semilogy(altitude_m / 1e3, density, **look, label=label)
        bottom.plot(altitude_m / 1e3, 100 * (density / standard - 1), **look)
    top.set_ylabel(r"density $\rho$ (kg/m$^3$)")
    top.legend()
    bottom.axhspan(-1, 1, color="0.85", label=r"within $\pm$1 %")
    bottom.axhline(0, color="k", lw=0.6)
    bottom.set_xlabel("altitude (km)")
    bottom.set_yscale("symlog", linthresh=1.0)
    bottom.set_ylabel("error vs the 1976\nstandard (%)")
    bottom.legend(loc="upper left")
    return fig


def draw_exponential_model(top_altitude_km: float = 100.0) -> Figure:
    """Fig 3.2: eq 3.11's exponential density with the text's decay constant and with the
    least-squares optimum of the literal reading
    (:func:`~harp_analysis.models.atmosphere.literal_fit`) against the 1976 standard up to
    ``top_altitude_km``."""
    altitude_m = _altitudes_m(top_altitude_km)
    fit = atm.literal_fit()
    text_k_per_km = atm.TEXT_DECAY_CONSTANT_PER_M * 1e3
    fig, ax = new_figure(figsize=(FULL_WIDTH_IN, 3.8), layout="constrained")
    ax.semilogy(altitude_m / 1e3, atm.standard_density(altitude_m), **_STANDARD,
                label=_STANDARD_LABEL)  # fmt: skip
    ax.semilogy(altitude_m / 1e3, atm.exponential_density(altitude_m),
                color=OKABE_ITO["grey"], linestyle="--", marker="x", **_MARKS,
                label=rf"exponential, $k$ = {text_k_per_km:.3f} km$^{{-1}}$ (text)")  # fmt: skip
    ax.semilogy(altitude_m / 1e3, atm.exponential_density(altitude_m, fit.decay_constant_per_m),
                color=_MKS_AIR, linestyle=":", linewidth=2.0, marker="D", **_MARKS_BETWEEN,
                label=rf"exponential, $k$ = {fit.decay_constant_per_km:.4f} km$^{{-1}}$ "
                      rf"(fit, $R^2$ = {fit.r_squared:.4f})")  # fmt: skip
    ax.set_xlabel("altitude (km)")
    ax.set_ylabel(r"density $\rho$ (kg/m$^3$)")
    ax.set_ylim(1e-8, 3)
    ax.legend(loc="lower left")
    return fig


#: The decay constants (1/km) :func:`draw_r_squared_flatness` scores by default.
_DECAY_CONSTANTS_PER_KM = np.linspace(0.10, 0.13, 121)
#: The altitude ranges (km) of :func:`draw_r_squared_flatness` and each one's look.
_FIT_TOPS_KM: dict[int, dict[str, Any]] = {
    20: {"linestyle": "-", "marker": "P"},
    50: {"linestyle": "--", "marker": "D"},
    100: {"linestyle": ":", "marker": "v", "linewidth": 2.0},
}


def draw_r_squared_flatness(k_per_km=_DECAY_CONSTANTS_PER_KM) -> Figure:
    """R^2 of the densities of eq 3.11's model (rho0 fixed, 1 km grid) against its decay
    constant ``k_per_km`` over 0-20, 0-50 and 0-100 km, with the text's k and R^2: flat near its
    maximum, so the text's k scores nearly the optimum (notebook 01; no figure of the text)."""
    fig, ax = new_figure(figsize=(FULL_WIDTH_IN, 3.8), layout="constrained")
    for top_km, look in _FIT_TOPS_KM.items():
        definition = atm.FitDefinition(top_km * 1e3, 1e3, "linear")
        r2 = [atm.model_r_squared(definition, k / 1e3) for k in k_per_km]
        ax.plot(k_per_km, r2, color=_MKS_AIR, **look, **_MARKS, label=f"0-{top_km} km")
    ax.axvline(atm.TEXT_DECAY_CONSTANT_PER_M * 1e3, color="k", lw=0.8, ls="--",
               label=r"text's $k$")  # fmt: skip
    ax.axhline(atm.TEXT_R_SQUARED, color="k", lw=0.8, ls=":", label=r"text's $R^2$")
    ax.set_ylim(0.985, 0.997)
    ax.set_xlabel(r"$k$ (km$^{-1}$)")
    ax.set_ylabel("$R^2$ of the densities")
    ax.legend()
    return fig
