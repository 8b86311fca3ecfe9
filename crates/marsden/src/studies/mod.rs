//! Many runs at once: ensembles of members in parallel ([`ensemble`]) and the empirical order of
//! convergence of a method against a reference solution ([`order`]).

pub mod ensemble;
pub mod order;
