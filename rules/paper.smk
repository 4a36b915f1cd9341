# The article: numbers from the package, then the PDF from paper/paper.typ.
#   snakemake --cores all paper/paper.pdf
# Included by the Snakefile after rules/common.smk and rules/figures.smk, whose
# FIGURE_FILES, PACKAGE_SOURCES and effective_config rule it uses; it falls
# back to a file pattern when included on its own.
from glob import glob as _paper_glob


def _paper_figures():
    """The 14 figure PNGs the article shows (figures/figNN_<slug>.png)."""
    try:
        files = FIGURE_FILES  # rules/common.smk: the pipeline's own names
    except NameError:  # included alone: whatever matches the pattern now
        files = _paper_glob("figures/fig[0-9][0-9]_*.png")
    return sorted(f for f in files if f.endswith(".png"))


def _paper_config():
    """The configuration after --config overrides, when the pipeline provides it."""
    try:
        return rules.effective_config.output[0]
    except (NameError, AttributeError):
        return "config/config.yaml"


def _package_sources():
    try:
        return PACKAGE_SOURCES
    except NameError:
        return sorted(_paper_glob("src/lumped/**/*.py", recursive=True))


rule paper_numbers:
    """Every number of the article, computed from the package (scripts/paper_numbers.py)."""
    input:
        script="scripts/paper_numbers.py",
        config=_paper_config(),
        package=_package_sources(),
    output:
        "paper/build/numbers.json",
    log:
        "logs/paper_numbers.log",
    shell:
        "LUMPED_CONFIG={input.config} python {input.script} {output} > {log} 2>&1"


rule paper:
    """Typeset paper/paper.typ with the typst Python package (byte-reproducible)."""
    input:
        script="scripts/build_paper.py",
        typ="paper/paper.typ",
        numbers=rules.paper_numbers.output[0],
        metadata="paper/metadata.yaml",
        deviations="paper/deviations.yaml",
        references="paper/references.yaml",
        figures=_paper_figures(),
    output:
        pdf="paper/paper.pdf",
    log:
        "logs/paper.log",
    shell:
        "python {input.script} --out {output.pdf} {input.figures} > {log} 2>&1"
