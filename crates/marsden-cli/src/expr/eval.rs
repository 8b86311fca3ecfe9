//! The interpreter loop, generic over [`Scalar`].
//!
//! The stack lives in a fixed-size array on the machine stack when the program's depth (known at
//! compile time) fits one of the sizes below, so evaluation does not allocate; deeper programs
//! fall back to a heap `Vec`. Array slots are addressed `i % N`, which the compiler can prove in
//! bounds, so the loop has no bounds checks on the stack and no panic paths.

use marsden::Scalar;

use super::functions::{atan2, powd};
use super::ops::{Code, Leaf, Op};

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
            Op::Powf(e) => acc = acc.powf(e),
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
