"""output= of moebius, reparam and bezier: the NURBS of p o r as JSON, as
STEP text, or a STEP file, identical to the CLI's --output."""

import json

import pytest

import uniparam as up
from conftest import same_document


@pytest.mark.parametrize("call,args", [
    (lambda o: up.moebius("(t, t^3)", output=o), ["moebius", "(t, t^3)"]),
    (lambda o: up.reparam("(t, t^2, t^3)", pieces=2, rational=True, output=o),
     ["reparam", "(t, t^2, t^3)", "--pieces", 2, "--rational"]),
    (lambda o: up.reparam("(t, t^3)", target="0.99", output=o), ["reparam", "(t, t^3)", "--target", "0.99"]),
    (lambda o: up.bezier([[0, 0], [0, 1], [3, 1]], output=o), ["bezier", "--control", "[[0,0],[0,1],[3,1]]"]),
    (lambda o: up.bezier([[0, 0], [1, 1], [2, 0]], weights=[1, 2, 1], output=o),
     ["bezier", "--control", "[[0,0],[1,1],[2,0]]", "--weights", "[1,2,1]"]),
])
def test_nurbs_outputs(cli, tmp_path, call, args):
    n = call("nurbs")
    code, out, err = cli.run(*args, "--output", "nurbs")
    assert isinstance(n, up.Result) and n["degree"] >= 1
    same_document(n.json, json.loads(out))
    step = call("step")
    _, out, _ = cli.run(*args, "--output", "step")
    assert isinstance(step, str) and step == out
    # a file: written, and the report returned (as the CLI prints it)
    (tmp_path / "py").mkdir()
    (tmp_path / "cli").mkdir()
    r = call(str(tmp_path / "py" / "curve.stp"))
    _, out, _ = cli.run(*args, "--json", "--output", str(tmp_path / "cli" / "curve.stp"))
    same_document(r.json, json.loads(out))
    assert (tmp_path / "py" / "curve.stp").read_text() == (tmp_path / "cli" / "curve.stp").read_text()


def test_bad_output():
    with pytest.raises(up.InvalidArgument, match="output"):
        up.moebius("(t, t^3)", output="curve.dxf")
    with pytest.raises(up.InvalidArgument, match="cannot write"):
        up.moebius("(t, t^3)", output="/nonexistent-dir/x.stp")
