"""Snakemake script: write the website's source folder from the pipeline's outputs.

The rule ``site_source`` (``rules/site.smk``) runs it; ``sphinx-build`` then
turns the folder into ``results/site/``. Nothing here is typed twice: the pages
follow the pipeline's own lists, so a notebook or figure added to
``NOTEBOOK_FIGURES`` (``rules/common.smk``) appears on the site without an edit
here.

The folder holds

* ``index.md``: the README's overview (its text before the first ``##``
  heading) and the tables of contents;
* ``tutorial/NN_name.ipynb``: the notebooks as the pipeline executed them
  (``results/notebooks/``), in the order of ``NOTEBOOK_FIGURES``; Sphinx shows
  their stored outputs and runs nothing;
* ``figures/index.md`` and one ``figures/<stem>.rst`` per figure: the PNG, the
  caption the Snakemake report uses (``CAPTIONS``, reStructuredText like the
  page, so it is pasted in as written), a link to the notebook that
  draws it and the vector PDF;
* ``article.md`` with ``paper.pdf``: the article's title, what it replicates
  (``paper/metadata.yaml``) and the PDF to download;
* ``readme.md``: the whole README, its links to repository files turned into
  links to the site's pages where there is one and into plain text otherwise;
* ``guide/index.md`` and the pages it lists: the guide and reference pages,
  written by hand in ``book/guide/`` (the README names each) and copied with
  the rest of ``book/``;
* a copy of ``book/`` (``conf.py``, ``_static/`` with the icon, a script and
  the code's style sheet, ``_templates/``) and ``_static/mathjax/``: MathJax 3
  from the ``django-static-mathjax`` package, so the pages render mathematics
  with no network.
"""

import json
import posixpath
import re
import shutil
from pathlib import Path
from typing import NamedTuple

import yaml

#: Repository files that the site shows as one of its pages (README links to them).
SITE_PAGE_OF = {"figures/README.md": "figures/index.md", "paper/README.md": "article.md"}
#: The folder of the site's source in the repository: ``book/<page>.md`` is the site's ``<page>.md``.
BOOK = "book/"
#: A Markdown inline link: [text](target).
LINK = re.compile(r"\[([^\]]+)\]\(([^)\s]+)\)")
#: The end of a caption's sentence: a full stop and a space, not after "eq", "eqs" or "Fig".
SENTENCE_END = re.compile(r"(?<!\beq)(?<!\beqs)(?<!\bFig)\.\s+")
#: Top-level files of MathJax's es5 folder that the site does not load (other combined builds).
MATHJAX_UNUSED = ("tex-mml-*.js", "tex-svg*.js", "mml-*.js", "tex-chtml-full*.js", "node-main.js", "latest.js")


class Caption(NamedTuple):
    """A figure caption for its page: ``title`` (first sentence), ``summary`` (second), ``text`` (as written)."""

    title: str
    summary: str
    text: str


def split_caption(text: str) -> Caption:
    """Title, summary and text of a caption ``"Figure 1 of the paper. The Bingham dashpot, ... ."``.

    Title and summary are on one line (line breaks become spaces); a caption
    of one sentence has an empty summary. The text is kept as written
    (reStructuredText, pasted into the figure's page).
    """
    parts = SENTENCE_END.split(" ".join(text.split()), maxsplit=2)
    title = parts[0].rstrip(".")
    summary = parts[1].rstrip(".") + "." if len(parts) > 1 and parts[1] else ""
    return Caption(title, summary, text.strip())


def rewrite_links(markdown: str, source: str) -> str:
    """Point the relative links of ``markdown`` (a repository file at ``source``) at site pages.

    A link to a page of the site (``SITE_PAGE_OF``, or a Markdown page in
    ``book/``) becomes a link to that page (relative to the site's root, where
    the rewritten file is placed); another
    relative link, to a file the site does not hold, keeps only its text; links
    with a scheme (``https:``) and anchors are left as they are.
    """

    def replace(match: re.Match) -> str:
        text, target = match.groups()
        if ":" in target or target.startswith("#"):
            return match.group(0)
        path = posixpath.normpath(posixpath.join(posixpath.dirname(source), target.split("#")[0]))
        page = SITE_PAGE_OF.get(path) or (path[len(BOOK) :] if path.startswith(BOOK) and path.endswith(".md") else None)
        return f"[{text}]({page})" if page else text

    return LINK.sub(replace, markdown)


def readme_overview(readme: str) -> str:
    """The README's text before its first ``##`` heading, its ``#`` title line dropped."""
    head = re.split(r"^## ", readme, maxsplit=1, flags=re.MULTILINE)[0]
    lines = head.splitlines()
    if lines and lines[0].startswith("# "):
        lines = lines[1:]
    return "\n".join(lines).strip() + "\n"


def toctree(entries: list[str], caption: str = "", hidden: bool = False) -> str:
    """A MyST ``toctree`` directive listing ``entries`` (document names without suffix)."""
    options = [":maxdepth: 1"]
    options += [f":caption: {caption}"] if caption else []
    options += [":hidden:"] if hidden else []
    return "```{toctree}\n" + "\n".join(options) + "\n\n" + "\n".join(entries) + "\n```\n"


def index_page(readme: str, notebooks: list[str]) -> str:
    """The home page: the README's overview, then the tutorial, the guide, the figures, the article, the README."""
    return "\n".join(
        [
            "# lumped\n",
            rewrite_links(readme_overview(readme), "README.md"),
            "The tutorial is meant to be read in order; the guide and reference pages take one subject",
            "each (set-up, the command line, system files, which method when, studies, benchmarks, ...);",
            "each figure of the paper and of the tutorial has a page with its caption and the notebook",
            "that draws it; the article replicates the paper with the package. Everything here was built",
            "from the repository by `snakemake --cores all site`.\n",
            toctree([f"tutorial/{name}" for name in notebooks], caption="Tutorial"),
            toctree(["guide/index"], caption="Guide and reference"),
            toctree(["figures/index", "article", "readme"], caption="Figures, article and README"),
        ]
    )


def figure_page(stem: str, notebook: str, caption: Caption) -> str:
    """One figure's page (reStructuredText): title, image, caption, notebook and PDF links."""
    title = caption.title
    return "\n".join(
        [
            title,
            "=" * len(title),
            "",
            f".. image:: {stem}.png",
            f"   :alt: {title}",
            "   :width: 100%",
            "",
            caption.text,
            "",
            f"Drawn by the notebook :doc:`/tutorial/{notebook}`. Vector version: :download:`{stem}.pdf`.",
            "",
        ]
    )


def notebook_title(path: Path) -> str:
    """The first ``#`` heading of the notebook at ``path`` (its page title), or its file name without one."""
    notebook = json.loads(path.read_text(encoding="utf-8"))
    for cell in notebook.get("cells", []):
        source = "".join(cell["source"]) if cell["cell_type"] == "markdown" else ""
        match = re.search(r"^# (.+)$", source, flags=re.MULTILINE)
        if match:
            return match.group(1).strip()
    return path.stem


def figures_index(notebook_figures: dict[str, list[str]], captions: dict[str, Caption], titles: dict[str, str]) -> str:
    """The figures' index: for each notebook that draws figures (``titles``: its title), its figures."""
    lines = [
        "# Figures\n",
        "Figures 1 to 14 of the paper (`figNN`) and the tutorial's own (`extNN`), each on a page with",
        "its caption, a link to the notebook that draws it and the figure as a vector PDF.\n",
    ]
    for notebook, stems in notebook_figures.items():
        if not stems:
            continue
        lines.append(f"## {titles[notebook]}\n")
        lines.append(f"Drawn by the notebook {{doc}}`/tutorial/{notebook}`:\n")
        lines += [f"- {{doc}}`{stem}`: {captions[stem].summary}" for stem in stems]
        lines += ["", toctree(stems, hidden=True)]
    return "\n".join(lines)


def article_page(metadata: dict, paper_stems: list[str]) -> str:
    """The article's page: title, what it replicates, the PDF, and its figures' pages."""
    figures = ", ".join(f"{{doc}}`{stem[3:5].lstrip('0')} <figures/{stem}>`" for stem in paper_stems)
    return "\n".join(
        [
            "# The article\n",
            f"*{metadata['title']}*: a replication, in the manner of ReScience C, of\n",
            f"> {metadata['replication']['cite']}\n",
            "Every number and verdict in it is computed by the package when the pipeline runs.\n",
            "{download}`Download the article (PDF) <paper.pdf>`\n",
            f"It embeds the paper's Figures {figures}.\n",
        ]
    )


def copy_mathjax(target: Path) -> None:
    """Copy MathJax 3's es5 folder from the ``mathjax`` package (django-static-mathjax) to ``target``."""
    import mathjax  # django-static-mathjax: MathJax's files, no Python code

    es5 = Path(mathjax.__file__).parent / "static" / "mathjax" / "es5"
    shutil.copytree(es5, target, ignore=shutil.ignore_patterns(*MATHJAX_UNUSED))


def write_source(
    out: Path,
    notebook_figures: dict[str, list[str]],
    executed: Path,
    figures: Path,
    captions: dict[str, Path],
    root: Path,
) -> list[str]:
    """Write the site's source folder ``out``; return the document names written.

    ``executed`` holds the executed notebooks, ``figures`` the PNG and PDF
    files, ``captions`` maps each figure to its caption file (``CAPTIONS`` of
    rules/common.smk), ``root`` is the repository (README.md,
    paper/metadata.yaml, paper/paper.pdf, book/).
    """
    shutil.copytree(root / "book", out, ignore=shutil.ignore_patterns("__pycache__"))
    (out / "tutorial").mkdir()
    (out / "figures").mkdir()
    copy_mathjax(out / "_static" / "mathjax")
    readme = (root / "README.md").read_text(encoding="utf-8")
    docs = ["index", "figures/index", "article", "readme"]
    (out / "index.md").write_text(index_page(readme, list(notebook_figures)), encoding="utf-8")
    text = rewrite_links(readme, "README.md").replace("# lumped\n", "# README\n", 1)
    (out / "readme.md").write_text(text, encoding="utf-8")
    for notebook in notebook_figures:
        shutil.copy(executed / f"{notebook}.ipynb", out / "tutorial" / f"{notebook}.ipynb")
        docs.append(f"tutorial/{notebook}")
    titles = {name: notebook_title(executed / f"{name}.ipynb") for name in notebook_figures}
    docs += write_figures(out / "figures", notebook_figures, figures, captions, titles)
    metadata = yaml.safe_load((root / "paper" / "metadata.yaml").read_text(encoding="utf-8"))
    paper_stems = [s for stems in notebook_figures.values() for s in stems if s.startswith("fig")]
    (out / "article.md").write_text(article_page(metadata, paper_stems), encoding="utf-8")
    shutil.copy(root / "paper" / "paper.pdf", out / "paper.pdf")
    return docs + guide_pages(root / "book")


def guide_pages(book: Path) -> list[str]:
    """The document names of the hand-written pages in ``book/guide/`` (copied with ``book/``)."""
    return sorted(f"guide/{page.stem}" for page in (book / "guide").glob("*.md"))


def write_figures(
    out: Path, notebook_figures: dict[str, list[str]], figures: Path, captions: dict[str, Path], titles: dict[str, str]
) -> list[str]:
    """Copy each figure's PNG and PDF to ``out``, write its page and the index; return the names."""
    split = {}
    for notebook, stems in notebook_figures.items():
        for stem in stems:
            split[stem] = split_caption(Path(captions[stem]).read_text(encoding="utf-8"))
            for ext in ("png", "pdf"):
                shutil.copy(figures / f"{stem}.{ext}", out / f"{stem}.{ext}")
            (out / f"{stem}.rst").write_text(figure_page(stem, notebook, split[stem]), encoding="utf-8")
    (out / "index.md").write_text(figures_index(notebook_figures, split, titles), encoding="utf-8")
    return [f"figures/{stem}" for stem in split]


def main(snakemake) -> None:
    """Run from the rule ``site_source``: inputs and parameters from Snakemake."""
    out = Path(snakemake.output[0])
    executed = Path(snakemake.input.notebooks[0]).parent
    figures = Path(snakemake.input.figures[0]).parent
    captions = snakemake.params.captions
    docs = write_source(out, snakemake.params.notebook_figures, executed, figures, captions, Path("."))
    Path(snakemake.log[0]).write_text("\n".join(["wrote", *docs, ""]), encoding="utf-8")


if __name__ == "__main__" and "snakemake" in globals():
    main(globals()["snakemake"])
