"""Failures: the Python exceptions mirror the C++ ones, with the CLI's exit
status (2 invalid input, 3 undefined mathematics, 4 budget) and message."""

import pytest

import uniparam as up

CASES = [
    # (python call, CLI arguments, exception, CLI exit status)
    (lambda: up.uniformity("(t, x)"), ["uniformity", "(t, x)"], up.ParseError, 2),
    (lambda: up.uniformity("(t, 1/(t-1/2))"), ["uniformity", "(t, 1/(t-1/2))"], up.DomainError, 3),
    (lambda: up.uniformity("(t, t^3)", digits=60, max_prec=64),
     ["uniformity", "(t, t^3)", "--digits", 60, "--max-prec", 64], up.BudgetExceeded, 4),
    (lambda: up.locate("(t, t)", angle="1/2"), ["locate", "(t, t)", "--angle", "1/2"], up.DomainError, 3),
    (lambda: up.radical("(t, t^3)", at="3/2"), ["radical", "(t, t^3)", "--at", "3/2"], up.InvalidArgument, 2),
    (lambda: up.bezier([[0, 0], [1, 1], [2, 0]], weights=[1, -1, 1]),
     ["bezier", "--control", "[[0,0],[1,1],[2,0]]", "--weights", "[1,-1,1]"], up.InvalidArgument, 2),
]


@pytest.mark.parametrize("call,args,exc,status", CASES)
def test_error_mirrors_cli(cli, call, args, exc, status):
    with pytest.raises(exc) as info:
        call()
    assert isinstance(info.value, up.Error)
    code, out, err = cli.run(*args, check=False)
    assert code == status and out == ""
    # the library's message, as the CLI prints it after "uniparam COMMAND: "
    assert err.strip().endswith(str(info.value))


def test_parse_error_column(cli):
    with pytest.raises(up.ParseError) as info:
        up.Curve("(t, t^2 + sin(t))")
    e = info.value
    assert e.column == 11 and e.expected
    _, _, err = cli.run("uniformity", "(t, t^2 + sin(t))", check=False)
    assert "column %d:" % e.column in err
    assert isinstance(e, ValueError)  # usable where a ValueError is expected


def test_invalid_options():
    with pytest.raises(up.InvalidArgument, match="digits"):
        up.uniformity("(t, t^3)", digits=0)
    with pytest.raises(up.InvalidArgument, match="threads"):
        up.uniformity("(t, t^3)", threads=0)
    with pytest.raises(up.InvalidArgument, match="timeout"):
        up.uniformity("(t, t^3)", timeout=-1)
    with pytest.raises(up.InvalidArgument, match="exactly one"):
        up.reparam("(t, t^3)", pieces=2, target="0.9")
    with pytest.raises(up.InvalidArgument, match="method"):
        up.sample("(t, t^3)", method="bogus")
    with pytest.raises(up.InvalidArgument, match="format"):
        up.radical("(t, t^3)", format="html")
    with pytest.raises(TypeError):
        up.uniformity("(t, t^3)", digits=1.5)
    with pytest.raises(TypeError):
        up.uniformity("(t, t^3)", bogus=1)


def test_timeout_is_a_budget_error():
    # a computation of seconds, stopped by its time budget
    with pytest.raises(up.TimeLimitExceeded) as info:
        up.uniformity("(t, t^7 - t^2 + 1/3)", digits=2000, timeout=0.3)
    assert isinstance(info.value, up.BudgetExceeded) and "time limit" in str(info.value)
