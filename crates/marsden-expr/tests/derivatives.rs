//! Derivatives through dual numbers: the expression agrees with hand-written Rust evaluated
//! over the same duals, and with finite differences.

use crate::common::{AllFunctions, DoublePendulum, Kepler, Model, Pendulum, PendulumHamiltonian};
use crate::common::{assert_close, compile};
use marsden::Scalar;
use marsden_expr::Program;
use nalgebra::SVector;
use num_dual::{Dual2SVec64, DualSVec64, HyperDualSVec64, gradient, hessian};
use proptest::prelude::*;

const N: usize = 4;

/// Evaluate on the first `M::INPUTS.len()` components of a length-4 vector.
fn eval_prefix<M: Model, S: Scalar>(program: &Program, v: &SVector<S, N>) -> (S, S) {
    let x = &v.as_slice()[..M::INPUTS.len()];
    (program.eval(x), M::rust(x))
}

/// Gradient and Hessian of the expression and of the Rust function, on 4-vectors (unused
/// trailing components have zero derivatives in both).
fn check_derivatives<M: Model>(x: [f64; N]) {
    let program = compile::<M>();
    let x = SVector::from(x);
    let (f_e, g_e) = gradient(
        |v: SVector<DualSVec64<N>, N>| eval_prefix::<M, _>(&program, &v).0,
        &x,
    );
    let (f_r, g_r) = gradient(
        |v: SVector<DualSVec64<N>, N>| eval_prefix::<M, _>(&program, &v).1,
        &x,
    );
    assert_close(f_e, f_r, 1e-14, "value");
    for i in 0..N {
        assert_close(g_e[i], g_r[i], 1e-14, &format!("{}: d/dx{i}", M::TEXT));
    }
    let (_, g2_e, h_e) = hessian(
        |v: SVector<Dual2SVec64<N>, N>| eval_prefix::<M, _>(&program, &v).0,
        &x,
    );
    let (_, _, h_r) = hessian(
        |v: SVector<Dual2SVec64<N>, N>| eval_prefix::<M, _>(&program, &v).1,
        &x,
    );
    for i in 0..N {
        assert_close(g2_e[i], g_e[i], 1e-14, "gradient from Dual2");
        for j in 0..N {
            assert_close(
                h_e[(i, j)],
                h_r[(i, j)],
                1e-14,
                &format!("{}: H[{i},{j}]", M::TEXT),
            );
        }
    }
    check_finite_differences::<M>(&program, x, &g_e, &h_e);
}

/// Central differences of the f64 value (gradient) and of the dual gradient (Hessian).
fn check_finite_differences<M: Model>(
    program: &Program,
    x: SVector<f64, N>,
    grad: &SVector<f64, N>,
    hess: &nalgebra::SMatrix<f64, N, N>,
) {
    let h = 1e-6;
    let grad_at = |y: SVector<f64, N>| {
        gradient(
            |v: SVector<DualSVec64<N>, N>| eval_prefix::<M, _>(program, &v).0,
            &y,
        )
        .1
    };
    for j in 0..M::INPUTS.len() {
        let mut e = SVector::<f64, N>::zeros();
        e[j] = h;
        let fd = (eval_prefix::<M, f64>(program, &(x + e)).0
            - eval_prefix::<M, f64>(program, &(x - e)).0)
            / (2.0 * h);
        assert_close(fd, grad[j], 1e-6, &format!("{}: FD d/dx{j}", M::TEXT));
        let column = (grad_at(x + e) - grad_at(x - e)) / (2.0 * h);
        for i in 0..M::INPUTS.len() {
            assert_close(
                column[i],
                hess[(i, j)],
                1e-6,
                &format!("{}: FD H[{i},{j}]", M::TEXT),
            );
        }
    }
}

fn inputs<M: Model>() -> impl Strategy<Value = [f64; N]> {
    let (lo, hi) = M::RANGE;
    [lo..hi, lo..hi, lo..hi, lo..hi]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(100))]

    #[test]
    fn pendulum(x in inputs::<Pendulum>()) { check_derivatives::<Pendulum>(x); }

    #[test]
    fn double_pendulum(x in inputs::<DoublePendulum>()) { check_derivatives::<DoublePendulum>(x); }

    #[test]
    fn kepler(x in inputs::<Kepler>()) { check_derivatives::<Kepler>(x); }

    #[test]
    fn hamiltonian(x in inputs::<PendulumHamiltonian>()) {
        check_derivatives::<PendulumHamiltonian>(x);
    }

    #[test]
    fn all_functions(x in inputs::<AllFunctions>()) { check_derivatives::<AllFunctions>(x); }

    /// The hyper-dual used for mixed second derivatives (e.g. d²L/dq dq̇) in the integrators.
    #[test]
    fn hyperdual_mixed_partials(q in -3.0..3.0_f64, v in -3.0..3.0_f64) {
        let program = compile::<Pendulum>();
        let x = HyperDualSVec64::<1, 1>::from_re(q).derivative1(0);
        let xd = HyperDualSVec64::<1, 1>::from_re(v).derivative2(0);
        let parts = |h: HyperDualSVec64<1, 1>| {
            let first = |d: Option<nalgebra::Matrix1<f64>>| d.map_or(0.0, |m| m[0]);
            [h.re, first(h.eps1.0), first(h.eps2.0), first(h.eps1eps2.0)]
        };
        let e = parts(program.eval(&[x, xd]));
        let r = parts(Pendulum::rust(&[x, xd]));
        for (a, b) in e.iter().zip(r) {
            assert_close(*a, b, 1e-14, "hyperdual");
        }
        // L = ½ m l² v² + m g l cos q: dL/dq, dL/dv, and the mixed partial (zero).
        let (m, l, g) = (1.3, 0.7, 9.81);
        assert_close(e[1], -m * g * l * q.sin(), 1e-14, "dL/dq");
        assert_close(e[2], m * l * l * v, 1e-14, "dL/dv");
        prop_assert_eq!(e[3], 0.0);
    }
}

#[test]
fn integer_powers_of_negative_duals_are_finite() {
    use num_dual::Dual64;
    let symbols = marsden_expr::Symbols::with_inputs(["x"]).unwrap();
    let program = Program::compile("x^3 + x^-2", &symbols).unwrap();
    let x = Dual64::from_re(-2.0).derivative();
    let y = program.eval(&[x]);
    assert_eq!(y.re, -8.0 + 0.25);
    assert_close(y.eps, 3.0 * 4.0 - 2.0 * (-2.0_f64).powi(-3), 1e-15, "d/dx");
}
