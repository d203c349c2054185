"""Exact inputs: control points and parameters as ints, Fractions, Decimals,
decimal strings and numpy integer arrays; floats refused unless
exact_float=True, which uses their binary values exactly."""

import decimal
from fractions import Fraction

import numpy as np
import pytest

import uniparam as up
from conftest import same_document


def test_control_point_types_agree(cli):
    text = "[[0,0],[1/3,1],[1,1/4],[2,2]]"
    ref = cli.json("bezier", "--control", text)
    for pts in ([[0, 0], [Fraction(1, 3), 1], [1, Fraction(1, 4)], [2, 2]],
                [["0", "0"], ["1/3", "1"], ["1", "0.25"], ["2", "2e0"]],
                [[0, 0], [Fraction(1, 3), 1], [1, decimal.Decimal("0.25")], [2, 2]]):
        same_document(up.bezier(pts).json, ref)


def test_numpy_integer_array(cli):
    pts = np.array([[0, 0], [0, 1], [3, 1]], dtype=np.int64)
    same_document(up.bezier(pts).json, cli.json("bezier", "--control", "[[0,0],[0,1],[3,1]]"))
    same_document(up.Curve.bezier(pts).uniformity().json,
                  cli.json("uniformity", "--control", "[[0,0],[0,1],[3,1]]"))


def test_floats_refused():
    with pytest.raises(TypeError, match="exact_float"):
        up.bezier([[0, 0], [0.1, 1], [3, 1]])
    with pytest.raises(TypeError, match="exact_float"):
        up.Curve.bezier(np.array([[0.0, 0.0], [1.0, 1.0]]))
    with pytest.raises(TypeError):
        up.reparam("(t, t^3)", target=0.99)
    with pytest.raises(TypeError):
        up.bezier([[0, 0], [True, 1], [3, 1]])


def test_exact_float_uses_the_binary_value(cli):
    q = Fraction(0.1)  # 3602879701896397/36028797018963968
    assert q != Fraction(1, 10)
    r = up.bezier(np.array([[0.0, 0.0], [0.1, 1.0], [3.0, 1.0]]), exact_float=True)
    same_document(r.json, cli.json("bezier", "--control", "[[0,0],[%d/%d,1],[3,1]]" % (q.numerator, q.denominator)))


def test_malformed_strings():
    with pytest.raises(up.InvalidArgument):
        up.bezier([[0, 0], ["1/0x", 1], [3, 1]])


def test_curve_pickles():
    import pickle
    c = up.Curve.bezier([[0, 0], [0, 1], [3, 1]], weights=[1, 2, 1])
    d = pickle.loads(pickle.dumps(c))
    assert d == c and d.weights == c.weights
    r = up.uniformity(c)
    same_document(pickle.loads(pickle.dumps(r)).json, r.json)
