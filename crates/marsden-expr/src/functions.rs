//! The built-in functions and constants of the expression language.

use marsden::Scalar;

/// A built-in function that expressions may call.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Function {
    /// `sin(x)`
    Sin,
    /// `cos(x)`
    Cos,
    /// `tan(x)`
    Tan,
    /// `asin(x)`
    Asin,
    /// `acos(x)`
    Acos,
    /// `atan(x)`
    Atan,
    /// `atan2(y, x)`: the angle of the point `(x, y)`.
    Atan2,
    /// `sinh(x)`
    Sinh,
    /// `cosh(x)`
    Cosh,
    /// `tanh(x)`
    Tanh,
    /// `exp(x)`
    Exp,
    /// `log(x)`: the natural logarithm.
    Log,
    /// `sqrt(x)`
    Sqrt,
    /// `abs(x)`
    Abs,
    /// `pow(x, y)`: the same as `x^y`.
    Pow,
}

/// Names of the built-in constants (currently only `pi`).
pub const CONSTANTS: &[(&str, f64)] = &[("pi", std::f64::consts::PI)];

impl Function {
    /// Every built-in function, in declaration order.
    pub const ALL: [Function; 15] = [
        Function::Sin,
        Function::Cos,
        Function::Tan,
        Function::Asin,
        Function::Acos,
        Function::Atan,
        Function::Atan2,
        Function::Sinh,
        Function::Cosh,
        Function::Tanh,
        Function::Exp,
        Function::Log,
        Function::Sqrt,
        Function::Abs,
        Function::Pow,
    ];

    /// The name used to call the function.
    pub fn name(self) -> &'static str {
        match self {
            Function::Sin => "sin",
            Function::Cos => "cos",
            Function::Tan => "tan",
            Function::Asin => "asin",
            Function::Acos => "acos",
            Function::Atan => "atan",
            Function::Atan2 => "atan2",
            Function::Sinh => "sinh",
            Function::Cosh => "cosh",
            Function::Tanh => "tanh",
            Function::Exp => "exp",
            Function::Log => "log",
            Function::Sqrt => "sqrt",
            Function::Abs => "abs",
            Function::Pow => "pow",
        }
    }

    /// Number of arguments the function takes.
    pub fn arity(self) -> usize {
        match self {
            Function::Atan2 | Function::Pow => 2,
            _ => 1,
        }
    }

    /// The function called `name`, if there is one.
    pub fn lookup(name: &str) -> Option<Function> {
        Function::ALL.into_iter().find(|f| f.name() == name)
    }

    /// The built-in function that `name` (a spelling common elsewhere, such as `ln` or
    /// `arctan`) most likely means.
    pub fn alias(name: &str) -> Option<Function> {
        Some(match name {
            "ln" => Function::Log,
            "arcsin" => Function::Asin,
            "arccos" => Function::Acos,
            "arctan" => Function::Atan,
            "arctan2" => Function::Atan2,
            "power" => Function::Pow,
            "fabs" => Function::Abs,
            _ => return None,
        })
    }

    /// All function names, sorted alphabetically.
    pub fn sorted_names() -> Vec<&'static str> {
        let mut names: Vec<_> = Function::ALL.iter().map(|f| f.name()).collect();
        names.sort_unstable();
        names
    }

    /// The one-argument operation behind this function, if it takes one argument.
    pub(crate) fn unary(self) -> Option<Unary> {
        Some(match self {
            Function::Sin => Unary::Sin,
            Function::Cos => Unary::Cos,
            Function::Tan => Unary::Tan,
            Function::Asin => Unary::Asin,
            Function::Acos => Unary::Acos,
            Function::Atan => Unary::Atan,
            Function::Sinh => Unary::Sinh,
            Function::Cosh => Unary::Cosh,
            Function::Tanh => Unary::Tanh,
            Function::Exp => Unary::Exp,
            Function::Log => Unary::Ln,
            Function::Sqrt => Unary::Sqrt,
            Function::Abs => Unary::Abs,
            Function::Atan2 | Function::Pow => return None,
        })
    }
}

/// Whether `name` is reserved (a built-in function or constant).
pub fn is_reserved(name: &str) -> bool {
    Function::lookup(name).is_some() || CONSTANTS.iter().any(|(c, _)| *c == name)
}

/// The value of the built-in constant `name`, if there is one.
pub(crate) fn constant(name: &str) -> Option<f64> {
    CONSTANTS.iter().find(|(c, _)| *c == name).map(|&(_, v)| v)
}

/// A one-argument elementary function, applied generically over [`Scalar`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Unary {
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Sinh,
    Cosh,
    Tanh,
    Exp,
    Ln,
    Sqrt,
    Abs,
}

impl Unary {
    /// Apply the function to `x`.
    #[inline(always)]
    pub(crate) fn apply<S: Scalar>(self, x: S) -> S {
        match self {
            Unary::Sin => x.sin(),
            Unary::Cos => x.cos(),
            Unary::Tan => x.tan(),
            Unary::Asin => x.asin(),
            Unary::Acos => x.acos(),
            Unary::Atan => x.atan(),
            Unary::Sinh => x.sinh(),
            Unary::Cosh => x.cosh(),
            Unary::Tanh => x.tanh(),
            Unary::Exp => x.exp(),
            Unary::Ln => x.ln(),
            Unary::Sqrt => x.sqrt(),
            Unary::Abs => abs(x),
        }
    }

    /// The name used in program listings.
    pub(crate) fn name(self) -> &'static str {
        self.function().name()
    }

    pub(crate) fn function(self) -> Function {
        match self {
            Unary::Sin => Function::Sin,
            Unary::Cos => Function::Cos,
            Unary::Tan => Function::Tan,
            Unary::Asin => Function::Asin,
            Unary::Acos => Function::Acos,
            Unary::Atan => Function::Atan,
            Unary::Sinh => Function::Sinh,
            Unary::Cosh => Function::Cosh,
            Unary::Tanh => Function::Tanh,
            Unary::Exp => Function::Exp,
            Unary::Ln => Function::Log,
            Unary::Sqrt => Function::Sqrt,
            Unary::Abs => Function::Abs,
        }
    }
}

/// `|x|`, with the derivative of `x` (sign +1) at `x = 0`.
#[inline(always)]
pub(crate) fn abs<S: Scalar>(x: S) -> S {
    if x < 0.0 { -x } else { x }
}

/// `x^e` for a constant exponent. At `x = 0` with `e > 2` the value and the first and second
/// derivatives all vanish (`d^k x^e/dx^k = e(e−1)…(e−k+1)·x^(e−k) → 0` for `k < e`), which is
/// returned exactly: num-dual's `powf` forms them from `x^(e−3)`, infinite at 0 for `e < 3`,
/// and would give `∞·0 = NaN` (so `t^2.5` at `t = 0` would poison a whole Lagrangian).
#[inline(always)]
pub(crate) fn powf<S: Scalar>(x: S, e: f64) -> S {
    if e > 2.0 && x == 0.0 {
        x * 0.0
    } else {
        x.powf(e)
    }
}

/// `x^y` for a variable exponent: num-dual's `powd` (`powf` at `f64`, `exp(y ln x)` for duals).
#[inline(always)]
pub(crate) fn powd<S: Scalar>(x: S, y: S) -> S {
    x.powd(y)
}

/// `atan2(y, x)`.
#[inline(always)]
pub(crate) fn atan2<S: Scalar>(y: S, x: S) -> S {
    y.atan2(x)
}
