# Rebuild every figure of the paper (and, once rules/paper.smk exists, the article).
#   snakemake --cores all                      # figures/figNN_*.pdf and .png
#   snakemake --cores all --config dt=1e-3     # same with another time step
#   snakemake --report report.html             # browsable report with captions
# Rules live in rules/*.smk; figures/README.md lists what each figure shows.
import os

configfile: "config/config.yaml"


report: "report/workflow.rst"


include: "rules/common.smk"
include: "rules/figures.smk"


PAPER_RULES = os.path.join(workflow.basedir, "rules", "paper.smk")
if os.path.exists(PAPER_RULES):

    include: "rules/paper.smk"


rule all:
    default_target: True
    input:
        figures=FIGURE_FILES,
        paper=["paper/paper.pdf"] if os.path.exists(PAPER_RULES) else [],
