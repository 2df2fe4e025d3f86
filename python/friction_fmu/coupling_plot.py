"""The plot of a coupled run (friction_fmu.couple): nut velocity, drive force Fd and friction
force FF against time, one panel each over a shared time axis, as PNG and SVG.

Drawn on matplotlib's Agg canvas without pyplot, so plotting changes no backend or figure state
of a program that imports this. Time is in ms and the nut velocity in mm/s, the scales of the
case (tens of ms, 0.5 mm/s); forces in N.
"""
# Every panel drawn alike: one line color and width, light grid, no top and right frame.
STYLE = {
    "font.size": 9,
    "axes.titlesize": 10,
    "axes.labelsize": 9,
    "axes.grid": True,
    "grid.color": "#d0d0d0",
    "grid.linewidth": 0.6,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "lines.linewidth": 1.2,
    "svg.hashsalt": "friction-fmu",  # the same run gives the same SVG (no random ids)
}
COLOR = "#1f5f9e"
# (CSV column, scale to the plotted unit, axis label)
PANELS = [
    ("v_nut", 1e3, "nut velocity v_nut (mm/s)"),
    ("Fd", 1.0, "drive force Fd (N)"),
    ("FF", 1.0, "friction force FF (N)"),
]


def plot(rows, png, svg, subtitle, stopped=None):
    """Writes the plot of `rows` (couple.run's) to the paths `png` and `svg`. `stopped`: the time
    an FMU failed at, said in the title (the rows end there)."""
    import matplotlib
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    with matplotlib.rc_context(STYLE):
        figure = Figure(figsize=(7.0, 6.0), layout="constrained")
        FigureCanvasAgg(figure)
        axes = figure.subplots(len(PANELS), 1, sharex=True)
        time_ms = [row["time"] * 1e3 for row in rows]
        for ax, (column, scale, label) in zip(axes, PANELS):
            ax.plot(time_ms, [row[column] * scale for row in rows], color=COLOR)
            ax.set_ylabel(label)
        axes[-1].set_xlabel("time t (ms)")
        title = "DriveTrain coupled to TransverseFriction"
        if stopped is not None:
            title += f", stopped at t = {stopped * 1e3:.6g} ms (an FMU failed)"
        figure.suptitle(f"{title}\n{subtitle}")
        figure.savefig(png, dpi=150)
        figure.savefig(svg, metadata={"Date": None})  # no date: the same run, the same file
