"""Healing in slide-hold-slide tests under load, through the module: the
table of `python -m mdrmap healing` (dmu_peak against the hold time) in a few lines.

    PYTHONPATH=build/python python3 docs/examples/healing.py
    (the same as: python3 -m mdrmap healing --F0 0.0533 --holds 0.1,1,10,100)
"""
import math

import numpy as np

import mdrmap

F0, R, TAU, G, ZETA0 = 0.0533, 100.0, 1.0, 1.0, 1.0
HOLDS = [0.1, 1.0, 10.0, 100.0]  # in units of tau

a0 = (3.0 * F0 * R / (16.0 * G)) ** (1.0 / 3.0)  # Hertz radius of F0
v0 = ZETA0 * a0 / TAU
T = max(20.0 * TAU, 20.0 * a0 / v0)  # the reslide


def peak(hold):
    """(dmu_peak / (a0/R), slip of the peak / a0) of the reslide after a hold."""
    r = mdrmap.simulate(F0=F0, R=R, tau=TAU, G=G, v=v0, history=[(0.0, hold * TAU), (v0, T)],
                        samples=121, spacing="log", log_decades=6, rtol=1e-4)
    a = r.case["a0"]
    mu, t = r.mu[r.segment == 1], r.t[r.segment == 1]
    i = int(mu.argmax())
    return (mu[i] - r.pre["mu"]) / (a / R), v0 * (t[i] - t[0]) / a


y = [peak(h) for h in HOLDS]
print("# dmu_peak in units of a0/R, slip_peak of a0; per_decade = change of dmu_peak from "
      "the previous hold / decades between them")
print(f"zeta0 = {ZETA0:g}")
print(f"{'t_hold/tau':>12} {'dmu_peak':>12} {'slip_peak':>12} {'per_decade':>12}")
for k, h in enumerate(HOLDS):
    per = (y[k][0] - y[k - 1][0]) / math.log10(h / HOLDS[k - 1]) if k else math.nan
    print(f"{h:>12.4g} {y[k][0]:>12.5g} {y[k][1]:>12.4g} {per:>12.5g}")
slope = np.polyfit(np.log10(HOLDS), [v[0] for v in y], 1)[0]
print(f"slope d(dmu_peak)/d(log10 t_hold) over all holds: {slope:.5g}")
