"""An ensemble: the pendulum from ten amplitudes, on all cores (or any executor, e.g. Dask's
``Client().get_executor()``)."""

import marsden

pendulum = marsden.Problem(
    builtin="pendulum", q0=[0.5], v0=[0.0], method="midpoint", h=0.05, steps=4000)
amplitudes = [0.05 * (k + 1) for k in range(10)]
members = marsden.sweep(pendulum, initial="q[0]", values=amplitudes)
errors = [m.summary["energy"]["max_rel_error"] for m in members]
for a, e in zip(amplitudes, errors):
    print(f"q0 = {a:.2f}: max |ΔE/E0| = {e:.2e}")

result = {"max_energy_error_small_amplitude": max(errors)}
