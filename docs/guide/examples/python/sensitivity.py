"""∂(x_N, p_N)/∂(x_0, p_0) for the midpoint oscillator: the rotation by Nθ, θ = 2 arctan(h/2)
(reference case R1)."""

import numpy as np

import marsden

oscillator = marsden.Problem(
    lagrangian="0.5*x_dot^2 - 0.5*x^2", coordinates=["x"],
    q0=[1.0], p0=[0.0], method="midpoint", h=0.1, steps=100, tolerance=1e-14)
solution = oscillator.solve(sensitivity=True)
jacobian = solution.sensitivity.final
theta = 2 * np.arctan(0.05)
print(jacobian)
print("rotation by Nθ:", np.array([[np.cos(100 * theta), np.sin(100 * theta)],
                                   [-np.sin(100 * theta), np.cos(100 * theta)]]))

result = {"dq_dq0": float(jacobian[0, 0])}
