"""Kepler's problem (e = 0.6) from a SymPy Lagrangian, one period of the midpoint rule: the
angular momentum is a discrete momentum map (reference case R10)."""

import numpy as np
import sympy as sp

import marsden

x, y, x_dot, y_dot = sp.symbols("x y x_dot y_dot")
lagrangian = sp.Rational(1, 2) * (x_dot**2 + y_dot**2) + 1 / sp.sqrt(x**2 + y**2)
print("L =", marsden.to_grammar(lagrangian))  # the problem-file grammar

kepler = marsden.Problem(
    lagrangian=lagrangian,
    coordinates=[x, y],
    q0=[0.4, 0.0],                 # pericentre 1 − e
    p0=[0.0, 2.0],                 # √((1 + e)/(1 − e))
    method="midpoint",
    h=2 * np.pi / 1000,
    steps=1000,                    # one period
    tolerance=1e-14,
    symmetries={"Lz": [-y, x]},    # the generator ξ_Q(q) of rotations about z
)
solution = kepler.solve(every=2)
lz = solution.momenta["Lz"]
drift = float(np.max(np.abs(lz - lz[0])))
print(f"L_z = {lz[0]:.15f}, max drift {drift:.1e}; q after one period = {solution.q[-1]}")

result = {"angular_momentum_drift": drift, "q_x_after_one_period": float(solution.q[-1, 0])}
