"""The shared parameter file ``config/config.yaml`` and the objects it describes.

The notebooks, the Snakemake pipeline and the article all read the same file.
The environment variable ``LUMPED_CONFIG`` points to another file (the
pipeline sets it to the configuration after ``--config`` overrides).
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any

from lumped.forcing import SwitchedSine
from lumped.system import Oscillator

__all__ = ["load", "find_root", "oscillator", "forcing"]


def find_root(start: Path | None = None) -> Path:
    """The repository root: the first folder upwards holding ``config/config.yaml``."""
    here = (start or Path.cwd()).resolve()
    for folder in (here, *here.parents):
        if (folder / "config" / "config.yaml").is_file():
            return folder
    raise ValueError(f"config: no config/config.yaml above {here}")


def load(path: str | os.PathLike[str] | None = None) -> dict[str, Any]:
    """Read the configuration (``path``, else ``$LUMPED_CONFIG``, else the repository's)."""
    import yaml

    path = path or os.environ.get("LUMPED_CONFIG") or find_root() / "config" / "config.yaml"
    with open(path, encoding="utf-8") as fh:
        return yaml.safe_load(fh)


def oscillator(cfg: dict[str, Any]) -> Oscillator:
    """The paper's system with the configured parameters."""
    return Oscillator.bingham(cfg["mass"], cfg["stiffness"], cfg["threshold"], float(cfg["gamma"]))


def forcing(cfg: dict[str, Any], which: str) -> SwitchedSine:
    """Eq. (17a) for ``which="small"``, eq. (17b) for ``"large"``."""
    if which not in ("small", "large"):
        raise ValueError(f"which must be 'small' or 'large', got {which!r}")
    return SwitchedSine(
        amplitude=cfg[f"force_amplitude_{which}"],
        omega=cfg["force_omega_over_pi"] * math.pi,
        phase=0.0,
        until=cfg["force_until"],
    )
