"""The two records of the card example in docs/fitting.md: velocity steps of
a sphere R = 0.05 under the load F0 = 0.01 on the material of
jobs/examples/rubber_card.inp, shifted by aT = 0.3, simulated at rtol 1e-6,
mu and the depth d with 1% Gaussian noise (seeded). Writes
jobs/examples/fit_card_a.csv and fit_card_b.csv.

    PYTHONPATH=build/python python3 docs/examples/fit_card_records.py
"""
import os
import tempfile

import numpy as np

import mdrmap

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
CARD = os.path.join(ROOT, "jobs", "examples", "rubber_card.inp")
SCENES = {"a": [(0.1, 2.0), (1.0, 2.0), (0.1, 4.0)],  # (v, duration), 8 rows each
          "b": [(1.0, 1.0), (0.01, 4.0), (1.0, 2.0)]}
rng = np.random.default_rng(33)

for name, segments in SCENES.items():
    t = np.concatenate([t0 + np.arange(8) * T / 8 for t0, (_, T) in
                        zip(np.cumsum([0.0] + [T for _, T in segments[:-1]]), segments)])
    v = np.repeat([w for w, _ in segments], 8)
    t, v = np.append(t, sum(T for _, T in segments)), np.append(v, segments[-1][0])
    with tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False) as f:
        f.write("t,v\n" + "".join(f"{a:.17g},{b:.17g}\n" for a, b in zip(t, v)))
    r = mdrmap.simulate(material=CARD, tau=0, F0=0.01, R=0.05, aT=0.3, history_file=f.name,
                        rtol=1e-6)
    os.unlink(f.name)
    mu = r.mu * (1 + 0.01 * rng.standard_normal(r.mu.size))
    d = r.d * (1 + 0.01 * rng.standard_normal(r.d.size))
    with open(os.path.join(ROOT, "jobs", "examples", f"fit_card_{name}.csv"), "w") as out:
        out.write("t,v,mu,d\n")
        out.writelines(f"{a:g},{b:g},{m:.6g},{x:.6g}\n" for a, b, m, x in zip(t, v, mu, d))
