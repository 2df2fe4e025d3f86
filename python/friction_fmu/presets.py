"""Stored sweeps. `fig8`: the steady mean friction force of Scene T over drive velocity x
vibration velocity at 3 and 2 kHz (Fig. 8 of the transverse-vibration paper), with the values
`friction-fmu report` uses (src/report/transverse.rs): 120 periods from steady sliding to settle,
then the mean of FFx over the 30 periods that follow."""
import pathlib

from .grid import Output, Plan, Span

ROOT = pathlib.Path(__file__).resolve().parents[2]


def fig8():
    return Plan(
        grid={
            "vd": [1e-4, 3e-4, 5e-4, 8e-4, 2e-3, 4e-3],
            "va": [3e-4, 6e-4, 1.5e-3, 2e-3, 4e-3, 12e-3],
            "f": [3000.0, 2000.0],
        },
        fixed={"initial": "sliding", "tolerance": 1e-8},
        # FFx_mean is the mean over the period just completed; sampled once per period, the
        # mean of its last 30 samples is the mean of FFx over the last 30 periods.
        outputs=[Output("FFx_mean"), Output("FFx_mean", Span(30.0, "f"))],
        stop_time=Span(150.0, "f"),
        step=Span(1.0, "f"),
    )


PRESETS = {
    "fig8": {
        "plan": fig8,
        "fmu": str(ROOT / "fmu-out" / "TransverseFriction.fmu"),
        "out": "fmu-out/sweeps/fig8",
        "heatmap": {"x": "va", "y": "vd", "color": "FFx_mean:mean_last=30/f"},
        "title": "TransverseFriction: steady mean FFx over the last 30 periods (Fig. 8)",
    },
}
