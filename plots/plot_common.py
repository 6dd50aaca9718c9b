"""Shared by the plot scripts: matplotlib without a display, reading the JSON granchain writes,
and saving a figure as PREFIX.png and PREFIX.pdf."""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402,F401  (re-exported)


def load(path):
    with open(path) as f:
        return json.load(f)


def usage(doc, argv, count):
    """True (after printing the usage) when argv does not hold `count` arguments."""
    if len(argv) != count + 1:
        sys.stderr.write(doc)
        return True
    return False


def save(fig, prefix):
    fig.tight_layout()
    fig.savefig(prefix + ".png", dpi=150)
    fig.savefig(prefix + ".pdf")
