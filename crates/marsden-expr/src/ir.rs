//! The resolved, constant-folded expression tree.
//!
//! Nodes are built only through the smart constructors below ([`add`], [`mul`], [`pow`], …),
//! which fold constants as the tree is built. The normal form they maintain:
//!
//! * a constant operand of `+` or `*` is always on the right (`x + c`, `x * c`); commuting two
//!   operands is exact in floating point;
//! * constant factors and terms are pulled outwards and merged: `(x*2)*(y*3)` becomes
//!   `(x*y)*6` and `(x+1)+2` becomes `x+3` (this re-association may change the last bit);
//! * `x - c` becomes `x + (-c)`, `x + (-y)` becomes `x - y`, `--x` becomes `x` (all exact);
//! * `x^n` with an integer constant `n` becomes `powi`, `x^0.5` becomes `sqrt`, another
//!   constant exponent `powf`, and `c^y` with `c > 0` becomes `exp(y * ln c)`.

use crate::functions::{Unary, atan2, powd};

/// A binary arithmetic operation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Arith {
    Add,
    Sub,
    Mul,
    Div,
}

/// A node of the folded tree.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Node {
    Const(f64),
    Input(usize),
    Neg(Box<Node>),
    Bin(Arith, Box<Node>, Box<Node>),
    Unary(Unary, Box<Node>),
    Powi(Box<Node>, i32),
    Powf(Box<Node>, f64),
    Powd(Box<Node>, Box<Node>),
    Atan2(Box<Node>, Box<Node>),
}

use Node::{Bin, Const};

impl Node {
    /// The value, if the node is a constant.
    pub(crate) fn as_const(&self) -> Option<f64> {
        match *self {
            Const(c) => Some(c),
            _ => None,
        }
    }
}

fn bin(op: Arith, a: Node, b: Node) -> Node {
    Bin(op, Box::new(a), Box::new(b))
}

/// `-a`
pub(crate) fn neg(a: Node) -> Node {
    match a {
        Const(c) => Const(-c),
        Node::Neg(x) => *x,
        Bin(Arith::Mul, x, c) if c.as_const().is_some() => mul(*x, neg(*c)),
        other => Node::Neg(Box::new(other)),
    }
}

/// `a + b`
pub(crate) fn add(a: Node, b: Node) -> Node {
    match (a, b) {
        (Const(x), Const(y)) => Const(x + y),
        (Const(c), x) => add(x, Const(c)),
        (x, Const(0.0)) => x,
        (Bin(Arith::Add, x, c1), Const(c2)) if c1.as_const().is_some() => {
            add(*x, add(*c1, Const(c2)))
        }
        (x, Const(c)) => bin(Arith::Add, x, Const(c)),
        (Bin(Arith::Add, x, c), y) if c.as_const().is_some() => add(add(*x, y), *c),
        (x, Bin(Arith::Add, y, c)) if c.as_const().is_some() => add(add(x, *y), *c),
        (x, Node::Neg(y)) => sub(x, *y),
        (Node::Neg(x), y) => sub(y, *x),
        (x, y) => bin(Arith::Add, x, y),
    }
}

/// `a - b`
pub(crate) fn sub(a: Node, b: Node) -> Node {
    match (a, b) {
        (Const(x), Const(y)) => Const(x - y),
        (x, Const(c)) => add(x, Const(-c)),
        (x, Node::Neg(y)) => add(x, *y),
        (Bin(Arith::Add, x, c), y) if c.as_const().is_some() => add(sub(*x, y), *c),
        (x, y) => bin(Arith::Sub, x, y),
    }
}

/// `a * b`
pub(crate) fn mul(a: Node, b: Node) -> Node {
    match (a, b) {
        (Const(x), Const(y)) => Const(x * y),
        (Const(c), x) => mul(x, Const(c)),
        (x, Const(1.0)) => x,
        // `0·e = 0` even where `e` (or an AD derivative of it, such as that of `√t` at
        // `t = 0`) is infinite: the term does not affect the motion.
        (_, Const(0.0)) => Const(0.0),
        (x, Const(-1.0)) => neg(x),
        (Bin(Arith::Mul, x, c1), Const(c2)) if c1.as_const().is_some() => {
            mul(*x, mul(*c1, Const(c2)))
        }
        (Bin(Arith::Div, x, c1), Const(c2)) if c1.as_const().is_some() => {
            mul(*x, div(Const(c2), *c1))
        }
        (Node::Neg(x), Const(c)) => mul(*x, Const(-c)),
        (x, Const(c)) => bin(Arith::Mul, x, Const(c)),
        (Bin(Arith::Mul, x, c), y) if c.as_const().is_some() => mul(mul(*x, y), *c),
        (x, Bin(Arith::Mul, y, c)) if c.as_const().is_some() => mul(mul(x, *y), *c),
        (Node::Neg(x), y) => neg(mul(*x, y)),
        (x, Node::Neg(y)) => neg(mul(x, *y)),
        (x, y) => bin(Arith::Mul, x, y),
    }
}

/// `a / b`
pub(crate) fn div(a: Node, b: Node) -> Node {
    match (a, b) {
        (Const(x), Const(y)) => Const(x / y),
        (x, Const(1.0)) => x,
        (Bin(Arith::Mul, x, c1), Const(c2)) if c1.as_const().is_some() => {
            mul(*x, div(*c1, Const(c2)))
        }
        (x, Const(c)) => bin(Arith::Div, x, Const(c)),
        (Bin(Arith::Mul, x, c), y) if c.as_const().is_some() => mul(div(*x, y), *c),
        (x, y) => bin(Arith::Div, x, y),
    }
}

/// `f(a)`
pub(crate) fn unary(f: Unary, a: Node) -> Node {
    match a {
        Const(c) => Const(f.apply(c)),
        x => Node::Unary(f, Box::new(x)),
    }
}

/// `atan2(y, x)`
pub(crate) fn atan2_node(y: Node, x: Node) -> Node {
    match (y, x) {
        (Const(y), Const(x)) => Const(atan2(y, x)),
        (y, x) => Node::Atan2(Box::new(y), Box::new(x)),
    }
}

/// The exponent as an `i32`, if it is an integer in range.
fn integer_exponent(e: f64) -> Option<i32> {
    let in_range = e.fract() == 0.0 && e.abs() <= f64::from(i32::MAX);
    // The cast is exact: `e` is integral and within i32's range.
    in_range.then_some(e as i32)
}

/// `a ^ b`
pub(crate) fn pow(a: Node, b: Node) -> Node {
    match (a, b) {
        (Const(x), Const(y)) => Const(match integer_exponent(y) {
            Some(n) => x.powi(n),
            None => powd(x, y),
        }),
        (_, Const(0.0)) => Const(1.0),
        (x, Const(1.0)) => x,
        // (a²)ᵉ = |a|²ᵉ for real a: the same value, and derivatives without the 0·∞ that
        // (a²)ᵉ's chain rule forms at a = 0 (`(x^2)^1.5` is |x|³, twice differentiable there).
        (Node::Powi(a, 2), Const(e)) if integer_exponent(e).is_none() => {
            pow(unary(Unary::Abs, *a), Const(2.0 * e))
        }
        (x, Const(0.5)) => unary(Unary::Sqrt, x),
        (x, Const(e)) => match integer_exponent(e) {
            Some(n) => Node::Powi(Box::new(x), n),
            None => Node::Powf(Box::new(x), e),
        },
        (Const(c), y) if c > 0.0 => unary(Unary::Exp, mul(y, Const(c.ln()))),
        (x, y) => Node::Powd(Box::new(x), Box::new(y)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn x() -> Node {
        Node::Input(0)
    }
    fn y() -> Node {
        Node::Input(1)
    }

    #[test]
    fn constants_are_merged_across_products() {
        // (2*x) * (y*3) → (x*y)*6
        let e = mul(mul(Const(2.0), x()), mul(y(), Const(3.0)));
        assert_eq!(e, bin(Arith::Mul, bin(Arith::Mul, x(), y()), Const(6.0)));
        // (x*4)/2 → x*2 ; x*1 → x ; x*(-1) → -x
        assert_eq!(
            div(mul(x(), Const(4.0)), Const(2.0)),
            bin(Arith::Mul, x(), Const(2.0))
        );
        assert_eq!(mul(x(), Const(1.0)), x());
        assert_eq!(mul(x(), Const(-1.0)), Node::Neg(Box::new(x())));
    }

    #[test]
    fn sums_and_signs() {
        assert_eq!(
            add(add(x(), Const(1.0)), Const(2.0)),
            bin(Arith::Add, x(), Const(3.0))
        );
        assert_eq!(sub(x(), Const(1.0)), bin(Arith::Add, x(), Const(-1.0)));
        assert_eq!(add(x(), neg(y())), bin(Arith::Sub, x(), y()));
        assert_eq!(neg(neg(x())), x());
        assert_eq!(neg(mul(x(), Const(3.0))), bin(Arith::Mul, x(), Const(-3.0)));
    }

    #[test]
    fn a_power_of_a_square_is_a_power_of_the_absolute_value() {
        let square = || pow(x(), Const(2.0));
        let abs_x = || unary(Unary::Abs, x());
        assert_eq!(pow(square(), Const(1.5)), Node::Powi(Box::new(abs_x()), 3));
        assert_eq!(pow(square(), Const(0.5)), abs_x());
        assert_eq!(
            pow(square(), Const(1.25)),
            Node::Powf(Box::new(abs_x()), 2.5)
        );
        // An integer power of a square stays a power of x.
        assert_eq!(pow(square(), Const(2.0)), Node::Powi(Box::new(square()), 2));
    }

    #[test]
    fn powers_pick_the_cheapest_form() {
        assert_eq!(pow(x(), Const(2.0)), Node::Powi(Box::new(x()), 2));
        assert_eq!(pow(x(), Const(-3.0)), Node::Powi(Box::new(x()), -3));
        assert_eq!(
            pow(x(), Const(0.5)),
            Node::Unary(Unary::Sqrt, Box::new(x()))
        );
        assert_eq!(pow(x(), Const(1.5)), Node::Powf(Box::new(x()), 1.5));
        assert_eq!(pow(x(), Const(1.0)), x());
        assert_eq!(pow(x(), y()), Node::Powd(Box::new(x()), Box::new(y())));
        assert_eq!(pow(Const(2.0), Const(10.0)), Const(1024.0));
        assert!(matches!(pow(Const(2.0), y()), Node::Unary(Unary::Exp, _)));
        assert_eq!(pow(x(), Const(1e10)), Node::Powf(Box::new(x()), 1e10));
    }
}
