"""Sphinx configuration of the tutorial's website (``snakemake --cores all site``).

The stack is Jupyter Book 1's engine, Sphinx with myst-nb and the book theme,
configured here directly (``book/guide/website.md``, the site's page "The
website", says why not its ``jupyter-book`` command). ``scripts/site_source.py`` copies this file into the generated source
folder ``results/site-src/`` with ``_static/`` (the site's icon and one script)
beside the pages it writes; ``rules/site.smk`` runs
``sphinx-build -W --keep-going`` on that folder.

Everything a page needs is served from the site itself: MathJax is copied into
``_static/mathjax`` from the ``django-static-mathjax`` wheel (pinned in
environment-pip.txt), and every feature of the theme that would reach another
host (launch buttons, Thebe, repository and issue buttons, comments, analytics)
is left off.
"""

from docutils import nodes
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
html_favicon = "_static/favicon.svg"
# Runs MathJax on the search results (see setup below for their titles).
html_js_files = ["search-math.js"]
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


class MathTitlesHTMLBuilder(StandaloneHTMLBuilder):
    """Sphinx's HTML builder, giving the search index titles whose math MathJax can find.

    Sphinx indexes a page under its title's plain text, in which a formula
    (notebook 02's "sgn(0) = 0") is bare TeX with no delimiters; the search
    page would show it as such. Only the displayed title changes; the words
    searched for are collected from the page as before.
    """

    def index_page(self, pagename: str, doctree: nodes.document, title: str) -> None:
        node = self.env.longtitles.get(pagename)
        super().index_page(pagename, doctree, tex_text(node) if node is not None and title else title)


def setup(app) -> None:
    """Load MathJax on every page, and index titles with their math delimited.

    MathJax is loaded even where a page's body has no math: the navigation bar
    shows notebook titles with mathematics (notebook 02's "sgn(0) = 0") on
    every page, and would show them as raw TeX without it.
    """
    app.set_html_assets_policy("always")
    app.add_builder(MathTitlesHTMLBuilder, override=True)
