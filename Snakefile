# Rebuild every figure of the paper, the executed notebooks and the article.
#   snakemake --cores all                      # figures/figNN_*.pdf and .png
#   snakemake --cores all --config dt=1e-3     # same with another time step
#   snakemake --report report.html             # browsable report with captions
#   snakemake --cores all site                 # the website, results/site/index.html
# Rules live in rules/*.smk; figures/README.md lists what each figure shows.
configfile: "config/config.yaml"


report: "report/workflow.rst"


include: "rules/common.smk"
include: "rules/figures.smk"
include: "rules/accuracy.smk"
include: "rules/studies.smk"
include: "rules/sweeps.smk"
include: "rules/paper.smk"
include: "rules/site.smk"


rule all:
    default_target: True
    input:
        figures=FIGURE_FILES,
        notebooks=EXECUTED_NOTEBOOKS,
        paper=rules.paper.output.pdf,
