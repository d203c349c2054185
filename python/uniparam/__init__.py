"""uniparam: certified uniform-speed reparameterization of rational curves.

    >>> import uniparam as up
    >>> r = up.uniformity("(t, t^3)")
    >>> r.u                                   # a certified Ball
    Ball('0.845695243153366342', '1.2e-19')

Every method takes a curve (a ``Curve``, its text "(x(t), y(t), ...)", a
Bezier curve from ``Curve.bezier``, or a composite curve from ``Curve.svg``
or ``Curve.nurbs``) and the options of the CLI as keyword
arguments: ``speed`` ("angular" or "parametric"), ``digits`` (correct
decimal digits, default 15), ``max_prec``, ``max_degree``, ``max_bits``,
``max_length``, ``max_depth``, ``timeout`` (seconds, default None: no limit)
and ``threads`` (worker threads, default: UNIPARAM_THREADS, else the cores,
at most 8). Results are ``Result`` dicts with the keys of ``uniparam COMMAND
--json`` (the same strings, from the same C++ code); certified reals are
``Ball``. Errors are ``uniparam.Error`` subclasses; Ctrl-C interrupts a
computation (KeyboardInterrupt) within a fraction of a second.
"""

import json as _json
import os as _os
import warnings as _warnings

from ._errors import (BudgetExceeded, DomainError, Error, InvalidArgument, ParseError, TargetNotReachedWarning,
                      TimeLimitExceeded)
from ._types import Algebraic, Ball, Result, Surd, to_fraction
from . import _uniparam

__all__ = [
    "Curve", "Ball", "Algebraic", "Surd", "Result", "SampleResult", "Plot",
    "uniformity", "radical", "moebius", "reparam", "bezier", "sample", "locate", "plot",
    "Error", "ParseError", "DomainError", "InvalidArgument", "BudgetExceeded", "TimeLimitExceeded",
    "TargetNotReachedWarning",
]
__version__ = "0.1.0"


def _fraction_text(q):
    return str(q.numerator) if q.denominator == 1 else "%d/%d" % (q.numerator, q.denominator)


def _exact_text(x, exact_float, what):
    try:
        return _fraction_text(to_fraction(x, exact_float=exact_float))
    except ValueError as e:
        raise InvalidArgument("%s: %s" % (what, e)) from None


class Curve:
    """A rational curve p(t), t in [0, 1], or a composite curve.

    ``Curve("(t, t^3)")`` parses the CLI's curve syntax (the parser's limits
    as keyword arguments max_degree, max_bits, max_length, max_depth);
    ``Curve.bezier(points, weights=None)`` builds a (rational) Bezier curve
    from exact control points; ``Curve.svg(path)`` and ``Curve.nurbs(spline)``
    build composite curves (the CLI's --svg and --nurbs). ``str(curve)`` is
    the canonical text of its power-basis form, or for a composite curve of
    several segments the CLI's description ("SVG path of 4 segments").
    Raises ParseError (with .column), DomainError (a pole in [0, 1], a
    constant curve), InvalidArgument, BudgetExceeded.
    """

    _svg = None
    _subpath = None
    _nurbs = None

    def __init__(self, text, **limits):
        if not isinstance(text, str):
            raise TypeError("Curve(text): text must be a str such as '(t, t^2)'; for control points use "
                            "Curve.bezier(points)")
        self._text, self._control, self._weights = text, "", ""
        self._limits = limits
        self._str = _uniparam.curve_text(self._common(**limits))

    @classmethod
    def svg(cls, path, subpath=None, max_degree=1000, max_length=1048576):
        """The composite curve of SVG path data (``uniparam --svg PATH``):
        commands M L H V C S Q T Z and elliptical arcs that are exactly
        rational quadratics (others raise InvalidArgument; uniparam never
        approximates), numbers read exactly as decimals. Each segment keeps
        its exact Bezier data; segment j of m runs over t in [j/m, (j+1)/m].
        A path of several subpaths needs ``subpath`` (0-based); a path of
        one segment is that Bezier curve. ``max_length`` bounds the path's
        characters, ``max_degree`` the segments' degrees. Raises ParseError
        (with .column) for bad path data."""
        if not isinstance(path, str):
            raise TypeError("Curve.svg(path): path must be the SVG path data as a str, such as "
                            "'M 0 0 Q 1 2 2 2'")
        if subpath is not None:
            subpath = _int("subpath", subpath)
        self = cls.__new__(cls)
        self._text, self._control, self._weights = "", "", ""
        self._svg, self._subpath = path, subpath
        self._limits = {"max_degree": max_degree, "max_length": max_length}
        self._str = _uniparam.curve_text(self._common())
        return self

    @classmethod
    def nurbs(cls, spline, exact_float=False, max_degree=1000, max_length=1048576):
        """The composite curve of a NURBS or B-spline (``uniparam --nurbs
        JSON``): a dict {"degree": p, "knots": [...], "control": [[x, y,
        ...], ...], "weights": [...]} ("weights" optional) or its JSON text.
        In a dict, knots, coordinates and weights are exact (int, Fraction,
        Decimal, decimal/rational strings; floats raise TypeError unless
        exact_float=True); in JSON text, numbers are read exactly as
        decimals. One segment per nonempty knot span, the knots mapped onto
        [0, 1]; a spline of one segment is that Bezier curve."""
        if isinstance(spline, (bytes, bytearray)):
            spline = spline.decode("utf-8")
        if isinstance(spline, dict):
            spline = _nurbs_text(spline, exact_float)
        elif not isinstance(spline, str):
            raise TypeError("Curve.nurbs(spline): expected a dict {'degree', 'knots', 'control', 'weights'} or "
                            "its JSON text, got %s" % type(spline).__name__)
        self = cls.__new__(cls)
        self._text, self._control, self._weights = "", "", ""
        self._nurbs = spline
        self._limits = {"max_degree": max_degree, "max_length": max_length}
        self._str = _uniparam.curve_text(self._common())
        return self

    @property
    def path(self):
        """The SVG path data of a Curve.svg (else None)."""
        return self._svg

    @property
    def spline(self):
        """The NURBS JSON text of a Curve.nurbs (else None)."""
        return self._nurbs

    @property
    def segments(self):
        """The segments as Curves, each on its own parameter [0, 1] (one
        for a curve that is not composite)."""
        return [_curve(text, parsed=True) for text in self._parts()[0]]

    @property
    def knots(self):
        """The knots 0 = k_0 < ... < k_m = 1 as Fractions: segment j runs
        over t in [k_j, k_{j+1}]."""
        return [to_fraction(k) for k in self._parts()[1]]

    @property
    def labels(self):
        """What each segment is ("segment 2: L at column 17", "span [0, 1] (knots 1 and 2)")."""
        return list(self._parts()[2])

    def _parts(self):
        if getattr(self, "_parts_cache", None) is None:
            self._parts_cache = _uniparam.curve_parts(self._common())
        return self._parts_cache

    @classmethod
    def bezier(cls, points, weights=None, exact_float=False, max_degree=1000):
        """The Bezier curve of the control points (a sequence of n + 1 points
        of equal dimension >= 2, e.g. a list of lists or a 2-D numpy array),
        rational with positive ``weights`` when given. Coordinates and weights
        are exact: int, Fraction, Decimal or decimal/rational strings; floats
        raise TypeError unless exact_float=True (then their binary values are
        used exactly)."""
        self = cls.__new__(cls)
        rows = []
        for i, p in enumerate(points):
            if isinstance(p, (str, bytes)):
                raise TypeError("control point %d: expected a sequence of coordinates, got %r" % (i, p))
            rows.append("[" + ",".join(_exact_text(x, exact_float, "control point %d" % i) for x in p) + "]")
        self._control = "[" + ",".join(rows) + "]"
        self._weights = ""
        if weights is not None:
            self._weights = "[" + ",".join(_exact_text(w, exact_float, "weight") for w in weights) + "]"
        self._text = ""
        self._limits = {"max_degree": max_degree}
        self._str = _uniparam.curve_text(self._common(max_degree=max_degree))
        return self

    @property
    def control(self):
        """The control points' text "[[x0,y0],...]" ("" for a curve from text)."""
        return self._control

    @property
    def weights(self):
        """The weights' text "[w0,...]" ("" for none)."""
        return self._weights

    def _common(self, speed="angular", digits=15, max_prec=None, max_degree=None, max_bits=None,
                max_length=None, max_depth=None, timeout=None, threads=None):
        c = _uniparam.Common()
        c.curve, c.control, c.weights = self._text, self._control, self._weights
        c.svg, c.subpath, c.nurbs = self._svg, self._subpath, self._nurbs
        c.speed = speed
        c.digits = _int("digits", digits)
        c.max_prec = 0 if max_prec is None else _int("max_prec", max_prec)
        lim = dict(self._limits)
        for k, v in (("max_degree", max_degree), ("max_bits", max_bits), ("max_length", max_length),
                     ("max_depth", max_depth)):
            if v is not None:
                lim[k] = v
        for k, v in lim.items():
            if k not in ("max_degree", "max_bits", "max_length", "max_depth"):
                raise TypeError("unknown keyword argument %r" % k)
            setattr(c, k, _int(k, v))
        if timeout is not None:
            if isinstance(timeout, bool) or not isinstance(timeout, (int, float)) or not timeout > 0 \
                    or timeout > 1e9:
                raise InvalidArgument("timeout must be a positive number of seconds up to 1e9 (or None), got %r"
                                      % (timeout,))
            c.timeout = float(timeout)
        c.threads = 0 if threads is None else _int("threads", threads)
        if threads is not None and not 1 <= c.threads <= 64:
            raise InvalidArgument("threads must be an integer from 1 to 64, got %r" % (threads,))
        return c

    def __str__(self):
        return self._str

    def __repr__(self):
        if self._svg is not None:
            return "Curve.svg(%r%s)" % (self._svg, "" if self._subpath is None else ", subpath=%d" % self._subpath)
        if self._nurbs is not None:
            return "Curve.nurbs(%r)" % self._nurbs
        if self._control:
            return "Curve.bezier(%s%s)" % (self._control, ", weights=" + self._weights if self._weights else "")
        return "Curve(%r)" % self._str

    def _key(self):
        # A composite curve is its data; one curve (a path of one segment
        # too) is its canonical text.
        if self._svg is not None or self._nurbs is not None:
            if len(self._parts()[0]) > 1:
                return (self._svg, self._subpath, self._nurbs)
        return str(self)

    def __eq__(self, other):
        return isinstance(other, Curve) and self._key() == other._key()

    def __hash__(self):
        return hash(self._key())

    def __reduce__(self):  # picklable (Dask ships curves to workers)
        return (_rebuild_curve, (self._text, self._control, self._weights, self._limits, self._svg, self._subpath,
                                 self._nurbs))

    # The methods, also as module functions.
    def uniformity(self, **kw):
        return uniformity(self, **kw)

    def radical(self, **kw):
        return radical(self, **kw)

    def moebius(self, **kw):
        return moebius(self, **kw)

    def reparam(self, **kw):
        return reparam(self, **kw)

    def sample(self, **kw):
        return sample(self, **kw)

    def locate(self, **kw):
        return locate(self, **kw)

    def plot(self, **kw):
        return plot(self, **kw)


def _rebuild_curve(text, control, weights, limits, svg=None, subpath=None, nurbs=None):
    c = Curve.__new__(Curve)
    c._text, c._control, c._weights, c._limits = text, control, weights, dict(limits)
    c._svg, c._subpath, c._nurbs = svg, subpath, nurbs
    c._str = _uniparam.curve_text(c._common())
    return c


def _nurbs_text(spline, exact_float):
    """The JSON text of a NURBS given as a dict, its numbers exact ("p/q"
    strings for non-integers); other keys and values are passed on for the
    reader to judge."""
    def number(x, what):
        if isinstance(x, bool):
            raise TypeError("%s: expected a number, got %r" % (what, x))
        q = to_fraction(x, exact_float=exact_float)
        return q.numerator if q.denominator == 1 else _fraction_text(q)

    def exact(x, what):
        try:
            return number(x, what)
        except ValueError as e:
            raise InvalidArgument("%s: %s" % (what, e)) from None

    out = {}
    for key, value in spline.items():
        if key in ("knots", "weights") and not isinstance(value, (str, bytes, dict)):
            value = [exact(x, "%s[%d]" % (key, i)) for i, x in enumerate(value)]
        elif key == "control" and not isinstance(value, (str, bytes, dict)):
            rows = []
            for i, p in enumerate(value):
                if isinstance(p, (str, bytes, dict)):
                    raise TypeError("control point %d: expected a sequence of coordinates, got %r" % (i, p))
                rows.append([exact(x, "control point %d" % i) for x in p])
            value = rows
        elif key == "degree" and not isinstance(value, (str, bool)):
            import numbers
            if isinstance(value, numbers.Integral):
                value = int(value)
        out[key] = value
    return _json.dumps(out)


def _int(name, v):
    import numbers
    if isinstance(v, bool) or not isinstance(v, numbers.Integral):
        raise TypeError("%s must be an int, got %r" % (name, v))
    return int(v)


def _curve(curve, parsed=False):
    if isinstance(curve, Curve):
        return curve
    if isinstance(curve, str):
        c = Curve.__new__(Curve)
        c._text, c._control, c._weights, c._limits, c._str = curve, "", "", {}, curve if parsed else None
        return c
    raise TypeError("expected a Curve or the text of a curve, got %s" % type(curve).__name__)


def _rational_text(name, v):
    """An exact rational parameter (target, at, breakpoints, length, ...)
    as text: int, Fraction, Decimal, string; a float is refused (TypeError)."""
    if v is None:
        return None
    if isinstance(v, str):
        return v
    return _exact_text(v, False, name)


def _doc(text):
    return _json.loads(text)


def _warn_missed(message, stacklevel=3):
    if message:  # the warning points at the caller of the uniparam function
        _warnings.warn(message, TargetNotReachedWarning, stacklevel=stacklevel)


def uniformity(curve, **options):
    """Certified mean speed mu and uniformity u = mu^2 / int sigma^2, the
    exact squared speed and the zeros of the speed (``uniparam uniformity``).
    """
    c = _curve(curve)
    return Result(_doc(_uniparam.uniformity(c._common(**options))))


def radical(curve, format="text", at=None, **options):
    """The optimal piecewise radical reparameterization r = phi o m
    (``uniparam radical``); ``format`` of the formulas: text, latex, maple;
    ``at``: also r(z), p(r(z)) and the speed at a rational z in [0, 1]."""
    c = _curve(curve)
    return Result(_doc(_uniparam.radical(c._common(**options), format, _rational_text("at", at))))


def _breakpoints(bp):
    if bp is None:
        return []
    if isinstance(bp, str):
        return [s for s in bp.split(",")]
    return [_rational_text("breakpoints", b) for b in bp]


def _answer(answer):
    """The Python value of a command's answer (kind, text, missed)."""
    kind, text, missed = answer
    _warn_missed(missed, stacklevel=4)
    return text if kind == "step" else Result(_doc(text))


_OUTPUT_DOC = """
    ``output`` as the CLI's --output: "nurbs" returns the NURBS of p o r
    (a Result with the keys of docs/nurbs.md) instead of the report, "step"
    its STEP AP214 text (a str), and a file name ending in .stp or .step
    writes that file and returns the report."""


def moebius(curve, breakpoints=None, format="text", rational=False, rational_digits=None, output=None, **options):
    """The optimal Moebius reparameterization (one piece), or C0 piecewise
    Moebius with fixed ``breakpoints`` (a list of exact rationals from 0 to
    1) (``uniparam moebius``). ``rational=True`` rounds alpha, S and T to
    short rationals (``rational_digits``, default 8) and certifies that map."""
    c = _curve(curve)
    bp = _breakpoints(breakpoints) if breakpoints is not None else None
    return _answer(_uniparam.moebius(c._common(**options), bp, format, bool(rational), rational_digits,
                                     _output(output)))


moebius.__doc__ += _OUTPUT_DOC


def _output(output):
    if output is None:
        return ""
    import os
    out = os.fspath(output)
    if not out:
        raise InvalidArgument("output expects nurbs, step, or a file name ending in .stp or .step, got ''")
    return out


def reparam(curve, pieces=None, breakpoints=None, target=None, max_pieces=None, format="text", rational=False,
            rational_digits=None, output=None, **options):
    """Piecewise Moebius reparameterization (``uniparam reparam``): exactly
    one of ``pieces`` (C0, N pieces, optimised breakpoints), ``breakpoints``
    (C0, fixed) and ``target`` (C1, refined until u >= target, at most
    ``max_pieces`` pieces; when missed, the best map is returned with a
    TargetNotReachedWarning and result.target["reached"] False)."""
    c = _curve(curve)
    return _answer(_uniparam.reparam(c._common(**options), None if pieces is None else _int("pieces", pieces),
                                     _breakpoints(breakpoints), _rational_text("target", target),
                                     None if max_pieces is None else _int("max_pieces", max_pieces), format,
                                     bool(rational), rational_digits, _output(output)))


reparam.__doc__ += _OUTPUT_DOC


def bezier(points, weights=None, exact_weights="auto", exact_float=False, output=None, **options):
    """The optimal bilinear reparameterization of a Bezier curve for the
    parametric speed (``uniparam bezier --control``): exact P, Q, alpha and
    weights for integral curves. ``points`` and ``weights`` as Curve.bezier,
    or a Curve made by Curve.bezier."""
    c = points if isinstance(points, Curve) else Curve.bezier(points, weights, exact_float=exact_float)
    if not c.control and c.path is None and c.spline is None:  # paths and splines: the module's message
        raise InvalidArgument("bezier needs control points: pass them, or a Curve.bezier(...)")
    if "speed" in options:
        raise TypeError("bezier works with the parametric speed only (no speed=)")
    return _answer(_uniparam.bezier(c._common(**options), exact_weights, _output(output)))


bezier.__doc__ += _OUTPUT_DOC


def locate(curve, length=None, angle=None, fraction=None, speed=None, **options):
    """The parameter t at an arc length (``length``, parametric speed), a
    turning angle (``angle``, angular speed) or a ``fraction`` of either,
    certified, with the point p(t) (``uniparam locate``)."""
    given = [(k, v) for k, v in (("length", length), ("angle", angle), ("fraction", fraction)) if v is not None]
    if len(given) != 1:
        raise InvalidArgument("give exactly one of length, angle and fraction")
    option, value = given[0]
    if speed is None:
        speed = "parametric" if option == "length" else "angular"
    kind = "parametric" if speed in ("parametric", "arclength") else speed
    if option == "length" and kind == "angular":
        raise InvalidArgument("length is an arc length, measured by the parametric speed: drop speed='angular', "
                              "or give a turning angle with angle=")
    if option == "angle" and kind == "parametric":
        raise InvalidArgument("angle is a turning angle, measured by the angular speed: drop speed=%r, or give "
                              "an arc length with length=" % speed)
    c = _curve(curve)
    return Result(_doc(_uniparam.locate(c._common(speed=speed, **options), option,
                                        _rational_text(option, value))))


class SampleResult(Result):
    """A sample (``uniparam sample --json``) plus numpy arrays of the rows:
    ``s``, ``t``, ``speed`` (shape (K,)) and ``points`` (shape (K, n)), the
    balls' midpoints as floats, and ``t_rad``, ``speed_rad``, ``points_rad``,
    their radii rounded up to floats (so [mid - rad, mid + rad] in floats
    still holds the printed ball up to the rounding of mid). ``samples``
    holds the rows with their Balls."""

    def __init__(self, doc):
        super().__init__(doc)
        import numpy as np
        rows = self["samples"]

        def up(d):
            f = float(d)
            return f if decimal_ge(f, d) else np.nextafter(f, np.inf)

        object.__setattr__(self, "s", np.array([float(r["s"]) for r in rows]))
        object.__setattr__(self, "t", np.array([float(r["t"]) for r in rows]))
        object.__setattr__(self, "speed", np.array([float(r["speed"]) for r in rows]))
        object.__setattr__(self, "points", np.array([[float(x) for x in r["point"]] for r in rows]))
        object.__setattr__(self, "t_rad", np.array([up(r["t"].rad) for r in rows]))
        object.__setattr__(self, "speed_rad", np.array([up(r["speed"].rad) for r in rows]))
        object.__setattr__(self, "points_rad", np.array([[up(x.rad) for x in r["point"]] for r in rows]))


def decimal_ge(f, d):
    import decimal
    return decimal.Decimal(f) >= d


def _method_args(method, pieces, target, max_pieces):
    return (method, None if pieces is None else _int("pieces", pieces), _rational_text("target", target),
            None if max_pieces is None else _int("max_pieces", max_pieces))


def sample(curve, method="radical", points=40, pieces=None, target=None, max_pieces=None, deviation=False,
           **options):
    """K = ``points`` certified points of p o r at s = 0, 1/(K-1), ..., 1
    (``uniparam sample --json``). ``method``: radical, c0 (``pieces``), c1
    (``target``, ``max_pieces``), none (p itself) or exact (points at
    exactly equal steps of arc length / turning angle). ``deviation=True``
    adds each row's distance from the exact equal step. Returns a
    SampleResult (numpy arrays ``s``, ``t``, ``points``, ``speed``)."""
    c = _curve(curve)
    text, missed = _uniparam.sample(c._common(**options), *_method_args(method, pieces, target, max_pieces),
                                    _int("points", points), bool(deviation))
    _warn_missed(missed)
    return SampleResult(_doc(text))


class Plot:
    """The picture of ``uniparam plot``: ``svg`` holds the SVG document.
    Jupyter shows it inline (``_repr_svg_``); ``save(path)`` writes .svg, or
    .png through rsvg-convert (Debian package librsvg2-bin)."""

    def __init__(self, svg):
        self.svg = svg

    def _repr_svg_(self):
        return self.svg

    def save(self, path):
        path = _os.fspath(path)
        low = path.lower()
        if low.endswith(".png"):
            _uniparam.write_png(self.svg, path)
        elif low.endswith(".svg"):
            with open(path, "w", encoding="utf-8") as f:
                f.write(self.svg)
        else:
            raise InvalidArgument("the file name must end in .svg or .png, got %r" % path)

    def __str__(self):
        return self.svg


def plot(curve, method="radical", points=40, pieces=None, target=None, max_pieces=None, projection=None,
         output=None, **options):
    """Plot p and p o r at equal parameter steps and their speeds (``uniparam
    plot``). Returns a Plot (``.svg``, shown inline by Jupyter); with
    ``output`` ("file.svg" or "file.png") also saves it there."""
    if "digits" in options:
        raise TypeError("plot has no digits= (a picture is drawn from 15-digit data)")
    c = _curve(curve)
    svg, missed = _uniparam.plot(c._common(**options), *_method_args(method, pieces, target, max_pieces),
                                 _int("points", points), projection or "")
    _warn_missed(missed)
    p = Plot(svg)
    if output is not None:
        p.save(output)
    return p
