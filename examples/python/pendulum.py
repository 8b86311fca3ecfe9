"""The planar pendulum from Python: the problem of examples/pendulum.toml as keyword arguments.

    pip install ./crates/marsden-py matplotlib
    python examples/python/pendulum.py
"""

import marsden

pendulum = marsden.Problem(
    lagrangian="0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)",
    coordinates=["theta"],
    parameters={"m": 1.0, "l": 1.0, "g": 1.0},
    q0=[1.5],
    v0=[0.0],
    method="midpoint",
    h=0.05,
    steps=100_000,
)
solution = pendulum.solve(every=10)
print(solution)
print("final state:", solution.final_state())
print("max |ΔE/E0| =", solution.summary["energy"]["max_rel_error"])

try:
    solution.plot().savefig("pendulum.png")
    print("wrote pendulum.png")
except ImportError:
    print("(install matplotlib for the plots)")
