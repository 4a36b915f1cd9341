"""A sweep's progress report on stderr (:class:`Progress`), never in the output file."""

from __future__ import annotations

import time


class Progress:
    """Progress of a sweep on a text stream (stderr), called as ``progress(done, total)``.

    On a terminal one line is rewritten in place (``\\r``) and ended at the
    last row; elsewhere (a log file) a line is written at most every
    ``every`` seconds, and none at all when ``enabled`` is false.  ``label`` and
    ``unit`` name the task and what it counts (``sweep``, ``rows``; no ``unit``: the percentage alone).  It writes
    to the stream only, never to the output file.
    """

    def __init__(  # noqa: ANN001 (a text stream)
        self, stream, enabled: bool, every: float = 10.0, label: str = "sweep", unit: str = "rows"
    ) -> None:
        self.stream, self.enabled, self.every = stream, enabled, every
        self.label, self.unit = label, unit
        self.tty = bool(getattr(stream, "isatty", lambda: False)())
        self.start = self.last = time.monotonic()

    def __call__(self, done: int, total: int) -> None:
        now = time.monotonic()
        if not self.enabled or (not self.tty and now - self.last < self.every and done < total):
            return
        self.last = now
        count = f"{done}/{total} {self.unit} (" if self.unit else "("
        line = f"{self.label}: {count}{100 * done / total:.0f}%, {now - self.start:.1f} s)"
        end = "\n" if done == total or not self.tty else ""
        self.stream.write(("\r" if self.tty else "") + line + end)
        self.stream.flush()
