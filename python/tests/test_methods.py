"""Every method of the Python module against the CLI's --json on the same
curves and options: the documents must be identical, key for key and string
for string (the balls' printed mid and rad included)."""

import warnings

import pytest

import uniparam as up
from conftest import same_document

CURVES = [
    "(t, t^3)",                           # an inflection at t = 0
    "(t^2, t^3)",                         # a cusp: the parametric speed vanishes
    "((1-t^2)/(1+t^2), 2*t/(1+t^2))",     # a rational curve (a quarter circle)
    "(t, t^2, t^3)",                      # a space curve
]


@pytest.mark.parametrize("curve", CURVES)
@pytest.mark.parametrize("speed", ["angular", "parametric"])
def test_uniformity(cli, curve, speed):
    r = up.uniformity(curve, speed=speed)
    same_document(r.json, cli.json("uniformity", curve, "--speed", speed))
    assert isinstance(r.mu, up.Ball) and r.mu.mid_text == r.json["mu"]["mid"]


def test_uniformity_digits(cli):
    r = up.uniformity("(t, t^3)", digits=40, max_prec=4096)
    same_document(r.json, cli.json("uniformity", "(t, t^3)", "--digits", 40, "--max-prec", 4096))


@pytest.mark.parametrize("curve", CURVES[:3])
def test_radical(cli, curve):
    same_document(up.radical(curve).json, cli.json("radical", curve))


def test_radical_at_and_format(cli):
    r = up.radical("(t^2, t^3)", at="1/3", format="latex", digits=20)
    same_document(r.json, cli.json("radical", "(t^2, t^3)", "--at", "1/3", "--format", "latex", "--digits", 20))
    assert r.at.z.exact == up.to_fraction("1/3")


@pytest.mark.parametrize("curve", CURVES)
def test_moebius(cli, curve):
    same_document(up.moebius(curve).json, cli.json("moebius", curve))


def test_moebius_breakpoints_rational(cli):
    r = up.moebius("(t, t^3)", breakpoints=["0", "1/3", "1"], rational=True, rational_digits=6, format="maple")
    same_document(r.json, cli.json("moebius", "(t, t^3)", "--breakpoints", "0,1/3,1", "--rational",
                                   "--rational-digits", 6, "--format", "maple"))
    # exact rationals come as Fraction
    assert all(a.exact is not None for a in r.alpha)


@pytest.mark.parametrize("how,args", [
    ({"pieces": 3}, ["--pieces", 3]),
    ({"breakpoints": [0, up.to_fraction("1/2"), 1]}, ["--breakpoints", "0,1/2,1"]),
    ({"target": "0.99"}, ["--target", "0.99"]),
    ({"pieces": 2, "rational": True}, ["--pieces", 2, "--rational"]),
])
@pytest.mark.parametrize("curve", CURVES[::2])
def test_reparam(cli, curve, how, args):
    same_document(up.reparam(curve, **how).json, cli.json("reparam", curve, *args))


def test_reparam_target_missed_warns(cli):
    # one piece cannot reach u >= 0.9999 on this curve: the best map, a
    # warning (the CLI: exit status 4 with the same document)
    with pytest.warns(up.TargetNotReachedWarning):
        r = up.reparam("(t, t^5)", target="0.9999", max_pieces=1)
    assert r.target["reached"] is False
    same_document(r.json, cli.json("reparam", "(t, t^5)", "--target", "0.9999", "--max-pieces", 1, status=4))


BEZIER = [
    ([[0, 0], [0, 1], [3, 1]], None, "[[0,0],[0,1],[3,1]]", None),
    ([[0, 0], ["1/3", 1], [1, "0.25"], [2, 2]], None, "[[0,0],[1/3,1],[1,1/4],[2,2]]", None),
    ([[0, 0], [1, 1], [2, 0]], [1, 2, 1], "[[0,0],[1,1],[2,0]]", "[1,2,1]"),
    ([[0, 0, 0], [1, 2, 0], [1, 1, 3]], None, "[[0,0,0],[1,2,0],[1,1,3]]", None),
]


@pytest.mark.parametrize("points,weights,control,wtext", BEZIER)
def test_bezier(cli, points, weights, control, wtext):
    r = up.bezier(points, weights)
    args = ["bezier", "--control", control] + (["--weights", wtext] if wtext else [])
    same_document(r.json, cli.json(*args))


def test_bezier_exact_weights_formula(cli):
    # the JSON carries every form (text, latex, maple) of the exact values
    r = up.bezier([[0, 0], [0, 1], [3, 1], [4, 0]], exact_weights="formula")
    same_document(r.json, cli.json("bezier", "--control", "[[0,0],[0,1],[3,1],[4,0]]", "--exact-weights",
                                   "formula"))
    assert r.weights_formula.latex.startswith("w_i")


def test_bezier_curve_in_other_methods(cli):
    c = up.Curve.bezier([[0, 0], [0, 1], [3, 1]])
    same_document(up.uniformity(c, speed="parametric").json,
                  cli.json("uniformity", "--control", "[[0,0],[0,1],[3,1]]", "--speed", "parametric"))


@pytest.mark.parametrize("method,kw,args", [
    ("radical", {}, []),
    ("c0", {"pieces": 2}, ["--pieces", 2]),
    ("c1", {"target": "0.99"}, ["--target", "0.99"]),
    ("none", {}, []),
])
@pytest.mark.parametrize("curve", ["(t, t^3)", "(t^2, t^3)"])
def test_sample(cli, curve, method, kw, args):
    r = up.sample(curve, method=method, points=7, **kw)
    same_document(r.json, cli.json("sample", curve, "--method", method, "--points", 7, *args))
    assert r.points.shape == (7, 2) and r.t.shape == (7,)
    for k, row in enumerate(r.samples):
        assert r.t[k] == float(row.t.mid) and r.speed[k] == float(row.speed.mid)


def test_sample_exact_and_deviation(cli):
    r = up.sample("(t, t^2)", method="exact", speed="parametric", points=5)
    same_document(r.json, cli.json("sample", "(t, t^2)", "--method", "exact", "--speed", "parametric",
                                   "--points", 5))
    d = up.sample("(t, t^3)", method="c0", pieces=2, points=5, deviation=True, digits=10)
    same_document(d.json, cli.json("sample", "(t, t^3)", "--method", "c0", "--pieces", 2, "--points", 5,
                                   "--deviation", "--digits", 10))


def test_sample_space_curve_arrays(cli):
    r = up.sample("(t, t^2, t^3)", points=4)
    same_document(r.json, cli.json("sample", "(t, t^2, t^3)", "--points", 4))
    assert r.points.shape == (4, 3) and r.points_rad.shape == (4, 3)
    # the float radii are upper bounds of the printed ones
    for k, row in enumerate(r.samples):
        for i, x in enumerate(row.point):
            assert up.to_fraction(r.points_rad[k, i], exact_float=True) >= up.to_fraction(x.rad)


@pytest.mark.parametrize("kw,args", [
    ({"length": "1/2"}, ["--length", "1/2"]),
    ({"angle": "0.25"}, ["--angle", "0.25"]),
    ({"fraction": "1/3"}, ["--fraction", "1/3"]),
    ({"fraction": "1/3", "speed": "parametric"}, ["--fraction", "1/3", "--speed", "parametric"]),
])
def test_locate(cli, kw, args):
    same_document(up.locate("(t, t^3)", **kw).json, cli.json("locate", "(t, t^3)", *args))


@pytest.mark.parametrize("kw,args", [
    ({}, []),
    ({"method": "c0", "pieces": 2, "points": 12}, ["--method", "c0", "--pieces", 2, "--points", 12]),
    ({"method": "c1", "target": "0.98"}, ["--method", "c1", "--target", "0.98"]),
])
def test_plot_svg(cli, kw, args, tmp_path):
    p = up.plot("(t, t^3)", **kw)
    code, out, _ = cli.run("plot", "(t, t^3)", "-o", "-", *args)
    assert code == 0 and p.svg == out and p._repr_svg_() == out
    f = tmp_path / "p.svg"
    p.save(f)
    assert f.read_text(encoding="utf-8") == out


def test_plot_space_projection(cli, tmp_path):
    p = up.plot("(t, t^2, t^3)", projection="1,3", output=str(tmp_path / "q.svg"))
    _, out, _ = cli.run("plot", "(t, t^2, t^3)", "--projection", "1,3", "-o", "-")
    assert p.svg == out == (tmp_path / "q.svg").read_text(encoding="utf-8")


def test_threads_do_not_change_results():
    a = up.radical("(t^2, t^5 - t^3 + t/7)", threads=1)
    b = up.radical("(t^2, t^5 - t^3 + t/7)", threads=2)
    same_document(a.json, b.json)


def test_curve_object_methods(cli):
    c = up.Curve("( t , t^3 )")
    assert str(c) == cli.json("uniformity", "(t, t^3)")["curve"]
    same_document(c.uniformity().json, up.uniformity("(t, t^3)").json)
    same_document(c.moebius(digits=20).json, cli.json("moebius", "(t, t^3)", "--digits", 20))
