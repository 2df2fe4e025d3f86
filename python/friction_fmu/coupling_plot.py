"""The plot of a coupled run (friction_fmu.couple): nut velocity, drive force Fd and friction
force FF against time, one panel each over a shared time axis, as PNG and SVG in the package's
style (friction_fmu.style).

Time is in ms and the nut velocity in mm/s, the scales of the case (tens of ms, 0.5 mm/s);
forces in N.
"""
from . import style

# (CSV column, scale to the plotted unit, axis label)
PANELS = [
    ("v_nut", 1e3, "nut velocity v_nut (mm/s)"),
    ("Fd", 1.0, "drive force Fd (N)"),
    ("FF", 1.0, "friction force FF (N)"),
]


def plot(rows, prefix, subtitle, stopped=None):
    """Writes the plot of `rows` (couple.run's) to PREFIX.png and PREFIX.svg; returns both
    paths. `stopped`: the time an FMU failed at, said in the title (the rows end there)."""
    with style.context():
        figure = style.figure(7.0, 6.0)
        axes = figure.subplots(len(PANELS), 1, sharex=True)
        time_ms = [row["time"] * 1e3 for row in rows]
        # one quantity a panel, nothing to tell apart: the plain line, no markers
        line = style.SINGLE.line(markers=False)
        for ax, (column, scale, label) in zip(axes, PANELS):
            ax.plot(time_ms, [row[column] * scale for row in rows], **line)
            ax.set_ylabel(label)
        axes[-1].set_xlabel("time t (ms)")
        title = "DriveTrain coupled to TransverseFriction"
        if stopped is not None:
            title += f", stopped at t = {stopped * 1e3:.6g} ms (an FMU failed)"
        figure.suptitle(f"{title}\n{subtitle}")
        return style.save(figure, prefix)
