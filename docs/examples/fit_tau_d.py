"""Fit the relaxation time tau and the indentation depth d of a material to a
measured velocity step (here a synthetic one: mdrmap's own curve plus noise),
with scipy.optimize.least_squares calling mdrmap.simulate, and their 95%
confidence intervals from the Jacobian at the optimum.

    PYTHONPATH=build/python python3 docs/examples/fit_tau_d.py
"""
import time

import numpy as np
from scipy.optimize import least_squares

import mdrmap

# the experiment: a parabolic indenter (R = 10) slides at v = 1, then at 0.1
# from t = 0 on; mu is recorded at 201 instants over 8 time units
R, V0, V1, T_END, SAMPLES = 10.0, 1.0, 0.1, 8.0, 201
TRUE = {"tau": 1.5, "d": 0.02}
NOISE = 2e-4  # standard deviation of the measured mu


def curve(tau, d):
    r = mdrmap.simulate(d=d, R=R, tau=tau, v=V0, v1=V1, t_end=T_END, samples=SAMPLES)
    return r.t, r.mu


t, mu_true = curve(**TRUE)
measured = mu_true + np.random.default_rng(1).normal(0.0, NOISE, mu_true.size)


def residuals(x):  # x = (log tau, log d): both positive, over decades
    return curve(np.exp(x[0]), np.exp(x[1]))[1] - measured


start = time.perf_counter()
fit = least_squares(residuals, x0=np.log([0.5, 0.05]), x_scale=1.0)
seconds = time.perf_counter() - start

# covariance of (log tau, log d): s^2 (J^T J)^-1, s^2 the residual variance
dof = measured.size - fit.x.size
s2 = 2.0 * fit.cost / dof
cov = s2 * np.linalg.inv(fit.jac.T @ fit.jac)
ok = True
for k, name in enumerate(["tau", "d"]):
    est, half = np.exp(fit.x[k]), 1.96 * np.sqrt(cov[k, k])  # half-width in log
    lo, hi = est * np.exp(-half), est * np.exp(half)
    inside = lo <= TRUE[name] <= hi
    ok &= inside
    print(f"{name:>4} = {est:.6g}   95% CI [{lo:.6g}, {hi:.6g}]   true {TRUE[name]:g}"
          f"   {'inside' if inside else 'OUTSIDE'}")
print(f"residual rms {np.sqrt(s2):.3g} (noise {NOISE:g}); {fit.nfev} evaluations, "
      f"{fit.njev} Jacobians; run time {seconds:.3f} s")
print("recovered the true values" if ok else "did NOT recover the true values")
raise SystemExit(0 if ok else 1)
