"""Shared fixtures of the Python module's tests: the module itself and the granchain executable."""

import json
import re
import os
import pathlib
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
# Run from CTest, PYTHONPATH points at <build>/python; run by hand, the default build folder.
if not any(pathlib.Path(p, "granchain", "__init__.py").exists() for p in sys.path if p):
    sys.path.insert(0, str(ROOT / "build" / "python"))


@pytest.fixture(scope="session")
def cli():
    """Runs the granchain executable: cli('run', '--N', '3', ...) -> CompletedProcess (text)."""
    binary = os.environ.get("GRANCHAIN_BINARY", str(ROOT / "build" / "granchain"))
    assert os.access(binary, os.X_OK), f"granchain executable not found at {binary} (build it first)"

    def call(*args, cwd=None):
        return subprocess.run([binary, *map(str, args)], capture_output=True, text=True, cwd=cwd, timeout=300)

    return call


@pytest.fixture(scope="session")
def cli_json(cli):
    """Runs a granchain command with --json to standard output and returns the parsed JSON."""

    def call(*args, cwd=None):
        p = cli(*args, "--json", "-", cwd=cwd)
        assert p.returncode == 0, p.stderr
        return json.loads(p.stdout)

    return call


def cli_error(proc):
    """The one-line message of a CLI failure, without its 'granchain: error: ' prefix."""
    assert proc.returncode == 2, (proc.returncode, proc.stderr)
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("granchain: error: "), proc.stderr
    return lines[0][len("granchain: error: "):]


def keyword_form(message, names):
    """The CLI's message as the module words it: a flag "--dt-factor" becomes the keyword
    "dt_factor", and a hyphenated parameter name standing alone (in a range) the same."""
    for name in sorted(names, key=len, reverse=True):
        message = re.sub(r"--" + re.escape(name) + r"(?![\w-])", name.replace("-", "_"), message)
    for name in sorted(names, key=len, reverse=True):
        if "-" in name:
            message = re.sub(r"(?<![\w-])" + re.escape(name) + r"(?![\w-])", name.replace("-", "_"), message)
    return message


class ctrl_c_after:
    """SIGINT to this process `seconds` after entering the block, with Python's own handler
    installed (a shell's background job starts with SIGINT ignored); `elapsed` is the time from
    the signal to the end of the block."""

    def __init__(self, seconds):
        self.seconds = seconds

    def __enter__(self):
        import signal
        import threading
        import time
        self._signal, self._time = signal, time
        self._previous = signal.signal(signal.SIGINT, signal.default_int_handler)
        self._timer = threading.Timer(self.seconds, lambda: os.kill(os.getpid(), signal.SIGINT))
        self._t0 = time.monotonic()
        self._timer.start()
        return self

    def __exit__(self, *exc):
        self.elapsed = self._time.monotonic() - self._t0 - self.seconds
        self._timer.join()
        self._signal.signal(self._signal.SIGINT, self._previous)
        return False
