#!/usr/bin/env python3
"""Writes the problem file of a hanging chain of N hinged rods (the multibody scaling case).

    scripts/chain_toml.py N [STEPS] > chain.toml

Rod i (1 kg, 1 m, body axis e3 along the rod) hangs from rod i-1 (rod 0 from the ground at the
origin) by a hinge about e_y; it starts at the angle 0.3 sin(0.7 i) from the downward vertical
with the rate 0.2 cos(1.3 i), on the joints by construction: the same chain as the core's
`marsden::lie::multibody::chain::HangingChain`.
"""
import math
import sys


def chain(n: int, steps: int) -> str:
    out = [
        f"# A hanging chain of {n} hinged rods (written by scripts/chain_toml.py {n} {steps}).",
        "[system]",
        f'name = "chain_{n}"',
        "gravity = [0.0, 0.0, -9.81]",
        "",
    ]
    across = 1.0 / 12.0
    for i in range(n):
        out += ["[[system.body]]", f'name = "link{i}"', "mass = 1.0",
                f"inertia = [{across!r}, {across!r}, 0.001]", ""]
    for i in range(n):
        upper, point = ('"ground"', "[0.0, 0.0, 0.0]") if i == 0 else (f'"link{i - 1}"', "[0.0, 0.0, -0.5]")
        out += ["[[system.joint]]", f'name = "hinge{i}"', 'kind = "revolute"',
                f'bodies = [{upper}, "link{i}"]', f"at = [{point}, [0.0, 0.0, 0.5]]",
                "axis = [[0.0, 1.0, 0.0], [0.0, 1.0, 0.0]]", ""]
    top, top_v = [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]
    for i in range(n):
        theta = 0.3 * math.sin(0.7 * i)
        rate = 0.2 * math.cos(1.3 * i)
        along = [math.sin(theta), 0.0, math.cos(theta)]
        turning = [math.cos(theta) * rate, 0.0, -math.sin(theta) * rate]
        x = [top[k] - 0.5 * along[k] for k in range(3)]
        v = [top_v[k] - 0.5 * turning[k] for k in range(3)]
        out += [f"[initial.link{i}]", f"rotation_vector = [0.0, {theta!r}, 0.0]",
                f"x = [{x[0]!r}, {x[1]!r}, {x[2]!r}]", f"v = [{v[0]!r}, {v[1]!r}, {v[2]!r}]",
                f"Omega = [0.0, {rate!r}, 0.0]", ""]
        top = [top[k] - along[k] for k in range(3)]
        top_v = [top_v[k] - turning[k] for k in range(3)]
    out += ["[integrator]", 'method = "trapezoid"', "h = 0.001", f"steps = {steps}", "",
            "[output]", f"every = {max(1, steps // 100)}", ""]
    return "\n".join(out)


if __name__ == "__main__":
    n = int(sys.argv[1])
    steps = int(sys.argv[2]) if len(sys.argv) > 2 else 2000
    sys.stdout.write(chain(n, steps))
