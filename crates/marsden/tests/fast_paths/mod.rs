//! Every fast path against the general path (bit for bit or to round-off), and the work statistics.

mod compensated;
mod explicit;
mod explicit_run;
mod hessian_contract;
mod jacobian_reuse;
mod separable;
mod small_constrained_kernels;
mod small_kernels;
mod statistics;
mod validity;
