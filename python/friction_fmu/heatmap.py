"""A heat map of a sweep as hand-written SVG: two grid axes (or one, drawn as a single row),
color = one output column.

The other grid axes are either pinned (`fixed`, e.g. f = 3000) or faceted into small multiples,
one panel per combination of their values. All panels share one color scale and one color bar.
Grid values are drawn as equal cells in grid order (the axes are lists, not ranges). A failed
point is a gray cell whose tooltip is the FMU's message.
"""
import itertools
import math
from xml.sax.saxutils import escape

CELL_W, CELL_H = 56, 26
LEFT, TOP, BOTTOM, GAP = 96, 44, 56, 36
BAR_W, BAR_GAP, BAR_LABEL = 16, 34, 90
# viridis at five stops; colors in between are interpolated linearly in RGB
STOPS = [(0x44, 0x01, 0x54), (0x3B, 0x52, 0x8B), (0x21, 0x91, 0x8C), (0x5E, 0xC9, 0x62),
         (0xFD, 0xE7, 0x25)]


def color(fraction):
    fraction = min(max(fraction, 0.0), 1.0) * (len(STOPS) - 1)
    i = min(int(fraction), len(STOPS) - 2)
    a, b, w = STOPS[i], STOPS[i + 1], fraction - i
    return "#" + "".join(f"{round(x + (y - x) * w):02x}" for x, y in zip(a, b))


def label(name, units):
    unit = units.get(name)
    return f"{name} ({unit})" if unit else name


def _value(row, column):
    value = row.get(column)
    if row.get("status") != "ok" or not isinstance(value, float) or not math.isfinite(value):
        return None
    return value


def _key(values):
    return tuple(str(v) for v in values)


def render(rows, grid, x, y, column, units=None, fixed=None, title=None):
    """The SVG text. `grid` is the ordered axes {name: values}; `y` None draws one row of
    cells along x (a one-axis sweep); `units` maps a name (grid axis or output variable) to its
    unit; `fixed` pins other axes to one value each."""
    units, fixed = units or {}, fixed or {}
    for axis in (x, *([y] if y is not None else []), *fixed):
        if axis not in grid:
            raise ValueError(f"{axis!r} is not a grid axis (axes: {', '.join(grid)})")
    facets = [a for a in grid if a not in (x, y) and a not in fixed]
    panels = list(itertools.product(*(grid[a] for a in facets)))
    ys = grid[y] if y is not None else [None]
    names = [x, *([y] if y is not None else []), *fixed, *facets]
    by_key = {_key(row[n] for n in names): row for row in rows}

    def row_at(xv, yv, panel):
        return by_key.get(_key([xv, *([yv] if y is not None else []), *fixed.values(), *panel]))

    shown = [_value(row_at(xv, yv, p) or {}, column)
             for p in panels for xv in grid[x] for yv in ys]
    finite = [v for v in shown if v is not None]
    low, high = (min(finite), max(finite)) if finite else (0.0, 1.0)
    span = (high - low) or 1.0

    nx, ny = len(grid[x]), len(ys)
    panel_w, panel_h = LEFT + nx * CELL_W + GAP, TOP + ny * CELL_H + BOTTOM
    columns = min(len(panels), 3)
    width = columns * panel_w + BAR_GAP + BAR_W + BAR_LABEL
    bar_h = max(ny * CELL_H, 120)  # tall enough for five readable ticks
    height = max(30 + math.ceil(len(panels) / columns) * panel_h, 30 + TOP + bar_h + 20)
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'font-family="sans-serif" font-size="11">',
           f'<rect width="{width}" height="{height}" fill="white"/>',
           f'<text x="{width / 2}" y="18" text-anchor="middle" font-size="14">'
           f'{escape(title or label(column, units))}</text>']
    for n, panel in enumerate(panels):
        ox = (n % columns) * panel_w + LEFT
        oy = 30 + (n // columns) * panel_h + TOP
        heading = ", ".join(f"{a} = {_plain(v)} {units.get(a, '')}".strip()
                            for a, v in [*fixed.items(), *zip(facets, panel)])
        out.append(f'<text x="{ox + nx * CELL_W / 2}" y="{oy - 10}" text-anchor="middle">'
                   f'{escape(heading)}</text>')
        for i, xv in enumerate(grid[x]):
            for j, yv in enumerate(ys):
                row = row_at(xv, yv, panel) or {"status": "missing", "message": "not run"}
                value = _value(row, column)
                cx, cy = ox + i * CELL_W, oy + (ny - 1 - j) * CELL_H  # y grows upward
                fill = "#cccccc" if value is None else color((value - low) / span)
                where = f"{x}={xv}" + (f", {y}={yv}" if y is not None else "")
                tip = (f"{row.get('status')}: {row.get('message')}" if value is None
                       else f"{value:.6g}")
                out.append(f'<rect class="cell" x="{cx}" y="{cy}" width="{CELL_W}" '
                           f'height="{CELL_H}" fill="{fill}" stroke="white">'
                           f'<title>{escape(f"{where}: {tip}")}</title></rect>')
                text = "failed" if value is None else f"{value:.3g}"
                ink = "black" if value is None or (value - low) / span > 0.6 else "white"
                out.append(f'<text x="{cx + CELL_W / 2}" y="{cy + CELL_H / 2 + 4}" '
                           f'text-anchor="middle" font-size="9" fill="{ink}">{text}</text>')
        for i, xv in enumerate(grid[x]):
            out.append(f'<text x="{ox + (i + 0.5) * CELL_W}" y="{oy + ny * CELL_H + 14}" '
                       f'text-anchor="middle">{_tick(xv)}</text>')
        out.append(f'<text x="{ox + nx * CELL_W / 2}" y="{oy + ny * CELL_H + 36}" '
                   f'text-anchor="middle">{escape(label(x, units))}</text>')
        if y is None:
            continue  # one row: no y ticks or label
        for j, yv in enumerate(ys):
            out.append(f'<text x="{ox - 6}" y="{oy + (ny - 1 - j + 0.5) * CELL_H + 4}" '
                       f'text-anchor="end">{_tick(yv)}</text>')
        ly = oy + ny * CELL_H / 2
        lx = ox - LEFT + 14
        out.append(f'<text x="{lx}" y="{ly}" text-anchor="middle" '
                   f'transform="rotate(-90 {lx} {ly})">{escape(label(y, units))}</text>')
    out.extend(_color_bar(columns * panel_w + BAR_GAP, 30 + TOP, bar_h, low, high,
                          label(column, units)))
    out.append("</svg>")
    return "\n".join(out) + "\n"


def _plain(value):
    return f"{value:g}" if isinstance(value, float) else str(value)


def _tick(value):
    return escape(_plain(value))


def _color_bar(x, y, h, low, high, text):
    out = ['<defs><linearGradient id="bar" x1="0" y1="1" x2="0" y2="0">']
    for k in range(len(STOPS)):
        at = k / (len(STOPS) - 1)
        out.append(f'<stop offset="{at}" stop-color="{color(at)}"/>')
    out.append("</linearGradient></defs>")
    out.append(f'<rect x="{x}" y="{y}" width="{BAR_W}" height="{h}" fill="url(#bar)" '
               'stroke="black"/>')
    for k in range(5):
        v = low + (high - low) * k / 4
        ty = y + h - h * k / 4
        out.append(f'<line x1="{x + BAR_W}" y1="{ty}" x2="{x + BAR_W + 4}" y2="{ty}" '
                   'stroke="black"/>')
        out.append(f'<text x="{x + BAR_W + 6}" y="{ty + 4}">{v:.4g}</text>')
    lx, ly = x + BAR_W + 66, y + h / 2  # the bar's title, written upward beside its ticks
    out.append(f'<text x="{lx}" y="{ly}" text-anchor="middle" '
               f'transform="rotate(-90 {lx} {ly})">{escape(text)}</text>')
    return out
