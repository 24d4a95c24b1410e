#!/usr/bin/python3
"""What implicit (backward) Euler itself does to a rotating body, apart from any linearization: a
point mass m on a stiff spring (stiffness k, rest length r0) about a fixed centre, set turning at
omega, each step solved exactly (scipy's fsolve on the implicit Euler residual
m (v - v_n) = h F(x_n + h v)). Prints the energy kept after n steps and 1 / (1 + (omega h)^2)^n,
the per-step factor of an undamped oscillation of frequency omega under backward Euler.
  /usr/bin/python3 scripts/backward_euler_rotation.py [--omega 20] [--h 0.005] [--steps 100] [--k 1e6]"""
import argparse

import numpy as np
import warnings

from scipy.optimize import fsolve

warnings.filterwarnings("ignore", module="scipy")  # fsolve: no improvement possible at round-off

ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("--omega", type=float, default=20.0)
ap.add_argument("--h", type=float, default=0.005)
ap.add_argument("--steps", type=int, default=100)
ap.add_argument("--k", type=float, default=1e6)
a = ap.parse_args()
m, r0 = 1.0, 1.0
x, v = np.array([r0, 0.0]), np.array([0.0, a.omega * r0])


def force(y):
    r = np.linalg.norm(y)
    return -a.k * (r - r0) * y / r


def energy(y, w):
    return 0.5 * m * w @ w + 0.5 * a.k * (np.linalg.norm(y) - r0) ** 2


e0 = energy(x, v)
for _ in range(a.steps):
    v = fsolve(lambda w: m * (w - v) - a.h * force(x + a.h * w), v, xtol=1e-13)
    x = x + a.h * v
print("omega h = %g, %d steps: energy kept %.4f; 1 / (1 + (omega h)^2)^n = %.4f"
      % (a.omega * a.h, a.steps, energy(x, v) / e0, (1.0 + (a.omega * a.h) ** 2) ** -a.steps))
