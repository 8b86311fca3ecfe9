//! marsden: discrete mechanics and variational integrators.
