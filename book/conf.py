"""Sphinx configuration of the tutorial's website (``snakemake --cores all site``).

The stack is Jupyter Book 1's engine, Sphinx with myst-nb and the book theme,
configured here directly (``book/guide/website.md``, the site's page "The
website", says why not its ``jupyter-book`` command). ``scripts/site_source.py`` copies this file into the generated source
folder ``results/site-src/`` with ``_static/`` (the site's icon, a script and
the code's style sheet) and ``_templates/`` (two of the theme's components,
left out of the search page) beside the pages it writes; ``rules/site.smk``
runs ``sphinx-build -W --keep-going`` on that folder.

Code, in notebook cells and on the other pages, wraps its long lines on a
hanging indent instead of scrolling sideways (``LineSpanFormatter`` below and
``_static/code.css``), and each page shows one way to search: the sidebar's
field on a wide window, the article header's icon on a narrow one, the search
page's own form on that page.

Everything a page needs is served from the site itself: MathJax is copied into
``_static/mathjax`` from the ``django-static-mathjax`` wheel (pinned in
environment-pip.txt), and every feature of the theme that would reach another
host (launch buttons, Thebe, repository and issue buttons, comments, analytics)
is left off.
"""

import html
import re

from docutils import nodes
from pygments.formatters import HtmlFormatter
from sphinx.builders.html import StandaloneHTMLBuilder

project = "lumped"
author = "the lumped contributors"
copyright = "the lumped contributors"

extensions = ["myst_nb"]
exclude_patterns = ["_build", "**.ipynb_checkpoints"]
# The generated source holds only the site's pages; `root_doc` is its index.
root_doc = "index"

# -- Notebooks: shown as the pipeline executed them, never run again ---------
nb_execution_mode = "off"
# A notebook's stderr (a warning printed by a library) is shown, not dropped.
nb_output_stderr = "show"
# $...$, $$...$$ and \begin{align} in Markdown cells and pages.
myst_enable_extensions = ["dollarmath", "amsmath"]
# $$...$$ inside a paragraph is display math too, as Jupyter renders it (the
# notebooks write equations within paragraphs); without this MyST pairs the
# dollars wrongly and leaves TeX as text.
myst_dmath_double_inline = True
myst_heading_anchors = 3

# -- Mathematics: a local MathJax 3 ------------------------------------------
# A path without a scheme is relative to _static (Sphinx's rule for mathjax_path).
mathjax_path = "mathjax/tex-chtml.js"

# -- HTML: the book theme with every remote feature off -----------------------
html_theme = "sphinx_book_theme"
html_title = "lumped"
html_static_path = ["_static"]
# Two of the theme's components, left out of the search page (see the files).
templates_path = ["_templates"]
html_favicon = "_static/favicon.svg"
# Runs MathJax on the search results (see setup below for their titles).
html_js_files = ["search-math.js"]
# Long lines of code wrap on a hanging indent (see LineSpanFormatter).
html_css_files = ["code.css"]
# The theme's colour mode ("auto": follow the reader's system) set in the page:
# without it a first visit (nothing stored yet) logs "Got invalid theme mode".
html_context = {"default_mode": "auto"}
html_theme_options = {
    "use_download_button": True,
    "use_fullscreen_button": True,
    "use_repository_button": False,
    "use_issues_button": False,
    "use_edit_page_button": False,
    "use_source_button": False,
    "launch_buttons": {},
    "show_toc_level": 2,
    "navigation_with_keys": False,
    # One way to search at any width: the sidebar's field on wide windows, the
    # article header's icon on narrow ones (the search page has its own form
    # instead, _templates/). The book theme leaves the top bar empty, but
    # pydata-sphinx-theme 0.20 puts a search field there unless this option is
    # given, which made a bar holding a second search field above the sidebar's.
    "navbar_persistent": [],
}
# No date in the pages: a rebuild from the same notebooks changes nothing.
html_last_updated_fmt = None
html_show_sphinx = False


def tex_text(node: nodes.Node) -> str:
    """The text of a title with its mathematics between ``\\(`` and ``\\)``, for MathJax."""
    if isinstance(node, nodes.math):
        return f"\\({node.astext()}\\)"
    if isinstance(node, nodes.Text):
        return str(node)
    return "".join(tex_text(child) for child in node.children)


#: An HTML tag, in the markup Pygments writes for a line.
TAG = re.compile(r"<[^>]*>")


class LineSpanFormatter(HtmlFormatter):
    """Pygments' HTML formatter with each line in a ``<span class="line">``, for wrapping.

    ``_static/code.css`` makes the span an inline-block as wide as the
    block, so a long line wraps on a hanging indent: its continuation starts
    four characters deeper than the line itself, whose leading spaces are
    given as ``--indent`` (in ``ch``). The newline stays outside the span, so
    the text of the block, and what a reader copies, is the code as written.
    """

    def wrap(self, source):
        """Put each line of ``source`` (Pygments' ``(1, line)`` pairs) in its span, then wrap as usual."""
        return super().wrap(self.line_spans(source))

    @staticmethod
    def line_spans(source):
        """Yield each line of code in a ``<span class="line">``, its newline after the span."""
        for is_code, line in source:
            if not is_code:
                yield is_code, line
                continue
            body, newline = (line[:-1], "\n") if line.endswith("\n") else (line, "")
            text = html.unescape(TAG.sub("", body))
            indent = len(text) - len(text.lstrip(" "))
            style = f' style="--indent: {indent}ch"' if indent else ""
            yield is_code, f'<span class="line"{style}>{body}</span>{newline}'


class SiteHTMLBuilder(StandaloneHTMLBuilder):
    """Sphinx's HTML builder, writing code a line per span and indexing titles with delimited math.

    Code: see LineSpanFormatter. Titles: Sphinx indexes a page under its
    title's plain text, in which a formula (notebook 02's "sgn(0) = 0") is
    bare TeX with no delimiters; the search page would show it as such. Only
    the displayed title changes; the words searched for are collected from
    the page as before.
    """

    def init_highlighter(self) -> None:
        """Sphinx's highlighter, writing code with a span per line (LineSpanFormatter)."""
        super().init_highlighter()
        self.highlighter.formatter = LineSpanFormatter

    def index_page(self, pagename: str, doctree: nodes.document, title: str) -> None:
        node = self.env.longtitles.get(pagename)
        super().index_page(pagename, doctree, tex_text(node) if node is not None and title else title)


def setup(app) -> None:
    """Load MathJax on every page; the HTML builder with its two changes (SiteHTMLBuilder).

    MathJax is loaded even where a page's body has no math: the navigation bar
    shows notebook titles with mathematics (notebook 02's "sgn(0) = 0") on
    every page, and would show them as raw TeX without it.
    """
    app.set_html_assets_policy("always")
    app.add_builder(SiteHTMLBuilder, override=True)
