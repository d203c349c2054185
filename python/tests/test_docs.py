"""The interactive examples of docs/python.md (its ```python blocks with
>>> prompts), run as doctests in one namespace, in order: the tutorial's
outputs are what the package prints."""

import doctest
import os
import re

import pytest

DOC = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "docs", "python.md")


def test_tutorial_examples():
    if not os.path.exists(DOC):
        pytest.skip("docs/python.md is not next to these tests")
    with open(DOC, encoding="utf-8") as f:
        text = f.read()
    blocks = [b for b in re.findall(r"```python\n(.*?)```", text, re.S) if ">>>" in b]
    assert len(blocks) >= 3
    parser = doctest.DocTestParser()
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    globs = {}
    for i, block in enumerate(blocks):
        test = parser.get_doctest(block, globs, "python.md block %d" % i, DOC, 0)
        runner.run(test, clear_globs=False)
        globs.update(test.globs)  # the next block goes on from here
    failed, attempted = runner.summarize(verbose=False)
    assert attempted > 15 and failed == 0
