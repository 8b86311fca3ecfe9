"""The pendulum of pendulum.toml from Python (reference case R8: max |H − H0| = 8.9926e-5)."""

import marsden

pendulum = marsden.Problem(
    lagrangian="0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)",
    coordinates=["theta"],
    parameters={"m": 1.0, "l": 1.0, "g": 1.0},
    q0=[1.5],
    v0=[0.0],
    method="midpoint",
    h=0.05,
    steps=4000,
    tolerance=1e-14,
    every_step=True,  # the energy maxima over every step, not only the stored ones
)
solution = pendulum.solve(every=10)
energy = solution.summary["energy"]
print(solution)
print(f"E0 = {energy['initial']:.16f}, max |ΔE| = {energy['max_abs_error']:.4e}")

result = {"max_abs_energy_error": energy["max_abs_error"]}
