//! The Hamiltonian side: the same system as L and as H, the Legendre adapters.

mod cross_form;
mod legendre;
