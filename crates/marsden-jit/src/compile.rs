//! Translation of a [`Tape`] into Cranelift IR, one instruction at a time, and its compilation
//! for the host.
//!
//! The function has the signature `(head: *const f64, last: f64, out: *mut f64)`: for a split
//! at `h`, input register `i < h` is `head[i]` and register `h` is `last` (the time `t` of a
//! potential's tape over `[q, t]`, so `q` needs no copy); output `k` is stored to `out[k]`. (A
//! tape's inputs are the slots it reads, up to the last: `∇V` of Kepler reads `[x, y]` only.) Every
//! instruction becomes the IEEE 754 operations it names, in its order; functions other than
//! `√` are calls of the interpreter's own (`functions`).

use std::collections::HashMap;

use cranelift_codegen::ir::condcodes::FloatCC;
use cranelift_codegen::ir::{AbiParam, FuncRef, InstBuilder, MemFlags, Type, Value, types};
use cranelift_codegen::settings::{self, Configurable};
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext};
use cranelift_jit::{JITBuilder, JITModule};
use cranelift_module::{FuncId, Linkage, Module, default_libcall_names};
use marsden_expr::{Function, Tape, TapeOp};

use crate::functions;

/// Why a tape was not compiled (the caller keeps the interpreter).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum JitError {
    /// Cranelift has no back end for this machine.
    #[error("no native code generator for this machine: {0}")]
    UnsupportedHost(String),
    /// Cranelift rejected the settings, the function or its linking.
    #[error("native compilation failed: {0}")]
    Codegen(String),
    /// The tape reads more inputs than `head` and `last` hold.
    #[error("the tape reads {inputs} inputs, more than {head} and one")]
    Inputs {
        /// Inputs the tape reads.
        inputs: usize,
        /// Length of the `head` slice.
        head: usize,
    },
    /// A gradient tape without one output per degree of freedom.
    #[error("the gradient tape has {outputs} outputs for {dof} degrees of freedom")]
    Outputs {
        /// Outputs of the tape.
        outputs: usize,
        /// Degrees of freedom.
        dof: usize,
    },
    /// The tape calls a two-argument function as a one-argument one.
    #[error("the tape calls `{0}` with one argument")]
    Arity(&'static str),
}

/// Maps any Cranelift error to [`JitError::Codegen`].
pub(crate) fn codegen<E: std::fmt::Display>(e: E) -> JitError {
    JitError::Codegen(e.to_string())
}

/// A module for the host, optimising for speed, that resolves the interpreter's functions.
pub(crate) fn host_module() -> Result<JITModule, JitError> {
    let mut flags = settings::builder();
    for (name, value) in [
        ("opt_level", "speed"),
        ("use_colocated_libcalls", "false"),
        ("is_pic", "false"),
    ] {
        flags.set(name, value).map_err(codegen)?;
    }
    let isa = cranelift_native::builder()
        .map_err(|e| JitError::UnsupportedHost(e.to_string()))?
        .finish(settings::Flags::new(flags))
        .map_err(codegen)?;
    let mut builder = JITBuilder::with_isa(isa, default_libcall_names());
    for (name, address) in functions::symbols() {
        builder.symbol(name, address);
    }
    Ok(JITModule::new(builder))
}

/// Defines the function computing `tape` in `module` (not yet finalized), inputs split at
/// `head_len`.
pub(crate) fn define(
    module: &mut JITModule,
    tape: &Tape,
    head_len: usize,
) -> Result<FuncId, JitError> {
    check_inputs(tape, head_len)?;
    let pointer = AbiParam::new(module.target_config().pointer_type());
    let params = [pointer, AbiParam::new(types::F64), pointer];
    let split = |p: &[Value]| (p[0], p[1], head_len);
    define_with(module, "marsden_tape", &params, &[], split, |t, p| {
        let outputs = t.translate(tape, vec![None; tape.input_len()])?;
        for (k, value) in outputs.into_iter().enumerate() {
            let offset = i32::try_from(8 * k).map_err(codegen)?;
            t.b.ins().store(MemFlags::trusted(), value, p[2], offset);
        }
        t.b.ins().return_(&[]);
        Ok(())
    })
}

/// [`JitError::Inputs`] if `tape` reads more inputs than `head` values and one.
pub(crate) fn check_inputs(tape: &Tape, head: usize) -> Result<(), JitError> {
    match tape.input_len() > head + 1 {
        true => Err(JitError::Inputs {
            inputs: tape.input_len(),
            head,
        }),
        false => Ok(()),
    }
}

/// Declares the function `name(params) → returns` in `module` and defines it: `body` emits its
/// IR through a [`Translator`] positioned in the entry block (inputs read from the parameters
/// `split` picks), given the parameters' values; the blocks are sealed and the function
/// finished here.
pub(crate) fn define_with(
    module: &mut JITModule,
    name: &str,
    params: &[AbiParam],
    returns: &[AbiParam],
    split: impl FnOnce(&[Value]) -> (Value, Value, usize),
    body: impl FnOnce(&mut Translator<'_>, &[Value]) -> Result<(), JitError>,
) -> Result<FuncId, JitError> {
    let mut ctx = module.make_context();
    ctx.func.signature.params.extend_from_slice(params);
    ctx.func.signature.returns.extend_from_slice(returns);
    let id = module
        .declare_function(name, Linkage::Local, &ctx.func.signature)
        .map_err(codegen)?;
    let mut builder_ctx = FunctionBuilderContext::new();
    {
        let mut b = FunctionBuilder::new(&mut ctx.func, &mut builder_ctx);
        let entry = b.create_block();
        b.append_block_params_for_function_params(entry);
        b.switch_to_block(entry);
        let values = b.block_params(entry).to_vec();
        let (head, last, head_len) = split(&values);
        let mut t = Translator::new(b, module, head, last, head_len);
        body(&mut t, &values)?;
        t.b.seal_all_blocks();
        t.b.finalize();
    }
    module.define_function(id, &mut ctx).map_err(codegen)?;
    module.clear_context(&mut ctx);
    Ok(id)
}

/// The state of one translation: the builder and the SSA value of each register so far.
pub(crate) struct Translator<'a> {
    pub(crate) b: FunctionBuilder<'a>,
    module: &'a mut JITModule,
    head: Value,
    last: Value,
    /// Input registers below this are read from `head`; the one equal to it is `last`.
    head_len: usize,
    /// Input registers, loaded at their first use.
    inputs: Vec<Option<Value>>,
    /// The value of instruction `k` (register `inputs + k`).
    regs: Vec<Value>,
    /// Functions imported so far, by symbol.
    calls: HashMap<&'static str, FuncRef>,
    /// Registers whose sine and cosine the tape both takes, and the two values once computed
    /// (one call, [`functions::SIN_COS`]).
    sin_cos: HashMap<u32, Option<[Value; 2]>>,
}

impl<'a> Translator<'a> {
    /// A translator into `b`'s function, reading inputs missing from [`Translator::translate`]'s
    /// `inputs` from `(head, last)` split at `head_len`.
    pub(crate) fn new(
        b: FunctionBuilder<'a>,
        module: &'a mut JITModule,
        head: Value,
        last: Value,
        head_len: usize,
    ) -> Self {
        Self {
            b,
            module,
            head,
            last,
            head_len,
            inputs: Vec::new(),
            regs: Vec::new(),
            calls: HashMap::new(),
            sin_cos: HashMap::new(),
        }
    }

    /// The IR of `tape` at the current position of the builder: the SSA values of its outputs.
    /// `inputs` (length [`Tape::input_len`]) gives the value of an input register, or `None`
    /// to load it from `(head, last)` at its first use.
    pub(crate) fn translate(
        &mut self,
        tape: &Tape,
        inputs: Vec<Option<Value>>,
    ) -> Result<Vec<Value>, JitError> {
        self.inputs = inputs;
        self.regs.clear();
        self.sin_cos = sines_and_cosines(tape);
        for op in tape.instructions() {
            let value = self.op(op)?;
            self.regs.push(value);
        }
        Ok(tape.outputs().iter().map(|&reg| self.reg(reg)).collect())
    }

    /// The value of register `r` (an input, loaded on first use, or an earlier instruction).
    fn reg(&mut self, r: u32) -> Value {
        let r = r as usize;
        let n = self.inputs.len();
        if r >= n {
            return self.regs[r - n];
        }
        if let Some(v) = self.inputs[r] {
            return v;
        }
        let v = if r == self.head_len {
            self.last
        } else {
            // Fits: the tape's registers are indexed by `u32`.
            let offset = (8 * r) as i32;
            self.b
                .ins()
                .load(types::F64, MemFlags::trusted(), self.head, offset)
        };
        self.inputs[r] = Some(v);
        v
    }

    fn constant(&mut self, c: f64) -> Value {
        self.b.ins().f64const(c)
    }

    /// The IR of one instruction.
    fn op(&mut self, op: TapeOp) -> Result<Value, JitError> {
        Ok(match op {
            TapeOp::Load(c) => self.constant(c),
            TapeOp::Neg(a) => {
                let a = self.reg(a);
                self.b.ins().fneg(a)
            }
            TapeOp::Add(a, b) => self.binary(a, b, |b, x, y| b.ins().fadd(x, y)),
            TapeOp::Sub(a, b) => self.binary(a, b, |b, x, y| b.ins().fsub(x, y)),
            TapeOp::Mul(a, b) => self.binary(a, b, |b, x, y| b.ins().fmul(x, y)),
            TapeOp::Div(a, b) => self.binary(a, b, |b, x, y| b.ins().fdiv(x, y)),
            TapeOp::AddC(a, c) => self.with_constant(a, c, |b, x, k| b.ins().fadd(x, k)),
            TapeOp::SubC(a, c) => self.with_constant(a, c, |b, x, k| b.ins().fsub(x, k)),
            TapeOp::CSub(c, a) => self.with_constant(a, c, |b, x, k| b.ins().fsub(k, x)),
            TapeOp::MulC(a, c) => self.with_constant(a, c, |b, x, k| b.ins().fmul(x, k)),
            TapeOp::DivC(a, c) => self.with_constant(a, c, |b, x, k| b.ins().fdiv(x, k)),
            TapeOp::CDiv(c, a) => self.with_constant(a, c, |b, x, k| b.ins().fdiv(k, x)),
            TapeOp::Square(a) => self.binary(a, a, |b, x, y| b.ins().fmul(x, y)),
            TapeOp::Call(f, a) => self.call(f, a)?,
            TapeOp::Powi(a, n) => {
                let x = self.reg(a);
                let n = self.b.ins().iconst(types::I32, i64::from(n));
                let sig = [types::F64, types::I32];
                self.import(functions::POWI.0, &sig, &[x, n])?
            }
            TapeOp::Powf(a, e) => {
                let x = self.reg(a);
                let e = self.constant(e);
                self.import(functions::POWF.0, &[types::F64; 2], &[x, e])?
            }
            TapeOp::Powd(a, b) => {
                let (x, y) = (self.reg(a), self.reg(b));
                self.import(functions::POWD.0, &[types::F64; 2], &[x, y])?
            }
            TapeOp::Atan2(a, b) => {
                let (y, x) = (self.reg(a), self.reg(b));
                self.import(functions::ATAN2.0, &[types::F64; 2], &[y, x])?
            }
            TapeOp::MulAdd(a, b, c) => {
                let p = self.binary(a, b, |b, x, y| b.ins().fmul(x, y));
                let c = self.reg(c);
                self.b.ins().fadd(p, c)
            }
            TapeOp::SumSquares(a, b) => {
                let p = self.binary(a, a, |b, x, y| b.ins().fmul(x, y));
                let q = self.binary(b, b, |b, x, y| b.ins().fmul(x, y));
                self.b.ins().fadd(p, q)
            }
            TapeOp::MulSub(a, b, c) => {
                let p = self.binary(a, b, |b, x, y| b.ins().fmul(x, y));
                let c = self.reg(c);
                self.b.ins().fsub(p, c)
            }
            TapeOp::SubMul(c, a, b) => {
                let p = self.binary(a, b, |b, x, y| b.ins().fmul(x, y));
                let c = self.reg(c);
                self.b.ins().fsub(c, p)
            }
            TapeOp::Mul3(a, b, c) => {
                let p = self.binary(a, b, |b, x, y| b.ins().fmul(x, y));
                let c = self.reg(c);
                self.b.ins().fmul(p, c)
            }
            TapeOp::MulDiv(a, b, c) => {
                let p = self.binary(a, b, |b, x, y| b.ins().fmul(x, y));
                let c = self.reg(c);
                self.b.ins().fdiv(p, c)
            }
        })
    }

    fn binary(
        &mut self,
        a: u32,
        b: u32,
        f: impl FnOnce(&mut FunctionBuilder<'_>, Value, Value) -> Value,
    ) -> Value {
        let (x, y) = (self.reg(a), self.reg(b));
        f(&mut self.b, x, y)
    }

    fn with_constant(
        &mut self,
        a: u32,
        c: f64,
        f: impl FnOnce(&mut FunctionBuilder<'_>, Value, Value) -> Value,
    ) -> Value {
        let x = self.reg(a);
        let k = self.constant(c);
        f(&mut self.b, x, k)
    }

    /// A one-argument function: `√` as the (correctly rounded) instruction, `|x|` as the
    /// interpreter's `x < 0 ? −x : x` (which keeps the sign of `−0` and of `NaN`), the others
    /// as calls.
    fn call(&mut self, f: Function, a: u32) -> Result<Value, JitError> {
        let x = self.reg(a);
        match f {
            Function::Sqrt => Ok(self.b.ins().sqrt(x)),
            Function::Abs => {
                let zero = self.constant(0.0);
                let negative = self.b.ins().fcmp(FloatCC::LessThan, x, zero);
                let minus = self.b.ins().fneg(x);
                Ok(self.b.ins().select(negative, minus, x))
            }
            Function::Sin | Function::Cos if self.sin_cos.contains_key(&a) => {
                let pair = match self.sin_cos.get(&a).copied().flatten() {
                    Some(pair) => pair,
                    None => {
                        let pair = self.sin_and_cos(x)?;
                        self.sin_cos.insert(a, Some(pair));
                        pair
                    }
                };
                Ok(pair[usize::from(f == Function::Cos)])
            }
            _ => {
                let (name, _) = functions::unary(f).ok_or(JitError::Arity(f.name()))?;
                self.import(name, &[types::F64], &[x])
            }
        }
    }

    /// `[sin x, cos x]` from one call of [`functions::SIN_COS`].
    fn sin_and_cos(&mut self, x: Value) -> Result<[Value; 2], JitError> {
        let func = self.imported(functions::SIN_COS.0, &[types::F64], 2)?;
        let call = self.b.ins().call(func, &[x]);
        let results = self.b.inst_results(call);
        Ok([results[0], results[1]])
    }

    /// A call of the imported function `name` (parameters `params`, one `f64` result).
    fn import(
        &mut self,
        name: &'static str,
        params: &[Type],
        args: &[Value],
    ) -> Result<Value, JitError> {
        let func = self.imported(name, params, 1)?;
        let call = self.b.ins().call(func, args);
        Ok(self.b.inst_results(call)[0])
    }

    /// The imported function `name` (parameters `params`, `results` values of type `f64`),
    /// declared at its first use.
    fn imported(
        &mut self,
        name: &'static str,
        params: &[Type],
        results: usize,
    ) -> Result<FuncRef, JitError> {
        if let Some(&f) = self.calls.get(name) {
            return Ok(f);
        }
        let mut sig = self.module.make_signature();
        sig.params.extend(params.iter().map(|&t| AbiParam::new(t)));
        sig.returns
            .extend(std::iter::repeat_n(AbiParam::new(types::F64), results));
        let id = self
            .module
            .declare_function(name, Linkage::Import, &sig)
            .map_err(codegen)?;
        let f = self.module.declare_func_in_func(id, self.b.func);
        self.calls.insert(name, f);
        Ok(f)
    }
}

/// The registers whose sine and cosine `tape` both takes (none where the two cannot come
/// from one call, [`functions::SIN_COS_IN_ONE_CALL`]).
fn sines_and_cosines(tape: &Tape) -> HashMap<u32, Option<[Value; 2]>> {
    if !functions::SIN_COS_IN_ONE_CALL {
        return HashMap::new();
    }
    let (mut sines, mut cosines) = (Vec::new(), Vec::new());
    for op in tape.instructions() {
        match op {
            TapeOp::Call(Function::Sin, a) => sines.push(a),
            TapeOp::Call(Function::Cos, a) => cosines.push(a),
            _ => {}
        }
    }
    sines
        .into_iter()
        .filter(|a| cosines.contains(a))
        .map(|a| (a, None))
        .collect()
}
