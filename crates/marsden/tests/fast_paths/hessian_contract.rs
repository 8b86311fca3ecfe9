//! The contract of `Lagrangian::potential_hessian`: every caller in the crate hands it a matrix
//! whose entries start at zero, so an implementation may write only its nonzero entries (the
//! compiled Hessians of expression Lagrangians rely on it). A wrapper counts the calls and the
//! nonzero entries it was handed, through every separable path that assembles `∇²V`: the
//! α-rule Newton (banded, and the stack copy for n ≤ 4) and the step Jacobian of a tangent run
//! (banded, and the stack copy for n ≤ 4).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::cell::Cell;

use marsden::numerics::banded::Banded;
use marsden::sensitivity::{TangentOptions, tangent};
use marsden::systems::{Chain, Kepler};
use marsden::{
    DiscreteAction, GeneralizedMidpoint, Integrator, Lagrangian, Midpoint, Rule, Scalar, State,
    Structure, TimeGrid,
};

/// `L` whose `potential_hessian` records how often it was called and how many entries of the
/// matrix it received were not zero.
struct ZeroChecked<L> {
    inner: L,
    calls: Cell<usize>,
    dirty: Cell<usize>,
}

impl<L> ZeroChecked<L> {
    fn new(inner: L) -> Self {
        Self {
            inner,
            calls: Cell::new(0),
            dirty: Cell::new(0),
        }
    }
}

impl<L: Lagrangian> Lagrangian for ZeroChecked<L> {
    const FIXED_DOF: Option<usize> = L::FIXED_DOF;
    fn dof(&self) -> usize {
        self.inner.dof()
    }
    fn lagrangian<S: Scalar>(&self, t: S, q: &[S], v: &[S]) -> S {
        self.inner.lagrangian(t, q, v)
    }
    fn structure(&self) -> Structure {
        self.inner.structure()
    }
    fn potential_gradient(&self, t: f64, q: &[f64], grad: &mut [f64], scratch: &mut Vec<f64>) {
        self.inner.potential_gradient(t, q, grad, scratch);
    }
    fn potential_bandwidth(&self) -> Option<usize> {
        self.inner.potential_bandwidth()
    }
    fn potential_hessian(&self, t: f64, q: &[f64], hess: &mut Banded) {
        let n = hess.dim();
        let nonzero = (0..n)
            .flat_map(|i| hess.columns(i).map(move |j| (i, j)))
            .filter(|&(i, j)| hess.get(i, j).to_bits() != 0)
            .count();
        self.calls.set(self.calls.get() + 1);
        self.dirty.set(self.dirty.get() + nonzero);
        self.inner.potential_hessian(t, q, hess);
    }
}

fn kepler_start() -> State {
    State {
        t: 0.0,
        q: vec![0.4, 0.0],
        p: vec![0.0, 2.0],
    }
}

fn chain_start(n: usize) -> State {
    State {
        t: 0.0,
        q: (0..n).map(|i| 0.1 * (i as f64).sin()).collect(),
        p: (0..n).map(|i| 0.05 * (i as f64)).collect(),
    }
}

/// Takes `steps` steps of `action` from `start` (the counters are in its Lagrangian).
fn steps<A: DiscreteAction>(action: A, start: &State, steps: usize) {
    let mut integrator = Integrator::new(action);
    let mut s = start.clone();
    for _ in 0..steps {
        integrator.step(&mut s, 0.05).unwrap();
    }
}

fn assert_clean<L>(l: &ZeroChecked<L>, what: &str) {
    assert!(l.calls.get() > 0, "{what}: the Hessian was never asked for");
    assert_eq!(
        l.dirty.get(),
        0,
        "{what}: a caller passed a matrix with nonzero entries"
    );
}

#[test]
fn every_separable_caller_passes_a_zeroed_hessian() {
    let kepler = ZeroChecked::new(Kepler::default());
    steps(Midpoint.discretize(&kepler), &kepler_start(), 20);
    assert_clean(&kepler, "midpoint, n = 2 (stack copy)");

    let alpha = ZeroChecked::new(Kepler::default());
    steps(
        GeneralizedMidpoint { alpha: 0.25 }.discretize(&alpha),
        &kepler_start(),
        20,
    );
    assert_clean(&alpha, "α = 1/4, n = 2");

    let chain = ZeroChecked::new(Chain::new(9));
    steps(Midpoint.discretize(&chain), &chain_start(9), 20);
    assert_clean(&chain, "midpoint, banded chain of 9");

    for (n, what) in [(2, "tangent run, n = 2"), (9, "tangent run, chain of 9")] {
        let chain = ZeroChecked::new(Chain::new(n));
        let grid = TimeGrid::new(0.0, 0.05, 20).unwrap();
        let mut integrator = Integrator::new(Midpoint.discretize(&chain));
        tangent(
            &mut integrator,
            chain_start(n),
            &grid,
            &TangentOptions::default(),
        )
        .unwrap();
        assert_clean(&chain, what);
    }
}
