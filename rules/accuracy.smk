# The work-precision study (lumped.studies.accuracy): every method on five cases, written
# as strict JSON without wall times (results/accuracy/study.json, the same bytes
# from build to build), and the article's accuracy figure drawn from it.
#   snakemake --cores 1 results/accuracy/study.json
# Included by the Snakefile after rules/common.smk and rules/figures.smk.
# `snakemake --lint` waiver (conda/container per rule): see rules/figures.smk.
rule accuracy_study:
    """Run lumped.studies.accuracy.study at its default resolutions (about 15 s on one core).

    On config/config.yaml as committed, whatever --config overrides: the study
    compares methods on fixed cases, so it takes no configuration input and
    an override does not rerun it.
    """
    input:
        script="scripts/accuracy_study.py",
        params="config/config.yaml",
        package=PACKAGE_SOURCES,
    output:
        "results/accuracy/study.json",
    log:
        "logs/accuracy_study.log",
    shell:
        "python {input.script} {output} > {log} 2>&1"


rule accuracy_figure:
    """Convergence with reference slopes and work-precision (steps), for the article."""
    input:
        script="scripts/accuracy_figure.py",
        study=rules.accuracy_study.output[0],
        package=PACKAGE_SOURCES,
    output:
        "paper/build/accuracy.pdf",
    log:
        "logs/accuracy_figure.log",
    shell:
        "python {input.script} {input.study} {output} > {log} 2>&1"
