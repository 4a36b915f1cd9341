# The figures: each notebook is executed once and writes its figures.
#
# `snakemake --lint` waiver: it asks for a conda environment or container per
# rule. This project runs in one virtual environment made from
# environment-pip.txt (see README.md), so the rules name none; the executed
# notebooks record the kernel they ran with.


rule effective_config:
    """config/config.yaml after any --config overrides, for the notebooks.

    The checked values, as canonical YAML text (rules/common.smk), are a
    parameter: the params rerun trigger reruns this rule (and the notebooks)
    only when a value changes, not when an override repeats the default.
    """
    output:
        "results/config.yaml",
    params:
        text=CONFIG_TEXT,
    log:
        "logs/effective_config.log",
    script:
        "../scripts/write_config.py"


# One rule per notebook (a notebook writes several figures whose names do not
# share a wildcard pattern).
for _notebook in NOTEBOOK_FIGURES:

    rule:
        name:
            f"notebook_{_notebook[:2]}"
        input:
            notebook=f"notebooks/{_notebook}.py",
            config=rules.effective_config.output[0],
            runner="scripts/run_notebook.py",
            package=PACKAGE_SOURCES,
            data=NOTEBOOK_DATA.get(_notebook, []),
        output:
            executed=f"results/notebooks/{_notebook}.ipynb",
            figures=notebook_outputs(_notebook),
        log:
            f"logs/notebooks/{_notebook}.log",
        # Start the notebooks that draw the most figures first (figures are most of a
        # notebook's run time): on 2 cores the longest jobs then do not finish alone.
        priority: len(NOTEBOOK_FIGURES[_notebook])
        shell:
            "python {input.runner} {input.notebook} --output {output.executed}"
            " --figures figures --config {input.config} > {log} 2>&1"
