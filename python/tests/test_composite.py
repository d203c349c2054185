"""Composite curves (Curve.svg, Curve.nurbs) against the CLI's --svg and
--nurbs: every method's document identical to `uniparam ... --json`, string
for string; plots and NURBS/STEP outputs byte for byte; the readers' errors
as the CLI's, with its messages."""

import json
import os
import pickle
import warnings

import numpy as np
import pytest

import uniparam as up
from conftest import same_document

PATH = "M 0 0 Q 1 2 2 2 L 5 2 C 6 2 7 0 8 1"
SPLINE = {"degree": 2, "knots": [0, 0, 0, 1, 2, 3, 3, 3], "control": [[0, 0], [1, 2], [3, 3], [4, 1], [6, 2]]}
SPLINE_TEXT = json.dumps(SPLINE)
GLYPHS = os.path.join(os.path.dirname(__file__), "..", "..", "tests", "data", "glyphs.jsonl")

# (the Python curve, the CLI's arguments for it, a speed every map accepts:
# the path has a straight segment, whose angular speed is 0)
INPUTS = {
    "path": (lambda: up.Curve.svg(PATH), ["--svg", PATH], "parametric"),
    "nurbs": (lambda: up.Curve.nurbs(SPLINE), ["--nurbs", SPLINE_TEXT], "angular"),
}


def glyph(letter, contour):
    with open(GLYPHS, encoding="utf-8") as f:
        for line in f:
            g = json.loads(line)
            if g["glyph"] == letter and g["contour"] == contour:
                return g["svg"]
    raise KeyError((letter, contour))


@pytest.fixture(params=sorted(INPUTS))
def composite(request):
    make, args, speed = INPUTS[request.param]
    return make(), args, speed


def test_curves():
    c = up.Curve.svg(PATH)
    assert str(c) == "SVG path of 3 segments"
    assert c.knots == [up.to_fraction(x) for x in ("0", "1/3", "2/3", "1")]
    assert [str(s) for s in c.segments] == ["(2*t, -2*t^2 + 4*t)", "(3*t + 2, 2)", "(3*t + 5, 5*t^3 - 6*t^2 + 2)"]
    assert c.labels[1] == "segment 2: L at column 17"
    n = up.Curve.nurbs(SPLINE)
    assert str(n) == "NURBS curve of 3 segments" and len(n.segments) == 3
    # a dict and its JSON text are the same curve; other data another one
    assert up.Curve.nurbs(SPLINE_TEXT) == n and hash(up.Curve.nurbs(SPLINE_TEXT)) == hash(n)
    assert up.Curve.svg(PATH + " L 9 9") != c
    for x in (c, n, up.Curve.svg(PATH + " Z M 1 1 L 2 3 Q 3 3 4 1", subpath=1)):
        y = pickle.loads(pickle.dumps(x))
        assert y == x and repr(y) == repr(x)


def test_nurbs_dict_numbers_are_exact():
    exact = dict(SPLINE, knots=["0", 0, 0, up.to_fraction(1), "2", 3, 3, 3], weights=[1, 2, "1/2", 1, 1])
    text = dict(SPLINE, weights=[1, 2, "1/2", 1, 1])
    assert up.Curve.nurbs(exact).segments == up.Curve.nurbs(json.dumps(text)).segments
    with pytest.raises(TypeError, match="floats are refused"):
        up.Curve.nurbs(dict(SPLINE, weights=[1, 0.5, 1, 1, 1]))
    assert up.Curve.nurbs(dict(SPLINE, weights=[1, 0.5, 1, 1, 1]), exact_float=True) == \
        up.Curve.nurbs(dict(SPLINE, weights=[1, "1/2", 1, 1, 1]))


@pytest.mark.parametrize("speed", ["angular", "parametric"])
def test_uniformity(cli, composite, speed):
    c, args, _ = composite
    r = up.uniformity(c, speed=speed)
    same_document(r.json, cli.json("uniformity", *args, "--speed", speed))
    assert r.segments == 3 and isinstance(r.parts[0]["mu"], up.Ball)


def test_uniformity_digits(cli, composite):
    c, args, speed = composite
    r = c.uniformity(speed=speed, digits=30)
    same_document(r.json, cli.json("uniformity", *args, "--speed", speed, "--digits", 30))


def test_radical(cli, composite):
    c, args, speed = composite
    same_document(up.radical(c, speed=speed).json, cli.json("radical", *args, "--speed", speed))
    same_document(up.radical(c, speed=speed, format="latex").json,
                  cli.json("radical", *args, "--speed", speed, "--format", "latex"))


@pytest.mark.parametrize("how,extra", [
    ({}, []),
    ({"breakpoints": ["0", "1/2", "1"]}, ["--breakpoints", "0,1/2,1"]),
    ({"rational": True, "rational_digits": 6}, ["--rational", "--rational-digits", 6]),
    ({"format": "maple"}, ["--format", "maple"]),
])
def test_moebius(cli, composite, how, extra):
    c, args, speed = composite
    same_document(up.moebius(c, speed=speed, **how).json, cli.json("moebius", *args, "--speed", speed, *extra))


@pytest.mark.parametrize("how,extra", [
    ({"pieces": 5}, ["--pieces", 5]),
    ({"breakpoints": [0, up.to_fraction("1/2"), 1]}, ["--breakpoints", "0,1/2,1"]),
    ({"target": "0.99"}, ["--target", "0.99"]),
    ({"pieces": 4, "rational": True}, ["--pieces", 4, "--rational"]),
])
def test_reparam(cli, composite, how, extra):
    c, args, speed = composite
    r = up.reparam(c, speed=speed, **how)
    same_document(r.json, cli.json("reparam", *args, "--speed", speed, *extra))
    assert len(r.S) == r.segments + 1 and len(r.parts) == r.segments


def test_reparam_target_missed_warns(cli, composite):
    c, args, speed = composite
    with pytest.warns(up.TargetNotReachedWarning, match="not reached on every segment"):
        r = up.reparam(c, speed=speed, target="0.9999", max_pieces=1)
    assert r.target["reached"] is False
    same_document(r.json, cli.json("reparam", *args, "--speed", speed, "--target", "0.9999", "--max-pieces", 1,
                                   status=4))


@pytest.mark.parametrize("how,extra", [
    ({}, []),
    ({"method": "c0", "pieces": 4}, ["--method", "c0", "--pieces", 4]),
    ({"method": "c1", "target": "0.99"}, ["--method", "c1", "--target", "0.99"]),
    ({"method": "none"}, ["--method", "none"]),
    ({"method": "exact"}, ["--method", "exact"]),
    ({"method": "c0", "pieces": 4, "deviation": True}, ["--method", "c0", "--pieces", 4, "--deviation"]),
])
def test_sample(cli, composite, how, extra):
    c, args, speed = composite
    s = up.sample(c, speed=speed, points=7, **how)
    same_document(s.json, cli.json("sample", *args, "--speed", speed, "--points", 7, *extra))
    assert s.points.shape == (7, 2) and s.t.shape == (7,) and s.s[-1] == 1.0
    assert np.all(s.points_rad >= 0) and s.samples[3].point[0].contains(s.samples[3].point[0].mid)


def test_sample_target_missed_warns(cli):
    c, args, _ = INPUTS["nurbs"][0](), INPUTS["nurbs"][1], None
    with pytest.warns(up.TargetNotReachedWarning, match="best map was sampled"):
        s = up.sample(c, method="c1", target="0.9999", max_pieces=1, points=4)
    same_document(s.json, cli.json("sample", *args, "--method", "c1", "--target", "0.9999", "--max-pieces", 1,
                                   "--points", 4, status=4))


@pytest.mark.parametrize("how,extra", [
    ({"length": "3"}, ["--length", "3"]),
    ({"fraction": "1/2", "speed": "arclength"}, ["--fraction", "1/2", "--speed", "arclength"]),
    ({"fraction": "1/3", "speed": "parametric"}, ["--fraction", "1/3", "--speed", "parametric"]),
])
def test_locate(cli, composite, how, extra):
    c, args, _ = composite
    same_document(up.locate(c, **how).json, cli.json("locate", *args, *extra))


def test_locate_angle(cli):
    c, args = INPUTS["nurbs"][0](), INPUTS["nurbs"][1]
    same_document(up.locate(c, angle="1/2").json, cli.json("locate", *args, "--angle", "1/2"))


@pytest.mark.parametrize("how,extra", [
    ({}, []),
    ({"method": "c0", "pieces": 4}, ["--method", "c0", "--pieces", 4]),
    ({"method": "c1"}, ["--method", "c1"]),
])
def test_plot(cli, composite, tmp_path, how, extra):
    c, args, speed = composite
    p = up.plot(c, speed=speed, points=9, **how)
    _, out, _ = cli.run("plot", *args, "--speed", speed, "--points", 9, *extra, "-o", "-")
    assert p.svg == out and p._repr_svg_() == out
    up.plot(c, speed=speed, points=9, output=str(tmp_path / "c.svg"), **how)
    assert (tmp_path / "c.svg").read_text(encoding="utf-8") == out


def test_plot_target_missed_warns(cli):
    c, args = INPUTS["nurbs"][0](), INPUTS["nurbs"][1]
    with pytest.warns(up.TargetNotReachedWarning, match="best map is drawn"):
        p = up.plot(c, method="c1", target="0.9999", max_pieces=1, points=5)
    code, out, _ = cli.run("plot", *args, "--method", "c1", "--target", "0.9999", "--max-pieces", 1, "--points", 5,
                           "-o", "-", check=False)
    assert code == 4 and p.svg == out


@pytest.mark.parametrize("call,extra", [
    (lambda c, s, o: up.moebius(c, speed=s, output=o), ["moebius"]),
    (lambda c, s, o: up.reparam(c, speed=s, pieces=4, rational=True, output=o), ["reparam", "--pieces", 4,
                                                                                 "--rational"]),
    (lambda c, s, o: up.reparam(c, speed=s, target="0.99", output=o), ["reparam", "--target", "0.99"]),
])
def test_outputs(cli, composite, tmp_path, call, extra):
    c, args, speed = composite
    cmd = [extra[0], *args, "--speed", speed, *extra[1:]]
    n = call(c, speed, "nurbs")
    _, out, _ = cli.run(*cmd, "--output", "nurbs")
    same_document(n.json, json.loads(out))
    _, out, _ = cli.run(*cmd, "--output", "step")
    assert call(c, speed, "step") == out
    (tmp_path / "py").mkdir()
    (tmp_path / "cli").mkdir()
    r = call(c, speed, str(tmp_path / "py" / "c.stp"))
    _, out, _ = cli.run(*cmd, "--json", "--output", str(tmp_path / "cli" / "c.stp"))
    same_document(r.json, json.loads(out))
    assert (tmp_path / "py" / "c.stp").read_text() == (tmp_path / "cli" / "c.stp").read_text()


def test_subpath(cli):
    path = "M 0 0 Q 1 2 2 2 Z M 3 0 C 4 1 5 -1 6 0 Q 7 1 8 0"
    for k in (0, 1):
        c = up.Curve.svg(path, subpath=k)
        same_document(c.uniformity(speed="parametric").json,
                      cli.json("uniformity", "--svg", path, "--subpath", k, "--speed", "parametric"))


def test_one_segment_is_the_bezier_curve(cli):
    # as the CLI: a path or spline of one segment is that Bezier curve, with
    # the one-curve documents (--control's)
    c = up.Curve.svg("M 0 0 Q 1 2 2 2")
    b = up.Curve.bezier([[0, 0], [1, 2], [2, 2]])
    assert c == b and str(c) == str(b) and len(c.segments) == 1
    n = up.Curve.nurbs({"degree": 2, "knots": [0, 0, 0, 1, 1, 1], "control": [[0, 0], [1, 2], [2, 2]]})
    for x, args in ((c, ["--svg", "M 0 0 Q 1 2 2 2"]), (n, ["--nurbs", json.dumps(
            {"degree": 2, "knots": [0, 0, 0, 1, 1, 1], "control": [[0, 0], [1, 2], [2, 2]]})])):
        same_document(x.uniformity().json, cli.json("uniformity", *args))
        same_document(x.uniformity().json, cli.json("uniformity", "--control", "[[0,0],[1,2],[2,2]]"))
        same_document(x.radical(at="1/2").json, cli.json("radical", *args, "--at", "1/2"))
        same_document(x.reparam(pieces=2).json, cli.json("reparam", *args, "--pieces", 2))
        same_document(x.sample(points=4, method="exact").json, cli.json("sample", *args, "--points", 4, "--method",
                                                                          "exact"))
        same_document(x.locate(fraction="1/2").json, cli.json("locate", *args, "--fraction", "1/2"))


def test_glyph(cli):
    # a letter contour of DejaVu Sans: lines and quadratics, corners
    d = glyph("S", 0)
    g = up.Curve.svg(d)
    same_document(g.uniformity(speed="parametric").json, cli.json("uniformity", "--svg", d, "--speed", "parametric"))
    same_document(g.reparam(speed="parametric", pieces=40).json,
                  cli.json("reparam", "--svg", d, "--speed", "parametric", "--pieces", 40))
    same_document(g.locate(fraction="1/2", speed="parametric").json,
                  cli.json("locate", "--svg", d, "--fraction", "1/2", "--speed", "parametric"))


ERRORS = [
    # (python call, CLI arguments, exception, CLI exit status)
    (lambda: up.Curve.svg("M 0 0 Q 1 2 2 2 X"), ["--svg", "M 0 0 Q 1 2 2 2 X"], up.ParseError, 2),
    (lambda: up.Curve.svg("M 0 0 L 1"), ["--svg", "M 0 0 L 1"], up.ParseError, 2),
    (lambda: up.Curve.svg(""), ["--svg", ""], up.InvalidArgument, 2),
    (lambda: up.Curve.svg("M 0 0 A 1 2 30 0 1 3 1"), ["--svg", "M 0 0 A 1 2 30 0 1 3 1"], up.InvalidArgument, 2),
    (lambda: up.Curve.svg("M 0 0 A 3 3 0 0 1 4 1"), ["--svg", "M 0 0 A 3 3 0 0 1 4 1"], up.InvalidArgument, 2),
    (lambda: up.Curve.nurbs('{"degree": 2, "knots": [0,0,0,1,1,1], "control": [[0,0],[1,1]]}'),
     ["--nurbs", '{"degree": 2, "knots": [0,0,0,1,1,1], "control": [[0,0],[1,1]]}'], up.InvalidArgument, 2),
    (lambda: up.Curve.nurbs({"degree": 2}), ["--nurbs", '{"degree": 2}'], up.InvalidArgument, 2),
    (lambda: up.Curve.nurbs(dict(SPLINE, weights=[1, -1, 1, 1, 1])),
     ["--nurbs", json.dumps(dict(SPLINE, weights=[1, -1, 1, 1, 1]))], up.InvalidArgument, 2),
    (lambda: up.Curve.svg("M 0 0 C 1 1 2 1 3 0", max_degree=2), ["--svg", "M 0 0 C 1 1 2 1 3 0", "--max-degree", 2],
     up.BudgetExceeded, 4),
    (lambda: up.moebius(up.Curve.svg(PATH)), ["--svg", PATH], up.DomainError, 3),
]



@pytest.mark.parametrize("call,args,exc,status", ERRORS)
def test_errors_mirror_cli(cli, call, args, exc, status):
    with pytest.raises(exc) as info:
        call()
    command = "moebius" if exc is up.DomainError else "uniformity"
    code, out, err = cli.run(command, *args, check=False)
    assert code == status and out == ""
    message = str(info.value)
    if exc is up.BudgetExceeded:  # the limit named as the Python parameter
        message = message.replace("max_degree", "--max-degree")
    assert err.strip() == "uniparam %s: %s" % (command, message)


def test_locate_by_turning_refuses_a_straight_segment(cli):
    # the turning angle is constant along a straight segment: it determines no parameter there
    with pytest.raises(up.DomainError) as info:
        up.locate(up.Curve.svg(PATH), fraction="1/2")
    code, out, err = cli.run("locate", "--svg", PATH, "--fraction", "1/2", check=False)
    assert code == 3 and out == ""
    assert err.strip() == "uniparam locate: %s" % info.value


def test_parse_error_column(cli):
    with pytest.raises(up.ParseError) as info:
        up.Curve.svg("M 0 0 Q 1 2 2 2 X")
    assert info.value.column == 17 and isinstance(info.value, ValueError)


def test_several_subpaths_need_subpath(cli):
    path = PATH + " Z M 3 3 L 4 4"
    with pytest.raises(up.InvalidArgument) as info:
        up.Curve.svg(path)
    assert str(info.value) == "svg: the path has 2 subpaths; pick one with subpath=K (0 to 1)"
    code, _, err = cli.run("uniformity", "--svg", path, check=False)
    assert code == 2 and "the path has 2 subpaths" in err
    with pytest.raises(up.InvalidArgument, match="subpath must be an integer from 0 to 1, got 2"):
        up.Curve.svg(path, subpath=2)
    with pytest.raises(TypeError):
        up.Curve.svg(path, subpath="1")


def test_length_limits(cli):
    # the path's limit as the CLI's --max-length on the same text
    with pytest.raises(up.InvalidArgument) as info:
        up.Curve.svg(PATH, max_length=10)
    code, _, err = cli.run("uniformity", "--svg", PATH, "--max-length", 10, check=False)
    assert code == 2 and err.strip() == "uniparam uniformity: " + str(info.value)
    # a NURBS text above max_length: a budget, as the CLI's --nurbs @FILE
    with pytest.raises(up.BudgetExceeded, match="raise it with max_length"):
        up.Curve.nurbs(SPLINE_TEXT, max_length=20)
    assert str(up.Curve.nurbs(SPLINE_TEXT, max_length=len(SPLINE_TEXT))) == "NURBS curve of 3 segments"


def test_invalid_uses():
    c = up.Curve.svg(PATH)
    with pytest.raises(up.InvalidArgument, match="at on a composite curve"):
        up.radical(c, speed="parametric", at="1/2")
    with pytest.raises(up.InvalidArgument, match="does not apply to method exact itself"):
        up.sample(c, speed="parametric", method="exact", deviation=True)
    with pytest.raises(up.InvalidArgument, match="do not apply to method exact"):
        up.sample(c, speed="parametric", method="exact", pieces=3)
    with pytest.raises(up.InvalidArgument, match="pieces applies to method c0 only"):
        up.plot(c, speed="parametric", pieces=3)
    with pytest.raises(up.InvalidArgument, match="bezier takes one Bezier curve"):
        up.bezier(up.Curve.svg("M 0 0 Q 1 2 2 2"))
    with pytest.raises(TypeError):
        up.Curve.svg(["M 0 0 L 1 1"])
    with pytest.raises(TypeError):
        up.Curve.nurbs(42)
