//! Symbolic differentiation of the folded tree.
//!
//! [`derivative`] applies the chain rule node by node and builds the result with the folding
//! constructors of `ir`, so constant factors merge and the derivative of a term that does not
//! read the slot vanishes (an exact zero is dropped from sums and products here: `0 · x = 0`
//! for the finite values a step works with). Every rule reuses the nodes of the function itself
//! (`d√u = du / (2√u)` reuses `√u`, `d(a/b) = (da − (a/b) db) / b` reuses `a/b`), so the
//! common-subexpression pass of the tape ([`crate::tape`]) evaluates them once for the value
//! and all the partial derivatives.
//!
//! `abs` has no derivative here (its kink): an expression using it is differentiated by AD.

use crate::functions::Unary;
use crate::ir::{Arith, Node, add, div, mul, neg, pow, sub, unary};

use Node::Const;

/// Whether `node` is the constant 0.
fn is_zero(node: &Node) -> bool {
    node.as_const() == Some(0.0)
}

/// `a · b`, with an exact zero factor giving 0.
pub(crate) fn times(a: Node, b: Node) -> Node {
    if is_zero(&a) || is_zero(&b) {
        Const(0.0)
    } else {
        mul(a, b)
    }
}

/// `a + b`, with exact zeros dropped.
pub(crate) fn plus(a: Node, b: Node) -> Node {
    match (is_zero(&a), is_zero(&b)) {
        (true, _) => b,
        (_, true) => a,
        _ => add(a, b),
    }
}

/// `a − b`, with exact zeros dropped.
pub(crate) fn minus(a: Node, b: Node) -> Node {
    match (is_zero(&a), is_zero(&b)) {
        (_, true) => a,
        (true, _) => negate(b),
        _ => sub(a, b),
    }
}

/// `−a`, moving the sign into a negated factor or numerator where there is one (exact).
fn negate(a: Node) -> Node {
    match a {
        Node::Bin(op @ (Arith::Mul | Arith::Div), x, y) => match *x {
            Node::Neg(inner) => Node::Bin(op, inner, y),
            x => neg(Node::Bin(op, Box::new(x), y)),
        },
        other => neg(other),
    }
}

/// Whether `node` reads an input slot for which `reads` is true.
pub(crate) fn depends(node: &Node, reads: &impl Fn(usize) -> bool) -> bool {
    match node {
        Node::Const(_) => false,
        Node::Input(slot) => reads(*slot),
        Node::Neg(a) | Node::Unary(_, a) | Node::Powi(a, _) | Node::Powf(a, _) => depends(a, reads),
        Node::Bin(_, a, b) | Node::Powd(a, b) | Node::Atan2(a, b) => {
            depends(a, reads) || depends(b, reads)
        }
    }
}

/// `∂node/∂x_slot`, or `None` if the expression uses a function without a derivative rule here
/// (`abs`).
pub(crate) fn derivative(node: &Node, slot: usize) -> Option<Node> {
    if !depends(node, &|s| s == slot) {
        return Some(Const(0.0));
    }
    Some(match node {
        Node::Const(_) => Const(0.0),
        Node::Input(s) => Const(if *s == slot { 1.0 } else { 0.0 }),
        Node::Neg(a) => negate(derivative(a, slot)?),
        Node::Bin(op, a, b) => binary(*op, a, b, slot)?,
        Node::Unary(f, a) => times(derivative(a, slot)?, unary_rule(*f, a, node)?),
        // d(aⁿ) = n aⁿ⁻¹ da
        Node::Powi(a, n) => {
            let da = derivative(a, slot)?;
            let lower = pow(a.as_ref().clone(), Const(f64::from(*n) - 1.0));
            times(da, mul(lower, Const(f64::from(*n))))
        }
        // d(aᵉ) = e aᵉ⁻¹ da
        Node::Powf(a, e) => {
            let da = derivative(a, slot)?;
            let lower = pow(a.as_ref().clone(), Const(e - 1.0));
            times(da, mul(lower, Const(*e)))
        }
        // d(aᵇ) = aᵇ (db ln a + b da / a)
        Node::Powd(a, b) => {
            let (da, db) = (derivative(a, slot)?, derivative(b, slot)?);
            let log_part = times(db, unary(Unary::Ln, a.as_ref().clone()));
            let base_part = times(b.as_ref().clone(), div_nonzero(da, a));
            times(node.clone(), plus(log_part, base_part))
        }
        // d atan2(y, x) = (x dy − y dx) / (x² + y²)
        Node::Atan2(y, x) => {
            let (dy, dx) = (derivative(y, slot)?, derivative(x, slot)?);
            let (y, x) = (y.as_ref().clone(), x.as_ref().clone());
            let r2 = add(pow(x.clone(), Const(2.0)), pow(y.clone(), Const(2.0)));
            let numerator = minus(times(x, dy), times(y, dx));
            div_nonzero(numerator, &r2)
        }
    })
}

/// `a / b`, with a zero numerator giving 0.
fn div_nonzero(a: Node, b: &Node) -> Node {
    if is_zero(&a) {
        Const(0.0)
    } else {
        div(a, b.clone())
    }
}

/// The derivative of `a op b`.
fn binary(op: Arith, a: &Node, b: &Node, slot: usize) -> Option<Node> {
    let (da, db) = (derivative(a, slot)?, derivative(b, slot)?);
    let (a, b) = (a.clone(), b.clone());
    Some(match op {
        Arith::Add => plus(da, db),
        Arith::Sub => minus(da, db),
        Arith::Mul => plus(times(da, b), times(a, db)),
        // d(a/b) = (da − (a/b) db) / b
        Arith::Div => {
            let quotient = div(a, b.clone());
            div_nonzero(minus(da, times(quotient, db)), &b)
        }
    })
}

/// `f'(a)` for `node = f(a)`, written with `node` where that saves work; `None` for `abs`.
fn unary_rule(f: Unary, a: &Node, node: &Node) -> Option<Node> {
    let a = a.clone();
    let square = |x: Node| pow(x, Const(2.0));
    let one_minus_square = |x: Node| sub(Const(1.0), square(x));
    Some(match f {
        Unary::Sin => unary(Unary::Cos, a),
        Unary::Cos => neg(unary(Unary::Sin, a)),
        // tan' = 1 + tan²
        Unary::Tan => add(square(node.clone()), Const(1.0)),
        Unary::Asin => div(Const(1.0), unary(Unary::Sqrt, one_minus_square(a))),
        Unary::Acos => div(Const(-1.0), unary(Unary::Sqrt, one_minus_square(a))),
        Unary::Atan => div(Const(1.0), add(square(a), Const(1.0))),
        Unary::Sinh => unary(Unary::Cosh, a),
        Unary::Cosh => unary(Unary::Sinh, a),
        Unary::Tanh => one_minus_square(node.clone()),
        Unary::Exp => node.clone(),
        Unary::Ln => div(Const(1.0), a),
        // √' = (1/√a) · ½ (the constant then merges with those of the inner derivative)
        Unary::Sqrt => mul(div(Const(1.0), node.clone()), Const(0.5)),
        Unary::Abs => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::atan2_node as atan2_of;

    fn x() -> Node {
        Node::Input(0)
    }

    fn eval(node: &Node, at: f64) -> f64 {
        let code = crate::codegen::generate(node);
        crate::eval::evaluate(&code, &[at])
    }

    #[test]
    fn elementary_rules_match_difference_quotients() {
        let cases = [
            unary(Unary::Sin, mul(x(), Const(3.0))),
            unary(Unary::Tan, x()),
            unary(Unary::Atan, x()),
            unary(Unary::Asin, mul(x(), Const(0.5))),
            div(
                Const(2.0),
                unary(Unary::Sqrt, add(pow(x(), Const(2.0)), Const(1.0))),
            ),
            pow(x(), Const(1.5)),
            pow(x(), x()),
            atan2_of(x(), Const(2.0)),
            unary(Unary::Tanh, unary(Unary::Ln, x())),
        ];
        for node in cases {
            let d = derivative(&node, 0).unwrap();
            let (at, h) = (0.7, 1e-6);
            let fd = (eval(&node, at + h) - eval(&node, at - h)) / (2.0 * h);
            assert!((eval(&d, at) - fd).abs() < 1e-7, "{node:?}");
        }
    }

    #[test]
    fn abs_has_no_rule_and_constants_vanish() {
        assert_eq!(derivative(&unary(Unary::Abs, x()), 0), None);
        assert_eq!(derivative(&unary(Unary::Abs, x()), 1), Some(Const(0.0)));
        assert_eq!(derivative(&mul(x(), Const(3.0)), 0), Some(Const(3.0)));
    }
}
