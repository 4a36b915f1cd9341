"""scripts/perturbed_check.py: its environments really perturb, its errors are one line, and a subset passes."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
SCRIPT = ROOT / "scripts" / "perturbed_check.py"
sys.path.insert(0, str(SCRIPT.parent))
import perturbed_check  # noqa: E402


def _python(env_name: str, code: str) -> str:
    env = perturbed_check.environment(env_name)
    return subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True).stdout


def test_libm_ulp_moves_sin_by_one_ulp_and_leaves_exact_values():
    code = "import math, numpy as np; print(math.sin(0.5).hex(), np.sin(np.array([0.5]))[0].hex(), math.sin(0.0), np.exp(0.0))"
    plain, moved = _python("reference", code).split(), _python("libm-ulp", code).split()
    assert plain[0] == plain[1] and moved[0] == moved[1]  # math and numpy moved alike
    assert abs(float.fromhex(moved[0]) - float.fromhex(plain[0])) == 2**-54  # one ulp of sin(0.5) in [0.25, 0.5)
    assert moved[2:] == plain[2:] == ["0.0", "1.0"]


def test_unknown_environment_is_one_line():
    proc = subprocess.run([sys.executable, SCRIPT, "--env", "nope"], capture_output=True, text=True)
    assert proc.returncode == 2 and proc.stderr.count("\n") == 1 and "unknown environment nope" in proc.stderr


@pytest.mark.slow
def test_round_off_sensitive_tests_pass_under_libm_ulp():
    # The tests and notebooks that followed round-off before issue 19 (about 25 s on 2 cores).
    targets = ["tests/test_dop853.py", "tests/test_den_hartog.py"]
    targets += [
        f"notebooks/{n}.ipynb"
        for n in ("02_sgn_zero_failure", "05_free_vibrations", "09_which_method", "11_den_hartog")
    ]
    proc = subprocess.run([sys.executable, SCRIPT, "--env", "libm-ulp", *targets], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stdout
