"""Fitting parameters with scipy.optimize: the stiffness and damping coefficient of an
oscillator from noisy observations of its position. Each evaluation is one marsden run (in
Rust, no Python in the loop) that also returns the derivatives of every stored position with
respect to the parameters (`solve(sensitivity=["k", "c"])`: a tangent run beside the run), so
the least-squares solver gets an exact Jacobian instead of differencing runs.

    pip install ./crates/marsden-py scipy
    python examples/python/fit_scipy.py
"""

import numpy as np
from scipy.optimize import least_squares

import marsden

EVERY = 20


def oscillator(k: float, c: float) -> marsden.Problem:
    return marsden.Problem(
        lagrangian="0.5*m*x_dot^2 - 0.5*k*x^2",
        coordinates=["x"],
        parameters={"m": 1.0, "k": k, "c": c},
        forces=["-c*x_dot"],
        q0=[1.0],
        v0=[0.0],
        h=0.01,
        t_end=10.0,
    )


true_k, true_c = 4.0, 0.3
rng = np.random.default_rng(1)
truth = oscillator(true_k, true_c).solve(every=EVERY)
observed = truth.q[:, 0] + 0.01 * rng.standard_normal(len(truth.t))


def run(theta):
    return oscillator(*theta).solve(every=EVERY, sensitivity=["k", "c"])


def residuals(theta):
    return run(theta).q[:, 0] - observed


def jacobian(theta):
    # ∂x(t_i)/∂(k, c) at the stored samples: row 0 (q_x) of each stored Jacobian.
    return run(theta).sensitivity.jacobians[:, 0, :]


fit = least_squares(residuals, x0=[3.0, 0.1], jac=jacobian)
print(f"true (k, c) = ({true_k}, {true_c}), fitted = ({fit.x[0]:.4f}, {fit.x[1]:.4f}) "
      f"after {fit.nfev} runs and {fit.njev} Jacobians")
