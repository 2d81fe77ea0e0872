"""The figures of notebook 08 (X.3-X.7): reporting on :mod:`~harp_analysis.analyses.error_budget`,
:mod:`.confidence` and :mod:`.mks_improvement`. Each function draws from the tables the
analyses return and returns the figure; the notebook saves it."""

from __future__ import annotations

import math
from typing import Any, cast

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.artist import Artist
from matplotlib.colors import LinearSegmentedColormap, SymLogNorm
from matplotlib.lines import Line2D
from matplotlib.patches import Patch, Rectangle
from matplotlib.patheffects import withStroke
from matplotlib.ticker import FuncFormatter, LogFormatterSciNotation
from matplotlib.transforms import blended_transform_factory

from ...analyses.error_budget import CHAPTER_7B, OUTPUTS, Uncertainty
from ...analyses.mks_improvement import error_differences_m
from ...engines.mks import BETA_VALIDITY_LIMIT
from ...engines.mks_improved import VARIANTS
from ..plotting import (
    ENGINE_STYLES,
    FULL_WIDTH_IN,
    HOUSE_STYLE,
    OKABE_ITO,
    elevation_style,
    new_figure,
    style,
)

__all__ = [
    "launch_style",
    "size_label",
    "draw_error_budget",
    "draw_sensitivity",
    "draw_harp_confidence",
    "draw_judged",
    "draw_error_maps",
]

_BASELINE_ELEVATIONS = (30.0, 45.0, 65.0, 85.0)
_NEUTRAL = "#4D4D4D"  # a projectile that is neither an engine nor a measurement


def launch_style(name: str) -> dict:
    """Marker keywords of a representative launch
    (:func:`~harp_analysis.analyses.error_budget.representative_launches`): the baseline cone in the
    house's elevation shades and markers, HP with its open circle, the Martlet with a star, both in
    dark grey."""
    if name.startswith("baseline"):
        elevation = float(name.split(",")[1].split()[0])
        look = elevation_style(elevation, _BASELINE_ELEVATIONS)
        return {"color": look["color"], "marker": look["marker"]}
    if name.startswith("HP"):
        return {"color": _NEUTRAL, "marker": "o", "markerfacecolor": "none"}
    return {"color": _NEUTRAL, "marker": "*", "markersize": 7}


#: How Figure X.3 prints each input's 1-sigma size: (factor from the field's unit, unit).
_SIZE_UNITS = {
    "elevation_deg": (math.radians(1.0) * 1e3, "mrad"),
    "bearing_deg": (math.radians(1.0) * 1e3, "mrad"),
    "speed_m_s": (1.0, "m/s"),
    "latitude_deg": (3600.0, "arcsec"),
    "fire_time_s": (1e3, "ms"),
    "density_change_fraction": (100.0, "%"),
    "temperature_change_k": (1.0, "K"),
    "cross_wind_m_s": (1.0, "m/s"),
    "head_wind_m_s": (1.0, "m/s"),
}


def size_label(uncertainty: Uncertainty) -> str:
    """An input's name and its 1-sigma size in a reader's unit, e.g. ``elevation, 1 mrad``."""
    factor, unit = _SIZE_UNITS[uncertainty.field]
    return f"{uncertainty.name}, {uncertainty.sd * factor:.3g} {unit}"


def _zero_at_the_edge(ax, values_km: np.ndarray) -> float:
    """A log axis cannot show 0: put it a decade below the smallest positive value, at the
    axis's left end, tick it "0" and mark the break; returns where zeros are drawn (km)."""
    positive = values_km[values_km > 0]
    zero_at = 10.0 ** (np.floor(np.log10(positive.min())) - 1)
    ax.set_xlim(left=zero_at / 10**0.2)
    default = LogFormatterSciNotation()

    def label(value, position):
        return "0" if np.isclose(value, zero_at) else default(value, position)

    ax.xaxis.set_major_formatter(FuncFormatter(label))
    break_mark = blended_transform_factory(ax.transData, ax.transAxes)
    ax.text(zero_at * 10**0.5, 0.0, "//", transform=break_mark, ha="center", va="center",
            fontsize=9, backgroundcolor="white", clip_on=False)  # fmt: skip
    return zero_at


def draw_error_budget(
    inputs: dict[str, pd.DataFrame], budget: pd.DataFrame, uncertainties=CHAPTER_7B
):
    """Figure X.3: for each launch, each input's 1-sigma miss (one at a time; the size in the
    row's label), the miss of all of them at once (Monte Carlo) and the MKS's model error, at
    the impact point and at the nominal apogee time; a log scale whose left end, ticked "0",
    holds the inputs that cannot move an output at all; one marker per launch, rows offset per
    launch."""
    names = list(inputs)
    sizes = {u.name: size_label(u) for u in uncertainties}
    rows = [
        *(sizes[name] for name in next(iter(inputs.values())).index),
        "all inputs (Monte Carlo)",
        "MKS model error",
    ]
    fig, axes = new_figure(1, 2, figsize=(FULL_WIDTH_IN, 5.0), sharey=True, layout="constrained")
    offsets = np.linspace(-0.3, 0.3, len(names))
    for ax, output, title in zip(
        axes, ("impact", "position"), ("impact point", "position at the apogee time")
    ):
        values = {
            name: np.array(
                [
                    *inputs[name][f"{output}_m"],
                    budget.loc[(name, output), "dispersion_m"],
                    budget.loc[(name, output), "mks_error_m"],
                ]
            )
            / 1e3
            for name in names
        }
        ax.set_xscale("log")
        zero_at = _zero_at_the_edge(ax, np.concatenate(list(values.values())))
        for offset, name in zip(offsets, names):
            shown = np.where(values[name] > 0, values[name], zero_at)
            look = {"linestyle": "none", "markersize": 5, **launch_style(name)}
            ax.plot(shown, np.arange(len(rows)) + offset, label=name, clip_on=False, **look)
        ax.axhspan(len(rows) - 2.5, len(rows) - 0.5, color=OKABE_ITO["grey"], alpha=0.12, lw=0)
        ax.set_title(title.capitalize(), fontsize=10)
    axes[0].set_yticks(range(len(rows)), rows, fontsize=8.5)
    axes[0].invert_yaxis()
    fig.supxlabel("distance from the nominal 3DOF flight (km)", fontsize=10)
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside upper center", ncol=3, fontsize=8)
    return fig


def draw_sensitivity(indices: dict[str, pd.DataFrame]):
    """Figure X.4: total Sobol' indices (SALib) of each input (rows) for each launch (columns),
    one panel per output; grey shades with the index printed in each cell (values below 0.005
    print as a dot)."""
    names = list(indices)
    inputs = list(next(iter(indices.values())).index)
    titles = {
        "apogee": "apogee\naltitude",
        "impact_downrange": "impact,\ndownrange",
        "impact_crossrange": "impact,\ncross range",
        "position_along_track": "position at apogee\ntime, along track",
    }
    fig, axes = new_figure(
        1, len(OUTPUTS), figsize=(FULL_WIDTH_IN, 4.4), sharey=True, layout="constrained"
    )
    for ax, output in zip(axes, OUTPUTS):
        values = np.array([indices[name][f"{output}_ST"].to_numpy() for name in names]).T
        values = np.clip(values, 0.0, 1.0)
        ax.imshow(values, cmap="Greys", vmin=0.0, vmax=1.0, aspect="auto")
        for (i, j), value in np.ndenumerate(values):
            text = "·" if value < 0.005 else f"{value:.2f}".lstrip("0")
            ax.text(j, i, text, ha="center", va="center", fontsize=6.5,
                    color="white" if value > 0.55 else "black")  # fmt: skip
        ax.set_xticks(range(len(names)), names, fontsize=7, rotation=90)
        ax.set_title(titles[output], fontsize=8.5)
        ax.grid(False)
    axes[0].set_yticks(range(len(inputs)), inputs)
    return fig


#: Figure X.5's markers: (a) the statistic, (b) the air each site's rounds were flown in.
_STATISTIC_MARKERS = {"mean": "o", "std": "s"}
_AIR_MARKERS = {"site": "^", "temperature": "D"}
#: Figure X.5's hatched band behind the statistics of the site the drag area was fitted to.
_RECOVERED_BAND: dict[str, Any] = {"facecolor": "none", "edgecolor": OKABE_ITO["grey"], "lw": 0.0,
                                   "hatch": "////", "alpha": 0.5, "zorder": 0}  # fmt: skip


def _interval_point(ax, y: float, estimate_m: float, low_m: float, high_m: float, marker: str):
    """An estimate (km) and its 95 % interval as a black marker with bars, open where the
    interval holds zero (the one rule of both panels of Figure X.5)."""
    zero_inside = low_m <= 0.0 <= high_m
    measured = style("measured")
    ax.errorbar(
        estimate_m / 1e3,
        y,
        xerr=[[(estimate_m - low_m) / 1e3], [(high_m - estimate_m) / 1e3]],
        color=measured["color"],
        marker=marker,
        markerfacecolor="white" if zero_inside else measured["color"],
        capsize=3,
        linestyle="none",
    )


def draw_harp_confidence(
    residuals: pd.DataFrame,
    transfers: pd.DataFrame,
    text_std_km: dict,
    text_mean_km: dict,
    recovered_site: str | None = None,
):
    """Figure X.5: (a) each site's residual mean (circle) and standard deviation (square) with
    their 95 % intervals (Student's t, Bonett's: confidence.residual_intervals); (b) the
    mean residual of one site's rounds predicted with the drag area fitted at the other, with
    the text's densities (triangle) and with each site's density following its Mach-column
    temperature (diamond), with bootstrap intervals. In both panels a marker is open
    where its interval holds zero; the text's values (``text_std_km``, and ``text_mean_km``
    where the text gives a mean with its sign) are grey crosses. The statistics of
    ``recovered_site``, whose rounds the model's drag area was fitted to
    (:func:`harp_analysis.analyses.harp.apogees.fitted_site`), are recovered, not predicted:
    drawn apart on a hatched band and labelled so. One legend below both."""
    fig, (stats, transfer) = new_figure(1, 2, figsize=(FULL_WIDTH_IN, 3.9), layout="constrained")
    text_look = {"markersize": 9, "mew": 1.6, "zorder": 5, **style("text")}
    recovered = [site == recovered_site for site, _ in residuals.index]
    _draw_residual_statistics(stats, residuals, recovered, text_look, text_std_km, text_mean_km)
    _draw_transfers(transfer, transfers, text_look, text_mean_km)
    for ax in (stats, transfer):
        ax.axvline(0.0, color=OKABE_ITO["grey"], lw=0.8)
        ax.invert_yaxis()
    black: dict[str, Any] = {"color": OKABE_ITO["black"], "linestyle": "none"}
    handles: list[Artist] = [
        Line2D([], [], marker="o", label="(a) mean", **black),
        Line2D([], [], marker="s", label="(a) standard deviation", **black),
        Line2D([], [], marker="^", label="(b) the text's surface densities", **black),
        Line2D([], [], marker="D", label="(b) air from the Mach column", **black),
        Line2D([], [], marker="o", markerfacecolor="white", label="open: 0 inside the interval",
               **black),
        Line2D([], [], label="the text's value", **text_look),
    ]  # fmt: skip
    if any(recovered):
        handles.append(
            Patch(**_RECOVERED_BAND, label="(a) recovered: drag area fitted to these rounds")
        )
    fig.legend(handles=handles, loc="outside lower center", ncol=2 if any(recovered) else 3,
               fontsize=8)  # fmt: skip
    return fig


def _draw_residual_statistics(
    ax, residuals: pd.DataFrame, recovered: list[bool], text_look: dict, text_std_km: dict,
    text_mean_km: dict,
) -> None:  # fmt: skip
    """Figure X.5 (a): each site's residual mean and standard deviation with their intervals,
    the text's values beside them, the ``recovered`` site's rows on a hatched band."""
    for y, is_recovered in enumerate(recovered):
        if is_recovered:
            ax.axhspan(y - 0.5, y + 0.5, **_RECOVERED_BAND)
    for y, ((site, statistic), row) in enumerate(residuals.iterrows()):
        _interval_point(ax, y, row.estimate_m, row.low_m, row.high_m,
                        _STATISTIC_MARKERS[statistic])  # fmt: skip
        text = (text_std_km if statistic == "std" else text_mean_km).get(site)
        if text is not None:
            ax.plot(text, y, **text_look)
    ax.set_yticks(
        range(len(residuals)),
        [
            f"{s.capitalize()}, {t}" + ("\n(recovered)" if is_recovered else "")
            for (s, t), is_recovered in zip(residuals.index, recovered)
        ],
        fontsize=8,
    )
    ax.set_xlabel("residual statistic (km)")
    ax.set_title("(a) residuals: measured $-$ MKS", fontsize=9.5)


def _draw_transfers(ax, transfers: pd.DataFrame, text_look: dict, text_mean_km: dict) -> None:
    """Figure X.5 (b): the mean residual of one site's rounds predicted with the drag area
    fitted at the other, in either air, with its interval and the text's mean beside it."""
    for y, row in enumerate(transfers.itertuples()):
        _interval_point(ax, y, row.mean_residual_m, row.mean_residual_m_low,
                        row.mean_residual_m_high, _AIR_MARKERS[row.densities])  # fmt: skip
        if row.predict_site in text_mean_km:
            ax.plot(text_mean_km[row.predict_site], y, **text_look)
    labels = [
        f"{r.fit_site.capitalize()} $\\to$ {r.predict_site.capitalize()},\n"
        + ("text's air" if r.densities == "site" else "air from Mach")
        for r in transfers.itertuples()
    ]
    ax.set_yticks(range(len(transfers)), labels, fontsize=8)
    ax.set_xlabel("mean residual (km)")
    ax.set_title("(b) the other site's drag area", fontsize=9.5)


def _judged_label(row) -> str:
    name = "cone" if row.projectile == "baseline" else row.projectile
    where = f", {row.latitude_deg:g}° {row.bearing_deg:03.0f}T" if row.rotating else ", still Earth"
    return f"{name} {row.elevation_deg:g}°{where}"


def draw_judged(judged: pd.DataFrame):
    """Figure X.6: on the judging set (launches the improved MKS was not fitted to), the
    largest position error over the flight and the impact point's miss against the 3DOF, of the
    dissertation's MKS and of the improved one, joined per launch; log scale. The
    dissertation's marker is open, and the launch's label gives its beta, where that beta exceeds
    the text's validity (:data:`.mks.BETA_VALIDITY_LIMIT`)."""
    text, better = (judged[judged.variant == v].reset_index(drop=True) for v in VARIANTS)
    beyond = (text.beta > BETA_VALIDITY_LIMIT).to_numpy()
    labels = [
        _judged_label(row) + (rf", $\beta$ = {row.beta:.2f}" if far else "")
        for row, far in zip(text.itertuples(), beyond)
    ]
    fig, axes = new_figure(1, 2, figsize=(FULL_WIDTH_IN, 5.0), sharey=True, layout="constrained")
    y = np.arange(len(text))
    for ax, measure, title in zip(
        axes, ("max_error_m", "impact_miss_m"), ("largest error in flight", "impact point")
    ):
        for i in y:
            ax.plot([text[measure][i] / 1e3, better[measure][i] / 1e3], [i, i],
                    color=OKABE_ITO["grey"], lw=0.7)  # fmt: skip
        mks_look = {**style("MKS"), "linestyle": "none", "marker": "o", "markersize": 5}
        for chosen, name, face in (
            (~beyond, "dissertation's MKS", mks_look["color"]),
            (beyond, rf"dissertation's MKS beyond its validity, $\beta$ > {BETA_VALIDITY_LIMIT:g}",
             "white"),
        ):  # fmt: skip
            ax.plot(text[measure][chosen] / 1e3, y[chosen], label=name, markerfacecolor=face,
                    **mks_look)  # fmt: skip
        look = {**style("improved MKS"), "linestyle": "none", "marker": "s", "markersize": 5}
        ax.plot(better[measure] / 1e3, y, label="improved MKS", **look)
        ax.set_xscale("log")
        ax.set_title(title.capitalize(), fontsize=10)
    axes[0].set_yticks(y, labels, fontsize=7.5)
    axes[0].invert_yaxis()
    fig.supxlabel("error against the 3DOF (km)", fontsize=10)
    handles, names = axes[0].get_legend_handles_labels()
    fig.legend(handles, names, loc="outside upper center", ncol=3, fontsize=7.5)
    return fig


#: The diverging scale of Figure X.7: the improved MKS's hue where it is nearer the 3DOF, the
#: dissertation MKS's where it is farther, each darker the larger the difference, white where
#: they are equal (and, so that the sign reads in grey too, a plus sign on every cell where the
#: improved MKS is farther).
_DIFFERENCE_MAP = LinearSegmentedColormap.from_list(
    "improved_against_mks",
    [
        "#0B3C5D",
        ENGINE_STYLES["improved MKS"]["color"],
        "#FFFFFF",
        ENGINE_STYLES["MKS"]["color"],
        "#5C2800",
    ],
)
#: Below this difference (km) the scale is linear; above, logarithmic (SymLogNorm).
DIFFERENCE_LINEAR_KM = 0.1
#: The plus sign of a cell where the improved MKS is farther: black, haloed in white, so it
#: reads on the dark cells as on the light ones; the validity hatching, mid grey for the same.
_FARTHER: dict[str, Any] = dict(
    marker="+", color=OKABE_ITO["black"], markersize=4.5, mew=0.9, linestyle="none",
    path_effects=[withStroke(linewidth=2.2, foreground="white")],
)  # fmt: skip
_HATCH_GREY = "#8C8C8C"
_OUTSIDE: dict[str, Any] = dict(fill=False, hatch="////", linewidth=0, edgecolor=_HATCH_GREY)
_MAP_MEASURES = {
    "impact_miss_m": "(a) impact point's miss",
    "max_error_m": "(b) largest error in flight",
}


def draw_error_maps(error_map: pd.DataFrame, share_range: tuple[float, float]):
    """Figure X.7: the improved MKS's error minus the dissertation's
    (:func:`.mks_improvement.error_differences_m`, km) over bearing x elevation, one panel per
    latitude; row (a) the impact point's miss, row (b) the largest error in flight. A diverging
    scale from the improved MKS's colour (it is nearer the 3DOF) through white to the MKS's
    (it is farther), linear within :data:`DIFFERENCE_LINEAR_KM` and logarithmic beyond; a plus
    sign where the improved MKS is farther (the sign without colour), hatching on the cells
    outside its validity band ``share_range``, a black dot where it has no solution."""
    differences = error_differences_m(error_map) / 1e3
    latitudes = sorted(error_map.latitude_deg.unique())
    bearings = np.sort(error_map.bearing_deg.unique())
    elevations = np.sort(error_map.elevation_deg.unique())
    largest = float(np.nanmax(np.abs(differences.to_numpy())))
    norm = SymLogNorm(DIFFERENCE_LINEAR_KM, vmin=-largest, vmax=largest, base=10)
    half_bearing, half_elevation = np.diff(bearings).min() / 2, np.diff(elevations).min() / 2
    low, high = share_range
    plt.rcParams.update(HOUSE_STYLE)  # type: ignore[arg-type]  # keys checked at run time
    fig = plt.figure(figsize=(FULL_WIDTH_IN, 5.9), layout="constrained")
    rows = cast(np.ndarray, fig.subfigures(2, 1, hspace=0.04))  # two rows: an array
    for subfigure, (measure, heading) in zip(rows, _MAP_MEASURES.items()):
        axes = subfigure.subplots(1, len(latitudes), sharex=True, sharey=True, squeeze=False)[0]
        for ax, latitude in zip(axes, latitudes):
            here = error_map.latitude_deg == latitude
            points = error_map[here].assign(difference_km=differences[measure][here])
            grid = points.pivot(index="elevation_deg", columns="bearing_deg")
            values = grid.difference_km.to_numpy()
            image = ax.pcolormesh(bearings, elevations, values, cmap=_DIFFERENCE_MAP, norm=norm,
                                  shading="nearest")  # fmt: skip
            share = grid.air_momentum_share.to_numpy()
            for i, j in np.argwhere(~((share > low) & (share <= high))):
                corner = (bearings[j] - half_bearing, elevations[i] - half_elevation)
                ax.add_patch(Rectangle(corner, 2 * half_bearing, 2 * half_elevation, **_OUTSIDE))
            farther = np.argwhere(values > 0)
            ax.plot(bearings[farther[:, 1]], elevations[farther[:, 0]], **_FARTHER)
            missing = np.argwhere(~np.isfinite(values))
            ax.plot(bearings[missing[:, 1]], elevations[missing[:, 0]], "o",
                    color=OKABE_ITO["black"], markersize=3)  # fmt: skip
            ax.grid(False)
            ax.set_xticks([0, 90, 180, 270], ["0", "90", "180", "270"], fontsize=7)
            ax.tick_params(axis="y", labelsize=7)
            ax.set_title(f"latitude {latitude:g}°", fontsize=8)
        subfigure.suptitle(heading, fontsize=9)
        subfigure.supxlabel("bearing (deg T)", fontsize=8)
        subfigure.supylabel("gun elevation (deg)", fontsize=8)
        bar = subfigure.colorbar(image, ax=axes, fraction=0.04, pad=0.02)
        bar.set_label("improved $-$ dissertation (km)", fontsize=7.5)
        bar.ax.tick_params(labelsize=7)
    handles = [
        Line2D([], [], **_FARTHER, label="improved MKS farther from the 3DOF"),
        Patch(**_OUTSIDE, label="outside its validity band"),
        Line2D([], [], marker="o", color=OKABE_ITO["black"], markersize=3, linestyle="none",
               label="no re-entry solution"),
    ]  # fmt: skip
    fig.legend(handles=handles, loc="outside lower center", ncol=3, fontsize=7.5)
    return fig
