#!/usr/bin/env python3
"""Monolithic reference for the co-simulation of DriveTrain and TransverseFriction
(examples/drive_coupling.py): ONE ODE holding the drive's and the friction model's equations,
solved with scipy's Radau IIA (order 5, L-stable) at rtol = 1e-11. An independent implementation
(this file does not read the crate), so the coupled FMUs' error against it is the coupling error
plus their own (far smaller) integration error.

Run:    python3 tests/reference/drive/make_reference.py      (needs numpy, scipy)
Takes:  about a minute on one core.
Writes: reference.csv next to this file: t, v_nut, x_nut, Fd, x every 5e-5 s over [0, 0.04] s.

The case: both models at their defaults (TransverseFriction's defaults; DriveTrain's illustrative stage),
except no support vibration (va = 0). At t = 0 everything is at rest and the motor is switched
on at V = 1.58 V. The nut is the far end of the drive spring: Fd = kd (x_nut - x) + hd (v_nut - x')
is the spring's pull on the body and the load on the nut. With va = 0 the contact is classical
1D LuGre (the split law with v2 = 0):

    L i'        = V - R i - ke w
    J_eff w'    = kt_m i - b w - r Fd / eff,   r = lead / (2 pi n),  J_eff = J + m_nut r^2 / eff
    x_nut'      = r w
    z'          = x' - |x'| z / g(x'),   FFx = kt z + ht(x') z' + hv x'
    m x''       = Fd - FFx
    lam'        = r w - x'       (lam = x_nut - x, kept as a state so Fd keeps its digits)

The right-hand side has a kink at x' = 0 and the damping pulse |x'| < 4 vs; the integration stops
at x' = 0 and at x' = +-4 vs (terminal events) and restarts there, as in
tests/reference/transverse/make_reference.py.
"""
import csv
import math
import pathlib
import time

import numpy as np
from scipy.integrate import solve_ivp

HERE = pathlib.Path(__file__).resolve().parent

# DriveTrain defaults.
V = 1.58
R_ARM = 5.0
L_ARM = 1e-3
KT_M = 0.01
KE = 0.01
J = 2e-7
B = 1e-7
N = 50.0
EFF = 0.9
LEAD = 1e-3
M_NUT = 0.05
R_SCREW = LEAD / (2.0 * math.pi * N)
J_EFF = J + M_NUT * R_SCREW**2 / EFF

# TransverseFriction defaults, va = 0.
M = 0.56
FC = 0.178 * M * 9.81
FS = 1.1 * FC
VS = 1e-6
KT = 6.286e7
H0 = 2.0 * 1.0 * math.sqrt(M * KT)
HV = 0.0
KD = 9.2e5
HD = 0.0

RTOL = 1e-11
BAND = 4.0
STOP = 0.04
SAMPLE = 5e-5

# State: i, w, x_nut, x, vx, z, lam.
ATOL = RTOL * np.array([FC / KT_M, 5e-4 / R_SCREW, FC / KD, FC / KT, 5e-4, FC / KT, FC / KD])


def g_defl(v):
    return (FC + (FS - FC) * math.exp(-((v / VS) ** 2))) / KT


def outputs(y):
    """(v_nut, x_nut, Fd, x, FFx, z')."""
    i, w, x_nut, x, vx, z, lam = y
    v_nut = R_SCREW * w
    fd = KD * lam + HD * (v_nut - vx)
    dz = vx - abs(vx) / g_defl(vx) * z
    ffx = KT * z + H0 * math.exp(-((vx / VS) ** 2)) * dz + HV * vx
    return v_nut, x_nut, fd, x, ffx, dz


def rhs(t, y):
    i, w, x_nut, x, vx, z, lam = y
    v_nut, _, fd, _, ffx, dz = outputs(y)
    return [
        (V - R_ARM * i - KE * w) / L_ARM,
        (KT_M * i - B * w - R_SCREW * fd / EFF) / J_EFF,
        v_nut,
        vx,
        (fd - ffx) / M,
        dz,
        v_nut - vx,
    ]


def events():
    def band_low(t, y):
        return y[4] - BAND * VS

    def band_high(t, y):
        return y[4] + BAND * VS

    def kink(t, y):
        return y[4]

    for e in (band_low, band_high, kink):
        e.terminal = True
    return [band_low, band_high, kink]


def integrate(t0, t1, y):
    """y(t1) from y(t0), stopping and restarting at every kink and band edge."""
    t = t0
    first = 1e-9
    while t < t1:
        # A short event-free first step moves a restarted event function off its zero.
        t_next = min(t + first, t1)
        sol = solve_ivp(rhs, (t, t_next), y, method="Radau", rtol=RTOL, atol=ATOL,
                        first_step=t_next - t)
        y, t = sol.y[:, -1], t_next
        if t >= t1:
            break
        sol = solve_ivp(rhs, (t, t1), y, method="Radau", rtol=RTOL, atol=ATOL,
                        events=events(), first_step=min(first, t1 - t))
        if not sol.success:
            raise RuntimeError(sol.message)
        y, t = sol.y[:, -1], sol.t[-1]
    return y


def main():
    start = time.time()
    y = np.zeros(7)
    rows = []
    samples = round(STOP / SAMPLE)
    for k in range(samples + 1):
        t = k * SAMPLE
        if k > 0:
            y = integrate((k - 1) * SAMPLE, t, y)
        v_nut, x_nut, fd, x, _, _ = outputs(y)
        rows.append((t, v_nut, x_nut, fd, x))
    with open(HERE / "reference.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["t", "v_nut", "x_nut", "Fd", "x"])
        for row in rows:
            w.writerow([repr(round(row[0], 12))] + [f"{v:.15e}" for v in row[1:]])
    print(f"{len(rows)} samples in {time.time() - start:.1f} s; Fd at the end {rows[-1][3]:.6f} N")


if __name__ == "__main__":
    main()
