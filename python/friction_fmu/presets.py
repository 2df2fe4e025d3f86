"""Stored sweeps, each a grid file beside this module plus how to show it.

`fig8`: the steady mean friction force of Scene T over drive velocity x vibration velocity at 3
and 2 kHz (Fig. 8 of the transverse-vibration paper), with the values `friction-fmu run` uses
for its table (src/report/transverse.rs): each point starts on its periodic orbit (`initial =
periodic`), and the mean of FFx is taken over 30 periods. FFx_mean is the mean over the period
just completed; sampled once per period, the mean of its last 30 samples is that 30-period mean.
Where shooting stalls short of the tolerance (stick-slip at the slowest drives), the FMU warns,
the point's status says so, and the run starts from the state nearest to the orbit.
"""
import pathlib

from .grid import load_file

HERE = pathlib.Path(__file__).resolve().parent


def built(model):
    """The FMU `friction-fmu build` packed: under ./fmu-out, else in this checkout's fmu-out."""
    here = pathlib.Path("fmu-out") / f"{model}.fmu"
    return str(here if here.exists() else HERE.parents[1] / here)


PRESETS = {
    "fig8": {
        "plan": lambda: load_file(HERE / "fig8.toml"),
        "fmu": built("TransverseFriction"),
        "out": "fmu-out/sweeps/fig8",
        "heatmap": {"x": "va", "y": "vd", "color": "FFx_mean:mean_last=30/f"},
        "title": "TransverseFriction: steady mean FFx over the last 30 periods (Fig. 8)",
    },
}
