"""scripts/record_outputs.py: its record reads back, and a bad argument is one line with status 2."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SCRIPT = ROOT / "scripts" / "record_outputs.py"


def test_a_missing_record_is_one_line_and_status_2(tmp_path):
    run = subprocess.run(
        [sys.executable, str(SCRIPT), "--check", str(tmp_path / "none")], capture_output=True, text=True
    )
    assert run.returncode == 2 and run.stdout == ""
    assert run.stderr.strip() == f"record_outputs: --check: no file {tmp_path / 'none'}"


def test_the_committed_record_names_every_kind_of_output():
    sys.path.insert(0, str(SCRIPT.parent))
    try:
        import record_outputs
    finally:
        sys.path.pop(0)
    names = record_outputs.read(ROOT / "benchmarks" / "outputs.sha256")
    assert any(n.startswith("figures/fig14_") for n in names) and "paper/build/numbers.json" in names
    assert "results/studies/rest.csv" in names and any(n.startswith("lumped sweep") for n in names)
    assert all(len(h) == 64 and int(h, 16) >= 0 for h in names.values())
