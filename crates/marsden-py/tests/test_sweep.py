"""Ensembles: in process (rayon) and on executors (a process pool, a real Dask LocalCluster
with two worker processes), identical bit for bit; a failing member is reported in place."""

from __future__ import annotations

import concurrent.futures

import numpy as np
import pytest

import marsden
from conftest import PENDULUM

LENGTHS = [0.5 + 0.1 * k for k in range(16)]


def pendulum(steps: int = 2000) -> marsden.Problem:
    return marsden.Problem(**PENDULUM, steps=steps)


def assert_identical(a: list, b: list) -> None:
    assert len(a) == len(b)
    for k, (x, y) in enumerate(zip(a, b)):
        assert type(x) is type(y), k
        if isinstance(x, marsden.Solution):
            for field in ("t", "q", "p", "v", "energy"):
                assert np.array_equal(getattr(x, field), getattr(y, field)), (k, field)
            assert x.status == y.status and x.summary["final_state"] == y.summary["final_state"]
        else:
            assert str(x) == str(y), k


def test_in_process_sweep_members_equal_single_runs():
    sols = marsden.sweep(pendulum(), "l", LENGTHS[:4])
    assert [s.status for s in sols] == ["completed"] * 4
    for l, s in zip(LENGTHS[:4], sols):
        alone = marsden.Problem(**{**PENDULUM, "parameters": {"m": 1.0, "l": l, "g": 1.0}},
                                steps=2000).solve()
        assert np.array_equal(s.q, alone.q) and np.array_equal(s.p, alone.p)
    # Longer pendulums swing slower: the period grows like sqrt(l).
    assert sols[0].summary["final_state"] != sols[-1].summary["final_state"]


def test_threads_do_not_change_the_bits():
    one = marsden.sweep(pendulum(), "l", LENGTHS[:6], threads=1)
    two = marsden.sweep(pendulum(), "l", LENGTHS[:6], threads=2)
    assert_identical(one, two)


def test_sweep_over_an_initial_value():
    sols = marsden.sweep(pendulum(200), initial="q[0]", values=[0.1, 0.2])
    assert [s.q[0, 0] for s in sols] == [0.1, 0.2]


def test_a_failing_member_is_reported_and_the_others_complete():
    """Kepler (zero angular momentum for p_y = 0) collides at r = 0; the other members orbit."""
    kepler = marsden.Problem.builtin("kepler", q0=[1.0, 0.0], p0=[0.0, 1.0], h=0.01, steps=500)
    sols = marsden.sweep(kepler, initial="p[1]", values=[1.0, 0.0, 0.9])
    assert [s.status for s in sols] == ["completed", "failed", "completed"]
    failed = sols[1]
    assert failed.error and np.all(np.isfinite(failed.q)) and len(failed) < 501
    # A value the problem cannot take (a position off the constraint x² + y² = l²): that
    # member is a ProblemError in its place.
    cart = marsden.Problem(
        lagrangian="0.5*(x_dot^2 + y_dot^2) - y", coordinates=["x", "y"],
        constraints=["x^2 + y^2 - 1"], q0=[0.0, -1.0], v0=[0.0, 0.0], h=0.05, steps=100)
    bad = marsden.sweep(cart, initial="q[0]", values=[0.0, 0.5])
    assert isinstance(bad[0], marsden.Solution)
    assert isinstance(bad[1], marsden.ProblemError), bad[1]
    assert "constraint" in str(bad[1]), str(bad[1])


def test_process_pool_equals_in_process():
    values = LENGTHS[:4]
    local = marsden.sweep(pendulum(), "l", values)
    with concurrent.futures.ProcessPoolExecutor(max_workers=2) as pool:
        remote = marsden.sweep(pendulum(), "l", values, executor=pool)
    assert_identical(local, remote)


def test_dask_local_cluster_equals_in_process_bit_for_bit():
    """16 members on a Dask LocalCluster with 2 worker processes on localhost."""
    distributed = pytest.importorskip("dask.distributed")
    kepler = marsden.Problem.builtin("kepler", q0=[1.0, 0.0], p0=[0.0, 1.0], h=0.01, steps=500)
    values = [0.5 + 0.05 * k for k in range(15)] + [0.0]  # the last one collides
    local = marsden.sweep(kepler, initial="p[1]", values=values)
    with distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1,
                                  host="127.0.0.1", dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        remote = marsden.sweep(kepler, initial="p[1]", values=values,
                               executor=client.get_executor())
    assert_identical(local, remote)
    assert [s.status for s in remote].count("failed") == 1 and remote[-1].status == "failed"
