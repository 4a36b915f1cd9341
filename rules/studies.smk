# The studies of issue 12 (results/studies/): each is split into chunks, one
# Snakemake job per chunk (wildcard {chunk}), merged by a final rule; the
# study's notebook reads the merged CSV.
#   snakemake --cores 2 results/studies/rest.csv                      # default resolution
#   snakemake --cores 2 results/studies/rest.csv --config studies=full  # the figures' resolution
# Included by the Snakefile after rules/common.smk and rules/figures.smk.
# `snakemake --lint` waiver (conda/container per rule): see rules/figures.smk.

import lumped.studies


def study_chunks(name):
    """Chunk files of study `name` at the build's resolution (its module's CHUNKS)."""
    count = lumped.studies.study(name).CHUNKS[config["studies"]]
    return expand("results/studies/{name}/chunk-{chunk}.csv", name=name, chunk=range(count))



rule study_rest_chunk:
    """Rows {chunk} of REST_CHUNKS of the x0 grid (lumped.studies.rest): Algorithm 1 at the paper's dt and the exact solver.

    The physics comes from config/config.yaml as committed (the paper's
    values), whatever --config overrides: the study is about the paper's
    system, and notebook 10 says so.  Only the resolution, `studies`, is
    taken from the build's configuration (params: a change reruns the chunks).
    """
    input:
        script="scripts/study.py",
        config="config/config.yaml",
        package=PACKAGE_SOURCES,
    output:
        "results/studies/rest/chunk-{chunk}.csv",
    wildcard_constraints:
        chunk=r"\d+",
    params:
        resolution=config["studies"],
        chunks=lambda wildcards: lumped.studies.study("rest").CHUNKS[config["studies"]],
    log:
        "logs/studies/rest-{chunk}.log",
    shell:
        "python {input.script} chunk rest {input.config} {params.resolution} {wildcards.chunk} {params.chunks}"
        " {output} > {log} 2>&1"


rule study_rest:
    """Merge the chunks, in grid order, into results/studies/rest.csv."""
    input:
        script="scripts/study.py",
        chunks=study_chunks("rest"),
    output:
        "results/studies/rest.csv",
    log:
        "logs/studies/rest.log",
    shell:
        "python {input.script} merge rest {output} {input.chunks} > {log} 2>&1"


rule study_den_hartog_chunk:
    """Rows {chunk} of the (damping, F/P, r) grid of lumped.studies.den_hartog: long exact runs and the closed form.

    Like the rest study, the physics is config/config.yaml as committed (m, k,
    tau and the paper's gamma for the combined damping), whatever --config
    overrides; only the resolution, `studies`, comes from the build.
    """
    input:
        script="scripts/study.py",
        config="config/config.yaml",
        package=PACKAGE_SOURCES,
    output:
        "results/studies/den_hartog/chunk-{chunk}.csv",
    wildcard_constraints:
        chunk=r"\d+",
    params:
        resolution=config["studies"],
        chunks=lambda wildcards: lumped.studies.study("den_hartog").CHUNKS[config["studies"]],
    log:
        "logs/studies/den_hartog-{chunk}.log",
    shell:
        "python {input.script} chunk den_hartog {input.config} {params.resolution} {wildcards.chunk} {params.chunks}"
        " {output} > {log} 2>&1"


rule study_den_hartog:
    """Merge the chunks, in grid order, into results/studies/den_hartog.csv."""
    input:
        script="scripts/study.py",
        chunks=study_chunks("den_hartog"),
    output:
        "results/studies/den_hartog.csv",
    log:
        "logs/studies/den_hartog.log",
    shell:
        "python {input.script} merge den_hartog {output} {input.chunks} > {log} 2>&1"


rule study_stops_chunk:
    """Rows {chunk} of the (r, F/P) grid of lumped.studies.stops: exact Coulomb runs, stops counted from events.

    Like the rest study, the physics (m, k and the friction force F) comes from
    config/config.yaml as committed, whatever --config overrides (notebook 12
    says so); only the resolution, `studies`, is the build's.
    """
    input:
        script="scripts/study.py",
        config="config/config.yaml",
        package=PACKAGE_SOURCES,
    output:
        "results/studies/stops/chunk-{chunk}.csv",
    wildcard_constraints:
        chunk=r"\d+",
    params:
        resolution=config["studies"],
        chunks=lambda wildcards: lumped.studies.study("stops").CHUNKS[config["studies"]],
    log:
        "logs/studies/stops-{chunk}.log",
    shell:
        "python {input.script} chunk stops {input.config} {params.resolution} {wildcards.chunk} {params.chunks}"
        " {output} > {log} 2>&1"


rule study_stops:
    """Merge the chunks, in grid order, into results/studies/stops.csv."""
    input:
        script="scripts/study.py",
        chunks=study_chunks("stops"),
    output:
        "results/studies/stops.csv",
    log:
        "logs/studies/stops.log",
    shell:
        "python {input.script} merge stops {output} {input.chunks} > {log} 2>&1"


rule study_stops_low_chunk:
    """Rows {chunk} of the (r < 0.1, F/P) grid of lumped.studies.stops_low: periodic motions by shooting.

    The stops map continued to low frequency (notebook 12), with the physics
    of config/config.yaml as committed, as study_stops_chunk.
    """
    input:
        script="scripts/study.py",
        config="config/config.yaml",
        package=PACKAGE_SOURCES,
    output:
        "results/studies/stops_low/chunk-{chunk}.csv",
    wildcard_constraints:
        chunk=r"\d+",
    params:
        resolution=config["studies"],
        chunks=lambda wildcards: lumped.studies.study("stops_low").CHUNKS[config["studies"]],
    log:
        "logs/studies/stops_low-{chunk}.log",
    shell:
        "python {input.script} chunk stops_low {input.config} {params.resolution} {wildcards.chunk} {params.chunks}"
        " {output} > {log} 2>&1"


rule study_stops_low:
    """Merge the chunks, in grid order, into results/studies/stops_low.csv."""
    input:
        script="scripts/study.py",
        chunks=study_chunks("stops_low"),
    output:
        "results/studies/stops_low.csv",
    log:
        "logs/studies/stops_low.log",
    shell:
        "python {input.script} merge stops_low {output} {input.chunks} > {log} 2>&1"


rule study_burridge_knopoff:
    """Carlson and Langer's chain (lumped.studies.burridge_knopoff): its catalogue of slip events.

    Unlike the studies above, it follows --config: bk_blocks blocks while the plate travels bk_travel
    (in D_0) at the step bk_dt.  The defaults are the short run CI builds; the full run is one override,
    snakemake --cores 2 results/studies/burridge_knopoff.csv --config bk_blocks=1000 bk_travel=20.
    The values are params (not the configuration file), so that other overrides do not rerun it.
    """
    input:
        script="scripts/burridge_knopoff.py",
        package=PACKAGE_SOURCES,
    output:
        catalogue="results/studies/burridge_knopoff.csv",
        facts="results/studies/burridge_knopoff.json",
    params:
        blocks=int(config["bk_blocks"]),
        travel=repr(float(config["bk_travel"])),
        dt=repr(float(config["bk_dt"])),
    log:
        "logs/studies/burridge_knopoff.log",
    shell:
        "python {input.script} {params.blocks} {params.travel} {params.dt} {output.catalogue} > {log} 2>&1"
