"""``python -m landing``: the command line (see :mod:`landing.cli`)."""

from landing.cli import console

console()
