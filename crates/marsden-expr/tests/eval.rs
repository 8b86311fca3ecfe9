//! Evaluation at `f64` matches hand-written Rust on random inputs.

use crate::common::{AllFunctions, DoublePendulum, Kepler, Model, Pendulum, PendulumHamiltonian};
use crate::common::{assert_close, compile};
use marsden_expr::{Program, ProgramSet, Symbols};
use proptest::prelude::*;

/// Random input vectors for `M` (4 components; models use a prefix).
fn inputs<M: Model>() -> impl Strategy<Value = [f64; 4]> {
    let (lo, hi) = M::RANGE;
    [lo..hi, lo..hi, lo..hi, lo..hi]
}

fn check<M: Model>(program: &Program, x: &[f64; 4]) {
    let x = &x[..M::INPUTS.len()];
    assert_close(program.eval(x), M::rust(x), 1e-14, M::TEXT);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(500))]

    #[test]
    fn pendulum(x in inputs::<Pendulum>()) {
        check::<Pendulum>(&compile::<Pendulum>(), &x);
    }

    #[test]
    fn double_pendulum(x in inputs::<DoublePendulum>()) {
        check::<DoublePendulum>(&compile::<DoublePendulum>(), &x);
    }

    #[test]
    fn kepler(x in inputs::<Kepler>()) {
        check::<Kepler>(&compile::<Kepler>(), &x);
    }

    #[test]
    fn hamiltonian(x in inputs::<PendulumHamiltonian>()) {
        check::<PendulumHamiltonian>(&compile::<PendulumHamiltonian>(), &x);
    }

    #[test]
    fn all_functions(x in inputs::<AllFunctions>()) {
        check::<AllFunctions>(&compile::<AllFunctions>(), &x);
    }

    /// Nested products: commutative operands are reordered so the stack stays shallow.
    #[test]
    fn nested_products(a in -2.0..2.0_f64, b in -2.0..2.0_f64, levels in 1..40_usize) {
        let mut text = "a".to_owned();
        let mut expected = a;
        for _ in 0..levels {
            text = format!("sin(a)*(cos(b) + {text})");
            expected = a.sin() * (b.cos() + expected);
        }
        let program = Program::compile(&text, &Symbols::with_inputs(["a", "b"]).unwrap()).unwrap();
        prop_assert!(program.stack_depth() <= 1, "depth {}", program.stack_depth());
        assert_close(program.eval(&[a, b]), expected, 1e-13, &text);
    }

    /// Nested differences cannot be reordered: their depth grows with the nesting, which
    /// exercises both array stacks and the heap fallback.
    #[test]
    fn nested_differences(a in -2.0..2.0_f64, b in -2.0..2.0_f64, levels in 1..40_usize) {
        let mut text = "a".to_owned();
        let mut expected = a;
        for _ in 0..levels {
            text = format!("sin(a) - cos(b)/({text})");
            expected = a.sin() - b.cos() / expected;
        }
        let program = Program::compile(&text, &Symbols::with_inputs(["a", "b"]).unwrap()).unwrap();
        prop_assert!(program.stack_depth() + 1 >= levels, "depth {}", program.stack_depth());
        let value = program.eval(&[a, b]);
        prop_assert!(value == expected || (value.is_nan() && expected.is_nan()), "{} vs {}", value, expected);
    }

    /// A set of expressions writes each value to its slot.
    #[test]
    fn program_set(x in -3.0..3.0_f64, y in -3.0..3.0_f64) {
        let mut symbols = Symbols::with_inputs(["x", "y"]).unwrap();
        symbols.add_constant("k", 1.5).unwrap();
        let set = ProgramSet::compile(["-k*x + y^3", "-k*y*x", "atan2(y, x)"], &symbols).unwrap();
        let mut out = [0.0; 3];
        set.eval_into(&[x, y], &mut out);
        let expected = [-1.5 * x + y.powi(3), -1.5 * y * x, y.atan2(x)];
        for (value, expected) in out.iter().zip(expected) {
            assert_close(*value, expected, 1e-15, "program set");
        }
        prop_assert_eq!(set.eval(&[x, y]), out.to_vec());
    }
}

#[test]
fn set_metadata() {
    let mut symbols = Symbols::with_inputs(["q1", "q2", "t"]).unwrap();
    symbols.add_constant("k", 1.5).unwrap();
    let set = ProgramSet::compile(["k*q1", "q1 - q2^0"], &symbols).unwrap();
    assert_eq!(set.len(), 2);
    assert_eq!(set.names(), ["k", "q1", "q2"]);
    assert_eq!(set.input_len(), 1, "q2^0 folds to 1, so only q1 is read");
    assert_eq!(set.programs()[1].inputs_used(), [0]);
}
