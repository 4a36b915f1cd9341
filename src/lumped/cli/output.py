"""The output file: ``--output`` checked, written to a temporary file in its folder, then renamed.

The temporary file is created before the run (so an unwritable folder is
refused at once) and renamed when complete; every failure removes it.
"""

from __future__ import annotations

import contextlib
import json
import os
import stat
import tempfile
from typing import BinaryIO

import numpy as np

from lumped.cli.signals import signals_blocked


def check_output(path: str, suffixes: tuple[str, ...] = (".csv", ".npz")) -> str:
    """Refuse an ``--output`` that cannot name the file to write, with the reason (``suffixes``: those allowed)."""
    name = os.path.basename(path)
    kinds = " or ".join(suffixes)
    if not path.strip():
        raise ValueError("--output expects a file name, got an empty value")
    if os.path.isdir(path) or not name:
        raise ValueError(f"--output: {path!r} is a directory; name a {kinds} file")
    if name.lower() in suffixes:
        raise ValueError(f"--output: {path!r} has no file name before the suffix")
    if os.path.splitext(name)[1].lower() not in suffixes:
        raise ValueError(f"--output must end in {kinds}, got {path!r}")
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise ValueError(f"--output: directory {folder!r} does not exist")
    return path


#: The options that name a file a command reads (those a command lacks are skipped).
_INPUTS = ("system", "force_table", "data")


def refuse_inputs(args: object) -> None:
    """Refuse an ``--output`` that is a file the command reads, before any work: the ``--system``,
    ``--force-table`` or ``--data`` file, or a table that the system file names.

    Files are compared as the system sees them (:func:`os.path.samefile`: links and other spellings of a
    path included); a path that does not exist is compared as its resolved name.
    """
    output = getattr(args, "output", None)
    if output is None:
        return
    for what, path in _inputs(args):
        if _same_file(output, path):
            raise ValueError(f"--output {output!r} is {what}, which this command reads; name another output file")


def _inputs(args: object) -> list[tuple[str, str]]:
    """``(what, path)`` of each file that ``args`` name as inputs."""
    out = []
    for name in _INPUTS:
        path = getattr(args, name, None)
        if path is None:
            continue
        flag = "--" + name.replace("_", "-")
        out.append((f"the {flag} file", path))
        if name == "system":
            from lumped.model.files import table_files  # the system files' reader, only with --system

            out += [(f"the file of {entry} in {flag} {path!r}", str(p)) for entry, p in table_files(path)]
    return out


def _same_file(a: str, b: str) -> bool:
    try:
        return os.path.samefile(a, b)
    except (OSError, ValueError):  # one does not exist (or is no path): compare the names
        return os.path.realpath(a) == os.path.realpath(b)


def _new_file_mode(path: str) -> int:
    """Mode for the output: that of the file it replaces, else 0o666 less the umask."""
    with contextlib.suppress(OSError):
        return stat.S_IMODE(os.stat(path).st_mode)
    umask = os.umask(0)  # reading the umask means setting it; put it back at once
    os.umask(umask)
    return 0o666 & ~umask


class Output:
    """The output file: a temporary file in the target folder, then a rename.

    :meth:`create` makes the temporary file (before the run, so that a folder
    that cannot be written is refused at once), :meth:`commit` fills and
    renames it, :meth:`discard` removes it unless committed.  ``written`` tells
    whether the rename happened.
    """

    def __init__(self, path: str) -> None:
        self.path = path
        self.tmp: str | None = None
        self.written = False

    def create(self) -> None:
        """Create the temporary file with the final file's mode."""
        folder = os.path.dirname(os.path.abspath(self.path))
        try:
            fd, self.tmp = tempfile.mkstemp(dir=folder, prefix=os.path.basename(self.path) + ".", suffix=".part")
            try:
                os.fchmod(fd, _new_file_mode(self.path))  # mkstemp's 0o600 ignores the umask
            finally:
                os.close(fd)
        except OSError as err:
            why = err.strerror or str(err)
            raise ValueError(f"--output: cannot create a file in {folder!r}: {why}") from None

    def commit(self, columns: dict) -> None:
        """Write ``columns`` (arrays; a JSON document for ``.json``) to the temporary file and rename it to the output."""
        assert self.tmp is not None, "create() first"
        try:
            with open(self.tmp, "wb") as fh:
                _dump(fh, columns, os.path.splitext(self.path)[1].lower())
            with signals_blocked():
                os.replace(self.tmp, self.path)
                self.written = True
        except OSError as err:
            why = err.strerror or str(err)
            raise ValueError(f"--output: cannot write {self.path!r}: {why}") from None

    def discard(self) -> None:
        """Remove the temporary file if it is still there."""
        if self.tmp is not None and not self.written:
            with contextlib.suppress(FileNotFoundError):
                os.unlink(self.tmp)


def _dump(fh: BinaryIO, columns: dict[str, np.ndarray], suffix: str) -> None:
    """Write the columns as ``.npz`` arrays, as ``.csv`` with a header line, or (a dict) as ``.json``."""
    if suffix == ".json":
        fh.write((json.dumps(columns, indent=2, allow_nan=False) + "\n").encode("utf-8"))
    elif suffix == ".npz":
        np.savez(fh, **columns)
    elif all(np.asarray(c).dtype.kind == "f" for c in columns.values()):
        data = np.column_stack(list(columns.values()))
        np.savetxt(fh, data, fmt="%.17g", delimiter=",", header=",".join(columns), comments="")
    else:  # text and booleans (the response curve's kind and stable): each value as its own text
        cells = [[_cell(v) for v in np.asarray(c)] for c in columns.values()]
        lines = [",".join(columns)] + [",".join(row) for row in zip(*cells)]
        fh.write(("\n".join(lines) + "\n").encode("utf-8"))


def _cell(value: object) -> str:
    """A CSV cell: a float as ``%.17g``, a boolean as ``true``/``false``, ``None`` (no value) empty, text as it is."""
    if value is None:
        return ""
    if isinstance(value, (bool, np.bool_)):
        return "true" if value else "false"
    if isinstance(value, (float, np.floating)):
        return "%.17g" % value
    return str(value)
