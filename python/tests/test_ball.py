"""The certified reals: Ball, Algebraic, Fraction exact values."""

import decimal
from fractions import Fraction

import pytest

import uniparam as up


def test_ball_fields_are_the_printed_strings():
    r = up.uniformity("(t, t^3)")
    u = r.u
    assert u.mid == decimal.Decimal(r.json["u"]["mid"]) and u.rad == decimal.Decimal(r.json["u"]["rad"])
    assert (u.mid_text, u.rad_text) == (r.json["u"]["mid"], r.json["u"]["rad"])
    assert float(u) == float(r.json["u"]["mid"])
    assert u.contains(u.mid) and u.contains(u.lower) and u.contains(u.upper)
    assert not u.contains(Fraction(u.upper) + Fraction(1, 10 ** 40))
    assert not u.contains(Fraction(u.lower) - Fraction(1, 10 ** 40))
    assert u.contains(up.Ball(u.mid, u.rad / 2))


def test_exact_values():
    # the line's angular uniformity is exactly 1; the zero of the speed of
    # (t^2, t^3) is the exact rational 0
    assert up.uniformity("(t, 2*t)").u.contains(1)
    z = up.uniformity("(t^2, t^3)", speed="parametric").zeros[0]["t"]
    assert z.exact == 0 and isinstance(z.exact, Fraction)


def test_algebraic_numbers():
    # Bezier alpha = (-3 + sqrt(33))/8, a root of 8 t^2 + 6 t - 3
    a = up.bezier([[0, 0], [0, 1], [3, 1]]).alpha
    e = a.exact
    assert isinstance(e, up.Algebraic) and e.coefficients == [-3, 6, 8]
    lo, hi = e.interval
    p = lambda x: sum(c * x ** k for k, c in enumerate(e.coefficients))
    assert p(lo) * p(hi) < 0                          # isolating: a sign change
    assert e.text and "sqrt(33)" in e.text
    assert a.contains(lo) or a.contains(hi) or lo < Fraction(a.mid) < hi


def test_radical_breakpoints_are_algebraic():
    # (t, t^3 - t/2): the angular speed's critical points are irrational
    r = up.radical("(t, t^4 - t)")
    irr = [b.exact for b in r.t if isinstance(b.exact, up.Algebraic)]
    for e in irr:
        lo, hi = e.interval
        p = lambda x: sum(c * x ** k for k, c in enumerate(e.coefficients))
        assert p(lo) * p(hi) <= 0 and e.ball.contains((lo + hi) / 2) in (True, False)


def test_to_mpmath():
    mpmath = pytest.importorskip("mpmath")
    u = up.uniformity("(t, t^3)", digits=30).u
    iv = u.to_mpmath()
    assert isinstance(iv, type(mpmath.mpi(0, 1)))
    # the interval holds the ball: its ends (binary, exactly) are outside
    # or on [mid - rad, mid + rad]
    def exact(x):
        man, exp = mpmath.mpf(x).man_exp
        return Fraction(man) * Fraction(2) ** exp
    assert exact(iv.a) <= Fraction(u.lower) and exact(iv.b) >= Fraction(u.upper)
