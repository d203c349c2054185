"""Certified reals and results: Ball, Algebraic, Surd and Result.

The values come from the C++ library's JSON documents (the same ones the
CLI prints with --json): a certified real is {"mid": "<decimal>", "rad":
"<decimal>"} and the true value lies in [mid - rad, mid + rad]. ``Ball`` keeps
those decimal strings exactly (``decimal.Decimal``); an exact value rides
along in ``Ball.exact`` as a ``fractions.Fraction``, an ``Algebraic`` (integer
polynomial and isolating interval) or a ``Surd`` (a quadratic surd's text).
"""

import decimal
import math
import numbers
import re
from fractions import Fraction

__all__ = ["Ball", "Algebraic", "Surd", "Result", "to_fraction"]


def to_fraction(x, exact_float=False):
    """The exact rational value of x: an int, Fraction, Decimal, a decimal or
    rational string ("1/3", "0.25", "1e-3"), or, with exact_float=True, a
    float (its binary value, exactly).

    Raises TypeError for floats without exact_float (a float is usually a
    rounded decimal: pass Fraction or a string instead) and for other types;
    ValueError for malformed strings and non-finite values.
    """
    if isinstance(x, bool):
        raise TypeError("a bool is not a number here")
    try:  # numpy scalars without importing numpy
        import numpy as np
        if isinstance(x, np.bool_):
            raise TypeError("a bool is not a number here")
        if isinstance(x, np.integer):
            return Fraction(int(x))
        if isinstance(x, np.floating):
            x = float(x)
    except ImportError:
        pass
    if isinstance(x, Fraction):
        return x
    if isinstance(x, numbers.Integral):
        return Fraction(int(x))
    if isinstance(x, decimal.Decimal):
        if not x.is_finite():
            raise ValueError("not a finite number: %r" % (x,))
        return Fraction(x)
    if isinstance(x, str):
        return Fraction(x.strip())
    if isinstance(x, float):
        if not exact_float:
            raise TypeError(
                "floats are refused: %r is a binary approximation; pass an int, fractions.Fraction or a "
                "decimal string such as '0.1', or exact_float=True to use the float's binary value "
                "exactly" % (x,))
        if not math.isfinite(x):
            raise ValueError("not a finite number: %r" % (x,))
        return Fraction(x)
    if isinstance(x, numbers.Rational):
        return Fraction(x.numerator, x.denominator)
    raise TypeError("expected an exact number (int, Fraction, Decimal or string), got %s" % type(x).__name__)


def _exact_decimal_context(*values):
    """A decimal context in which sums of the given Decimals are exact."""
    hi = max(v.adjusted() for v in values if v != 0) if any(v != 0 for v in values) else 0
    lo = min(v.as_tuple().exponent for v in values)
    return decimal.Context(prec=max(28, hi - lo + 3), rounding=decimal.ROUND_HALF_EVEN)


class Ball:
    """A certified real: the true value lies in [mid - rad, mid + rad].

    ``mid`` and ``rad`` are ``decimal.Decimal`` built from the printed
    strings, so they hold exactly the digits the C++ printers wrote (the
    CLI's JSON). ``exact`` is the exact value when known (Fraction, Algebraic
    or Surd), else None.
    """

    __slots__ = ("mid", "rad", "exact", "mid_text", "rad_text")

    def __init__(self, mid, rad="0", exact=None):
        self.mid_text, self.rad_text = str(mid), str(rad)  # as printed
        self.mid = decimal.Decimal(mid)
        self.rad = decimal.Decimal(rad)
        if not (self.mid.is_finite() and self.rad.is_finite()) or self.rad < 0:
            raise ValueError("a ball needs a finite mid and a finite rad >= 0")
        self.exact = exact

    @property
    def lower(self):
        """mid - rad, exactly (a Decimal)."""
        return self.mid.fma(1, -self.rad, context=_exact_decimal_context(self.mid, self.rad))

    @property
    def upper(self):
        """mid + rad, exactly (a Decimal)."""
        return self.mid.fma(1, self.rad, context=_exact_decimal_context(self.mid, self.rad))

    def contains(self, x, exact_float=True):
        """Whether x lies in [mid - rad, mid + rad]. x is a number (int,
        Fraction, Decimal, string; a float by its exact binary value) or a
        Ball (then the whole of it)."""
        lo, hi = Fraction(self.mid) - Fraction(self.rad), Fraction(self.mid) + Fraction(self.rad)
        if isinstance(x, Ball):
            return lo <= Fraction(x.lower) and Fraction(x.upper) <= hi
        v = to_fraction(x, exact_float=exact_float)
        return lo <= v <= hi

    def __contains__(self, x):
        return self.contains(x)

    def __float__(self):
        return float(self.mid)

    def is_exact(self):
        """True when the ball is a point (rad = 0)."""
        return self.rad == 0

    def to_mpmath(self):
        """The ball as an mpmath interval (mpmath.mpi) that contains it:
        its ends rounded outward. Raises ImportError without mpmath."""
        import mpmath
        lo, hi = mpmath.iv.mpf(str(self.lower)), mpmath.iv.mpf(str(self.upper))
        return mpmath.mpi(lo.a, hi.b)

    def __repr__(self):
        return "Ball(%r, %r)" % (self.mid_text, self.rad_text)

    def __str__(self):
        return self.mid_text if self.rad == 0 else "[%s +/- %s]" % (self.mid_text, self.rad_text)

    def __eq__(self, other):
        """Same printed mid and rad (and exact value): equality of the
        certified data, not of the real numbers."""
        if not isinstance(other, Ball):
            return NotImplemented
        return self.mid_text == other.mid_text and self.rad_text == other.rad_text and self.exact == other.exact

    def __hash__(self):
        return hash((self.mid_text, self.rad_text))


_TERM = re.compile(r"([+-]?)(\d*)(\*?t(?:\^(\d+))?)?$")


def _poly_coefficients(text):
    """Integer coefficients (constant term first) of a polynomial in t printed
    by the library ("27*t^4 - 1"), or None when the text has another form."""
    s = text.replace(" ", "")
    if not s:
        return None
    terms = re.findall(r"[+-]?[^+-]+", s)
    if "".join(terms) != s:
        return None
    coeffs = {}
    for term in terms:
        m = _TERM.match(term)
        if not m or (not m.group(2) and not m.group(3)):
            return None
        c = int(m.group(2)) if m.group(2) else 1
        if m.group(1) == "-":
            c = -c
        k = 0 if not m.group(3) else (int(m.group(4)) if m.group(4) else 1)
        coeffs[k] = coeffs.get(k, 0) + c
    return [coeffs.get(k, 0) for k in range(max(coeffs) + 1)]


class Algebraic:
    """An exact real algebraic number: the unique root of the integer
    polynomial ``poly`` (text; ``coefficients`` constant term first) in the
    isolating interval ``interval`` (two Fractions). ``ball`` encloses it to
    the printed digits. A quadratic surd also has its ``text``, ``latex`` and
    ``maple`` forms."""

    __slots__ = ("poly", "coefficients", "interval", "ball", "text", "latex", "maple")

    def __init__(self, poly, interval, ball=None, text=None, latex=None, maple=None):
        self.poly = poly
        self.coefficients = _poly_coefficients(poly)
        self.interval = (Fraction(interval[0]), Fraction(interval[1]))
        self.ball = ball
        self.text, self.latex, self.maple = text, latex, maple

    def __float__(self):
        return float(self.ball) if self.ball is not None else float((self.interval[0] + self.interval[1]) / 2)

    def __repr__(self):
        return "Algebraic(root of %s in (%s, %s))" % (self.poly, self.interval[0], self.interval[1])

    def __eq__(self, other):
        if not isinstance(other, Algebraic):
            return NotImplemented
        return self.poly == other.poly and self.interval == other.interval

    def __hash__(self):
        return hash((self.poly, self.interval))


class Surd:
    """An exact quadratic surd (a + b*sqrt(r)) / c as the library prints it:
    ``text``, ``latex`` and ``maple``."""

    __slots__ = ("text", "latex", "maple")

    def __init__(self, text, latex, maple):
        self.text, self.latex, self.maple = text, latex, maple

    def __repr__(self):
        return "Surd(%r)" % self.text

    def __str__(self):
        return self.text

    def __eq__(self, other):
        return isinstance(other, Surd) and self.text == other.text

    def __hash__(self):
        return hash(self.text)


def _exact_of(e, ball):
    if isinstance(e, str):
        return Fraction(e)
    if "poly" in e:
        return Algebraic(e["poly"], e["interval"], ball, e.get("text"), e.get("latex"), e.get("maple"))
    return Surd(e.get("text"), e.get("latex"), e.get("maple"))


def convert(value):
    """The Python form of a JSON value of the library's documents: balls
    become Ball, objects Result, arrays lists."""
    if isinstance(value, dict):
        if "mid" in value and "rad" in value and set(value) <= {"mid", "rad", "exact"}:
            b = Ball(value["mid"], value["rad"])
            if "exact" in value:
                b.exact = _exact_of(value["exact"], b)
            return b
        return Result(value)
    if isinstance(value, list):
        return [convert(v) for v in value]
    return value


class Result(dict):
    """A result: a dict with the keys of the CLI's JSON document (``uniparam
    COMMAND --json``), its certified reals as Ball; keys also read as
    attributes (``r.mu``). ``r.json`` is the document itself (plain dicts,
    lists and strings, exactly as the CLI prints it)."""

    def __init__(self, doc):
        super().__init__((k, convert(v)) for k, v in doc.items())
        object.__setattr__(self, "_json", doc)

    @property
    def json(self):
        return self._json

    def __getattr__(self, key):
        try:
            return self[key]
        except KeyError:
            raise AttributeError(key) from None

    def __dir__(self):
        return list(super().__dir__()) + [k for k in self if k.isidentifier()]
