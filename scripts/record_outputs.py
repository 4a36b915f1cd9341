"""Record the outputs that matter with their SHA-256, or check a build against a record.

A redesign of the package must not change a number (issue 20, item 7).  This
hashes what a build of the pipeline leaves (``snakemake --cores all`` first):
every figure (PDF and PNG, written with fixed metadata), the article's numbers
(``paper/build/numbers.json``, ``figures.json``), the studies' CSV files, the
accuracy study's JSON, the text outputs of every executed notebook, and the
rows of the sweep the benchmark times (``python -m lumped sweep --vary
x0=-1:1:20001 --t-end 4 --dt 1e-4``, run here into a temporary file).

The hashes hold on one machine and environment (book/guide/reproducibility.md): compare records made on the same machine.

Examples::

    python scripts/record_outputs.py > outputs.sha256          # record
    python scripts/record_outputs.py --check outputs.sha256    # after the change: differences, exit 1 if any
"""

from __future__ import annotations

import argparse
import hashlib
import json
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PATTERNS = (
    "figures/*.pdf",
    "figures/*.png",
    "paper/build/numbers.json",
    "paper/build/figures.json",
    "results/studies/*.csv",
    "results/accuracy/study.json",
)
SWEEP = ["sweep", "--vary", "x0=-1:1:20001", "--t-end", "4", "--dt", "1e-4"]


def digest(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def notebook_outputs(path: Path) -> bytes:
    """The text outputs of an executed notebook, cell by cell (not its metadata or timings)."""
    cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
    texts = []
    for cell in cells:
        for out in cell.get("outputs", []):
            text = out.get("text") or out.get("data", {}).get("text/plain", "")
            texts.append("".join(text) if isinstance(text, list) else text)
    return "\n\x00".join(texts).encode()


def sweep_rows() -> bytes:
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp, "sweep.csv")
        subprocess.run([sys.executable, "-m", "lumped", *SWEEP, "--output", str(out)], check=True, capture_output=True)
        return out.read_bytes()


def record() -> dict[str, str]:
    found = {str(p.relative_to(ROOT)): digest(p.read_bytes()) for pat in PATTERNS for p in sorted(ROOT.glob(pat))}
    for nb in sorted(ROOT.glob("results/notebooks/*.ipynb")):
        found[f"{nb.relative_to(ROOT)} (text outputs)"] = digest(notebook_outputs(nb))
    found["lumped " + " ".join(SWEEP)] = digest(sweep_rows())
    return found


def read(path: Path) -> dict[str, str]:
    lines = path.read_text(encoding="utf-8").splitlines()
    return {line[66:]: line[:64] for line in lines if line and not line.startswith("#")}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", type=Path, metavar="FILE", help="compare with a record written by this script")
    args = parser.parse_args(argv)
    if args.check is not None and not args.check.is_file():
        print(f"record_outputs: --check: no file {args.check}", file=sys.stderr)
        return 2
    if not (ROOT / "paper" / "build" / "numbers.json").is_file():
        print("record_outputs: no build to record: run snakemake --cores all first", file=sys.stderr)
        return 2
    now = record()
    if args.check is None:
        print("# sha256  output (scripts/record_outputs.py; one machine and environment)")
        print("\n".join(f"{h}  {name}" for name, h in now.items()))
        return 0
    before = read(args.check)
    changed = [n for n in before if now.get(n) != before[n]] + [n for n in now if n not in before]
    for name in changed:
        print(f"{'changed' if name in before and name in now else 'missing' if name in before else 'new'}: {name}")
    print(f"{len(now) - len(changed)} of {len(now)} outputs identical to {args.check}")
    return 1 if changed else 0


if __name__ == "__main__":
    sys.exit(main())
