"""The command line's help and its reference page say what the registry says (issue 31).

``lumped.drivers.methods.METHODS`` declares each method once: what it is,
what it runs (:attr:`Method.runs`), its options and whether a sweep runs it.
``simulate --help``, ``sweep --help`` and the generated section of
``book/guide/cli.md`` are rendered from it (:mod:`lumped.cli.reference`);
these tests fail when either drifts from the registry, and check the
registry's own claims (which methods run a network) against what the
methods do.  ``lumped --help`` names every command with one line.
"""

from __future__ import annotations

import argparse
import re

import pytest
from cli_run import run_lumped
from conftest import ROOT

from lumped.cli import build_parser
from lumped.cli.reference import BEGIN, END, methods_markdown
from lumped.drivers.methods import METHODS, OPTIONS, SWEEP_METHODS

GUIDE = ROOT / "book" / "guide" / "cli.md"


@pytest.fixture(autouse=True)
def _terminal_width(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("COLUMNS", "80")  # argparse wraps to the terminal: the same help everywhere


def _help(*command: str) -> str:
    done = run_lumped(*command, "--help")
    assert done.returncode == 0 and done.stderr == ""
    return done.stdout


def _flat(text: str) -> str:
    """``text`` with its line breaks and indentation as single spaces (argparse wraps at its width)."""
    return " ".join(text.split())


def _blocks(text: str, head: str) -> dict[str, str]:
    """The methods' table of ``--help`` after ``head``: each method's name (a line of its own, indented by 2)
    and its text (the lines indented by 4 below it, flattened)."""
    blocks: dict[str, str] = {}
    name = None
    for line in text[text.index(head) + len(head) :].splitlines():
        if re.match(r"^  \S+$", line):
            name = line.strip()
            blocks[name] = ""
        elif line.startswith("    ") and name is not None:
            blocks[name] = _flat(blocks[name] + " " + line)
        elif line.strip():
            break
    return blocks


def test_the_guides_methods_section_is_the_registrys() -> None:
    """The section between the markers is what ``scripts/guide_methods.py`` writes from the registry."""
    text = GUIDE.read_text()
    assert text.count(BEGIN) == text.count(END) == 1
    section = text[text.index(BEGIN) : text.index(END) + len(END)]
    assert section == methods_markdown()
    rows = [line for line in section.splitlines() if line.startswith("| `")][1:]  # below the header
    assert [re.match(r"\| `([^`]+)`", r).group(1) for r in rows] == list(METHODS)  # every method, once
    for row, m in zip(rows, METHODS.values()):
        assert m.runs in row and all(o.flag in row for o in m.options)
        assert row.endswith("| yes |" if m.batch else "| no |")


def test_simulate_help_lists_every_method_with_what_it_runs_and_its_options() -> None:
    text = _help("simulate")
    assert "--method {" + ",".join(METHODS) + "}" in text
    blocks = _blocks(text, "methods (--method NAME):")
    assert list(blocks) == list(METHODS)
    for name, m in METHODS.items():
        alias = f" Alias: {', '.join(m.aliases)} (a former name; it selects this method)." if m.aliases else ""
        assert blocks[name] == f"{m.description}. Runs {m.runs}.{alias} Options: {'; '.join(m.option_texts) or 'none'}."
    for option, users in OPTIONS.values():  # each option's help names the methods that take it
        assert f"{option.flag} {option.name.upper()} {option.help} of --method {', '.join(users)}" in _flat(text)


def test_no_help_says_a_network_needs_backward_euler() -> None:
    """``exact`` and ``event-locating`` run networks: no help may say that another method needs one mass."""
    text = _flat(_help("simulate"))
    assert "needs one mass" not in text
    networks = [n for n, m in METHODS.items() if m.runs_networks or m.piecewise_networks is not None]
    assert networks == ["backward-euler", "exact", "event-driven", "event-locating"]
    for name in networks:
        assert re.search(rf" {name} .*?Runs one mass [^.]*; (any network|networks of )", text), name


def test_sweep_help_offers_the_methods_a_sweep_runs_and_only_their_options() -> None:
    text = _help("sweep")
    assert "--method {" + ",".join(SWEEP_METHODS) + "}" in text
    blocks = _blocks(text, "methods a sweep runs (--method NAME):")
    assert list(blocks) == list(SWEEP_METHODS)
    for name, block in blocks.items():
        m = METHODS[name]
        assert block == f"{m.description}. Options: {'; '.join(m.option_texts) or 'none'}."
    for option, users in OPTIONS.values():
        offered = option.flag in text
        assert offered == any(u in SWEEP_METHODS for u in users), option.flag
    assert "--theta" not in text and "moreau-jean" not in text


@pytest.mark.parametrize("method", [m for m in METHODS if m not in SWEEP_METHODS])
def test_a_method_the_sweep_help_leaves_out_is_refused_by_the_sweep(method: str, tmp_path) -> None:
    done = run_lumped("sweep", "--vary", "x0=0:1:2", "--method", method, "--output", tmp_path / "s.csv")
    assert done.returncode == 2 and len(done.stderr.splitlines()) == 1
    assert f"'{method}' cannot run a sweep" in done.stderr


def test_an_option_the_sweep_help_leaves_out_is_refused_in_one_line(tmp_path) -> None:
    done = run_lumped("sweep", "--vary", "x0=0:1:2", "--theta", "0.5", "--output", tmp_path / "s.csv")
    assert done.returncode == 2 and len(done.stderr.splitlines()) == 1 and "--theta" in done.stderr


TWO_MASSES = """
[[mass]]
name = "a"
mass = 1.0
x0 = 0.1
[[mass]]
name = "b"
mass = 1.0
[[element]]
name = "ka"
kind = "spring"
between = ["ground", "a"]
stiffness = 100.0
[[element]]
name = "kab"
kind = "spring"
between = ["a", "b"]
stiffness = 100.0
[[element]]
name = "floor"
kind = "bingham"
between = ["ground", "b"]
threshold = 1.0
gamma = 1.0
"""


@pytest.mark.parametrize("method", METHODS)
def test_what_the_help_says_a_method_runs_is_what_it_runs(method: str, tmp_path) -> None:
    """A two-mass chain of springs and a Bingham contact (what every network-running method takes): it runs
    exactly with the methods whose ``runs`` names networks, and the others refuse it in one line."""
    system = tmp_path / "two.toml"
    system.write_text(TWO_MASSES)
    args = ["--system", system, "--t-end", "0.05", "--dt", "1e-3", "--method", method]
    done = run_lumped("simulate", *args, "--output", tmp_path / "run.csv")
    if "no network of more than one mass" in METHODS[method].runs:
        assert done.returncode == 2 and len(done.stderr.splitlines()) == 1
        assert method in done.stderr and not (tmp_path / "run.csv").exists()
    else:
        assert done.returncode == 0, done.stderr
        assert (tmp_path / "run.csv").read_text().splitlines()[0].startswith("t,x_a,x_b,")


def test_lumped_help_names_every_command_with_one_line() -> None:
    parser = build_parser()
    (sub,) = (a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    commands = {c.dest: c.help for c in sub._choices_actions}
    assert list(commands) == ["simulate", "sweep", "response", "cycles", "fit"]
    text = _help()
    lines = text.splitlines()
    for name, help_ in commands.items():
        (i,) = [j for j, line in enumerate(lines) if re.match(rf"^    {name} +\S", line)]
        assert lines[i].split(None, 1)[1] == help_, name  # the whole help on the command's line
        assert not lines[i + 1].startswith("      "), name  # and not wrapped onto the next
    assert f'"python -m lumped COMMAND --help" for the options of a command ({", ".join(commands)})' in _flat(text)
