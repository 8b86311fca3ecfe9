"""The pendulum swing-up (DMOC) from Python: the problem file of pendulum_swing_up.toml."""

import pathlib

import marsden

here = pathlib.Path(__file__).resolve().parent
solution = marsden.Problem.load(here.parent / "pendulum_swing_up.toml").optimize()
print(solution)
print(f"status {solution.status}, cost {solution.cost:.6f}, max |u| = {abs(solution.u).max():.3f}")

result = {"cost": solution.cost}
