"""The website's source folder (scripts/site_source.py): pages follow the pipeline's lists.

Fast checks of the page writer on the repository's own captions and README and
on a small made-up pipeline; the built site itself is tested in a browser by
tests/test_site.py (slow).
"""

import importlib.util
import json
import re

import pytest
from conftest import ROOT


def load_site_source():
    """scripts/site_source.py as a module (it is a Snakemake script, not a package module)."""
    spec = importlib.util.spec_from_file_location("site_source", ROOT / "scripts" / "site_source.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


S = load_site_source()
CAPTIONS = sorted((ROOT / "report").glob("[a-z]*[0-9][0-9].rst"))  # every figure's caption (fig, ext, acc, st)


def test_every_figure_of_the_pipeline_has_a_caption_here():
    stems = {p.stem for p in CAPTIONS}
    assert {"fig01", "ext01", "acc01", "st01"} <= stems and len(stems) >= 24, sorted(stems)


@pytest.mark.parametrize("path", CAPTIONS, ids=lambda p: p.stem)
def test_a_caption_is_clean_restructuredtext(path):
    """The site and the report parse captions as reStructuredText, where ``|x|`` is a
    substitution: a caption that docutils warns about breaks the site's -W build."""
    from docutils.core import publish_doctree

    settings = {"report_level": 2, "halt_level": 5, "warning_stream": False}  # keep level >= 2 messages
    doctree = publish_doctree(path.read_text(encoding="utf-8"), settings_overrides=settings)
    messages = [n.astext() for n in doctree.findall() if n.tagname in ("system_message", "problematic")]
    assert not messages, messages


@pytest.mark.parametrize("path", CAPTIONS, ids=lambda p: p.stem)
def test_a_caption_splits_at_its_first_sentence(path):
    """Title = the first sentence ("Figure N of the paper", "Tutorial figure extNN ...", "Study figure stNN ..."),
    whole text kept."""
    caption = S.split_caption(path.read_text(encoding="utf-8"))
    kind, number = path.stem[:-2], path.stem[-2:]
    expected = {
        "fig": f"Figure {int(number)} of the paper",
        "ext": f"Tutorial figure ext{number}",
        "acc": f"Tutorial figure acc{number}",
        "st": f"Study figure st{number}",
        "dh": f"Study figure dh{number}",
        "sp": f"Study figure sp{number}",
        "rc": f"Tutorial figure rc{number}",
        "fit": f"Tutorial figure fit{number}",
        "fr": f"Tutorial figure fr{number}",
        "cy": f"Tutorial figure cy{number}",
        "bk": f"Study figure bk{number}",
    }[kind]
    assert caption.title.startswith(expected)
    flat = " ".join(caption.text.split())
    assert flat.startswith(caption.title + ". ")
    assert caption.summary and caption.summary in flat
    assert caption.text == path.read_text(encoding="utf-8").strip()


def test_a_sentence_does_not_end_at_an_equation_number():
    """'eq. (6)' inside the second sentence does not end it."""
    caption = S.split_caption("Figure 1 of the paper. The dashpot, eq. (6), read both ways. More.")
    assert caption[:2] == ("Figure 1 of the paper", "The dashpot, eq. (6), read both ways.")


@pytest.mark.parametrize(
    "source, markdown, expected",
    [
        ("README.md", "see [`figures/README.md`](figures/README.md)", "see [`figures/README.md`](figures/index.md)"),
        ("README.md", "the [article](paper/README.md#build)", "the [article](article.md)"),
        ("paper/README.md", "[figures](../figures/README.md)", "[figures](figures/index.md)"),
        ("README.md", "[setup.py](setup.py) and [x](src/lumped/laws/contract.py)", "setup.py and x"),
        ("README.md", "[home](https://example.org/lumped)", "[home](https://example.org/lumped)"),
        ("README.md", "[below](#the-package)", "[below](#the-package)"),
        ("README.md", "[`book/guide/cli.md`](book/guide/cli.md)", "[`book/guide/cli.md`](guide/cli.md)"),
        ("README.md", "[conf](book/conf.py)", "conf"),
    ],
)
def test_links_point_at_site_pages_or_become_text(source, markdown, expected):
    """A repository file the site shows becomes its page; another loses its link; URLs and anchors stay."""
    assert S.rewrite_links(markdown, source) == expected


def test_the_overview_is_the_readme_before_its_first_section():
    """The title line dropped, everything up to the first ``##`` kept."""
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    overview = S.readme_overview(readme)
    assert not overview.startswith("#") and "## " not in overview
    assert overview.strip() in readme and overview.split()[0] == readme.split("\n## ")[0].split()[2]


def make_pipeline_outputs(root, notebook_figures):
    """A made-up repository with the files the page writer reads, for the given notebooks and figures."""
    for folder in ("results/notebooks", "figures", "report", "paper"):
        (root / folder).mkdir(parents=True)
    for notebook, stems in notebook_figures.items():
        title = {"cell_type": "markdown", "source": [f"# Notebook {notebook[:2]}\n", "Text."]}
        (root / "results" / "notebooks" / f"{notebook}.ipynb").write_text(json.dumps({"cells": [title]}))
        for stem in stems:
            (root / "figures" / f"{stem}.png").write_bytes(b"png")
            (root / "figures" / f"{stem}.pdf").write_bytes(b"pdf")
            (root / "report" / f"{stem[:5]}.rst").write_text(f"Tutorial figure {stem[:5]}. What {stem} shows.\n")
    (root / "README.md").write_text("# lumped\n\nThe overview.\n\n## Set-up\n\nSee [figures](figures/README.md).\n")
    (root / "paper" / "metadata.yaml").write_text("title: T\nreplication:\n  cite: C\n")
    (root / "paper" / "paper.pdf").write_bytes(b"pdf")
    (root / "book").symlink_to(ROOT / "book", target_is_directory=True)


def test_a_new_notebook_and_figure_get_pages_without_an_edit(tmp_path):
    """A notebook 09 drawing ext07, added to the pipeline's list only, is in the tutorial and has a figure page."""
    pytest.importorskip("mathjax", reason="django-static-mathjax is not installed (environment-pip.txt)")
    notebook_figures = {"01_first": [], "09_new": ["ext07_new_thing"], "02_second": ["fig01_one"]}
    make_pipeline_outputs(tmp_path, notebook_figures)
    out = tmp_path / "site-src"
    captions = {stem: tmp_path / "report" / f"{stem[:5]}.rst" for stems in notebook_figures.values() for stem in stems}
    docs = S.write_source(
        out, notebook_figures, tmp_path / "results/notebooks", tmp_path / "figures", captions, tmp_path
    )
    assert {"tutorial/09_new", "figures/ext07_new_thing", "figures/fig01_one"} <= set(docs)
    index = (out / "index.md").read_text()
    assert re.findall(r"^tutorial/\S+", index, flags=re.MULTILINE) == [
        "tutorial/01_first",
        "tutorial/09_new",
        "tutorial/02_second",
    ]  # the order of the pipeline's list, not alphabetical
    page = (out / "figures" / "ext07_new_thing.rst").read_text()
    assert page.startswith("Tutorial figure ext07\n=====================\n")
    assert ":doc:`/tutorial/09_new`" in page and "What ext07_new_thing shows." in page
    figures_index = (out / "figures" / "index.md").read_text()
    assert "## Notebook 09\n\nDrawn by the notebook {doc}`/tutorial/09_new`:" in figures_index
    assert "{doc}`ext07_new_thing`: What ext07_new_thing shows." in figures_index
    assert (
        out / "readme.md"
    ).read_text() == "# README\n\nThe overview.\n\n## Set-up\n\nSee [figures](figures/index.md).\n"
    assert (out / "_static" / "mathjax" / "tex-chtml.js").is_file() and (out / "conf.py").is_file()


GUIDE = sorted((ROOT / "book" / "guide").glob("*.md"))


def test_the_guide_index_lists_every_guide_page_once():
    """book/guide/index.md's toctree names each page of book/guide/ (Sphinx -W refuses a page in no toctree)."""
    index = (ROOT / "book" / "guide" / "index.md").read_text(encoding="utf-8")
    listed = re.search(r"```\{toctree\}\n(?::.*\n)*\n(.*?)```", index, flags=re.DOTALL).group(1).split()
    assert sorted(listed) == sorted(p.stem for p in GUIDE if p.stem != "index")


def test_the_guide_pages_are_documents_of_the_site():
    """write_source returns the guide's pages with the rest, and the home page's toctree reaches the guide."""
    assert S.guide_pages(ROOT / "book") == sorted(f"guide/{p.stem}" for p in GUIDE)
    assert "guide/index" in S.index_page("# lumped\n\nOverview.\n", ["01_first"])


@pytest.mark.parametrize("page", GUIDE, ids=lambda p: p.stem)
def test_a_guide_page_links_only_to_pages_of_the_site(page):
    """A relative link of a guide page names a page of the guide, or a page the site writes (figures, article)."""
    links = re.findall(r"\]\(([^)\s]+)\)", page.read_text(encoding="utf-8"))
    written = {"../figures/index.md", "../article.md"}
    relative = [link.split("#")[0] for link in links if ":" not in link and not link.startswith("#")]
    assert [link for link in relative if link not in written and not (page.parent / link).is_file()] == []


def load_book_conf():
    """book/conf.py as a module (Sphinx reads it as a file; it holds the site's code formatter)."""
    spec = importlib.util.spec_from_file_location("book_conf", ROOT / "book" / "conf.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


CODE = 'def f(x):\n    return "<a & b>"  # a comment\n\n        # deeper\nprint(f(1))\n'


@pytest.mark.parametrize("lexer", ["python", "text"])
def test_code_is_written_a_span_per_line_with_its_indent(lexer):
    """Each line of highlighted code is one ``<span class="line">`` holding that line, with its leading spaces as
    ``--indent`` (book/_static/code.css hangs a wrapped line's continuation from it); the newlines lie outside the
    spans, and the text of the block, tags removed, is the code as written (so what a reader copies is the code)."""
    import html

    from pygments import highlight
    from pygments.lexers import get_lexer_by_name

    conf = load_book_conf()
    written = highlight(CODE, get_lexer_by_name(lexer), conf.LineSpanFormatter())
    pre = re.search(r"<pre>(.*)</pre>", written, flags=re.DOTALL).group(1)
    assert html.unescape(re.sub(r"<[^>]*>", "", pre)) == CODE
    lines = re.findall(
        r'<span class="line"(?: style="--indent: (\d+)ch")?>((?:(?!<span class="line").)*?)</span>\n', pre
    )
    texts = [html.unescape(re.sub(r"<[^>]*>", "", body)) for _, body in lines]
    assert texts == CODE.splitlines()
    assert [int(indent or 0) for indent, _ in lines] == [0, 4, 0, 8, 0]
