"""What ``--help`` and the guide's command-line reference say about the methods, rendered from the registry.

:data:`lumped.drivers.methods.METHODS` declares each method once: its
description, what it runs (:attr:`~lumped.drivers.methods.Method.runs`),
its options and whether a sweep runs it.  :func:`methods_help` renders that
table for the epilog of ``simulate --help`` and ``sweep --help``;
:func:`methods_markdown` for the generated section of ``book/guide/cli.md``
(between :data:`BEGIN` and :data:`END`, rewritten by
``scripts/guide_methods.py``).  ``tests/test_cli_reference.py`` requires the
page and the help to say what the registry says.
"""

from __future__ import annotations

import textwrap
from collections.abc import Sequence

from lumped.drivers.methods import METHODS, SWEEP_METHODS

__all__ = ["BEGIN", "END", "methods_help", "methods_markdown", "sweep_option_names"]

#: The markers of the generated section in ``book/guide/cli.md``.
BEGIN = "<!-- methods: generated from lumped.drivers.methods.METHODS by scripts/guide_methods.py; do not edit -->"
END = "<!-- end of the generated methods -->"
#: Width of ``--help`` (argparse's default for a terminal of 80 columns, less its margin).
_WIDTH = 78
_INDENT = 4


def _names(sweep: bool) -> Sequence[str]:
    return SWEEP_METHODS if sweep else tuple(METHODS)


def sweep_option_names() -> tuple[str, ...]:
    """The options of the methods a sweep runs (``--rtol``): the only method options ``sweep`` offers."""
    return tuple(dict.fromkeys(o.name for n in SWEEP_METHODS for o in METHODS[n].options))


def _alias_text(aliases: tuple[str, ...]) -> list[str]:
    """``["Alias: event-capturing (a former name; ...)."]`` for a method with former names, else nothing."""
    return [f"Alias: {', '.join(aliases)} (a former name; it selects this method)."] if aliases else []


def methods_help(sweep: bool = False) -> str:
    """The ``--method`` table of ``--help``: each method's name, description, what it runs and its options.

    A sweep's lists the methods it runs, without what they run (a sweep runs the single mass).
    """
    lines = ["methods a sweep runs (--method NAME):" if sweep else "methods (--method NAME):"]
    for name in _names(sweep):
        m = METHODS[name]
        texts = [f"{m.description}.", *([] if sweep else [f"Runs {m.runs}."]), *_alias_text(m.aliases)]
        texts.append(f"Options: {'; '.join(m.option_texts) or 'none'}.")
        lines.append(f"  {name}")
        for text in texts:
            lines.extend(" " * _INDENT + b for b in textwrap.wrap(text, _WIDTH - _INDENT, break_on_hyphens=False))
    return "\n".join(lines)


def methods_markdown() -> str:
    """The generated section of ``book/guide/cli.md``: one table row per method, between the markers."""
    rows = [
        "| `--method` | what it is | what it runs | its options | in a sweep |",
        "| --- | --- | --- | --- | --- |",
    ]
    for name, m in METHODS.items():
        opts = "; ".join(f"`{t.split(':', 1)[0]}`:{t.split(':', 1)[1]}" for t in m.option_texts) or "none"
        what = " ".join([m.description + ".", *_alias_text(m.aliases)])
        rows.append(f"| `{name}` | {what} | {m.runs} | {opts} | {'yes' if m.batch else 'no'} |")
    return "\n".join([BEGIN, "", *rows, "", END])
