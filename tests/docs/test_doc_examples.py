"""The examples in the documentation run as shown and print what the documentation says.

A fenced block of README.md or docs/*.md preceded by the line ``<!-- doc-test -->`` is run: a
``sh`` block line by line with bash (-e: every command must succeed), a ``python`` block with
Debian's /usr/bin/python3. With ``<!-- doc-test output -->`` its standard output must equal the
next fenced block, line for line (trailing blanks ignored). Blocks run in a fresh folder that
sees the repository's build, data, examples and plots folders, so `./build/granchain`,
`data/quick/quick.db` and `PYTHONPATH=build/python` read as they do from the repository root.
Only cheap examples are marked (seconds each); docs/testing.md lists them.
"""

import os
import pathlib
import re
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = pathlib.Path(os.environ.get("GRANCHAIN_BUILD_DIR", ROOT / "build")).resolve()
MARK = re.compile(r"^<!-- doc-test( output)? -->$")


def fenced_blocks(lines):
    """(first line number, language, body) of every fenced block."""
    i = 0
    while i < len(lines):
        if lines[i].startswith("```"):
            j = i + 1
            while j < len(lines) and not lines[j].startswith("```"):
                j += 1
            yield i, lines[i][3:].strip(), lines[i + 1:j]
            i = j + 1
        else:
            i += 1


def marked_examples():
    for doc in [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md")):
        lines = doc.read_text().split("\n")
        blocks = list(fenced_blocks(lines))
        for n, (start, lang, body) in enumerate(blocks):
            mark = MARK.match(lines[start - 1]) if start > 0 else None
            if not mark:
                continue
            expected = None
            if mark.group(1):
                assert n + 1 < len(blocks), f"{doc.name}:{start + 1}: 'doc-test output' without a block after it"
                expected = blocks[n + 1][2]
            yield pytest.param(lang, body, expected, id=f"{doc.relative_to(ROOT)}:{start + 1}")


@pytest.fixture
def workdir(tmp_path):
    for name, target in (("build", BUILD), ("data", ROOT / "data"), ("examples", ROOT / "examples"), ("plots", ROOT / "plots")):
        (tmp_path / name).symlink_to(target)
    return tmp_path


@pytest.mark.parametrize("lang,body,expected", list(marked_examples()))
def test_example_runs_as_documented(workdir, lang, body, expected):
    env = dict(os.environ, PYTHONPATH=str(BUILD / "python"), PYTHONDONTWRITEBYTECODE="1")
    if lang == "sh":
        cmd = ["bash", "-e", "-o", "pipefail", "-c", "\n".join(body)]
    elif lang == "python":
        cmd = ["/usr/bin/python3", "-W", "ignore", "-c", "\n".join(body)]
    else:
        pytest.fail(f"a doc-test block must be sh or python, not {lang!r}")
    p = subprocess.run(cmd, cwd=workdir, env=env, capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, f"exit {p.returncode}\n{p.stderr[-3000:]}"
    if expected is not None:
        got = [line.rstrip() for line in p.stdout.rstrip("\n").split("\n")]
        want = [line.rstrip() for line in expected]
        assert got == want, "\n".join(["printed:"] + got)


def test_some_examples_are_marked():
    assert len(list(marked_examples())) >= 3
