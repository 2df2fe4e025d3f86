"""One look for every plot of the package: the report's figures (friction_fmu.figures), the
sweep's line plots and heat maps (friction_fmu.sweep_plot) and the coupled run's plot
(friction_fmu.coupling_plot).

A solver or friction law keeps one colour, marker and line style in every figure, so dopri5 read
in one plot is dopri5 in the next. The names are the items of the FMUs' `solver`, `law` and
`slip_law` switches (src/models/*/table.rs). Any other series (a family such as vd = 0.1, 0.3, 0.8
mm/s) takes its colour from a sequential colour map in the order given, so an ordered parameter
reads as ordered.

Figures are drawn on matplotlib's Agg canvas without pyplot, so drawing changes no backend or
global figure state of a program that imports this.
"""
import contextlib
import pathlib
from dataclasses import dataclass


@dataclass(frozen=True)
class Style:
    color: str
    marker: str
    linestyle: object = "-"

    def line(self, markers=True):
        """Keyword arguments of Axes.plot for a series in this style."""
        return {"color": self.color, "linestyle": self.linestyle,
                "marker": self.marker if markers else "None"}


# Solvers: the strong colours of matplotlib's tab10, a distinct marker and dash each, so they
# stay apart in greyscale print too.
SOLVERS = {
    "dopri5": Style("#1f77b4", "o", "-"),
    "radau5": Style("#d62728", "s", "--"),
    "rk4": Style("#2ca02c", "^", "-."),
    "exponential": Style("#ff7f0e", "D", ":"),
    "two_phase": Style("#9467bd", "v", (0, (6, 2, 1, 2))),  # the paper's own scheme (paper T)
    "dop853": Style("#8c6d31", "H", (0, (3, 1, 1, 1))),
}
# Friction laws (scenes L and O) and slip laws (scene T). The exact switch models, the oracles
# the regularised laws are compared with, are black and grey and dashed, so a law drawn under
# its oracle still shows through.
LAWS = {
    "exact": Style("#000000", "*", (0, (4, 2))),
    "exact_stiction": Style("#666666", "X", (0, (1, 1.5))),
    "linear": Style("#8c564b", "h", "-"),
    "trigonometric": Style("#e377c2", "p", "-"),
    "linear_stiction": Style("#bcbd22", "<", "--"),
    "trigonometric_stiction": Style("#17becf", ">", "--"),
    "coulomb": Style("#7f7f7f", "P", "-"),
    "dahl": Style("#393b79", "d", "-"),
    "lugre": Style("#637939", "8", "-"),
    "split": Style("#6b6ecf", "o", "-"),
    "total": Style("#ad494a", "s", "--"),
}
NAMED = {**SOLVERS, **LAWS}
# A plot of one quantity, with no solver or law to tell apart (the coupled run, a sweep).
SINGLE = Style("#222222", "o", "-")
# Families of series without a name of their own; markers cycle as well as colours.
FAMILY_MAP = "viridis"
FAMILY_MARKERS = ["o", "s", "^", "D", "v", "P", "X", "<", ">"]
# Heat maps: the colour map, and the cell of a point that failed.
HEAT_MAP = "viridis"
FAILED = "#cccccc"
DPI = 150
LEGEND_COLUMNS = 5

RC = {
    "font.size": 9,
    "axes.titlesize": 9,
    "axes.titlelocation": "left",
    "axes.labelsize": 9,
    "legend.fontsize": 8,
    "legend.frameon": False,
    "figure.titlesize": 11,
    "axes.grid": True,
    "grid.color": "#d8d8d8",
    "grid.linewidth": 0.6,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "lines.linewidth": 1.3,
    "lines.markersize": 4.5,
    "svg.hashsalt": "friction-fmu",  # the same data gives the same SVG (no random ids)
}


def of(name):
    """The style of a solver or law, or None for any other name."""
    return NAMED.get(name)


def series(names):
    """{name: Style} for the series of one figure, in the order given: a solver or law its own
    style, every other name the next colour of the family map (dark to light)."""
    from matplotlib import colormaps

    names = list(dict.fromkeys(names))
    others = [n for n in names if n not in NAMED]
    cmap = colormaps[FAMILY_MAP]
    styles = {}
    for i, name in enumerate(others):
        # the map's last fifth (yellow) is too light on white
        at = 0.0 if len(others) == 1 else 0.8 * i / (len(others) - 1)
        rgb = cmap(at)[:3]
        color = "#" + "".join(f"{round(255 * c):02x}" for c in rgb)
        styles[name] = Style(color, FAMILY_MARKERS[i % len(FAMILY_MARKERS)], "-")
    return {n: NAMED.get(n) or styles[n] for n in names}


@contextlib.contextmanager
def context():
    """The package's rc settings, for creating and drawing a figure."""
    import matplotlib

    with matplotlib.rc_context(RC):
        yield


def figure(width, height):
    """A Figure of width x height inches on an Agg canvas, laid out by matplotlib's constrained
    layout (titles, labels, colour bars and outside legends never overlap). Create it inside
    `context()`."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(width, height), layout="constrained")
    FigureCanvasAgg(fig)
    return fig


def legend(fig, handles):
    """One legend for the whole figure, below its panels: outside every axes, so it covers no
    curve, and clear of the title. Handles labelled with a leading underscore (matplotlib's
    "no label") are left out."""
    shown = [h for h in handles if not h.get_label().startswith("_")]
    return fig.legend(shown, [h.get_label() for h in shown], loc="outside lower center",
                      ncols=min(len(shown), LEGEND_COLUMNS))


def save(fig, prefix):
    """Writes PREFIX.png and PREFIX.svg (any dot in PREFIX kept); returns both paths. Call it
    inside `context()`."""
    prefix = pathlib.Path(prefix)
    png, svg = (prefix.with_name(prefix.name + suffix) for suffix in (".png", ".svg"))
    fig.savefig(png, dpi=DPI)
    fig.savefig(svg, metadata={"Date": None})  # no date: the same data, the same file
    return png, svg
