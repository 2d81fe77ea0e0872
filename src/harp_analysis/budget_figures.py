"""The figures of notebook 08 (X.3-X.7): reporting on :mod:`.error_budget`,
:mod:`.harp_confidence` and :mod:`.mks_improvement`. Each function draws from the tables the
analyses return and returns the figure; the notebook saves it."""

from __future__ import annotations

import numpy as np
import pandas as pd

from .error_budget import OUTPUTS
from .mks_improved import VARIANTS
from .plotting import FULL_WIDTH_IN, OKABE_ITO, elevation_style, new_figure, style

__all__ = [
    "launch_style",
    "draw_error_budget",
    "draw_sensitivity",
    "draw_harp_confidence",
    "draw_judged",
    "draw_error_maps",
]

_BASELINE_ELEVATIONS = (30.0, 45.0, 65.0, 85.0)
_NEUTRAL = "#4D4D4D"  # a projectile that is neither an engine nor a measurement


def launch_style(name: str) -> dict:
    """Marker keywords of a representative launch (:func:`error_budget.representative_launches`):
    the baseline cone in the house's elevation shades and markers, HP with its open circle,
    the Martlet with a star, both in dark grey."""
    if name.startswith("baseline"):
        elevation = float(name.split(",")[1].split()[0])
        look = elevation_style(elevation, _BASELINE_ELEVATIONS)
        return {"color": look["color"], "marker": look["marker"]}
    if name.startswith("HP"):
        return {"color": _NEUTRAL, "marker": "o", "markerfacecolor": "none"}
    return {"color": _NEUTRAL, "marker": "*", "markersize": 7}


def draw_error_budget(inputs: dict[str, pd.DataFrame], budget: pd.DataFrame):
    """Figure X.3: for each launch, each input's 1-sigma miss (one at a time), the miss of all
    of them at once (Monte Carlo) and the MKS's model error, at the impact point and at the
    nominal apogee time; a log scale, one marker per launch, rows offset per launch."""
    names = list(inputs)
    rows = [*next(iter(inputs.values())).index, "all inputs (Monte Carlo)", "MKS model error"]
    fig, axes = new_figure(1, 2, figsize=(FULL_WIDTH_IN, 4.6), sharey=True)
    offsets = np.linspace(-0.3, 0.3, len(names))
    for ax, output, title in zip(
        axes, ("impact", "position"), ("impact point", "position at the apogee time")
    ):
        for offset, name in zip(offsets, names):
            values = [
                *inputs[name][f"{output}_m"],
                budget.loc[(name, output), "dispersion_m"],
                budget.loc[(name, output), "mks_error_m"],
            ]
            y = np.arange(len(rows)) + offset
            shown = np.array(values) > 0  # an input that cannot move this output: no marker
            look = {"linestyle": "none", "markersize": 5, **launch_style(name)}
            ax.plot(np.array(values)[shown] / 1e3, y[shown], label=name, **look)
        ax.axhspan(len(rows) - 2.5, len(rows) - 0.5, color=OKABE_ITO["grey"], alpha=0.12, lw=0)
        ax.set_xscale("log")
        ax.set_xlabel("distance from the nominal 3DOF flight (km)")
        ax.set_title(title.capitalize(), fontsize=10)
    axes[0].set_yticks(range(len(rows)), rows)
    axes[0].invert_yaxis()
    handles, labels = axes[0].get_legend_handles_labels()
    fig.tight_layout(rect=(0, 0.1, 1, 1))
    fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=8)
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
    fig, axes = new_figure(1, len(OUTPUTS), figsize=(FULL_WIDTH_IN, 4.4), sharey=True)
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
    fig.tight_layout()
    return fig


def draw_harp_confidence(
    residuals: pd.DataFrame, transfers: pd.DataFrame, text_std_km: dict, text_mean_km: dict
):
    """Figure X.5: (a) each site's residual mean and standard deviation with 95 % bootstrap
    intervals, the text's values as grey crosses; (b) the mean residual of one
    site's rounds predicted with the drag area fitted at the other, with the text's densities
    and with each site's density following its Mach-column temperature; the text's mean
    residual of a site (``text_mean_km``, where it gives one with its sign) as a grey cross."""
    fig, (stats, transfer) = new_figure(1, 2, figsize=(FULL_WIDTH_IN, 3.4))
    measured = style("measured")
    for y, ((site, statistic), row) in enumerate(residuals.iterrows()):
        stats.errorbar(
            row.estimate_m / 1e3,
            y,
            xerr=[[(row.estimate_m - row.low_m) / 1e3], [(row.high_m - row.estimate_m) / 1e3]],
            color=measured["color"],
            marker="o" if statistic == "mean" else "s",
            capsize=3,
            linestyle="none",
        )
        text = (text_std_km if statistic == "std" else text_mean_km).get(site)
        if text is not None:
            stats.plot(text, y, markersize=9, mew=1.6, zorder=5, **style("text"))
    stats.set_yticks(range(len(residuals)), [f"{s.capitalize()}, {t}" for s, t in residuals.index])
    stats.axvline(0.0, color=OKABE_ITO["grey"], lw=0.8)
    stats.invert_yaxis()
    stats.set_xlabel("residual statistic (km), 95 % bootstrap interval")
    stats.set_title("(a) apogee residuals: measured - MKS", fontsize=9.5)
    for y, row in enumerate(transfers.itertuples()):
        transfer.errorbar(
            row.mean_residual_m / 1e3,
            y,
            xerr=[
                [(row.mean_residual_m - row.mean_residual_m_low) / 1e3],
                [(row.mean_residual_m_high - row.mean_residual_m) / 1e3],
            ],
            color=measured["color"],
            marker="o" if row.densities == "site" else "D",
            markerfacecolor="none" if row.holds else measured["color"],
            capsize=3,
            linestyle="none",
        )
    labels = [
        f"{r.fit_site.capitalize()} -> {r.predict_site.capitalize()}, "
        + ("text's air" if r.densities == "site" else "air from Mach")
        for r in transfers.itertuples()
    ]
    for y, row in enumerate(transfers.itertuples()):
        if row.predict_site in text_mean_km:
            transfer.plot(text_mean_km[row.predict_site], y, markersize=9, mew=1.6, zorder=5,
                          **style("text"))  # fmt: skip
    transfer.set_yticks(range(len(transfers)), labels, fontsize=8)
    transfer.axvline(0.0, color=OKABE_ITO["grey"], lw=0.8)
    transfer.invert_yaxis()
    transfer.set_xlabel("mean residual at the other site (km)")
    transfer.set_title("(b) drag area carried to the other site", fontsize=9.5)
    fig.tight_layout()
    return fig


def _judged_label(row) -> str:
    name = "cone" if row.projectile == "baseline" else row.projectile
    where = f", {row.latitude_deg:g}° {row.bearing_deg:03.0f}T" if row.rotating else ", still Earth"
    return f"{name} {row.elevation_deg:g}°{where}"


def draw_judged(judged: pd.DataFrame):
    """Figure X.6: on the judging set (launches the improved MKS was not fitted to), the
    largest position error over the flight and the impact point's miss against the 3DOF, of the
    dissertation's MKS and of the improved one, joined per launch; log scale."""
    text, better = (judged[judged.variant == v].reset_index(drop=True) for v in VARIANTS)
    labels = [_judged_label(row) for row in text.itertuples()]
    fig, axes = new_figure(1, 2, figsize=(FULL_WIDTH_IN, 4.6), sharey=True)
    y = np.arange(len(text))
    for ax, measure, title in zip(
        axes, ("max_error_m", "impact_miss_m"), ("largest error in flight", "impact point")
    ):
        for i in y:
            ax.plot([text[measure][i] / 1e3, better[measure][i] / 1e3], [i, i],
                    color=OKABE_ITO["grey"], lw=0.7)  # fmt: skip
        for frame, variant, marker in ((text, "MKS", "o"), (better, "improved MKS", "s")):
            look = {**style(variant), "linestyle": "none", "marker": marker, "markersize": 5}
            name = "dissertation's MKS" if variant == "MKS" else "improved MKS"
            ax.plot(frame[measure] / 1e3, y, label=name, **look)
        ax.set_xscale("log")
        ax.set_xlabel("error against the 3DOF (km)")
        ax.set_title(title.capitalize(), fontsize=10)
    axes[0].set_yticks(y, labels, fontsize=7.5)
    axes[0].invert_yaxis()
    handles, names = axes[0].get_legend_handles_labels()
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    fig.legend(handles, names, loc="lower center", ncol=2, fontsize=8)
    return fig


def draw_error_maps(error_map: pd.DataFrame, share_range: tuple[float, float]):
    """Figure X.7: the improved MKS's error over the dissertation's (log10 of the ratio) over
    bearing x elevation, one panel per latitude; top row the impact point's miss, bottom row
    the largest error in flight. A diverging purple-orange scale (purple: improved better), a
    black contour where the two are equal, hatching where the improved MKS is outside its
    validity band, crosses where it has no solution."""
    latitudes = sorted(error_map.latitude_deg.unique())
    bearings = np.sort(error_map.bearing_deg.unique())
    elevations = np.sort(error_map.elevation_deg.unique())
    fig, axes = new_figure(
        2, len(latitudes), figsize=(FULL_WIDTH_IN, 4.4), sharex=True, sharey=True
    )
    low, high = share_range
    image = None
    for column, latitude in enumerate(latitudes):
        rows = error_map[error_map.latitude_deg == latitude]
        grid = rows.pivot(index="elevation_deg", columns="bearing_deg")
        outside = ~((grid.air_momentum_share > low) & (grid.air_momentum_share <= high))
        for row, measure in enumerate(("impact_miss_m", "max_error_m")):
            ax = axes[row, column]
            ratio = np.log10(grid[f"improved_{measure}"] / grid[f"dissertation_{measure}"])
            image = ax.pcolormesh(bearings, elevations, ratio.to_numpy(), cmap="PuOr_r",
                                  vmin=-2.1, vmax=2.1, shading="nearest")  # fmt: skip
            if np.nanmin(ratio.to_numpy()) < 0 < np.nanmax(ratio.to_numpy()):
                ax.contour(bearings, elevations, ratio.to_numpy(), levels=[0.0],
                           colors=OKABE_ITO["black"], linewidths=1.0)  # fmt: skip
            ax.contourf(bearings, elevations, outside.to_numpy().astype(float), levels=[0.5, 1.5],
                        colors="none", hatches=["////"])  # fmt: skip
            missing = np.argwhere(~np.isfinite(ratio.to_numpy()))
            ax.plot(bearings[missing[:, 1]], elevations[missing[:, 0]], "x",
                    color=OKABE_ITO["black"], markersize=4)  # fmt: skip
            ax.grid(False)
            ax.set_xticks([0, 90, 180, 270], ["0", "90", "180", "270"], fontsize=6.5)
            if row == 0:
                ax.set_title(f"latitude {latitude:g}°", fontsize=8.5)
            if row == 1:
                ax.set_xlabel("bearing (deg T)", fontsize=8)
        axes[0, 0].set_ylabel("impact point\nelevation (deg)", fontsize=8)
        axes[1, 0].set_ylabel("largest in flight\nelevation (deg)", fontsize=8)
    fig.tight_layout(rect=(0, 0, 0.9, 1))
    bar = fig.colorbar(image, ax=axes, fraction=0.03, pad=0.02)
    bar.set_label("log10(improved / dissertation)", fontsize=8)
    return fig
