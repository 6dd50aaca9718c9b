"""Shared by the plot scripts: matplotlib without a display, reading the JSON granchain writes,
and saving a figure as PREFIX.png and PREFIX.pdf, each written whole or not at all."""
import json
import os
import signal
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402,F401  (re-exported)


def _end_on_sigterm(signum, frame):
    # SIGTERM (also sent when granchain, which started this script, ends) ends the script through
    # SystemExit, so that save_file removes its unfinished temporary file.
    raise SystemExit(128 + signum)


signal.signal(signal.SIGTERM, _end_on_sigterm)


def load(path):
    with open(path) as f:
        return json.load(f)


def usage(doc, argv, count):
    """True (after printing the usage) when argv does not hold `count` arguments."""
    if len(argv) != count + 1:
        sys.stderr.write(doc)
        return True
    return False


def save_file(fig, path, **kwargs):
    """Writes the figure to path whole or not at all: a temporary file beside it, then a rename."""
    fmt = path.rsplit(".", 1)[-1]
    tmp = "%s.tmp%d.%s" % (path, os.getpid(), fmt)
    try:
        fig.savefig(tmp, format=fmt, **kwargs)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def save(fig, prefix):
    fig.tight_layout()
    # bbox "tight": legends placed outside the axes are kept in the file.
    save_file(fig, prefix + ".png", dpi=150, bbox_inches="tight")
    save_file(fig, prefix + ".pdf", bbox_inches="tight")
