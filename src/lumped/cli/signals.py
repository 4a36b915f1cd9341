"""Interrupts: SIGTERM and SIGHUP unwind a run as Ctrl-C does, and a rename is never split by one."""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Iterator

#: Signals that unwind through the cleanup while a run is under way (SIGINT
#: already does, as KeyboardInterrupt).
UNWIND_SIGNALS = tuple(getattr(signal, n) for n in ("SIGTERM", "SIGHUP") if hasattr(signal, n))


class Terminated(BaseException):
    """Raised by the SIGTERM/SIGHUP handler; a BaseException, like KeyboardInterrupt,
    so that no ``except Exception`` on the way swallows it."""

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum


def _raise_terminated(signum: int, frame: object) -> None:
    """The handler of SIGTERM and SIGHUP while a run is under way."""
    raise Terminated(signum)


@contextlib.contextmanager
def signals_unwind() -> Iterator[None]:
    """While active, SIGTERM and SIGHUP raise :class:`Terminated`.

    Signals that the caller ignores (``nohup``) stay ignored; the previous
    handlers are restored on exit.  Outside the main thread nothing changes
    (Python delivers signals to the main thread only).
    """
    old = {}
    if threading.current_thread() is threading.main_thread():
        for sig in UNWIND_SIGNALS:
            if signal.getsignal(sig) is not signal.SIG_IGN:
                old[sig] = signal.signal(sig, _raise_terminated)
    try:
        yield
    finally:
        for sig, handler in old.items():
            signal.signal(sig, signal.SIG_DFL if handler is None else handler)


@contextlib.contextmanager
def signals_blocked() -> Iterator[None]:
    """Hold back the unwinding signals (so a rename and its record are not split)."""
    held = {signal.SIGINT, *UNWIND_SIGNALS}
    if not hasattr(signal, "pthread_sigmask"):  # not POSIX: nothing to hold
        yield
        return
    old = signal.pthread_sigmask(signal.SIG_BLOCK, held)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, old)
