"""Strict JSON for the studies' files: :func:`clean`, shared by the article's numbers and the accuracy study.

``paper/build/numbers.json`` (:func:`lumped.studies.replication.compute`) and
``results/accuracy/study.json`` (:func:`lumped.studies.accuracy.to_json`) are
read by Typst's ``json()`` and by notebooks: no NaN or infinity may reach them.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["clean"]


def clean(value: Any) -> Any:
    """NaN to None and infinities to "inf"/"-inf" (strict JSON); numpy scalars to Python numbers."""
    if isinstance(value, dict):
        return {k: clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [clean(v) for v in value]
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        if math.isnan(value):
            return None
        return float(value) if math.isfinite(value) else ("inf" if value > 0 else "-inf")
    return value
