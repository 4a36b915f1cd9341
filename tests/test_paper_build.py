"""The article builds, has every figure and at least six pages, and is byte-reproducible.

Skipped when the ``typst`` Python package is not installed or when the
figures have not been built yet (``snakemake --cores all`` makes them).
"""

from __future__ import annotations

import importlib.util
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
typst = pytest.importorskip("typst")


def _script(name: str):
    spec = importlib.util.spec_from_file_location(name, ROOT / "scripts" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def builds(tmp_path_factory: pytest.TempPathFactory) -> tuple[bytes, bytes]:
    build = _script("build_paper")
    figures = build.find_figures()
    if len(figures) < build.FIGURE_COUNT:
        pytest.skip("figures not built yet (run snakemake --cores all)")
    numbers = ROOT / "paper" / "build" / "numbers.json"
    if not numbers.is_file():
        assert _script("paper_numbers").main([str(numbers)]) == 0
    out = tmp_path_factory.mktemp("paper")
    first, second = out / "a.pdf", out / "b.pdf"
    build.build(first, figures)
    build.build(second, figures)
    return first.read_bytes(), second.read_bytes()


def test_pdf_is_byte_identical_across_builds(builds: tuple[bytes, bytes]) -> None:
    assert builds[0] == builds[1]


def test_pdf_has_at_least_six_pages(builds: tuple[bytes, bytes]) -> None:
    pages = len(re.findall(rb"/Type\s*/Page(?![sL])", builds[0]))  # not /Pages, /PageLabel
    assert pages >= 6


def test_every_original_figure_is_shown() -> None:
    text = (ROOT / "paper" / "paper.typ").read_text(encoding="utf-8")
    shown = sorted(int(n) for n in re.findall(r"^#fig\((\d+)\)", text, flags=re.M))
    assert shown == list(range(1, 15))


def test_no_number_typed_by_hand_in_the_prose() -> None:
    """Decimal numbers in the article come from the JSON, not from the source text.

    Layout lengths and the original's section numbers are not data and are removed first.
    """
    text = (ROOT / "paper" / "paper.typ").read_text(encoding="utf-8")
    deviations = (ROOT / "paper" / "deviations.yaml").read_text(encoding="utf-8")
    body = re.sub(r"//.*", "", text[text.index("= Introduction"):])  # Typst comments
    body += re.sub(r"^\s*#.*", "", deviations, flags=re.M)  # YAML comments
    body = re.sub(r"\d+(\.\d+)?(pt|em|cm|fr)\b", "", body)  # lengths of the layout
    body = re.sub(r"Sections? \d+\.\d+ and \d+\.\d+", "", body)  # the original's numbering
    body = re.sub(r"(Remark|Sections?|Algorithm|section) \d+(\.\d+)*", "", body)
    typed = re.findall(r"(?<![\w.#])\d+\.\d+(?![\w.])", body)
    assert typed == [], f"decimal numbers typed by hand: {typed}"
