//! A velocity Störmer–Verlet run with a potential's gradient tape inside its loop, as one
//! native function.
//!
//! For `L = ½ vᵀ M v − V(t, q)` with a diagonal mass, the trapezoid rule's steps are
//! ([MW01] §2.2.1; `marsden::mechanics::kernel`)
//!
//! ```text
//!     p½ = p_k − c g_k,    q_{k+1} = q_k + d ⊙ p½,    g_{k+1} = ∇V(t₀ + (k+1)·h, q_{k+1}),    p_{k+1} = p½ − c g_{k+1},
//! ```
//!
//! `c = 0.5·h`, `dᵢ = h/mᵢ`. The function is
//! `(q: *mut f64, p: *mut f64, g: *mut f64, d: *const f64, t₀: f64, h: f64, steps: i64) → i64`:
//! it loads `q, p, g, d` (n values each), runs up to `steps` steps with the state in SSA
//! variables (machine registers where the allocator can) and `∇V` translated inline
//! ([`crate::compile::Translator`]), stops before the first step whose `(q_{k+1}, p_{k+1})` is
//! not finite (`|x| < ∞`, false for NaN, as Rust's `f64::is_finite`), stores `q, p, g` back
//! and returns the steps completed. Every operation is the one the generic Rust loop performs,
//! in its order and rounding (no fused multiply–add), so the runs agree bit for bit.
//!
//! [MW01]: marsden#references

use cranelift_codegen::ir::condcodes::{FloatCC, IntCC};
use cranelift_codegen::ir::{AbiParam, InstBuilder, MemFlags, Value, types};
use cranelift_frontend::{FunctionBuilder, Variable};
use cranelift_jit::JITModule;
use cranelift_module::{FuncId, Module};
use marsden_expr::Tape;

use crate::compile::{JitError, Translator, check_inputs, codegen, define_with};

/// Defines the Verlet run of the gradient tape `gradient` (over `[q, t]`, `n` outputs) in
/// `module` (not yet finalized).
pub(crate) fn define(
    module: &mut JITModule,
    gradient: &Tape,
    n: usize,
) -> Result<FuncId, JitError> {
    check_inputs(gradient, n)?;
    if gradient.len() != n {
        return Err(JitError::Outputs {
            outputs: gradient.len(),
            dof: n,
        });
    }
    let (pointer, float) = (
        AbiParam::new(module.target_config().pointer_type()),
        AbiParam::new(types::F64),
    );
    let integer = AbiParam::new(types::I64);
    let params = [pointer, pointer, pointer, pointer, float, float, integer];
    // The tape's inputs are all given as values (`q_{k+1}` and `t`): the split is never read.
    let split = |p: &[Value]| (p[0], p[4], n);
    define_with(
        module,
        "marsden_verlet",
        &params,
        &[integer],
        split,
        |t, p| emit_run(t, gradient, n, p),
    )
}

/// The state carried from step to step: the steps done and `q`, `p`, `g`.
struct Carried {
    k: Variable,
    q: Vec<Variable>,
    p: Vec<Variable>,
    g: Vec<Variable>,
}

/// The loop: `entry → head → (body → accept → head | exit)`.
fn emit_run(
    t: &mut Translator<'_>,
    gradient: &Tape,
    n: usize,
    params: &[Value],
) -> Result<(), JitError> {
    let [q_ptr, p_ptr, g_ptr, d_ptr, t0, h, steps] = params[..] else {
        return Err(codegen("the Verlet function has seven parameters"));
    };
    let half = t.b.ins().f64const(0.5);
    let c = t.b.ins().fmul(half, h);
    let d = load(&mut t.b, d_ptr, n)?;
    let state = Carried {
        k: t.b.declare_var(types::I64),
        q: declare(&mut t.b, n),
        p: declare(&mut t.b, n),
        g: declare(&mut t.b, n),
    };
    let zero = t.b.ins().iconst(types::I64, 0);
    t.b.def_var(state.k, zero);
    for (vars, ptr) in [(&state.q, q_ptr), (&state.p, p_ptr), (&state.g, g_ptr)] {
        let values = load(&mut t.b, ptr, n)?;
        define_all(&mut t.b, vars, &values);
    }
    let (head, body, accept, exit) = (
        t.b.create_block(),
        t.b.create_block(),
        t.b.create_block(),
        t.b.create_block(),
    );
    t.b.ins().jump(head, &[]);

    t.b.switch_to_block(head);
    let k = t.b.use_var(state.k);
    let more = t.b.ins().icmp(IntCC::UnsignedLessThan, k, steps);
    t.b.ins().brif(more, body, &[], exit, &[]);

    t.b.switch_to_block(body);
    let (q, p, g) = (
        use_all(&mut t.b, &state.q),
        use_all(&mut t.b, &state.p),
        use_all(&mut t.b, &state.g),
    );
    let p_half = kick(&mut t.b, c, &p, &g);
    let q_next: Vec<Value> = (0..n)
        .map(|i| {
            let step = t.b.ins().fmul(d[i], p_half[i]);
            t.b.ins().fadd(q[i], step)
        })
        .collect();
    let one = t.b.ins().iconst(types::I64, 1);
    let k_next = t.b.ins().iadd(k, one);
    let time = grid_time(&mut t.b, t0, h, k_next);
    let mut inputs: Vec<Option<Value>> = q_next.iter().copied().map(Some).collect();
    inputs.push(Some(time));
    inputs.truncate(gradient.input_len());
    let g_next = t.translate(gradient, inputs)?;
    let p_next = kick(&mut t.b, c, &p_half, &g_next);
    let finite = all_finite(&mut t.b, q_next.iter().chain(&p_next));
    t.b.ins().brif(finite, accept, &[], exit, &[]);

    t.b.switch_to_block(accept);
    t.b.def_var(state.k, k_next);
    define_all(&mut t.b, &state.q, &q_next);
    define_all(&mut t.b, &state.p, &p_next);
    define_all(&mut t.b, &state.g, &g_next);
    t.b.ins().jump(head, &[]);

    t.b.switch_to_block(exit);
    for (vars, ptr) in [(&state.q, q_ptr), (&state.p, p_ptr), (&state.g, g_ptr)] {
        let values = use_all(&mut t.b, vars);
        store(&mut t.b, ptr, &values)?;
    }
    let done = t.b.use_var(state.k);
    t.b.ins().return_(&[done]);
    Ok(())
}

/// `p − c·g`, each product rounded first.
fn kick(b: &mut FunctionBuilder<'_>, c: Value, p: &[Value], g: &[Value]) -> Vec<Value> {
    p.iter()
        .zip(g)
        .map(|(&pi, &gi)| {
            let impulse = b.ins().fmul(c, gi);
            b.ins().fsub(pi, impulse)
        })
        .collect()
}

/// `t₀ + k·h` with `k` converted to `f64` (Rust's `k as f64`: rounded to nearest).
fn grid_time(b: &mut FunctionBuilder<'_>, t0: Value, h: Value, k: Value) -> Value {
    let k = b.ins().fcvt_from_uint(types::F64, k);
    let elapsed = b.ins().fmul(k, h);
    b.ins().fadd(t0, elapsed)
}

/// Whether every value is finite: `|x| < ∞` for all (false for ±∞ and NaN).
fn all_finite<'v>(b: &mut FunctionBuilder<'_>, values: impl Iterator<Item = &'v Value>) -> Value {
    let infinity = b.ins().f64const(f64::INFINITY);
    let mut all = b.ins().iconst(types::I8, 1);
    for &x in values {
        let magnitude = b.ins().fabs(x);
        let finite = b.ins().fcmp(FloatCC::LessThan, magnitude, infinity);
        all = b.ins().band(all, finite);
    }
    all
}

fn declare(b: &mut FunctionBuilder<'_>, n: usize) -> Vec<Variable> {
    (0..n).map(|_| b.declare_var(types::F64)).collect()
}

fn define_all(b: &mut FunctionBuilder<'_>, vars: &[Variable], values: &[Value]) {
    for (&var, &value) in vars.iter().zip(values) {
        b.def_var(var, value);
    }
}

fn use_all(b: &mut FunctionBuilder<'_>, vars: &[Variable]) -> Vec<Value> {
    vars.iter().map(|&var| b.use_var(var)).collect()
}

/// `n` values loaded from `ptr[0 … n)`.
fn load(b: &mut FunctionBuilder<'_>, ptr: Value, n: usize) -> Result<Vec<Value>, JitError> {
    (0..n)
        .map(|i| {
            let offset = i32::try_from(8 * i).map_err(codegen)?;
            Ok(b.ins().load(types::F64, MemFlags::trusted(), ptr, offset))
        })
        .collect()
}

/// Stores `values` to `ptr[0 … n)`.
fn store(b: &mut FunctionBuilder<'_>, ptr: Value, values: &[Value]) -> Result<(), JitError> {
    for (i, &value) in values.iter().enumerate() {
        let offset = i32::try_from(8 * i).map_err(codegen)?;
        b.ins().store(MemFlags::trusted(), value, ptr, offset);
    }
    Ok(())
}
