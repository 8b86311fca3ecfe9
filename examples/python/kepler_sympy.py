"""The Kepler problem written in SymPy: the Lagrangian is printed in the problem-file grammar and
integrated in Rust; the angular momentum L_z is a monitored momentum map.

    pip install ./crates/marsden-py sympy
    python examples/python/kepler_sympy.py
"""

import numpy as np
import sympy as sp

import marsden

x, y, x_dot, y_dot, mu = sp.symbols("x y x_dot y_dot mu")
lagrangian = sp.Rational(1, 2) * (x_dot**2 + y_dot**2) + mu / sp.sqrt(x**2 + y**2)
print("L =", marsden.to_grammar(lagrangian))

e = 0.6  # eccentricity: released at the pericentre 1 - e with the speed sqrt((1 + e)/(1 - e))
kepler = marsden.Problem(
    lagrangian=lagrangian,
    coordinates=[x, y],
    parameters={"mu": 1.0},
    q0=[1 - e, 0.0],
    p0=[0.0, np.sqrt((1 + e) / (1 - e))],
    method="gauss-2",
    # The period is 2π (semi-major axis 1): 600 steps a period, ten periods. (`t_end = 20π`
    # with h = 0.01 would not be a whole number of steps, which is refused.)
    h=2 * np.pi / 600,
    steps=6000,
    tolerance=1e-14,  # Newton to round-off: L_z then drifts by round-off only
    symmetries={"Lz": [-y, x]},
)
solution = kepler.solve(every=10)
print(solution)
lz = solution.momenta["Lz"]
print(f"L_z = {lz[0]:.15f}, max drift {np.max(np.abs(lz - lz[0])):.1e}")
