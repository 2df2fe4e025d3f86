"""The plot of a fit (friction_fmu.fit), as PNG and SVG: per measured output, the measured
values and the fitted model against the experiment variable (a table's first column that
differs between rows, or a series' time), and below them the residuals, fitted - measured."""
import math

from . import heatmap, style

MEASURED = style.Style("#000000", "o", "None")
FITTED = style.Style("#d62728", "s", "-")


def label(name, units):
    unit = units.get(name)
    return f"{name} ({unit})" if unit else name


def figure(data, fitted, report, model, units):
    """The fit's plot as a matplotlib Figure (create it inside style.context())."""
    outputs = list(data.measured)
    x_name = data.experiment
    if data.form == "series":
        xs = list(data.times)
    elif x_name is not None and all(isinstance(v, float) for v in data.settings[x_name]):
        xs = list(data.settings[x_name])
    else:  # no numeric column differs: the experiments in their order
        x_name, xs = "experiment", list(range(1, data.rows + 1))
    order = sorted(range(len(xs)), key=lambda i: xs[i])
    series = data.form == "series"
    fig = style.figure(max(5.0, 4.2 * len(outputs)), 4.6)
    axes = fig.subplots(2, len(outputs), squeeze=False, sharex="col",
                        gridspec_kw={"height_ratios": [2.2, 1]})
    for k, output in enumerate(outputs):
        top, bottom = axes[0][k], axes[1][k]
        measured = [data.measured[output][i] for i in order]
        model_values = [float(fitted[output][i]) for i in order]
        x = [xs[i] for i in order]
        top.plot(x, measured, **MEASURED.line(), markersize=3 if series else 5,
                 label="measured")
        top.plot(x, model_values, **FITTED.line(markers=not series), label="fitted")
        top.set_ylabel(label(output, units))
        residuals = [f - m for f, m in zip(model_values, measured)]
        bottom.axhline(0.0, color="#888888", linewidth=0.8)
        if series:
            bottom.plot(x, residuals, color=FITTED.color, linewidth=0.8)
        else:
            bottom.vlines(x, 0.0, residuals, color=FITTED.color)
            bottom.plot(x, residuals, color=FITTED.color, marker=FITTED.marker,
                        linestyle="None")
        bottom.set_ylabel(f"fitted - measured ({units[output]})" if output in units
                          else "fitted - measured")
        bottom.set_xlabel(label(x_name, {**units, "time": "s"}))
        rms = report["residuals"][output]["rms"]
        top.set_title(f"{output}: rms residual {heatmap.plain(_sig(rms))}"
                      f"{' ' + units[output] if output in units else ''}")
    style.legend(fig, axes[0][0].get_lines())
    fitted_text = ", ".join(_parameter(name, entry)
                            for name, entry in report["parameters"].items())
    fig.suptitle(f"{model} fitted to {data.path.rsplit('/', 1)[-1]}\n{fitted_text}")
    return fig


def _sig(value):
    return float(f"{value:.3g}") if math.isfinite(value) else value


def _parameter(name, entry):
    unit = f" {entry['unit']}" if entry["unit"] else ""
    error = f" ± {entry['stderr']:.2g}" if entry["stderr"] is not None else ""
    return f"{name} = {entry['value']:.4g}{error}{unit}"


def write(prefix, data, fitted, report, model, units):
    """Draws the fit's plot into PREFIX.png and PREFIX.svg; returns both paths."""
    with style.context():
        fig = figure(data, fitted, report, model, units)
        return style.save(fig, prefix)
