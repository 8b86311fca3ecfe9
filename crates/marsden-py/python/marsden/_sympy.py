"""SymPy expressions printed in the problem-file grammar.

The grammar (see the ``marsden-expr`` crate) has ``+ - * / ^``, parentheses, numbers, the
constant ``pi`` and the functions ``sin cos tan asin acos atan atan2 sinh cosh tanh exp log
sqrt abs pow``. Names are coordinates ``q``, velocities ``q_dot``, momenta ``p_q`` (in a
Hamiltonian), ``t`` and parameters. SymPy's ``dynamicsymbols`` are understood: ``theta(t)``
prints as ``theta`` and its time derivative as ``theta_dot``.

Anything else (``Piecewise``, ``gamma``, a second derivative, ...) is refused with a
:class:`marsden.ProblemError` naming every unsupported piece at once.

>>> import sympy as sp
>>> x, y, x_dot, y_dot, mu = sp.symbols("x y x_dot y_dot mu")
>>> to_grammar(sp.Rational(1, 2) * (x_dot**2 + y_dot**2) + mu / sp.sqrt(x**2 + y**2))
'mu/sqrt(x^2 + y^2) + (1/2)*x_dot^2 + (1/2)*y_dot^2'
"""

from __future__ import annotations

import re
from typing import Any, List

from ._errors import ProblemError

#: SymPy function class name -> grammar function name.
FUNCTIONS = {
    "sin": "sin",
    "cos": "cos",
    "tan": "tan",
    "asin": "asin",
    "acos": "acos",
    "atan": "atan",
    "atan2": "atan2",
    "sinh": "sinh",
    "cosh": "cosh",
    "tanh": "tanh",
    "exp": "exp",
    "log": "log",
    "Abs": "abs",
}

_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


def is_sympy(value: Any) -> bool:
    """Whether ``value`` is a SymPy object (without importing SymPy)."""
    return any((c.__module__ or "").startswith("sympy") for c in type(value).__mro__)


def to_grammar(expr: Any) -> str:
    """The text of a SymPy expression in the problem-file grammar.

    Raises :class:`marsden.ProblemError` naming the unsupported functions or objects.
    """
    import sympy

    expr = sympy.sympify(expr)
    printer = _Printer(sympy)
    text = printer.print(expr)
    if printer.unsupported:
        names = ", ".join(f"`{n}`" for n in sorted(set(printer.unsupported)))
        supported = ", ".join(sorted(set(FUNCTIONS.values()) | {"sqrt", "pow"}))
        raise ProblemError(
            f"error: the SymPy expression uses what the problem-file grammar does not have: "
            f"{names}\n  = note: the grammar's functions: {supported}; constants: pi\n"
            f"  = help: rewrite them with these (e.g. a Piecewise as a smooth formula), or "
            f"give the expression as a string"
        )
    return text


class _Printer:
    """A recursive printer that parenthesises every compound operand (unambiguous, and
    read back by the expression compiler exactly as written)."""

    def __init__(self, sympy: Any) -> None:
        self.sp = sympy
        self.unsupported: List[str] = []

    def print(self, e: Any) -> str:
        sp = self.sp
        if isinstance(e, sp.Derivative):
            return self._derivative(e)
        if isinstance(e, sp.Symbol):
            return self._name(e.name)
        if e is sp.pi:
            return "pi"
        if e is sp.E:
            return "exp(1)"
        if isinstance(e, sp.Integer):
            return str(int(e))
        if isinstance(e, sp.Rational):
            return f"({e.p}/{e.q})"
        if isinstance(e, sp.Float):
            return repr(float(e))
        if isinstance(e, sp.Add):
            return self._add(e)
        if isinstance(e, sp.Mul):
            return self._mul(e)
        if isinstance(e, sp.Pow):
            return self._pow(e)
        if isinstance(e, sp.Function):
            return self._function(e)
        self.unsupported.append(type(e).__name__)
        return "0"

    def _name(self, name: str) -> str:
        if not _NAME.match(name):
            self.unsupported.append(f"symbol {name}")
        return name

    def _operand(self, e: Any) -> str:
        """``e`` as an operand of ``*``, ``/`` or ``^``: parenthesised unless atomic."""
        text = self.print(e)
        atomic = isinstance(e, (self.sp.Symbol, self.sp.Function, self.sp.Derivative))
        plain_number = e.is_Number and not e.is_negative and not isinstance(e, self.sp.Rational)
        if atomic or plain_number or (isinstance(e, self.sp.Integer) and not e.is_negative):
            return text
        if isinstance(e, self.sp.Rational) and not e.is_negative:
            return text  # already "(p/q)"
        return f"({text})"

    def _add(self, e: Any) -> str:
        terms = [self.print(a) for a in e.as_ordered_terms()]
        out = terms[0]
        for t in terms[1:]:
            out += f" - {t[1:]}" if t.startswith("-") and not t.startswith("-(") else f" + {t}"
        return out

    def _mul(self, e: Any) -> str:
        coefficient, factors = e.as_coeff_mul()
        sign = ""
        if coefficient.is_negative:
            sign, coefficient = "-", -coefficient
        parts = [] if coefficient == 1 else [self._operand(coefficient)]
        numerator, denominator = [], []
        for f in factors:
            base, exponent = f.as_base_exp()
            if exponent.is_Number and exponent.is_negative:
                denominator.append(base if exponent == -1 else self.sp.Pow(base, -exponent))
            else:
                numerator.append(f)
        parts += [self._factor(f) for f in numerator]
        text = "*".join(parts) if parts else "1"
        if denominator:
            below = "*".join(self._factor(f) for f in denominator)
            text += f"/{below}" if len(denominator) == 1 else f"/({below})"
        return sign + text

    def _factor(self, e: Any) -> str:
        if isinstance(e, self.sp.Add):
            return f"({self.print(e)})"
        return self._operand(e) if e.is_Number else self.print(e)

    def _pow(self, e: Any) -> str:
        base, exponent = e.args
        if exponent == self.sp.Rational(1, 2):
            return f"sqrt({self.print(base)})"
        if exponent == -1:
            return f"1/{self._base(base)}"
        if exponent.is_Number and exponent.is_negative:
            return f"1/{self._base(self.sp.Pow(base, -exponent))}"
        return f"{self._base(base)}^{self._operand(exponent)}"

    def _base(self, e: Any) -> str:
        text = self.print(e)
        simple = isinstance(e, (self.sp.Symbol, self.sp.Function, self.sp.Derivative))
        if simple or (isinstance(e, self.sp.Integer) and not e.is_negative):
            return text
        return f"({text})"

    def _function(self, e: Any) -> str:
        name = type(e).__name__
        args = e.args
        # A dynamicsymbol: theta(t) is the coordinate theta.
        if isinstance(e, self.sp.core.function.AppliedUndef):
            if len(args) == 1 and isinstance(args[0], self.sp.Symbol) and args[0].name == "t":
                return self._name(name)
            self.unsupported.append(f"{name}({', '.join(map(str, args))})")
            return "0"
        grammar = FUNCTIONS.get(name)
        if grammar is None:
            self.unsupported.append(name)
            return "0"
        return f"{grammar}({', '.join(self.print(a) for a in args)})"

    def _derivative(self, e: Any) -> str:
        function, *variables = e.args
        once = len(variables) == 1 and variables[0][1] == 1 and str(variables[0][0]) == "t"
        if once and isinstance(function, self.sp.core.function.AppliedUndef):
            return self._name(f"{type(function).__name__}_dot")
        self.unsupported.append(f"Derivative({e.args[0]}, ...)")
        return "0"
