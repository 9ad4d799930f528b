"""Progress of long work, wherever it is watched: a bar in terminals and notebooks (tqdm), and
in logs (stderr not a terminal) one line every half minute instead of a bar redrawn in place,
so that a campaign's log says how far it got."""

from __future__ import annotations

import sys
from typing import Any, Optional, TextIO

#: Seconds between two lines of progress in a log.
LOG_INTERVAL = 30.0


def _interactive(stream: TextIO) -> bool:
    """A terminal or a notebook (where tqdm.auto draws a widget)."""
    if "ipykernel" in sys.modules:
        return True
    isatty = getattr(stream, "isatty", None)
    return bool(isatty and isatty())


class _Lines:
    """A stream for tqdm that turns its in-place redraws into whole lines (for logs)."""

    def __init__(self, stream: TextIO):
        self.stream = stream

    def write(self, text: str) -> None:
        line = text.replace("\r", "").strip()
        if line:
            self.stream.write(line + "\n")

    def flush(self) -> None:
        self.stream.flush()


class ProgressBar:
    """Counts the ``unit``s (cases, by default) done out of ``total``: ``update(k)`` after each
    chunk, ``close()`` at the end (also on error)."""

    def __init__(self, total: int, label: str = "", stream: Optional[TextIO] = None, unit: str = "case"):
        # tqdm is imported when a bar is drawn: importing it loads some 120 modules (asyncio with
        # tqdm.auto), which import landing need not pay for
        from tqdm import tqdm as plain
        from tqdm.auto import tqdm

        stream = stream if stream is not None else sys.stderr
        options: dict[str, Any] = dict(total=total, desc=label or None, unit=unit, smoothing=0.1)
        if _interactive(stream):
            self._bar = tqdm(file=stream, **options)
        else:
            # plain tqdm (no widget), one line per LOG_INTERVAL seconds
            self._bar = plain(file=_Lines(stream), ascii=True, mininterval=LOG_INTERVAL,
                              maxinterval=LOG_INTERVAL, ncols=100, **options)

    def update(self, n: int) -> None:
        self._bar.update(n)

    def close(self) -> None:
        self._bar.close()
