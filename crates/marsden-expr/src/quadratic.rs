//! Reading a Lagrangian as a polynomial in the velocities: is it `½ vᵀ M v − V(t, q)`?
//!
//! [`split`] walks the folded tree and writes every subtree as
//! `c₀ + Σᵢ cᵢ vᵢ + Σ_{i≤j} c_{ij} vᵢ vⱼ` with coefficients that do not read a velocity (trees
//! of their own). Sums, differences, negation, products of total degree ≤ 2, squares of degree-1
//! terms and division by a velocity-free term are followed exactly; any other occurrence of a
//! velocity (under a function, a non-integer power, a cube) makes the expression "not
//! quadratic", and so does a product of degree above 2. The Lagrangian is separable when, in
//! addition, every linear coefficient is the constant 0 (no magnetic or gyroscopic term
//! `A(q)·v`) and every quadratic coefficient is a constant (no `M(q)` nor `M(t)`). The check is
//! syntactic on the folded form, so it may miss a separable Lagrangian written in a roundabout
//! way (`(x_dot + x)^2 - 2*x*x_dot - x^2`), which then keeps the general path; it never accepts
//! one that is not separable.

use std::collections::BTreeMap;

use crate::derive::{depends, minus, plus, times};
use crate::ir::{Arith, Node, div, neg};

use Node::Const;

/// `c₀ + Σ cᵢ vᵢ + Σ_{i≤j} c_{ij} vᵢ vⱼ`.
#[derive(Debug, Clone)]
struct Poly {
    c0: Node,
    c1: Vec<Node>,
    c2: BTreeMap<(usize, usize), Node>,
}

impl Poly {
    fn constant(c0: Node, n: usize) -> Poly {
        Poly {
            c0,
            c1: vec![Const(0.0); n],
            c2: BTreeMap::new(),
        }
    }

    fn degree(&self) -> usize {
        let nonzero = |c: &Node| c.as_const() != Some(0.0);
        if self.c2.values().any(nonzero) {
            2
        } else if self.c1.iter().any(nonzero) {
            1
        } else {
            0
        }
    }

    fn map(self, f: impl Fn(Node) -> Node) -> Poly {
        Poly {
            c0: f(self.c0),
            c1: self.c1.into_iter().map(&f).collect(),
            c2: self.c2.into_iter().map(|(k, c)| (k, f(c))).collect(),
        }
    }

    /// `self ± other` (`sign` true: plus).
    fn combine(self, other: Poly, sign: bool) -> Poly {
        let op = |a: Node, b: Node| if sign { plus(a, b) } else { minus(a, b) };
        let mut c2 = self.c2;
        for (k, c) in other.c2 {
            let sum = op(c2.remove(&k).unwrap_or(Const(0.0)), c);
            c2.insert(k, sum);
        }
        Poly {
            c0: op(self.c0, other.c0),
            c1: self
                .c1
                .into_iter()
                .zip(other.c1)
                .map(|(a, b)| op(a, b))
                .collect(),
            c2,
        }
    }

    /// `self · other`, if the product has degree ≤ 2.
    fn product(self, other: Poly) -> Option<Poly> {
        if self.degree() + other.degree() > 2 {
            return None;
        }
        let n = self.c1.len();
        let scaled = |p: &Poly, s: &Node| p.clone().map(|c| times(c, s.clone()));
        let mut result = scaled(&self, &other.c0).combine(scaled(&other, &self.c0), true);
        // c0 was counted twice above.
        result.c0 = times(self.c0.clone(), other.c0.clone());
        for i in 0..n {
            for j in 0..n {
                let term = times(self.c1[i].clone(), other.c1[j].clone());
                let key = (i.min(j), i.max(j));
                let sum = plus(result.c2.remove(&key).unwrap_or(Const(0.0)), term);
                result.c2.insert(key, sum);
            }
        }
        Some(result)
    }
}

/// `node` as a polynomial of degree ≤ 2 in the velocity slots `n..2n`, if it is one.
fn poly(node: &Node, n: usize) -> Option<Poly> {
    let is_velocity = |slot: usize| (n..2 * n).contains(&slot);
    if !depends(node, &is_velocity) {
        return Some(Poly::constant(node.clone(), n));
    }
    match node {
        Node::Input(slot) => {
            let mut p = Poly::constant(Const(0.0), n);
            p.c1[slot - n] = Const(1.0);
            Some(p)
        }
        Node::Neg(a) => Some(poly(a, n)?.map(neg)),
        Node::Bin(Arith::Add, a, b) => Some(poly(a, n)?.combine(poly(b, n)?, true)),
        Node::Bin(Arith::Sub, a, b) => Some(poly(a, n)?.combine(poly(b, n)?, false)),
        Node::Bin(Arith::Mul, a, b) => poly(a, n)?.product(poly(b, n)?),
        Node::Bin(Arith::Div, a, b) if !depends(b, &is_velocity) => {
            Some(poly(a, n)?.map(|c| divided(c, b)))
        }
        Node::Powi(a, 2) => {
            let p = poly(a, n)?;
            p.clone().product(p)
        }
        _ => None,
    }
}

/// `c / b`, keeping an exact zero.
fn divided(c: Node, b: &Node) -> Node {
    if c.as_const() == Some(0.0) {
        c
    } else {
        div(c, b.clone())
    }
}

/// The split `L = ½ vᵀ M v − V(t, q)` of a Lagrangian over `[q₁ … qₙ, v₁ … vₙ, t]`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Split {
    /// `M`, dense row-major `n × n`, symmetric positive definite.
    pub mass: Vec<f64>,
    /// `V(t, q)` over the same slots (it reads no velocity).
    pub potential: Node,
}

/// The split of `node` if it is exactly `½ vᵀ M v − V(t, q)` with a constant symmetric
/// positive definite `M`; `None` otherwise.
pub(crate) fn split(node: &Node, n: usize) -> Option<Split> {
    let p = poly(node, n)?;
    if p.c1.iter().any(|c| c.as_const() != Some(0.0)) {
        return None;
    }
    let mut mass = vec![0.0; n * n];
    for (&(i, j), c) in &p.c2 {
        let c = c.as_const()?;
        if i == j {
            mass[i * n + i] = 2.0 * c;
        } else {
            mass[i * n + j] = c;
            mass[j * n + i] = c;
        }
    }
    positive_definite(&mass, n).then(|| Split {
        mass,
        potential: neg(p.c0),
    })
}

/// Whether the symmetric `n × n` matrix `m` is positive definite (a Cholesky factorisation
/// succeeds with positive, finite pivots).
fn positive_definite(m: &[f64], n: usize) -> bool {
    let mut l = vec![0.0; n * n];
    for j in 0..n {
        let d = m[j * n + j] - (0..j).map(|k| l[j * n + k] * l[j * n + k]).sum::<f64>();
        if !(d > 0.0 && d.is_finite()) {
            return false;
        }
        let d = d.sqrt();
        l[j * n + j] = d;
        for i in j + 1..n {
            let s = m[i * n + j] - (0..j).map(|k| l[i * n + k] * l[j * n + k]).sum::<f64>();
            l[i * n + j] = s / d;
        }
    }
    true
}
