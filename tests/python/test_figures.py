"""The figures `friction-fmu` writes as data (CSV + JSON, src/report/figure.rs), drawn by
`python -m friction_fmu.figures DIR`: each kind (a multi-panel line plot, a log-log plot with
markers, a heat map) becomes PNG and SVG beside its CSV, and is not drawn again while the drawing
is newer than its data; a solver keeps its colour and marker from one figure to the next; panels
are lettered (a), (b), (c) in order; the legend is outside the axes; a colour bar is ticked at
round values, not at the data's extremes. No FMU is run, so the file takes a few seconds, most
of it importing matplotlib and drawing three figures.
"""
import json
import sys
import xml.etree.ElementTree as ET

import pytest

from conftest import ROOT

sys.path.insert(0, str(ROOT / "python"))
from friction_fmu import figures, style  # noqa: E402


def panel(title, x, y, log=False):
    return {"title": title, "x": x, "y": y, "log_x": log, "log_y": log}


def write(directory, stem, spec, header, rows):
    (directory / f"{stem}.json").write_text(json.dumps(spec))
    lines = [header, *(",".join(str(v) for v in row) for row in rows)]
    (directory / f"{stem}.csv").write_text("\n".join(lines) + "\n")
    return directory / f"{stem}.csv"


@pytest.fixture
def figure_dir(tmp_path):
    """One figure of each kind, the solvers dopri5 and rk4 in two of them."""
    write(tmp_path, "work_precision", {
        "kind": "lines", "title": "error against CPU time", "columns": 1, "markers": True,
        "panels": [panel("", "CPU time (s)", "relative error", log=True)],
    }, "panel,series,x,y", [
        (0, "rk4", 1e-4, 1e-3), (0, "rk4", 2e-4, 6e-5), (0, "rk4", 4e-4, "nan"),
        (0, "dopri5", 1e-4, 1e-5), (0, "dopri5", 3e-4, 1e-9),
        (0, "exponential", 2e-4, 0.0),  # not drawable on a log axis: left out, not a crash
    ])
    write(tmp_path, "traces", {
        "kind": "lines", "title": "three panels", "columns": 2,
        "labels": {"dopri5": "dopri5, rtol 1e-6"},
        "panels": [panel("u", "t (s)", "u (m)"), panel("v", "t (s)", "v (m/s)"),
                   panel("phase", "u (m)", "v (m/s)")],
    }, "panel,series,x,y", [
        (p, s, t, (p + 1) * t * k) for p in range(3) for k, s in [(1, "dopri5"), (2, "rk4")]
        for t in (0.0, 0.5, 1.0)
    ])
    write(tmp_path, "grid", {
        "kind": "heatmap", "title": "mean over vd x va", "columns": 2,
        "value": "FFx_mean / FC",
        "panels": [panel("f = 3 kHz", "va (mm/s)", "vd (mm/s)"),
                   panel("f = 2 kHz", "va (mm/s)", "vd (mm/s)")],
    }, "panel,x,y,value", [
        (p, va, vd, "nan" if (p, va, vd) == (1, 2, 4) else round(0.7704 - 0.1 * va / vd, 7))
        for p in range(2) for vd in (0.5, 4) for va in (0.3, 2, 12)
    ])
    return tmp_path


def read(directory, stem):
    return figures.read(directory / f"{stem}.csv")


def test_every_figure_is_drawn_as_png_and_svg(figure_dir, capsys):
    (figure_dir / "notes.json").write_text('{"not": "a figure"}')  # another tool's: skipped
    assert figures.main([str(figure_dir)]) == 0
    drawn = capsys.readouterr().out.splitlines()
    assert len(drawn) == 3
    for stem in ("work_precision", "traces", "grid"):
        png = (figure_dir / f"{stem}.png").read_bytes()
        assert png.startswith(b"\x89PNG\r\n\x1a\n")
        svg = (figure_dir / f"{stem}.svg").read_text()
        ET.fromstring(svg)  # well-formed
        assert f"{figure_dir / stem}.png" in "\n".join(drawn)
    # drawn again only when the data (or the drawing code) is newer than the drawing
    before = (figure_dir / "grid.png").stat().st_mtime_ns
    assert figures.main([str(figure_dir)]) == 0
    said = capsys.readouterr().out
    assert said == f"3 figures in {figure_dir} up to date (--force draws again)\n"
    assert (figure_dir / "grid.png").stat().st_mtime_ns == before


def test_a_solver_keeps_its_colour_and_marker_across_figures(figure_dir):
    def lines(stem):
        with style.context():
            fig = figures.figure(*read(figure_dir, stem))
        found = {}
        for ax in fig.axes:
            for line in ax.get_lines():
                found.setdefault(line.get_label().split(",")[0], line)
        return found

    a, b = lines("work_precision"), lines("traces")
    for solver in ("dopri5", "rk4"):
        assert a[solver].get_color() == b[solver].get_color() == style.SOLVERS[solver].color
        assert a[solver].get_linestyle() == b[solver].get_linestyle()
        assert a[solver].get_marker() == style.SOLVERS[solver].marker
    assert a["dopri5"].get_color() != a["rk4"].get_color()
    assert a["dopri5"].get_marker() != a["rk4"].get_marker()
    # markers where the figure asks for them, lines alone where it does not
    assert b["dopri5"].get_marker() in ("None", "", None)


def test_panels_are_lettered_in_order_and_the_legend_is_outside(figure_dir):
    with style.context():
        fig = figures.figure(*read(figure_dir, "traces"))
    shown = [ax for ax in fig.axes if ax.get_visible()]
    assert [ax.get_title("left") for ax in shown] == ["(a) u", "(b) v", "(c) phase"]
    assert all(ax.get_legend() is None for ax in shown)  # no legend inside an axes
    (legend,) = fig.legends
    assert [t.get_text() for t in legend.get_texts()] == ["dopri5, rtol 1e-6", "rk4"]
    with style.context():
        single = figures.figure(*read(figure_dir, "work_precision"))
    assert single.axes[0].get_title("left") == ""  # one panel: no letter


def test_heat_map_colour_bar_is_ticked_at_round_values(figure_dir):
    with style.context():
        fig = figures.figure(*read(figure_dir, "grid"))
        fig.canvas.draw()
    heat = [ax for ax in fig.axes if ax.get_label() != "<colorbar>"]
    assert [ax.get_title("left") for ax in heat] == ["(a) f = 3 kHz", "(b) f = 2 kHz"]
    assert [t.get_text() for t in heat[0].get_xticklabels()] == ["0.3", "2", "12"]
    assert [t.get_text() for t in heat[0].get_yticklabels()] == ["0.5", "4"]
    # one cell per point, the failed one (empty, grey) among them
    cells = heat[1].collections[0].get_array()
    assert cells.size == 6 and cells.mask.sum() == 1
    assert "failed" in [t.get_text() for t in heat[1].texts]
    (bar,) = [ax for ax in fig.axes if ax.get_label() == "<colorbar>"]
    ticks = [v for v in bar.get_yticks() if bar.get_ylim()[0] <= v <= bar.get_ylim()[1]]
    assert len(ticks) >= 3
    # round values (a multiple of the step of the default locator), not the extremes
    step = ticks[1] - ticks[0]
    assert all(abs(v / step - round(v / step)) < 1e-9 for v in ticks)
    low = min(v for v in cells.compressed())
    assert all(abs(v - low) > 1e-12 for v in ticks)


def test_a_directory_without_figures_is_refused(tmp_path, capsys):
    (tmp_path / "sweep.csv").write_text("point,vd\n0,1e-4\n")
    assert figures.main([str(tmp_path)]) == 2
    assert "no figure data" in capsys.readouterr().err
