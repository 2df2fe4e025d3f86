"""A heat map on one matplotlib Axes: values over two grid axes drawn as equal cells in grid
order (the axes are lists of values, not ranges), a failed point as a grey cell marked "failed".
Used by the sweep (friction_fmu.sweep_plot) and by the report's figures (friction_fmu.figures);
panels of one figure share a colour scale (`norm`) and one colour bar (`colour_bar`).
"""
import math

from . import style

# Above this many cells the values no longer fit in them: the colour bar alone reads them.
MAX_ANNOTATED = 12 * 12


def plain(value):
    """A grid value as a tick label: 0.0005 rather than 5e-04, 3000 rather than 3000.0."""
    return f"{value:g}" if isinstance(value, float) else str(value)


def finite(value):
    return isinstance(value, float) and math.isfinite(value)


def norm(values):
    """One colour scale over every finite value of every panel."""
    from matplotlib.colors import Normalize

    shown = [v for v in values if finite(v)]
    low, high = (min(shown), max(shown)) if shown else (0.0, 1.0)
    if low == high:  # one value: a scale around it rather than a zero-width one
        low, high = low - 0.5 * (abs(low) or 1.0), high + 0.5 * (abs(high) or 1.0)
    return Normalize(low, high)


def draw(ax, xs, ys, values, scale, x_label, y_label):
    """Draws values[j][i], the value at (xs[i], ys[j]) or None (NaN) for a failed point, on
    `ax` with y growing upward; returns the mesh, for the colour bar."""
    import numpy as np
    from matplotlib import colormaps

    nx, ny = len(xs), len(ys)
    data = np.full((ny, nx), np.nan)
    for j in range(ny):
        for i in range(nx):
            v = values[j][i]
            if finite(v):
                data[j, i] = v
    cmap = colormaps[style.HEAT_MAP].with_extremes(bad=style.FAILED)
    mesh = ax.pcolormesh(np.arange(nx + 1) - 0.5, np.arange(ny + 1) - 0.5,
                         np.ma.masked_invalid(data), cmap=cmap, norm=scale,
                         edgecolors="white", linewidth=0.8)
    ax.set_xticks(range(nx), [plain(x) for x in xs],
                  rotation=45 if sum(len(plain(x)) for x in xs) > 60 else 0)
    ax.set_yticks(range(ny), [plain(y) for y in ys])
    ax.set_xlim(-0.5, nx - 0.5)
    ax.set_ylim(-0.5, ny - 0.5)
    ax.set_xlabel(x_label)
    ax.set_ylabel(y_label)
    ax.grid(False)
    ax.tick_params(length=0)
    for spine in ax.spines.values():
        spine.set_visible(False)
    if nx * ny <= MAX_ANNOTATED:
        for j in range(ny):
            for i in range(nx):
                v = data[j, i]
                if np.isnan(v):
                    ax.text(i, j, "failed", ha="center", va="center", fontsize=7,
                            color="#444444")
                    continue
                r, g, b, _ = cmap(scale(v))
                ink = "black" if 0.299 * r + 0.587 * g + 0.114 * b > 0.5 else "white"
                ax.text(i, j, f"{v:.3g}", ha="center", va="center", fontsize=7, color=ink)
    return mesh


def colour_bar(fig, mesh, axes, label):
    """One colour bar beside `axes`, ticked by matplotlib's own locator and formatter (round
    values, a common offset or power of ten shown once)."""
    bar = fig.colorbar(mesh, ax=axes, shrink=0.9, pad=0.02)
    bar.set_label(label)
    bar.outline.set_visible(False)
    return bar
