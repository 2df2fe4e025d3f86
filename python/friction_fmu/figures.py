"""Draws the figures `friction-fmu` writes as data (src/report/figure.rs): every DIR/STEM.csv
with a DIR/STEM.json beside it becomes DIR/STEM.png and DIR/STEM.svg.

    python -m friction_fmu.figures [--force] DIR [DIR ...]

STEM.json describes the figure:

    {"kind": "lines" or "heatmap", "title": "...", "columns": 3, "markers": true,
     "value": "colour bar label (heatmap)", "labels": {"series": "legend text", ...},
     "panels": [{"title": "...", "x": "x label (unit)", "y": "y label (unit)",
                 "log_x": false, "log_y": false}, ...]}

STEM.csv holds its points, after a header line: `panel,series,x,y` (lines) or `panel,x,y,value`
(heatmap), `panel` an index into "panels". A value that is empty or not finite is a gap in a line
and a failed cell in a heat map. A series named after a solver or friction law is drawn in that
one's style (friction_fmu.style), the same in every figure. Panels get consecutive letters
(a), (b), ... when there are several; the legend goes below the axes, so it covers no curve.
A figure whose PNG and SVG are newer than its data and than this drawing code is left as it is
(`--force` draws it again); friction-fmu leaves a file it would write unchanged untouched, so a
run that computes the same data draws nothing. Exit status: 0 when every figure is drawn (or up
to date), 1 when one could not be, 2 when a directory holds no figure data.
"""
import csv
import json
import math
import pathlib
import sys

from . import heatmap, style

KINDS = ("lines", "heatmap")
# inches: a panel of several, and a figure's only panel
PANEL_W, PANEL_H = 3.3, 2.5
SINGLE_W, SINGLE_H = 5.2, 3.8


def read(csv_path):
    """The figure's description and its rows (each a dict of the header's columns, numbers as
    floats, NaN where empty)."""
    csv_path = pathlib.Path(csv_path)
    spec = json.loads(csv_path.with_suffix(".json").read_text())
    if spec.get("kind") not in KINDS:
        raise ValueError(f"{csv_path.with_suffix('.json')}: kind {spec.get('kind')!r}: "
                         f"expected one of {', '.join(KINDS)}")
    with open(csv_path, newline="") as handle:
        rows = list(csv.DictReader(handle))
    numbers = ("x", "y") if spec["kind"] == "lines" else ("x", "y", "value")
    for row in rows:
        row["panel"] = int(row["panel"])
        for name in numbers:
            row[name] = float(row[name]) if row[name].strip() else math.nan
    return spec, rows


def letters(count):
    """(a), (b), ... for several panels; nothing for one."""
    return [f"({chr(ord('a') + i)}) " if count > 1 else "" for i in range(count)]


def _grid(spec, count):
    columns = max(1, min(int(spec.get("columns", 1)), count))
    return columns, math.ceil(count / columns)


def figure(spec, rows):
    """The figure as a matplotlib Figure (create it inside style.context())."""
    panels = spec["panels"]
    columns, nrows = _grid(spec, len(panels))
    draw = _lines if spec["kind"] == "lines" else _heatmap
    return draw(spec, rows, panels, columns, nrows)


def _lines(spec, rows, panels, columns, nrows):
    names = list(dict.fromkeys(row["series"] for row in rows))
    styles = style.series(names)
    labels = spec.get("labels", {})
    width, height = (SINGLE_W, SINGLE_H) if len(panels) == 1 else (PANEL_W, PANEL_H)
    fig = style.figure(width * columns, height * nrows + 0.5)
    axes = fig.subplots(nrows, columns, squeeze=False).ravel()
    for ax in axes[len(panels):]:
        ax.set_visible(False)
    markers = bool(spec.get("markers", False))
    handles = {}
    for index, (ax, panel, letter) in enumerate(zip(axes, panels, letters(len(panels)))):
        log_x, log_y = bool(panel.get("log_x")), bool(panel.get("log_y"))
        for name in names:
            points = [(r["x"], r["y"]) for r in rows if r["panel"] == index and r["series"] == name]
            if not points:
                continue

            def shown(v, log):
                return v if math.isfinite(v) and (v > 0 or not log) else math.nan

            xs = [shown(x, log_x) for x, _ in points]
            ys = [shown(y, log_y) for _, y in points]
            drawable = sum(math.isfinite(x) and math.isfinite(y) for x, y in zip(xs, ys))
            if drawable == 0:
                continue
            # a point between gaps would be invisible as a line alone: mark it
            lone = drawable == 1
            (line,) = ax.plot(xs, ys, **styles[name].line(markers or lone),
                              label=labels.get(name, name))
            handles.setdefault(name, line)
        if log_x:
            ax.set_xscale("log")
        if log_y:
            ax.set_yscale("log")
        if log_x or log_y:
            ax.grid(True, which="minor", color="#eeeeee", linewidth=0.4)
        ax.set_title(letter + panel.get("title", ""))
        ax.set_xlabel(panel.get("x", ""))
        ax.set_ylabel(panel.get("y", ""))
    if len(handles) > 1 or any(n in labels for n in handles):
        style.legend(fig, list(handles.values()))
    fig.suptitle(spec.get("title", ""))
    return fig


def _heatmap(spec, rows, panels, columns, nrows):
    cells = []
    for index in range(len(panels)):
        mine = [r for r in rows if r["panel"] == index]
        xs = list(dict.fromkeys(r["x"] for r in mine))
        ys = list(dict.fromkeys(r["y"] for r in mine))
        at = {(r["x"], r["y"]): r["value"] for r in mine}
        cells.append((xs, ys, [[at.get((x, y), math.nan) for x in xs] for y in ys]))
    nx = max((len(c[0]) for c in cells), default=1)
    ny = max((len(c[1]) for c in cells), default=1)
    # cells about 0.45 x 0.3 inch, so a 3 significant digit value fits in each
    width = max(PANEL_W, 1.0 + 0.45 * nx) * columns + 1.2
    fig = style.figure(width, max(PANEL_H, 1.0 + 0.3 * ny) * nrows + 0.6)
    axes = fig.subplots(nrows, columns, squeeze=False).ravel()
    for ax in axes[len(panels):]:
        ax.set_visible(False)
    scale = heatmap.norm([v for _, _, values in cells for row in values for v in row])
    mesh = None
    for ax, panel, letter, (xs, ys, values) in zip(axes, panels, letters(len(panels)), cells):
        mesh = heatmap.draw(ax, xs, ys, values, scale, panel.get("x", ""), panel.get("y", ""))
        ax.set_title(letter + panel.get("title", ""))
    if mesh is not None:
        heatmap.colour_bar(fig, mesh, list(axes[:len(panels)]), spec.get("value", ""))
    fig.suptitle(spec.get("title", ""))
    return fig


def figure_files(directory):
    """The CSV files of `directory` that have a figure description beside them, sorted."""
    found = []
    for path in sorted(pathlib.Path(directory).glob("*.csv")):
        sidecar = path.with_suffix(".json")
        if not sidecar.is_file():
            continue
        try:
            kind = json.loads(sidecar.read_text()).get("kind")
        except (ValueError, AttributeError):  # another tool's JSON: not a figure
            continue
        if kind is not None:
            found.append(path)
    return found


# The code a drawing depends on: a change to any of it makes every figure out of date.
CODE = [pathlib.Path(__file__).with_name(name) for name in ("figures.py", "style.py", "heatmap.py")]


def up_to_date(csv_path):
    """True when STEM.png and STEM.svg are newer than STEM.csv, STEM.json and the drawing code."""
    csv_path = pathlib.Path(csv_path)
    drawn = [csv_path.with_suffix(s) for s in (".png", ".svg")]
    if not all(p.is_file() for p in drawn):
        return False
    sources = [csv_path, csv_path.with_suffix(".json"), *CODE]
    newest = max(p.stat().st_mtime_ns for p in sources if p.exists())
    return min(p.stat().st_mtime_ns for p in drawn) >= newest


def draw(csv_path):
    """Draws one figure into PNG and SVG beside its CSV; returns both paths."""
    spec, rows = read(csv_path)
    with style.context():
        return style.save(figure(spec, rows), pathlib.Path(csv_path).with_suffix(""))


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if any(a in ("-h", "--help") for a in argv):
        print(__doc__)
        return 0
    force = "--force" in argv
    directories = [a for a in argv if a != "--force"]
    if not directories or any(a.startswith("-") for a in directories):
        print("usage: python -m friction_fmu.figures [--force] DIR [DIR ...]", file=sys.stderr)
        return 2
    status = 0
    for directory in directories:
        files = figure_files(directory)
        if not files:
            print(f"error: {directory}: no figure data (STEM.csv with STEM.json)",
                  file=sys.stderr)
            status = max(status, 2)
            continue
        current = [p for p in files if not force and up_to_date(p)]
        if current:
            print(f"{len(current)} figure{'s' * (len(current) != 1)} in {directory} up to date "
                  "(--force draws again)")
        for path in files:
            if path in current:
                continue
            try:
                png, svg = draw(path)
            except (OSError, ValueError, KeyError) as error:
                print(f"error: {path}: {error}", file=sys.stderr)
                status = max(status, 1)
                continue
            print(f"drew {png} and {svg.name}")
    return status


if __name__ == "__main__":
    sys.exit(main())
