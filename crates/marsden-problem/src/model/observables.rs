//! Observables and event functions written as expressions of the state `(t, q, v, p)`.
//!
//! An observable (`[output] observables = { x2 = "…" }`) is compiled against the inputs
//! `[q₁ … qₙ, q̇₁ … q̇ₙ, p₁ … pₙ, t]` (names: the coordinates, `<name>_dot`, `p_<name>`, `t`;
//! the parameters are constants). An event's `when` is compiled against the same inputs
//! followed by the observables' values, so `when = "x2"` reads the observable `x2`: the event
//! function ([`ExprEvent`]) evaluates the observables first (only if its expression reads one),
//! then `when`. Every evaluation fills its inputs on the stack
//! ([`marsden::numerics::scratch::with_slice`]): no allocation per step.

#[cfg(feature = "jit")]
use std::sync::{Arc, OnceLock};

use marsden::numerics::scratch::with_slice;
use marsden::run::events::EventFunction;
use marsden_expr::Program;

use super::hamiltonian::momentum_name;
use super::slots::velocity_name;

/// The input names of an observable, in slot order: `q…`, `q̇…`, `p…`, `t`.
pub fn state_inputs(coordinates: &[String]) -> Vec<String> {
    let q = coordinates.iter().cloned();
    let v = coordinates.iter().map(|c| velocity_name(c));
    let p = coordinates.iter().map(|c| momentum_name(c));
    q.chain(v).chain(p).chain(["t".to_owned()]).collect()
}

/// Named expressions of the state, evaluated at every stored row (the trajectory's columns
/// after the existing ones) and readable by the events.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Observables {
    /// The names, in the file's order.
    pub names: Vec<String>,
    /// One program per name, compiled against [`state_inputs`].
    pub programs: Vec<Program>,
}

impl Observables {
    /// No observables.
    pub fn none() -> Self {
        Self::default()
    }

    /// Number of observables.
    pub fn len(&self) -> usize {
        self.programs.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.programs.is_empty()
    }

    /// Writes the value of every observable at `(t, q, v, p)` into `out` (its length is
    /// [`Observables::len`]).
    pub fn eval_into(&self, t: f64, q: &[f64], v: &[f64], p: &[f64], out: &mut [f64]) {
        let n = q.len();
        with_slice(3 * n + 1, t, |x| {
            fill_state(x, q, v, p);
            for (program, value) in self.programs.iter().zip(out.iter_mut()) {
                *value = program.eval(x);
            }
        });
    }
}

/// `x[..3n] ← [q, v, p]` (slot `3n`, `t`, is filled by the caller).
fn fill_state(x: &mut [f64], q: &[f64], v: &[f64], p: &[f64]) {
    let n = q.len();
    x[..n].copy_from_slice(q);
    x[n..2 * n].copy_from_slice(v);
    x[2 * n..3 * n].copy_from_slice(p);
}

/// An event's `when` as native code (`marsden_jit`, Cranelift), compiled at its first use:
/// the detector evaluates `g` at every step of the run, where the interpreter's dispatch costs
/// more than the arithmetic of a `when` such as `theta - 3`. Without it (`MARSDEN_JIT=0`, no
/// `jit` feature, or a failed compilation) `when` is interpreted; both give the same values bit
/// for bit (the JIT's contract: the same IEEE operations in the same order). One code belongs to
/// one program (the event's `when`, beside it in the spec).
#[derive(Debug, Clone, Default)]
pub struct WhenCode {
    #[cfg(feature = "jit")]
    native: Arc<OnceLock<Option<marsden_jit::CompiledTape>>>,
}

/// The code is a function of the program: any two are equal.
impl PartialEq for WhenCode {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl WhenCode {
    /// The native code of `when`, compiled now if this is its first use.
    #[cfg(feature = "jit")]
    fn native(&self, when: &Program) -> Option<&marsden_jit::CompiledTape> {
        let compile = || marsden_jit::CompiledTape::compile(&when.tape()).ok();
        (self.native)
            .get_or_init(|| super::lagrangian::jit_wanted().then(compile).flatten())
            .as_ref()
    }
}

/// An event's `when` as the core's [`EventFunction`]: `g(t, q, v, p)`, reading the observables
/// (slots `3n + 1 …`) when it names one. What the detector would otherwise look up at every
/// step — the native code, and whether `when` reads positions only — is settled when it is
/// made ([`ExprEvent::new`]).
#[derive(Debug, Clone, Copy)]
pub struct ExprEvent<'a> {
    /// `when`, compiled against [`state_inputs`] followed by the observables' names.
    pub when: &'a Program,
    /// The observables it may read.
    pub observables: &'a Observables,
    /// The native code of `when`, if it has any ([`WhenCode`]).
    #[cfg(feature = "jit")]
    native: Option<&'a marsden_jit::CompiledTape>,
    /// Whether `when` reads positions only (its slots all below `n`).
    positions_only: bool,
}

impl<'a> ExprEvent<'a> {
    /// The event function of `when` with its code (compiled here if this is its first use)
    /// for a system of `n` coordinates.
    pub fn new(
        when: &'a Program,
        code: &'a WhenCode,
        observables: &'a Observables,
        n: usize,
    ) -> Self {
        #[cfg(not(feature = "jit"))]
        let _ = code;
        Self {
            when,
            observables,
            #[cfg(feature = "jit")]
            native: code.native(when),
            positions_only: when.input_len() <= n,
        }
    }

    /// Whether `when` reads an observable (a slot past `t`, the slot `3n`).
    fn reads_observables(&self, n: usize) -> bool {
        self.when.input_len() > 3 * n + 1
    }

    /// `when` at `inputs`, by its native code if it has any.
    #[inline(always)]
    fn eval(&self, inputs: &[f64]) -> f64 {
        #[cfg(feature = "jit")]
        if let Some(native) = self.native {
            let mut out = [0.0];
            native.eval(inputs, &mut out);
            return out[0];
        }
        self.when.eval(inputs)
    }
}

impl EventFunction for ExprEvent<'_> {
    /// `when` at the state. A `when` that reads positions only (the common section `θ = 0`)
    /// is evaluated on `q` itself, the slots it reads the same values at the same places: no
    /// input slice is filled.
    #[inline(always)]
    fn value(&self, t: f64, q: &[f64], v: &[f64], p: &[f64]) -> f64 {
        match self.positions_only {
            true => self.eval(q),
            false => self.value_of_state(t, q, v, p),
        }
    }
}

impl ExprEvent<'_> {
    /// `when` over the whole state `[q, v, p, t]` and the observables it reads, filled on the
    /// stack (kept out of [`EventFunction::value`], whose common case, a `when` of the
    /// positions, needs no stack frame of its own).
    #[inline(never)]
    fn value_of_state(&self, t: f64, q: &[f64], v: &[f64], p: &[f64]) -> f64 {
        let n = q.len();
        let m = if self.reads_observables(n) {
            self.observables.len()
        } else {
            0
        };
        with_slice(3 * n + 1 + m, t, |x| {
            fill_state(x, q, v, p);
            if m > 0 {
                let (state, values) = x.split_at_mut(3 * n + 1);
                self.observables.eval_into(t, q, v, p, values);
                state[3 * n] = t;
            }
            self.eval(x)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use marsden_expr::Symbols;

    fn coordinates() -> Vec<String> {
        vec!["x".to_owned(), "y".to_owned()]
    }

    #[test]
    fn observables_read_positions_velocities_momenta_and_time() {
        let symbols = Symbols::with_inputs(state_inputs(&coordinates())).unwrap();
        let texts = ["x + 10*y", "x_dot*p_y", "t"];
        let programs = texts
            .iter()
            .map(|t| {
                marsden_expr::Expr::parse(t)
                    .unwrap()
                    .compile(&symbols)
                    .unwrap()
            })
            .collect();
        let obs = Observables {
            names: vec!["a".into(), "b".into(), "c".into()],
            programs,
        };
        let mut out = [0.0; 3];
        obs.eval_into(7.0, &[1.0, 2.0], &[3.0, 4.0], &[5.0, 6.0], &mut out);
        assert_eq!(out, [21.0, 18.0, 7.0]);
    }

    /// A `when` of the positions alone is evaluated on `q` itself: the same value as through
    /// the full input slice (a `when` reading `p` and `t` goes the long way).
    #[test]
    fn an_event_of_the_positions_reads_q_directly() {
        let symbols = Symbols::with_inputs(state_inputs(&coordinates())).unwrap();
        let compile = |text: &str| {
            marsden_expr::Expr::parse(text)
                .unwrap()
                .compile(&symbols)
                .unwrap()
        };
        let (section, mixed) = (compile("y - 0.25*x"), compile("y - p_x*t"));
        let obs = Observables::none();
        let codes = [
            WhenCode::default(),
            WhenCode::default(),
            WhenCode::default(),
        ];
        let event = |when: &'static str| {
            let (program, code) = match when {
                "section" => (&section, &codes[0]),
                "mixed" => (&mixed, &codes[1]),
                _ => (&mixed, &codes[2]),
            };
            ExprEvent::new(program, code, &obs, 2)
        };
        let (q, v, p) = ([2.0, 3.0], [f64::NAN, f64::NAN], [5.0, 6.0]);
        assert_eq!(event("section").value(0.5, &q, &v, &p), 2.5);
        assert_eq!(event("mixed").value(0.5, &q, &v, &p), 0.5);
        let mut full = [0.0; 7];
        fill_state(&mut full, &q, &v, &p);
        full[6] = 0.5;
        assert_eq!(event("section").value(0.5, &q, &v, &p), section.eval(&full));
    }

    #[test]
    fn an_event_reads_an_observable_after_the_state() {
        let inputs = state_inputs(&coordinates());
        let symbols = Symbols::with_inputs(&inputs).unwrap();
        let s = marsden_expr::Expr::parse("x*y")
            .unwrap()
            .compile(&symbols)
            .unwrap();
        let obs = Observables {
            names: vec!["s".into()],
            programs: vec![s],
        };
        let with_obs =
            Symbols::with_inputs(inputs.iter().map(String::as_str).chain(["s"])).unwrap();
        let when = marsden_expr::Expr::parse("s - t")
            .unwrap()
            .compile(&with_obs)
            .unwrap();
        let code = WhenCode::default();
        let event = ExprEvent::new(&when, &code, &obs, 2);
        let g = event.value(0.5, &[2.0, 3.0], &[0.0, 0.0], &[0.0, 0.0]);
        assert_eq!(g, 5.5);
    }

    /// The native code of `when` (positions only, and reading `v`, `p`, `t`) gives the
    /// interpreter's values bit for bit, at many states.
    #[test]
    fn native_when_is_the_interpreter_bit_for_bit() {
        let symbols = Symbols::with_inputs(state_inputs(&coordinates())).unwrap();
        let obs = Observables::none();
        let texts = [
            "x - 3",
            "sin(x)*cos(y) - 0.25*x^3 + 1/(1 + y^2)",
            "sqrt(x^2 + y^2) - exp(-x)*y",
            "x_dot*p_y - t^2 + atan2(y, x)",
        ];
        for text in texts {
            let when = marsden_expr::Expr::parse(text)
                .unwrap()
                .compile(&symbols)
                .unwrap();
            let code = WhenCode::default();
            let native = ExprEvent::new(&when, &code, &obs, 2);
            for k in 0..50 {
                let a = f64::from(k) * 0.37 - 9.0;
                let (q, v, p) = ([a, 1.3 - 0.1 * a], [0.5 * a, -a], [a * a, 0.2]);
                let t = 0.01 * f64::from(k);
                let mut full = [0.0; 7];
                fill_state(&mut full, &q, &v, &p);
                full[6] = t;
                let (got, want) = (native.value(t, &q, &v, &p), when.eval(&full));
                assert_eq!(got.to_bits(), want.to_bits(), "{text} at {full:?}");
            }
        }
    }
}
