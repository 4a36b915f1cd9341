"""The article builds, has every figure (as vector graphics) and at least six pages,
and is byte-reproducible.

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
    if not build.CONVERGENCE.is_file():
        assert _script("paper_figures").main([str(numbers), str(build.CONVERGENCE)]) == 0
    if not build.STUDY.is_file():
        assert _script("accuracy_study").main([str(build.STUDY)]) == 0
    if not build.ACCURACY.is_file():
        assert _script("accuracy_figure").main([str(build.STUDY), str(build.ACCURACY)]) == 0
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


def test_pdf_is_under_three_megabytes(builds: tuple[bytes, bytes]) -> None:
    """Dense curves are thinned to what the eye resolves (path.simplify in the style file)."""
    assert len(builds[0]) < 3_000_000, f"{len(builds[0]) / 1e6:.1f} MB"


def test_figures_are_embedded_as_vector_graphics(builds: tuple[bytes, bytes]) -> None:
    # Each embedded PDF becomes a form XObject; a PNG would be an image XObject.
    assert not re.search(rb"/Subtype\s*/Image", builds[0])
    assert len(re.findall(rb"/Subtype\s*/Form", builds[0])) >= 15  # 14 figures + convergence


def test_only_pdf_figures_are_accepted() -> None:
    build = _script("build_paper")
    figure = ROOT / "figures" / "fig09_forced_large_Fd"
    assert build.figure_table([f"{figure}.pdf"]) == {"09": "/figures/fig09_forced_large_Fd.pdf"}
    with pytest.raises(ValueError, match="figNN_<slug>.pdf"):
        build.figure_table([f"{figure}.png"])


def test_convergence_figure_is_byte_reproducible(tmp_path: Path) -> None:
    numbers = ROOT / "paper" / "build" / "numbers.json"
    if not numbers.is_file():
        pytest.skip("paper/build/numbers.json not built yet")
    draw = _script("paper_figures")
    first, second = draw.write(numbers, tmp_path / "a.pdf"), draw.write(numbers, tmp_path / "b.pdf")
    assert first.read_bytes() == second.read_bytes()
    assert b"CreationDate" not in first.read_bytes()


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
    body = re.sub(r"//.*", "", text[text.index("= Introduction") :])  # Typst comments
    body += re.sub(r"^\s*#.*", "", deviations, flags=re.M)  # YAML comments
    body = re.sub(r"\d+(\.\d+)?(pt|em|cm|fr)\b", "", body)  # lengths of the layout
    body = re.sub(r"Sections? \d+\.\d+ and \d+\.\d+", "", body)  # the original's numbering
    body = re.sub(r"(Remark|Sections?|Algorithm|section) \d+(\.\d+)*", "", body)
    typed = re.findall(r"(?<![\w.#])\d+\.\d+(?![\w.])", body)
    assert typed == [], f"decimal numbers typed by hand: {typed}"
