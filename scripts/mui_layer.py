"""The transient of a mu(I) layer on an infinite incline, from rest: the 1D
problem of tests/mui_layer_fixture.hpp (same scheme), for the figures of
scripts/validation_figures.py."""
import math

import numpy as np

RHO, PHI_MAX, G = 2500.0, 0.6, 9.81  # the shipped scenes' sand (validation_figures.py uses these)


def infinite_layer(times, cells=200, depth=0.02, theta=25.0, mu_s=0.38, delta_mu=0.26, i0=0.279,
                   d=5e-4):
    """The mu(I) layer of incline_mui2d (2 cm of Jop et al.'s glass beads at 25
    degrees) on an infinite incline: the cells' speeds at each of `times`."""
    g_t, g_n = G * math.sin(math.radians(theta)), G * math.cos(math.radians(theta))
    dz = depth / cells
    p = RHO * PHI_MAX * g_n * (depth - np.arange(cells) * dz)  # on face i, below cell i
    max_dt = 0.2 * dz * dz / (delta_mu / i0 * d * math.sqrt(g_n * depth / PHI_MAX))
    u, t, out = np.zeros(cells), 0.0, []
    for until in times:
        while t < until - 1e-12:
            dt = min(max_dt, until - t)
            rate = np.maximum(0.0, np.diff(np.concatenate([[0.0], u])) / dz)
            rate[0] = max(0.0, u[0] / (dz / 2))
            inertial = rate * d / np.sqrt(p / RHO)
            mu = mu_s + delta_mu * inertial / (inertial + i0)
            tau = np.append(mu * p, 0.0)
            u = u + dt * (g_t + np.diff(tau) / (RHO * PHI_MAX * dz))
            t += dt
        out.append(u.copy())
    return out
