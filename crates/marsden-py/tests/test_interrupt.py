"""Ctrl-C during a long run raises KeyboardInterrupt promptly, and the interpreter carries on
(nothing corrupted: the next run gives the same bits as before)."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time

SCRIPT = textwrap.dedent("""
    import signal, sys, time
    import numpy as np
    import marsden
    # Ctrl-C as in an interactive interpreter: a process started in the background by a shell
    # without job control inherits SIGINT ignored, and Python then installs no handler.
    signal.signal(signal.SIGINT, signal.default_int_handler)
    p = marsden.Problem(lagrangian="0.5*theta_dot^2 + cos(theta)", coordinates=["theta"],
                        q0=[1.5], v0=[0.0], h=0.05, steps=10**9)
    short = marsden.Problem(lagrangian="0.5*theta_dot^2 + cos(theta)", coordinates=["theta"],
                            q0=[1.5], v0=[0.0], h=0.05, steps=1000)
    before = short.solve()
    print("running", flush=True)
    start = time.perf_counter()
    try:
        p.solve(every=10**6)
        print("not interrupted", flush=True)
    except KeyboardInterrupt:
        print(f"interrupted after {time.perf_counter() - start:.2f} s", flush=True)
    after = short.solve()
    print("same after:", np.array_equal(before.q, after.q) and np.array_equal(before.p, after.p))
""")


def test_ctrl_c_raises_keyboard_interrupt_and_leaves_a_working_interpreter():
    child = subprocess.Popen([sys.executable, "-c", SCRIPT], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True)
    assert child.stdout is not None
    assert child.stdout.readline().strip() == "running"
    time.sleep(0.5)
    sent = time.perf_counter()
    os.kill(child.pid, signal.SIGINT)
    out, err = child.communicate(timeout=60)
    assert child.returncode == 0, err
    lines = out.strip().splitlines()
    assert lines[0].startswith("interrupted after"), out + err
    assert time.perf_counter() - sent < 10.0
    assert lines[1] == "same after: True", out
