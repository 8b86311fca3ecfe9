//! The functions compiled code calls: `extern "C"` wrappers around the `f64` functions of the
//! tape interpreter ([`marsden_expr::tape_f64`]), so that both compute the same values.

use marsden_expr::Function;
use marsden_expr::tape_f64::{atan2_f64, call_f64, powd_f64, powf_f64, powi_f64};

/// A one-argument function as compiled code calls it.
pub(crate) type UnaryFn = extern "C" fn(f64) -> f64;
/// A two-argument function (`f64`, `f64`) as compiled code calls it.
pub(crate) type BinaryFn = extern "C" fn(f64, f64) -> f64;
/// `xⁿ` as compiled code calls it.
pub(crate) type PowiFn = extern "C" fn(f64, i32) -> f64;

macro_rules! unary {
    ($($name:ident => $f:ident),* $(,)?) => {
        $(
            extern "C" fn $name(x: f64) -> f64 {
                call_f64(Function::$f, x)
            }
        )*

        /// The symbol and the address of the wrapper of `f`, if it takes one argument.
        pub(crate) fn unary(f: Function) -> Option<(&'static str, UnaryFn)> {
            match f {
                $(Function::$f => Some((stringify!($name), $name as UnaryFn)),)*
                _ => None,
            }
        }
    };
}

unary! {
    marsden_sin => Sin,
    marsden_cos => Cos,
    marsden_tan => Tan,
    marsden_asin => Asin,
    marsden_acos => Acos,
    marsden_atan => Atan,
    marsden_sinh => Sinh,
    marsden_cosh => Cosh,
    marsden_tanh => Tanh,
    marsden_exp => Exp,
    marsden_ln => Log,
    marsden_sqrt => Sqrt,
    marsden_abs => Abs,
}

extern "C" fn marsden_powi(x: f64, n: i32) -> f64 {
    powi_f64(x, n)
}

extern "C" fn marsden_powf(x: f64, e: f64) -> f64 {
    powf_f64(x, e)
}

extern "C" fn marsden_powd(x: f64, y: f64) -> f64 {
    powd_f64(x, y)
}

extern "C" fn marsden_atan2(y: f64, x: f64) -> f64 {
    atan2_f64(y, x)
}

/// `(sin x, cos x)`, returned in two registers (`#[repr(C)]`: both parts floating-point, the
/// C ABI of the targets where compiled code calls it, [`SIN_COS_IN_ONE_CALL`]).
#[repr(C)]
pub(crate) struct SinCos {
    sin: f64,
    cos: f64,
}

/// Both in one call where a tape takes the sine and the cosine of one register (the
/// derivatives of `cos(θ₁ − θ₂)`): the two calls of the interpreter, so the same values, and
/// LLVM may compute them together.
extern "C" fn marsden_sin_cos(x: f64) -> SinCos {
    SinCos {
        sin: call_f64(Function::Sin, x),
        cos: call_f64(Function::Cos, x),
    }
}

/// Whether compiled code takes a sine and cosine of one register in one call: where a
/// two-`f64` result comes back in two floating-point registers both in the C ABI and in
/// Cranelift's (System V x86-64, AArch64 outside Windows).
pub(crate) const SIN_COS_IN_ONE_CALL: bool = cfg!(all(
    not(windows),
    any(target_arch = "x86_64", target_arch = "aarch64")
));

/// `(sin x, cos x)`: symbol and address.
pub(crate) const SIN_COS: (&str, extern "C" fn(f64) -> SinCos) =
    ("marsden_sin_cos", marsden_sin_cos);

/// `xⁿ`: symbol and address.
pub(crate) const POWI: (&str, PowiFn) = ("marsden_powi", marsden_powi);
/// `x^e`, constant `e`: symbol and address.
pub(crate) const POWF: (&str, BinaryFn) = ("marsden_powf", marsden_powf);
/// `x^y`: symbol and address.
pub(crate) const POWD: (&str, BinaryFn) = ("marsden_powd", marsden_powd);
/// `atan2(y, x)`: symbol and address.
pub(crate) const ATAN2: (&str, BinaryFn) = ("marsden_atan2", marsden_atan2);

/// Every symbol compiled code may call, with its address.
pub(crate) fn symbols() -> Vec<(&'static str, *const u8)> {
    let mut all: Vec<(&'static str, *const u8)> = Function::ALL
        .into_iter()
        .filter_map(unary)
        .map(|(name, f)| (name, f as *const u8))
        .collect();
    all.push((POWI.0, POWI.1 as *const u8));
    for (name, f) in [POWF, POWD, ATAN2] {
        all.push((name, f as *const u8));
    }
    all.push((SIN_COS.0, SIN_COS.1 as *const u8));
    all
}
