"""Python tools around the friction-fmu FMUs: parameter sweeps (`python -m friction_fmu.sweep`)."""
