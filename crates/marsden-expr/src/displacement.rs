//! [`DisplacementForm`]: a two-point expression `E(q₀, q₁, h, t)` (a discrete Lagrangian)
//! rewritten in the variables the integrator steps, the start point `q₀` and the displacement
//! `Δ = q₁ − q₀`.
//!
//! The integrator solves for `Δ`, not for `q₁`: `q₁ − q₀` recomputed from the rounded end point
//! differs from `Δ` in the last bits, and so does every quantity formed from it. The built-in
//! rules form their node and velocity from `(q₀, Δ)` directly (`q_c = q₀ + cΔ`, `v = Δ·(1/h)`,
//! `L_d = h·L(t₀ + ch, q_c, v)`). This rewrite lets an expression written in `q₀`, `q₁` be
//! evaluated by the same operations, so that a hand-written `L_d` equal to a rule's evaluates
//! to the same bits as the rule (and so does every derivative taken through it).
//!
//! Each rewrite below is an identity in exact arithmetic; only the rounding changes, to the
//! rule's. Recognised on the folded tree (`i` a coordinate):
//!
//! | written | becomes | evaluated as |
//! |---|---|---|
//! | `q1_i − q0_i` | `Δ_i` | the displacement itself |
//! | `(q1_i − q0_i)/h` | `v_i` | `Δ_i · (1/h)` |
//! | `(q0_i + q1_i)/2`, `(q0_i + q1_i)*0.5` (either order), `q0_i + (q1_i − q0_i)/2` | `m_i` | `q0_i + Δ_i · 0.5` |
//! | `t + h/2`, `t + h*0.5` (either order) | `t_m` | `t + 0.5·h` (a number) |
//! | the whole expression `h*E` or `E*h` | `E·h` | `E` times the number `h` |
//! | any other `q1_i` | `q0_i + Δ_i` | `q0_i + Δ_i` |
//!
//! Everything else is kept as written. So `h*(0.5*((x_1 - x_0)/h)^2 - 0.5*((x_0 + x_1)/2)^2)`
//! becomes `(0.5·v² − 0.5·m²)·h`: the midpoint rule's `h·L(m, v)` of `L = ½ẋ² − ½x²`
//! instruction for instruction.

use crate::codegen::generate;
use crate::ir::{Arith, Node};
use crate::pipeline::collect_inputs;
use crate::program::Program;
use marsden::Scalar;
use marsden::numerics::scratch::with_slice;

/// The input slots of a two-point expression over `[q₀ (n), q₁ (n), h, t]`, and of its
/// rewritten body over `[q₀, Δ, h, t, m (n), v (n), q₀ + Δ (n), t_m]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Layout {
    n: usize,
}

impl Layout {
    fn h(self) -> usize {
        2 * self.n
    }
    fn t(self) -> usize {
        2 * self.n + 1
    }
    /// Coordinate `i` if `slot` is `q₀_i`.
    fn start(self, slot: usize) -> Option<usize> {
        (slot < self.n).then_some(slot)
    }
    /// Coordinate `i` if `slot` is `q₁_i` (in the original layout).
    fn end(self, slot: usize) -> Option<usize> {
        (self.n..2 * self.n).contains(&slot).then(|| slot - self.n)
    }
    fn delta(self, i: usize) -> usize {
        self.n + i
    }
    fn midpoint(self, i: usize) -> usize {
        2 * self.n + 2 + i
    }
    fn velocity(self, i: usize) -> usize {
        3 * self.n + 2 + i
    }
    fn end_point(self, i: usize) -> usize {
        4 * self.n + 2 + i
    }
    fn mid_time(self) -> usize {
        5 * self.n + 2
    }
    fn len(self) -> usize {
        5 * self.n + 3
    }
}

/// A two-point expression in the variables `(q₀, Δ)` (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct DisplacementForm {
    body: Program,
    times_h: bool,
    layout: Layout,
    /// Which derived groups the body reads: midpoints, velocities, end points, `t_m`.
    reads: [bool; 4],
}

impl DisplacementForm {
    /// The rewritten body (without the factor `h` when [`DisplacementForm::times_h`]).
    pub fn body(&self) -> &Program {
        &self.body
    }

    /// Whether the expression was `h·E` and the body is `E`.
    pub fn times_h(&self) -> bool {
        self.times_h
    }

    /// The value at `(q₀, Δ)` for the step from `t0` of length `h`.
    #[inline]
    pub fn eval<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], delta: &[S]) -> S {
        let value = with_slice(self.layout.len(), S::from(h), |x| {
            self.fill(t0, h, q0, delta, x);
            self.body.eval(x)
        });
        if self.times_h { value * h } else { value }
    }

    /// Writes the body's inputs into `x`, each derived one as the built-in rules form it.
    #[inline(always)]
    fn fill<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], delta: &[S], x: &mut [S]) {
        let (l, n) = (self.layout, self.layout.n);
        x[..n].copy_from_slice(q0);
        x[n..2 * n].copy_from_slice(delta);
        x[l.h()] = S::from(h);
        x[l.t()] = S::from(t0);
        let [mid, vel, end, mid_time] = self.reads;
        let inv_h = 1.0 / h;
        for i in 0..n {
            if mid {
                x[l.midpoint(i)] = q0[i] + delta[i] * 0.5;
            }
            if vel {
                x[l.velocity(i)] = delta[i] * inv_h;
            }
            if end {
                x[l.end_point(i)] = q0[i] + delta[i];
            }
        }
        if mid_time {
            x[l.mid_time()] = S::from(t0 + 0.5 * h);
        }
    }
}

impl Program {
    /// This program, compiled over `[q₀ (n), q₁ (n), h, t]`, rewritten in the start point and
    /// the displacement `Δ = q₁ − q₀` (the patterns in [`DisplacementForm`]'s module).
    ///
    /// ```
    /// use marsden_expr::{Program, Symbols};
    /// let symbols = Symbols::with_inputs(["x_0", "x_1", "h", "t"]).unwrap();
    /// let ld = Program::compile("h*(0.5*((x_1 - x_0)/h)^2 - 0.5*((x_0 + x_1)/2)^2)", &symbols)
    ///     .unwrap();
    /// let form = ld.displacement_form(1);
    /// assert!(form.times_h());
    /// let (q0, delta, h) = (0.3_f64, 0.2_f64, 0.1_f64);
    /// let (m, v) = (q0 + delta * 0.5, delta * (1.0 / h));
    /// assert_eq!(form.eval(0.0, h, &[q0], &[delta]), (0.5 * v * v - 0.5 * m * m) * h);
    /// ```
    pub fn displacement_form(&self, n: usize) -> DisplacementForm {
        let layout = Layout { n };
        let (times_h, inner) = match self.tree() {
            Node::Bin(Arith::Mul, a, b) if is_input(a, layout.h()) => (true, &**b),
            Node::Bin(Arith::Mul, a, b) if is_input(b, layout.h()) => (true, &**a),
            whole => (false, whole),
        };
        let tree = rewrite(inner, layout);
        let mut inputs_used = Vec::new();
        collect_inputs(&tree, &mut inputs_used);
        inputs_used.sort_unstable();
        inputs_used.dedup();
        let group = |from: usize, to: usize| inputs_used.iter().any(|s| (from..to).contains(s));
        let reads = [
            group(layout.midpoint(0), layout.midpoint(n)),
            group(layout.velocity(0), layout.velocity(n)),
            group(layout.end_point(0), layout.end_point(n)),
            group(layout.mid_time(), layout.len()),
        ];
        let body = Program::new(
            generate(&tree),
            tree,
            self.text(),
            self.names().to_vec(),
            inputs_used,
        );
        DisplacementForm {
            body,
            times_h,
            layout,
            reads,
        }
    }
}

fn is_input(node: &Node, slot: usize) -> bool {
    matches!(node, Node::Input(s) if *s == slot)
}

fn is_const(node: &Node, value: f64) -> bool {
    matches!(node, Node::Const(c) if *c == value)
}

/// `i` if `node` is `q1_i − q0_i`.
fn displacement(node: &Node, l: Layout) -> Option<usize> {
    let Node::Bin(Arith::Sub, a, b) = node else {
        return None;
    };
    let (Node::Input(a), Node::Input(b)) = (&**a, &**b) else {
        return None;
    };
    let i = l.end(*a)?;
    (l.start(*b) == Some(i)).then_some(i)
}

/// `i` if `node` is `q0_i + q1_i` or `q1_i + q0_i`.
fn endpoint_sum(node: &Node, l: Layout) -> Option<usize> {
    let Node::Bin(Arith::Add, a, b) = node else {
        return None;
    };
    let (Node::Input(a), Node::Input(b)) = (&**a, &**b) else {
        return None;
    };
    match (l.start(*a), l.end(*b), l.end(*a), l.start(*b)) {
        (Some(i), Some(j), _, _) | (_, _, Some(i), Some(j)) if i == j => Some(i),
        _ => None,
    }
}

/// `x` if `node` is `x/2` or `x*0.5`.
fn halved(node: &Node) -> Option<&Node> {
    match node {
        Node::Bin(Arith::Div, x, c) if is_const(c, 2.0) => Some(x),
        Node::Bin(Arith::Mul, x, c) if is_const(c, 0.5) => Some(x),
        _ => None,
    }
}

/// `i` if `node` is one of the written forms of the midpoint `(q0_i + q1_i)/2`.
fn midpoint(node: &Node, l: Layout) -> Option<usize> {
    if let Some(i) = halved(node).and_then(|x| endpoint_sum(x, l)) {
        return Some(i);
    }
    let Node::Bin(Arith::Add, a, b) = node else {
        return None;
    };
    let half_step = |start: &Node, half: &Node| {
        let Node::Input(s) = start else {
            return None;
        };
        let i = halved(half).and_then(|x| displacement(x, l))?;
        (l.start(*s) == Some(i)).then_some(i)
    };
    half_step(a, b).or_else(|| half_step(b, a))
}

/// Whether `node` is `t + h/2` (either order, `h/2` or `h*0.5`).
fn mid_time(node: &Node, l: Layout) -> bool {
    let Node::Bin(Arith::Add, a, b) = node else {
        return false;
    };
    let half_h = |x: &Node| halved(x).is_some_and(|y| is_input(y, l.h()));
    (is_input(a, l.t()) && half_h(b)) || (is_input(b, l.t()) && half_h(a))
}

/// The tree with the patterns replaced by the body's input slots, top-down (so that
/// `(q1_i − q0_i)/h` becomes `v_i` before `q1_i − q0_i` becomes `Δ_i`).
fn rewrite(node: &Node, l: Layout) -> Node {
    if let Node::Bin(Arith::Div, a, b) = node
        && is_input(b, l.h())
        && let Some(i) = displacement(a, l)
    {
        return Node::Input(l.velocity(i));
    }
    if let Some(i) = midpoint(node, l) {
        return Node::Input(l.midpoint(i));
    }
    if let Some(i) = displacement(node, l) {
        return Node::Input(l.delta(i));
    }
    if mid_time(node, l) {
        return Node::Input(l.mid_time());
    }
    let r = |x: &Node| Box::new(rewrite(x, l));
    match node {
        Node::Input(s) => match l.end(*s) {
            Some(i) => Node::Input(l.end_point(i)),
            None => Node::Input(*s),
        },
        Node::Const(c) => Node::Const(*c),
        Node::Neg(a) => Node::Neg(r(a)),
        Node::Unary(f, a) => Node::Unary(*f, r(a)),
        Node::Powi(a, k) => Node::Powi(r(a), *k),
        Node::Powf(a, e) => Node::Powf(r(a), *e),
        Node::Bin(op, a, b) => Node::Bin(*op, r(a), r(b)),
        Node::Powd(a, b) => Node::Powd(r(a), r(b)),
        Node::Atan2(a, b) => Node::Atan2(r(a), r(b)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Symbols;

    fn symbols(n: usize) -> Symbols {
        let names = (0..n)
            .map(|i| format!("a{i}_0"))
            .chain((0..n).map(|i| format!("a{i}_1")))
            .chain(["h".to_owned(), "t".to_owned()]);
        Symbols::with_inputs(names).unwrap()
    }

    /// The midpoint rule's `L_d` of `½ẋ² − ½x²` rewrites to the listing of `L` itself with `x`
    /// at the midpoint slot and `ẋ` at the velocity slot, times `h`.
    #[test]
    fn the_midpoint_discrete_lagrangian_becomes_the_lagrangian_at_the_node() {
        let text = "h*(0.5*((a0_1 - a0_0)/h)^2 - 0.5*((a0_0 + a0_1)/2)^2)";
        let form = Program::compile(text, &symbols(1))
            .unwrap()
            .displacement_form(1);
        let l = Program::compile(
            "0.5*v^2 - 0.5*m^2",
            &Symbols::with_inputs(["q0", "d", "h", "t", "m", "v"]).unwrap(),
        )
        .unwrap();
        assert!(form.times_h());
        assert_eq!(form.body().to_string(), l.to_string());
        assert_eq!(form.reads, [true, true, false, false]);
    }

    #[test]
    fn every_written_midpoint_and_the_mid_time_are_recognised() {
        let l = Layout { n: 2 };
        for text in [
            "(a1_0 + a1_1)/2",
            "(a1_1 + a1_0)*0.5",
            "0.5*(a1_0 + a1_1)",
            "a1_0 + (a1_1 - a1_0)/2",
            "(a1_1 - a1_0)*0.5 + a1_0",
        ] {
            let form = Program::compile(text, &symbols(2))
                .unwrap()
                .displacement_form(2);
            assert_eq!(form.body().inputs_used(), [l.midpoint(1)], "{text}");
        }
        for text in ["t + h/2", "0.5*h + t"] {
            let form = Program::compile(text, &symbols(2))
                .unwrap()
                .displacement_form(2);
            assert_eq!(form.body().inputs_used(), [l.mid_time()], "{text}");
        }
        // Not a midpoint: the coordinates differ. Both ends are kept, q₁ as q₀ + Δ.
        let form = Program::compile("(a0_0 + a1_1)/2", &symbols(2))
            .unwrap()
            .displacement_form(2);
        assert_eq!(form.body().inputs_used(), [0, l.end_point(1)]);
    }

    /// Values agree with the original program to round-off wherever nothing was recognised
    /// exactly, e.g. a non-quadratic `L_d` with a trailing factor that is not `h`.
    #[test]
    fn the_rewrite_keeps_the_value() {
        let text = "h*cos(a0_1 - a0_0)*exp((a1_0 + a1_1)/2) + sin(a1_1)*(t + h/2)/h - a0_1^2";
        let p = Program::compile(text, &symbols(2)).unwrap();
        let form = p.displacement_form(2);
        let (q0, delta, h, t) = ([0.3, -0.2], [0.01, 0.02], 0.1, 1.5);
        let q1 = [q0[0] + delta[0], q0[1] + delta[1]];
        let direct: f64 = p.eval(&[q0[0], q0[1], q1[0], q1[1], h, t]);
        let offset: f64 = form.eval(t, h, &q0, &delta);
        assert!(
            (direct - offset).abs() <= 1e-14 * direct.abs(),
            "{direct} {offset}"
        );
    }
}
