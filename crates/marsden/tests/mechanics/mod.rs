//! Continuous mechanics and the catalog: AD against finite differences, Legendre transform, accelerations, hand-written potential derivatives, forces.

mod ad_finite_differences;
mod catalog;
mod continuous;
mod forces;
mod potential_gradients;
