"""Shared fixtures: the CLI binary (UNIPARAM_BIN, set by CTest) run with
--json, for comparing the Python results with it string for string."""

import json
import os
import subprocess

import pytest


def cli_binary():
    path = os.environ.get("UNIPARAM_BIN")
    if not path:
        pytest.fail("UNIPARAM_BIN is not set: run the tests through ctest (test python_pytest), or set it to "
                    "build/cli/uniparam")
    if not os.access(path, os.X_OK):
        pytest.fail("UNIPARAM_BIN=%s is not an executable" % path)
    return path


class Cli:
    def __init__(self, path):
        self.path = path

    def run(self, *args, check=True):
        """Runs `uniparam ARGS`; returns (exit status, stdout, stderr)."""
        p = subprocess.run([self.path] + [str(a) for a in args], capture_output=True, text=True, timeout=600)
        if check and p.returncode not in (0,):
            raise AssertionError("uniparam %s failed (%d): %s" % (" ".join(map(str, args)), p.returncode, p.stderr))
        return p.returncode, p.stdout, p.stderr

    def json(self, *args, status=0):
        """The document of `uniparam ARGS --json` (its key order kept)."""
        code, out, err = self.run(*args, "--json", check=False)
        assert code == status, "uniparam %s: exit %d: %s" % (" ".join(map(str, args)), code, err)
        return json.loads(out)


@pytest.fixture(scope="session")
def cli():
    return Cli(cli_binary())


def same_document(py_doc, cli_doc):
    """Equal documents, bit for bit: the same keys in the same order and the
    same strings (json.dumps keeps the order of both)."""
    a = json.dumps(py_doc, indent=1, ensure_ascii=False)
    b = json.dumps(cli_doc, indent=1, ensure_ascii=False)
    assert a == b
