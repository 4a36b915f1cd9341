"""Execute the jupytext notebooks of ``notebooks/``.

Two uses:

* the Snakemake pipeline runs one notebook and keeps the executed copy::

      python scripts/run_notebook.py notebooks/04_forced_vibrations.py \\
          --output results/notebooks/04_forced_vibrations.ipynb \\
          --figures figures --config results/config.yaml

  The kernel runs in ``notebooks/`` with ``LUMPED_FIGURES_DIR`` (where
  :func:`lumped.plotting.save_figure` writes) and ``LUMPED_CONFIG`` (the
  pipeline's effective configuration) set;

* after editing a notebook's ``.py`` twin, refresh the committed ``.ipynb``
  (outputs included, as nbval compares them) from the repository root::

      python scripts/run_notebook.py --update-committed            # all of them
      python scripts/run_notebook.py --update-committed notebooks/05_free_vibrations.py

  These runs use ``config/config.yaml`` and write no figure files.

The output is the same bytes from run to run: cell ids are numbered from the
cell index (nbformat draws random ones), a cell's printed output is one piece
per stream (the kernel splits it at timing-dependent places), no timing is
recorded, and tracebacks are uncoloured. The kernel talks to this process over Unix sockets in a
temporary folder (IPC transport) rather than TCP on localhost, so no port is
opened and ipykernel has no reason to warn about unencrypted TCP. A failing
cell ends the run with the cell's source and the error, in plain text, and
exit status 1.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
from pathlib import Path

# jupytext and nbclient read notebooks through nbformat, which imports jsonschema, whose optional "iri"
# format checker (rfc3987-syntax, installed for JupyterLab) compiles some forty grammars on import: a second
# or more in each of the pipeline's notebook jobs. Notebook files use no such format; the checker is left out.
sys.modules.setdefault("rfc3987_syntax", None)  # an import of it now raises ImportError, which jsonschema skips

import jupytext
import nbclient
from nbclient.exceptions import CellExecutionError
from traitlets.config import Config

ROOT = Path(__file__).resolve().parent.parent
NOTEBOOKS = ROOT / "notebooks"
#: Variables a notebook kernel reads; cleared unless set on purpose.
ENV_VARS = ("LUMPED_FIGURES_DIR", "LUMPED_CONFIG")


def normalise(notebook) -> None:
    """Make the executed notebook independent of the run.

    Each cell gets the id ``cell-<index>`` in place of nbformat's random one,
    and consecutive pieces of the same stream are joined: where the kernel
    splits one cell's printing depends on timing.
    """
    for index, cell in enumerate(notebook.cells):
        cell["id"] = f"cell-{index}"
        outputs = []
        for output in cell.get("outputs", []):
            previous = outputs[-1] if outputs else None
            if (
                output["output_type"] == "stream"
                and previous is not None
                and previous["output_type"] == "stream"
                and previous["name"] == output["name"]
            ):
                previous["text"] += output["text"]
            else:
                outputs.append(output)
        if "outputs" in cell:
            cell["outputs"] = outputs


def execute(source: Path, env: dict[str, str], timeout: int = 600) -> object:
    """Read ``source`` (jupytext), run it in its folder with ``env``; return the notebook."""
    notebook = jupytext.read(source)
    for name in ENV_VARS:
        os.environ.pop(name, None)
    os.environ.update(env)
    with tempfile.TemporaryDirectory(prefix="lumped-kernel-") as sockets:
        client = nbclient.NotebookClient(
            notebook,
            timeout=timeout,
            kernel_name="python3",
            record_timing=False,  # no timestamps: the output does not change between runs
            resources={"metadata": {"path": str(source.resolve().parent)}},
            # ipc: the kernel's sockets are files <sockets>/kernel-<n>, not TCP ports
            config=Config(KernelManager={"transport": "ipc", "ip": f"{sockets}/kernel"}),
            extra_arguments=["--InteractiveShell.colors=nocolor"],
        )
        client.execute()
    normalise(notebook)
    return notebook


def update_committed(sources: list[Path]) -> None:
    """Re-execute each ``.py`` and overwrite its paired ``.ipynb`` next to it."""
    for source in [s.resolve() for s in sources] or sorted(NOTEBOOKS.glob("[0-9][0-9]_*.py")):
        notebook = execute(source, env={})
        target = source.with_suffix(".ipynb")
        jupytext.write(notebook, target)
        print(f"{source.relative_to(ROOT)} -> {target.relative_to(ROOT)}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("notebooks", nargs="*", type=Path, help="jupytext .py notebooks")
    parser.add_argument(
        "--update-committed", action="store_true", help="overwrite the paired .ipynb of each notebook (default: all)"
    )
    parser.add_argument("--output", type=Path, help="where to write the executed notebook")
    parser.add_argument("--figures", type=Path, help="folder for the figure files")
    parser.add_argument("--config", type=Path, help="configuration file for the notebook")
    args = parser.parse_args(argv)
    if args.update_committed:
        update_committed(args.notebooks)
        return 0
    if len(args.notebooks) != 1 or args.output is None:
        parser.error("give one notebook and --output (or use --update-committed)")
    env = {}
    if args.figures is not None:
        env["LUMPED_FIGURES_DIR"] = str(args.figures.resolve())
    if args.config is not None:
        env["LUMPED_CONFIG"] = str(args.config.resolve())
    try:
        notebook = execute(args.notebooks[0], env)
    except CellExecutionError as error:
        print(f"{args.notebooks[0]}: a cell failed\n{error}", file=sys.stderr)
        return 1
    args.output.parent.mkdir(parents=True, exist_ok=True)
    jupytext.write(notebook, args.output)
    return 0


if __name__ == "__main__":
    sys.exit(main())
