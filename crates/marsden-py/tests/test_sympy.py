"""Lagrangians from SymPy: printed in the problem-file grammar, run by the same code."""

from __future__ import annotations

import numpy as np
import pytest

import marsden

sp = pytest.importorskip("sympy")


def test_printer_writes_the_grammar():
    x, y, x_dot, y_dot, mu = sp.symbols("x y x_dot y_dot mu")
    kepler = sp.Rational(1, 2) * (x_dot**2 + y_dot**2) + mu / sp.sqrt(x**2 + y**2)
    assert marsden.to_grammar(kepler) == "mu/sqrt(x^2 + y^2) + (1/2)*x_dot^2 + (1/2)*y_dot^2"
    assert marsden.to_grammar(-x**-2 + sp.atan2(y, x) - sp.Abs(x)) == \
        "-abs(x) + atan2(y, x) - 1/x^2"
    assert marsden.to_grammar(x ** sp.Rational(3, 2) * sp.pi) == "pi*x^(3/2)"


def test_unsupported_functions_are_named():
    x = sp.Symbol("x")
    with pytest.raises(marsden.ProblemError) as info:
        marsden.to_grammar(sp.gamma(x) + sp.besselj(0, x) + sp.sin(x))
    message = str(info.value)
    assert "`gamma`" in message and "`besselj`" in message and "sin" in message, message


def test_dynamicsymbols_print_as_coordinates_and_velocities():
    from sympy.physics.mechanics import dynamicsymbols

    theta = dynamicsymbols("theta")
    t = sp.Symbol("t")
    m, l, g = sp.symbols("m l g")
    lagrangian = m * l**2 * sp.diff(theta, t) ** 2 / 2 + m * g * l * sp.cos(theta)
    text = marsden.to_grammar(lagrangian)
    assert "theta_dot^2" in text and "cos(theta)" in text, text
    problem = marsden.Problem(lagrangian=lagrangian, coordinates=[theta],
                              parameters={"m": 1.0, "l": 1.0, "g": 1.0}, q0=[1.5], v0=[0.0],
                              h=0.05, steps=100)
    assert problem.coordinates == ["theta"]


def test_sympy_and_string_forms_give_the_same_bits():
    """Kepler e = 0.6 (reference case R10) from SymPy and from the printed string."""
    x, y, x_dot, y_dot, mu = sp.symbols("x y x_dot y_dot mu")
    lagrangian = sp.Rational(1, 2) * (x_dot**2 + y_dot**2) + mu / sp.sqrt(x**2 + y**2)
    common = dict(coordinates=[x, y], parameters={"mu": 1.0}, q0=[0.4, 0.0], p0=[0.0, 2.0],
                  h=0.01, steps=2000, tolerance=1e-14, symmetries={"Lz": [-y, x]})
    from_sympy = marsden.Problem(lagrangian=lagrangian, **common).solve()
    as_text = marsden.Problem(lagrangian=marsden.to_grammar(lagrangian), **common).solve()
    assert np.array_equal(from_sympy.q, as_text.q) and np.array_equal(from_sympy.p, as_text.p)
    # The same system written by hand in another order: the same physics to round-off.
    by_hand = marsden.Problem(lagrangian="0.5*(x_dot^2 + y_dot^2) + mu/sqrt(x^2 + y^2)",
                              **{**common, "coordinates": ["x", "y"],
                                 "symmetries": {"Lz": ["-y", "x"]}}).solve()
    assert np.allclose(from_sympy.q, by_hand.q, rtol=0, atol=1e-9)
    assert np.max(np.abs(from_sympy.momenta["Lz"] - 0.8)) < 1e-12
