# The article: numbers from the package, its convergence figure, then the PDF
# from paper/paper.typ (which embeds the figures' PDFs, vector graphics).
#   snakemake --cores all paper/paper.pdf
# Included by the Snakefile after rules/common.smk and rules/figures.smk, whose
# PAPER_FIGURE_PDFS, PACKAGE_SOURCES and effective_config rule it uses, and after
# rules/accuracy.smk (the accuracy study and its figure).
# `snakemake --lint` waiver (conda/container per rule): see rules/figures.smk.
rule paper_numbers:
    """Every number and verdict of the article (lumped.studies.replication, via scripts/paper_numbers.py)."""
    input:
        script="scripts/paper_numbers.py",
        config=rules.effective_config.output[0],
        package=PACKAGE_SOURCES,
    output:
        "paper/build/numbers.json",
    log:
        "logs/paper_numbers.log",
    shell:
        "LUMPED_CONFIG={input.config} python {input.script} {output} > {log} 2>&1"


rule paper_figures:
    """The article's convergence figure, drawn from numbers.json (scripts/paper_figures.py)."""
    input:
        script="scripts/paper_figures.py",
        numbers=rules.paper_numbers.output[0],
        package=PACKAGE_SOURCES,
    output:
        "paper/build/convergence.pdf",
    log:
        "logs/paper_figures.log",
    shell:
        "python {input.script} {input.numbers} {output} > {log} 2>&1"


rule paper:
    """Typeset paper/paper.typ with the typst Python package (byte-reproducible)."""
    input:
        script="scripts/build_paper.py",
        typ="paper/paper.typ",
        format="paper/format.typ",
        numbers=rules.paper_numbers.output[0],
        metadata="paper/metadata.yaml",
        deviations="paper/deviations.yaml",
        references="paper/references.yaml",
        figures=PAPER_FIGURE_PDFS,
        convergence=rules.paper_figures.output[0],
        accuracy=rules.accuracy_figure.output[0],
        study=rules.accuracy_study.output[0],
    output:
        pdf="paper/paper.pdf",
    log:
        "logs/paper.log",
    shell:
        "python {input.script} --out {output.pdf} {input.figures} > {log} 2>&1"
