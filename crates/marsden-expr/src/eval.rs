//! The interpreter loop, generic over [`Scalar`].
//!
//! The stack lives in a fixed-size array on the machine stack when the program's depth (known at
//! compile time) fits one of the sizes below, so evaluation does not allocate; deeper programs
//! fall back to a heap `Vec`. Array slots are addressed `i % N`, which the compiler can prove in
//! bounds, so the loop has no bounds checks on the stack and no panic paths.

use marsden::Scalar;

use crate::functions::{atan2, powd};
use crate::ops::{Code, Leaf, Op};

/// Largest depth served by the small array.
const SMALL: usize = 4;
/// Largest depth served by the large array.
const LARGE: usize = 16;

/// Storage for pending left operands.
trait Stack<S> {
    fn set(&mut self, i: usize, value: S);
    fn get(&self, i: usize) -> S;
}

impl<S: Copy, const N: usize> Stack<S> for [S; N] {
    #[inline(always)]
    fn set(&mut self, i: usize, value: S) {
        self[i % N] = value;
    }

    #[inline(always)]
    fn get(&self, i: usize) -> S {
        self[i % N]
    }
}

/// Heap storage for deep programs; its length is at least 1 and at least the program depth.
struct HeapStack<S>(Vec<S>);

impl<S: Copy> Stack<S> for HeapStack<S> {
    #[inline]
    fn set(&mut self, i: usize, value: S) {
        let n = self.0.len();
        self.0[i % n] = value;
    }

    #[inline]
    fn get(&self, i: usize) -> S {
        self.0[i % self.0.len()]
    }
}

/// Evaluate `code`; `inputs` must be long enough for every input it reads.
#[inline]
pub(crate) fn evaluate<S: Scalar>(code: &Code, inputs: &[S]) -> S {
    let zero = S::from(0.0);
    if code.depth == 0 {
        run(code, inputs, &mut [zero; 1])
    } else if code.depth <= SMALL {
        run(code, inputs, &mut [zero; SMALL])
    } else if code.depth <= LARGE {
        run(code, inputs, &mut [zero; LARGE])
    } else {
        run(code, inputs, &mut HeapStack(vec![zero; code.depth]))
    }
}

#[inline(always)]
fn run<S: Scalar>(code: &Code, inputs: &[S], stack: &mut impl Stack<S>) -> S {
    let mut acc = match code.first {
        Leaf::Input(i) => inputs[i],
        Leaf::Const(c) => S::from(c),
    };
    let mut sp = 0_usize;
    for op in &code.ops {
        // Arms update `acc` in place where the scalar type supports it, so large dual numbers
        // are not copied through a temporary on every instruction.
        match *op {
            Op::PushInput(i) => {
                stack.set(sp, acc);
                sp += 1;
                acc = inputs[i];
            }
            Op::PushConst(c) => {
                stack.set(sp, acc);
                sp += 1;
                acc = S::from(c);
            }
            Op::Add => {
                sp -= 1;
                acc += stack.get(sp);
            }
            Op::Sub => {
                sp -= 1;
                acc = stack.get(sp) - acc;
            }
            Op::Mul => {
                sp -= 1;
                acc *= stack.get(sp);
            }
            Op::Div => {
                sp -= 1;
                acc = stack.get(sp) / acc;
            }
            Op::AddInput(i) => acc += inputs[i],
            Op::SubInput(i) => acc -= inputs[i],
            Op::MulInput(i) => acc *= inputs[i],
            Op::DivInput(i) => acc /= inputs[i],
            Op::AddConst(c) => acc += c,
            Op::MulConst(c) => acc *= c,
            Op::DivConst(c) => acc /= c,
            Op::ConstSub(c) => acc = S::from(c) - acc,
            Op::ConstDiv(c) => acc = S::from(c) / acc,
            Op::Neg => acc = -acc,
            Op::Call(f) => acc = f.apply(acc),
            Op::Powi(n) => acc = acc.powi(n),
            Op::Square => acc = acc * acc,
            Op::MulConstAdd(c) => {
                sp -= 1;
                acc *= c;
                acc += stack.get(sp);
            }
            Op::PushCall(i, f) => {
                stack.set(sp, acc);
                sp += 1;
                acc = f.apply(inputs[i]);
            }
            Op::PushSquare(i) => {
                stack.set(sp, acc);
                sp += 1;
                acc = inputs[i] * inputs[i];
            }
            Op::Powf(e) => acc = crate::functions::powf(acc, e),
            Op::Powd => {
                sp -= 1;
                acc = powd(stack.get(sp), acc);
            }
            Op::Atan2 => {
                sp -= 1;
                acc = atan2(stack.get(sp), acc);
            }
        }
    }
    acc
}

#[cfg(test)]
mod tests {
    use std::mem::discriminant;

    use super::*;
    use crate::functions::Unary;
    use crate::{Program, Symbols};

    type Case = (&'static str, Op, fn(f64, f64) -> f64);

    /// One expression per instruction, the instruction it must compile to, and its value.
    const CASES: &[Case] = &[
        ("atan2(sin(x), 2)", Op::PushConst(0.0), |x, _| {
            x.sin().atan2(2.0)
        }),
        ("sin(x) * (y + x)", Op::PushInput(0), |x, y| {
            x.sin() * (y + x)
        }),
        ("sin(x) + cos(y)", Op::Add, |x, y| x.sin() + y.cos()),
        ("sin(x) - cos(y)", Op::Sub, |x, y| x.sin() - y.cos()),
        ("sin(x) * cos(y)", Op::Mul, |x, y| x.sin() * y.cos()),
        ("sin(x) / cos(y)", Op::Div, |x, y| x.sin() / y.cos()),
        ("sin(x) + y", Op::AddInput(0), |x, y| x.sin() + y),
        ("sin(x) - y", Op::SubInput(0), |x, y| x.sin() - y),
        ("sin(x) * y", Op::MulInput(0), |x, y| x.sin() * y),
        ("sin(x) / y", Op::DivInput(0), |x, y| x.sin() / y),
        ("sin(x) + 2", Op::AddConst(0.0), |x, _| x.sin() + 2.0),
        ("sin(x) * 3", Op::MulConst(0.0), |x, _| x.sin() * 3.0),
        ("sin(x) / 3", Op::DivConst(0.0), |x, _| x.sin() / 3.0),
        ("2 - sin(x)", Op::ConstSub(0.0), |x, _| 2.0 - x.sin()),
        ("2 / sin(x)", Op::ConstDiv(0.0), |x, _| 2.0 / x.sin()),
        ("-sin(x)", Op::Neg, |x, _| -x.sin()),
        ("tanh(x)", Op::Call(Unary::Tanh), |x, _| x.tanh()),
        ("x^3", Op::Powi(0), |x, _| x.powi(3)),
        ("x^2", Op::Square, |x, _| x * x),
        ("x^1.5", Op::Powf(0.0), |x, _| x.powf(1.5)),
        ("x^y", Op::Powd, |x, y| x.powf(y)),
        ("atan2(sin(x), y^2)", Op::Atan2, |x, y| x.sin().atan2(y * y)),
        ("sin(x) + 3*cos(y)", Op::MulConstAdd(0.0), |x, y| {
            x.sin() + y.cos() * 3.0
        }),
        ("sin(x) * cos(y)", Op::PushCall(0, Unary::Cos), |x, y| {
            x.sin() * y.cos()
        }),
        ("sin(x) + y^2", Op::PushSquare(0), |x, y| x.sin() + y * y),
    ];

    #[test]
    fn every_instruction_evaluates_correctly() {
        let symbols = Symbols::with_inputs(["x", "y"]).unwrap();
        for &(text, op, expected) in CASES {
            let program = Program::compile(text, &symbols).unwrap();
            let found = program
                .ops()
                .iter()
                .any(|o| discriminant(o) == discriminant(&op));
            assert!(found, "`{text}` should use {op:?}:\n{program}");
            for (x, y) in [(0.7, 1.3), (1.9, 0.4), (2.5, 2.5), (0.1, 3.0)] {
                let (value, want) = (program.eval(&[x, y]), expected(x, y));
                assert!(
                    (value - want).abs() <= 1e-15 * want.abs(),
                    "{text} at ({x}, {y})"
                );
            }
        }
    }

    #[test]
    fn every_instruction_has_a_case() {
        // Adding an instruction without a case here makes this match non-exhaustive.
        for &(_, op, _) in CASES {
            match op {
                Op::PushInput(_) | Op::PushConst(_) | Op::Add | Op::Sub | Op::Mul | Op::Div => {}
                Op::AddInput(_) | Op::SubInput(_) | Op::MulInput(_) | Op::DivInput(_) => {}
                Op::AddConst(_) | Op::MulConst(_) | Op::DivConst(_) => {}
                Op::ConstSub(_) | Op::ConstDiv(_) | Op::Neg | Op::Call(_) => {}
                Op::Powi(_) | Op::Square | Op::Powf(_) | Op::Powd | Op::Atan2 => {}
                Op::MulConstAdd(_) | Op::PushCall(..) | Op::PushSquare(_) => {}
            }
        }
        let kinds: std::collections::HashSet<_> =
            CASES.iter().map(|(_, op, _)| discriminant(op)).collect();
        assert_eq!(kinds.len(), 25);
    }
}
