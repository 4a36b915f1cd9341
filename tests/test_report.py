"""The Snakemake report (``snakemake --report report.html``) opens without warnings.

Snakemake joins every caption with one block of link targets, one per result
and one per category (``.. _<category>: javascript:...``), and parses the whole
as one reStructuredText document.  A category name holding a colon is read by
docutils as a target *named by the text before the colon*, so every
"Tutorial: ..." category defined a target "tutorial" once more and each caption
showed "Duplicate explicit target name" boxes (issue 32: 231 of them).  The
first test checks the category names the way docutils reads them, without a
build; the second builds the report as Snakemake writes it and asserts that it
holds no docutils system message.
"""

import ast
import re
import subprocess
import sys

import pytest
from conftest import ROOT
from docutils import nodes
from docutils.core import publish_doctree


def categories() -> list[str]:
    """The report's category names, read from rules/common.smk's CATEGORY dict."""
    text = (ROOT / "rules" / "common.smk").read_text(encoding="utf-8")
    match = re.search(r"^CATEGORY = (\{.*?^\})", text, flags=re.DOTALL | re.MULTILINE)
    return list(ast.literal_eval(match.group(1)).values())


def test_each_category_is_one_link_target_of_its_own_name():
    """The line Snakemake writes for each category defines a target of that exact name."""
    names = categories()
    assert len(names) >= 12
    source = "\n".join(f".. _{name}: javascript:app.showCategory('x')" for name in names)
    tree = publish_doctree(source, settings_overrides={"report_level": 5})
    targets = [t for t in tree.findall(nodes.target)]
    assert not list(tree.findall(nodes.system_message))
    assert sorted(n for t in targets for n in t["names"]) == sorted(name.lower() for name in names)


def test_the_built_report_has_no_system_message(tmp_path):
    """``snakemake --report`` on the built pipeline: no docutils warning box in the page."""
    if not (ROOT / "paper" / "paper.pdf").is_file():  # the main job's last product
        pytest.skip("pipeline not built yet (run snakemake --cores all)")
    page = tmp_path / "report.html"
    run = subprocess.run(
        [sys.executable, "-m", "snakemake", "--report", str(page)],
        check=False,
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert run.returncode == 0, run.stderr[-2000:]
    html = page.read_text(encoding="utf-8")
    assert "System Message" not in html and "system-message" not in html
    assert "(WARNING/" not in run.stderr
