"""The plot of a sweep (friction_fmu.sweep), as PNG and SVG: one output column over the grid.

One free grid axis: a line plot of the column against that axis, a failed point a grey cross on
the axis' floor. Two: a heat map over x and y; any other grid axis is either pinned (`fixed`,
e.g. f = 3000) or faceted into small multiples, one panel per combination of its values, all
panels on one colour scale with one colour bar. Which point failed and why is in the sweep's CSV
(status and message columns).
"""
import itertools
import math

from . import heatmap, style
from .runner import RAN

PANEL_W, PANEL_H = 3.4, 2.8  # inches, one heat map panel
# A numeric axis spanning this ratio or more (all values positive) is drawn on a log scale.
LOG_SPAN = 100.0


def label(name, units):
    unit = units.get(name)
    return f"{name} ({unit})" if unit else name


def _value(row, column):
    value = row.get(column)
    if row.get("status") not in RAN or not isinstance(value, float) or not math.isfinite(value):
        return None
    return value


def _key(values):
    return tuple(str(v) for v in values)


def _check(grid, x, y, fixed):
    for axis in (x, *([y] if y is not None else []), *fixed):
        if axis not in grid:
            raise ValueError(f"{axis!r} is not a grid axis (axes: {', '.join(grid)})")


def panels(rows, grid, x, y, column, fixed=None):
    """The data of the plot: [(heading pairs, values)], one entry per panel; values[j][i] is the
    column at (grid[x][i], grid[y][j]) (one row, j = 0, when `y` is None), None where the point
    failed or was not run. Heading pairs: (axis, value) of the pinned and faceted axes."""
    fixed = fixed or {}
    _check(grid, x, y, fixed)
    facets = [a for a in grid if a not in (x, y) and a not in fixed]
    ys = grid[y] if y is not None else [None]
    names = [x, *([y] if y is not None else []), *fixed, *facets]
    by_key = {_key(row[n] for n in names): row for row in rows}
    out = []
    for panel in itertools.product(*(grid[a] for a in facets)):
        def at(xv, yv):
            key = _key([xv, *([yv] if y is not None else []), *fixed.values(), *panel])
            return _value(by_key.get(key, {}), column)
        values = [[at(xv, yv) for xv in grid[x]] for yv in ys]
        out.append(([*fixed.items(), *zip(facets, panel)], values))
    return out


def _heading(pairs, units):
    return ", ".join(f"{a} = {heatmap.plain(v)} {units.get(a, '')}".strip() for a, v in pairs)


def figure(rows, grid, x, y, column, units=None, fixed=None, title=None, solver=None):
    """The sweep's plot as a matplotlib Figure (create it inside style.context()). `units` maps
    a name (grid axis or output column) to its unit; `fixed` pins other axes to one value each;
    `solver`, the solver the plan fixed, if any, styles the line of a one-axis sweep."""
    units = units or {}
    data = panels(rows, grid, x, y, column, fixed)
    if y is None:
        title = title or f"{label(column, units)} against {x}"
        solver_style = style.of(solver) if isinstance(solver, str) else None
        return _line(grid[x], data, len(fixed or {}), label(x, units), label(column, units),
                     title, units, solver_style)
    title = title or f"{label(column, units)} over {x} and {y}"
    columns = min(len(data), 3)
    nrows = math.ceil(len(data) / columns)
    nx, ny = len(grid[x]), len(grid[y])
    # cells about 0.45 x 0.3 inch, so a 3 significant digit value fits in each
    width = max(PANEL_W, 1.0 + 0.45 * nx) * columns + 1.2
    height = max(PANEL_H, 1.0 + 0.3 * ny) * nrows + 0.6
    fig = style.figure(width, height)
    axes = fig.subplots(nrows, columns, squeeze=False).ravel()
    scale = heatmap.norm([v for _, values in data for row in values for v in row])
    mesh = None
    for ax, (pairs, values) in zip(axes, data):
        mesh = heatmap.draw(ax, grid[x], grid[y], values, scale, label(x, units),
                            label(y, units))
        if pairs:
            ax.set_title(_heading(pairs, units))
    for ax in axes[len(data):]:
        ax.set_visible(False)
    heatmap.colour_bar(fig, mesh, list(axes[:len(data)]), label(column, units))
    fig.suptitle(title)
    return fig


def _numeric(values):
    return all(isinstance(v, (int, float)) and math.isfinite(v) for v in values)


def _line(xs, data, pinned, x_label, y_label, title, units, solver_style):
    """One line of the column against x; with faceted axes, one line per combination of their
    values. The first `pinned` heading pairs (the pinned axes) go in the title."""
    fig = style.figure(5.6, 3.6)
    ax = fig.subplots()
    positions = list(xs) if _numeric(xs) else list(range(len(xs)))
    facets = [(pairs, values[0]) for pairs, values in data]
    names = [_heading(pairs[pinned:], units) for pairs, _ in facets]
    styles = style.series(names) if len(facets) > 1 else {names[0]: solver_style or style.SINGLE}
    # Items of a switch (a sweep over `solver`) are categories: points, no line between them,
    # and a solver or law in its own colour and marker.
    categories = not _numeric(xs)
    own = [style.of(xv) if isinstance(xv, str) else None for xv in xs]
    failed = []
    for name, (_, ys) in zip(names, facets):
        line = styles[name].line()
        if categories:
            line["linestyle"] = "None"
        shown = [math.nan if v is None or mine else v for v, mine in zip(ys, own)]
        ax.plot(positions, shown, **line, label=name or None)
        failed += [pos for pos, v in zip(positions, ys) if v is None]
        for pos, mine, v in zip(positions, own, ys):
            if mine is not None and v is not None:
                ax.plot([pos], [v], color=mine.color, marker=mine.marker, linestyle="None",
                        markersize=7, zorder=3)
    if categories:
        ax.set_xticks(positions, [heatmap.plain(x) for x in xs])
    elif min(xs) > 0 and max(xs) >= LOG_SPAN * min(xs):
        ax.set_xscale("log")
    if failed:
        # on the axes' floor: a failed point has no value to stand at
        ax.plot(failed, [0.0] * len(failed), linestyle="None", marker="x", color="#888888",
                markersize=7, clip_on=False, transform=ax.get_xaxis_transform(),
                label=f"failed ({len(failed)}): status and message in the CSV")
    if failed or len(facets) > 1:
        style.legend(fig, ax.get_lines())
    ax.set_xlabel(x_label)
    ax.set_ylabel(y_label)
    heading = _heading(facets[0][0][:pinned], units)
    fig.suptitle(f"{title}\n{heading}" if heading else title)
    return fig


def write(prefix, rows, grid, x, y, column, units=None, fixed=None, title=None, solver=None):
    """Draws the sweep's plot into PREFIX.png and PREFIX.svg; returns both paths."""
    with style.context():
        fig = figure(rows, grid, x, y, column, units, fixed, title, solver)
        return style.save(fig, prefix)
