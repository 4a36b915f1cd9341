"""The article's number formats (paper/format.typ) at every magnitude.

Each case typesets one value with one formatter in a throw-away Typst
document, reads the text back from the PDF (what a reader reads) and compares
it with the expected string. Skipped when ``typst`` or ``pypdf`` is missing.
"""

from __future__ import annotations

import io
import shutil
from pathlib import Path

import pytest

typst = pytest.importorskip("typst")
pypdf = pytest.importorskip("pypdf")

ROOT = Path(__file__).resolve().parent.parent

CASES = [
    # (Typst call, expected text); U+2212 is the minus sign
    ("num(0)", "0"),
    ("num(1e-300)", "1.00 × 10−300"),
    ("num(1.234e-12)", "1.23 × 10−12"),
    ("num(0.000999)", "9.99 × 10−4"),
    ("num(0.001)", "0.00100"),
    ("num(0.5)", "0.500"),
    ("num(1.5)", "1.50"),
    ("num(9.996)", "10.0"),
    ("num(9999.6)", "1.00 × 104"),
    ("num(1e300)", "1.00 × 10300"),
    ("num(-0.0067, d: 2)", "−0.0067"),
    ("sci(1.5)", "1.5"),
    ("sci(-2.0)", "−2.0"),
    ("sci(1e-4, d: 1)", "1 × 10−4"),
    ("sci(99.96)", "1.0 × 102"),
    ("fix(-0.0004, 2)", "0.00"),
    ("fix(2.5, 0)", "3"),
    ("plain(0.005)", "0.005"),
    ("plain(100.0)", "100"),
    ("plain(1e-4)", "1 × 10−4"),
    ("plain(1.5e-7)", "1.5 × 10−7"),
    ('plain("inf")', "∞"),
    ("num(none)", "n/a"),
    ("pct(0.3812)", "38 %"),
    ("decade(2.3e-9)", "between 10−9 and 10−8"),
    ("decade(1e-5)", "between 10−5 and 10−4"),
    ("decade(0.5)", "between 10−1 and 1"),
    ("decade(3.0)", "between 1 and 101"),
    ('column((0.000055, 0.00103, 0)).join("; ")', "5.50 × 10−5; 1.03 × 10−3; 0"),
    ('column((0.0077, 0.005, "still moving")).join("; ")', "0.00770; 0.00500; still moving"),
    ('column((1.5, 25.0, 100.0)).join("; ")', "1.50; 25.00; 100.00"),
]


def _typeset(tmp_path: Path, call: str) -> str:
    shutil.copy(ROOT / "paper" / "format.typ", tmp_path / "format.typ")
    doc = tmp_path / "case.typ"
    doc.write_text('#import "format.typ": *\n#set page(width: 30cm, height: auto)\n#(' + call + ")\n", encoding="utf-8")
    pdf = typst.compile(str(doc), ignore_system_fonts=True)
    return pypdf.PdfReader(io.BytesIO(pdf)).pages[0].extract_text().strip()


@pytest.mark.parametrize(("call", "expected"), CASES, ids=[c for c, _ in CASES])
def test_format(tmp_path: Path, call: str, expected: str) -> None:
    assert _typeset(tmp_path, call) == expected


@pytest.mark.parametrize("value", ["1.0", "3.7", "-5.2", "12.0", "999.0"])
def test_no_times_ten_to_the_zero(tmp_path: Path, value: str) -> None:
    """Values between 1 and 10 never print a factor 10⁰, whatever the formatter."""
    text = _typeset(tmp_path, f'(num({value}), sci({value}), plain({value})).join("; ")')
    assert "× 100" not in text  # an exponent 0 would read "× 10" then "0"
