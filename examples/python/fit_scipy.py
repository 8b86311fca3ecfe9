"""Fitting a parameter with scipy.optimize: the damping coefficient of an oscillator from
noisy observations of its position. Each evaluation of the misfit is one marsden run (in Rust,
no Python in the loop); sensitivities are not available yet, so the optimiser differentiates
by finite differences.

    pip install ./crates/marsden-py scipy
    python examples/python/fit_scipy.py
"""

import numpy as np
from scipy.optimize import minimize_scalar

import marsden


def oscillator(c: float) -> marsden.Problem:
    return marsden.Problem(
        lagrangian="0.5*m*x_dot^2 - 0.5*k*x^2",
        coordinates=["x"],
        parameters={"m": 1.0, "k": 4.0, "c": c},
        forces=["-c*x_dot"],
        q0=[1.0],
        v0=[0.0],
        h=0.01,
        t_end=10.0,
    )


true_c = 0.3
rng = np.random.default_rng(1)
truth = oscillator(true_c).solve(every=20)
observed = truth.q[:, 0] + 0.01 * rng.standard_normal(len(truth.t))


def misfit(c: float) -> float:
    return float(np.sum((oscillator(c).solve(every=20).q[:, 0] - observed) ** 2))


fit = minimize_scalar(misfit, bounds=(0.0, 1.0), method="bounded",
                      options={"xatol": 1e-6})
print(f"true c = {true_c}, fitted c = {fit.x:.4f} after {fit.nfev} runs")
