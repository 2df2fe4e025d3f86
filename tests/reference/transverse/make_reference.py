#!/usr/bin/env python3
"""Reference outputs for TransverseFriction: an independent implementation of the continuous-time ODE
("Scene T", continuous-time limit) solved with scipy's Radau IIA (order 5, L-stable) at
rtol = 1e-11.

Run:    python3 tests/reference/transverse/make_reference.py      (needs numpy, scipy)
Takes:  about 6 minutes on one core for both slip laws on the 3 x 3 grid (scipy may warn
        "overflow encountered in multiply" from its finite-difference Jacobian; harmless).
Writes next to this file:
  means.csv   slip_law, vd, va, f, t_end, FFx_mean  (mean of FFx over [t_end - 1/f, t_end])
  traces.csv  slip_law, vd, va, f, t, FF, FFx, FFy  (the last two periods, 40 samples a period)

Every case starts in steady 1D sliding at vd (the FMU's `initial = sliding`): x = 0, x' = vd,
drive stretched by FC/kd, contact deflected by g(vd) along x; the support starts vibrating at
t = 0. The run covers 60 vibration periods.

The right-hand side has kinks (|v1|, |v2| or |v1 + v2|) and, within a few vs of v1 + v2 = 0, a
damping pulse some tens of ns wide. Radau's error control cannot see a kink or pulse that falls
between its stages, so the integration stops at each zero of the kink functions and at the
edges |v1 + v2| = 4 vs of the pulse's band (terminal events), and restarts there with a short
first step.
"""
import csv
import math
import pathlib
import time

import numpy as np
from scipy.integrate import solve_ivp

HERE = pathlib.Path(__file__).resolve().parent

# Paper values (section 3 of paper T), SI units.
M = 0.56
MU = 0.178
G = 9.81
FC = MU * M * G
FS = 1.1 * FC
VS = 1e-6
KT = 62.86e6
ZETA = 1.0
HV = 0.0
KD = 0.92e6
HD = 0.0
ETA = 0.71
H0 = 2.0 * ZETA * math.sqrt(M * KT)

RTOL = 1e-11
PERIODS = 60
SAMPLES_PER_PERIOD = 40
BAND = 4.0


def g_defl(v):
    """Stribeck deflection g(v) (m), eq. 4."""
    return (FC + (FS - FC) * math.exp(-((v / VS) ** 2))) / KT


def ht(v):
    return H0 * math.exp(-((v / VS) ** 2))


class Case:
    def __init__(self, law, vd, va, f):
        self.law, self.vd, self.va, self.f = law, vd, va, f
        self.w = 2.0 * math.pi * f

    def support(self, t):
        """Velocity of the contact point M: eta * yp'."""
        return ETA * self.va * math.cos(self.w * t)

    def contact(self, t, y):
        """(FF, ex, ey, v1, v2, zx', zy') for state y = [x, vx, y, vy, zx, zy, lam, q]."""
        vx, vy, zx, zy = y[1], y[3], y[4], y[5]
        vm = self.support(t)
        wx, wy = vx, vy - vm
        s = math.hypot(zx, zy)
        if s > 0.0:
            ex, ey = zx / s, zy / s
        else:
            speed = math.hypot(wx, wy)
            ex, ey = (wx / speed, wy / speed) if speed > 0.0 else (1.0, 0.0)
        v1 = ex * vx + ey * vy
        v2 = -ey * vm
        if self.law == "split":
            slip = abs(v1) / g_defl(v1) + abs(v2) / g_defl(v2)
        else:
            slip = abs(v1 + v2) / g_defl(v1 + v2)
        dzx = wx - slip * zx
        dzy = wy - slip * zy
        sdot = ex * dzx + ey * dzy
        vr = v1 + v2
        ff = KT * s + ht(vr) * sdot + HV * vr
        return ff, ex, ey, v1, v2, dzx, dzy

    def rhs(self, t, y):
        ff, ex, ey, _, _, dzx, dzy = self.contact(t, y)
        fd = KD * y[6] + HD * (self.vd - y[1])
        return [y[1], (fd - ff * ex) / M, y[3], -ff * ey / M, dzx, dzy, self.vd - y[1], ff * ex]

    def kink_functions(self):
        def vr_minus(t, y):
            c = self.contact(t, y)
            return c[3] + c[4] - BAND * VS

        def vr_plus(t, y):
            c = self.contact(t, y)
            return c[3] + c[4] + BAND * VS

        if self.law == "split":
            def v1(t, y):
                return self.contact(t, y)[3]

            def v2(t, y):
                return self.contact(t, y)[4]

            events = [vr_minus, vr_plus, v1, v2]
        else:
            def vr(t, y):
                c = self.contact(t, y)
                return c[3] + c[4]

            events = [vr_minus, vr_plus, vr]
        for e in events:
            e.terminal = True
        return events

    def initial(self):
        y = np.zeros(8)
        y[1] = self.vd
        y[4] = g_defl(self.vd) * math.copysign(1.0, self.vd)
        y[6] = FC / KD * math.copysign(1.0, self.vd)
        return y

    def atol(self):
        z0 = FC / KT
        speed = abs(self.vd) + self.va + VS
        return RTOL * np.array([z0, speed, z0, speed, z0, z0, FC / KD, FC / self.f])


def integrate(case, t0, t1, y, events):
    """y(t1) from y(t0), stopping and restarting at every kink; q (y[7]) accumulates."""
    t = t0
    first = 1e-9 / max(1.0, case.f * 1e-3)
    while t < t1:
        # A short event-free first step moves the restarted kink function off its zero.
        t_next = min(t + first, t1)
        sol = solve_ivp(case.rhs, (t, t_next), y, method="Radau", rtol=RTOL,
                        atol=case.atol(), first_step=t_next - t)
        y, t = sol.y[:, -1], t_next
        if t >= t1:
            break
        sol = solve_ivp(case.rhs, (t, t1), y, method="Radau", rtol=RTOL, atol=case.atol(),
                        events=events, first_step=min(first, t1 - t))
        if not sol.success:
            raise RuntimeError(sol.message)
        y, t = sol.y[:, -1], sol.t[-1]
    return y


def run(case):
    period = 1.0 / case.f
    t_end = PERIODS * period
    events = case.kink_functions()
    y = case.initial()
    t = 0.0
    trace = []
    mean = None
    # Up to the start of the traced window, then from sample to sample.
    t_trace = t_end - 2.0 * period
    y = integrate(case, t, t_trace, y, events)
    t = t_trace
    samples = [t_trace + j * period / SAMPLES_PER_PERIOD for j in range(2 * SAMPLES_PER_PERIOD + 1)]
    samples[-1] = t_end
    for j, ts in enumerate(samples):
        if j > 0:
            y = integrate(case, t, ts, y, events)
            t = ts
        if j == SAMPLES_PER_PERIOD:
            y[7] = 0.0  # the last period's integral starts here
        ff, ex, ey, *_ = case.contact(t, y)
        trace.append((t, ff, ff * ex, -ff * ey))
    mean = y[7] / period
    return t_end, mean, trace


def main():
    grid_vd = [1e-4, 5e-4, 2e-3]
    grid_va = [3e-4, 2e-3, 12e-3]
    means, traces = [], []
    for law in ["split", "total"]:
        for vd in grid_vd:
            for va in grid_va:
                start = time.time()
                case = Case(law, vd, va, 3000.0)
                t_end, mean, trace = run(case)
                print(f"{law} vd {vd:g} va {va:g}: FFx_mean {mean:.12g} N "
                      f"({time.time() - start:.1f} s)", flush=True)
                means.append((law, vd, va, case.f, t_end, mean))
                traces += [(law, vd, va, case.f) + row for row in trace]
    with open(HERE / "means.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["slip_law", "vd", "va", "f", "t_end", "FFx_mean"])
        for row in means:
            w.writerow([row[0], repr(row[1]), repr(row[2]), repr(row[3]), repr(row[4]),
                        f"{row[5]:.15e}"])
    with open(HERE / "traces.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["slip_law", "vd", "va", "f", "t", "FF", "FFx", "FFy"])
        for row in traces:
            w.writerow([row[0], repr(row[1]), repr(row[2]), repr(row[3]), repr(row[4])]
                       + [f"{v:.15e}" for v in row[5:]])


if __name__ == "__main__":
    main()
