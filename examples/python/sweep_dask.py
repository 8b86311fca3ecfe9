"""An ensemble of pendulums on a Dask cluster: one member per rod length, distributed through
the cluster's concurrent.futures executor; the results equal the in-process sweep bit for bit.

    pip install ./crates/marsden-py "dask[distributed]"
    python examples/python/sweep_dask.py
"""

import numpy as np
from dask.distributed import Client, LocalCluster

import marsden

pendulum = marsden.Problem(
    lagrangian="0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)",
    coordinates=["theta"],
    parameters={"m": 1.0, "l": 1.0, "g": 9.81},
    q0=[1.0],
    v0=[0.0],
    h=0.01,
    t_end=20.0,
)
lengths = np.linspace(0.25, 4.0, 16)

if __name__ == "__main__":
    with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        on_dask = marsden.sweep(pendulum, "l", lengths, executor=client.get_executor())
    in_process = marsden.sweep(pendulum, "l", lengths)
    for l, s, t in zip(lengths, on_dask, in_process):
        same = np.array_equal(s.q, t.q) and np.array_equal(s.p, t.p)
        print(f"l = {l:5.2f}  θ(20) = {s.q[-1, 0]:+.6f}  "
              f"max |ΔE/E0| = {s.summary['energy']['max_rel_error']:.1e}  identical: {same}")
