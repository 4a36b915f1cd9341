# A sweep of a system file's parameters (issue 35, `sweep --system`), split into
# chunks, one Snakemake job each (wildcard {chunk}, `sweep --chunk I/N`),
# merged in grid order by a final rule; through profiles/cluster each chunk is
# a SLURM job.  Not part of `all` (no notebook reads it yet):
#   snakemake --cores 2 results/sweeps/two_blocks.csv
#   snakemake --profile profiles/cluster results/sweeps/two_blocks.csv
# Included by the Snakefile after rules/common.smk.

#: The sweep: the system file, its --vary texts (entry.key=START:STOP:COUNT, the first slowest), the grid.
SYSTEM_SWEEP = {
    "system": "examples/two_blocks.toml",
    "vary": ["fric.static=1.5:4.5:8", "m1.x0=0.1:0.6:4"],
    "t_end": 3.0,
    "dt": 1.0e-3,
}
#: Chunks of the sweep's 32 rows (8 each: some 5 to 10 s a job).
SYSTEM_SWEEP_CHUNKS = 4


rule sweep_system_chunk:
    """Rows {chunk} of SYSTEM_SWEEP_CHUNKS of the two-block sweep: python -m lumped sweep --system --chunk."""
    input:
        system=SYSTEM_SWEEP["system"],
        package=PACKAGE_SOURCES,
    output:
        "results/sweeps/two_blocks/chunk-{chunk}.csv",
    wildcard_constraints:
        chunk=r"\d+",
    params:
        vary=" ".join(f"--vary {v}" for v in SYSTEM_SWEEP["vary"]),
        grid=f"--t-end {SYSTEM_SWEEP['t_end']!r} --dt {SYSTEM_SWEEP['dt']!r}",
        chunks=SYSTEM_SWEEP_CHUNKS,
    log:
        "logs/sweeps/two_blocks-{chunk}.log",
    shell:
        "python -m lumped sweep --system {input.system} {params.vary} {params.grid}"
        " --chunk {wildcards.chunk}/{params.chunks} --output {output} > {log} 2>&1"


rule sweep_system:
    """Merge the chunks, in grid order, into results/sweeps/two_blocks.csv (the whole sweep's file, byte for byte)."""
    input:
        script="scripts/merge_chunks.py",
        chunks=expand("results/sweeps/two_blocks/chunk-{chunk}.csv", chunk=range(SYSTEM_SWEEP_CHUNKS)),
    output:
        "results/sweeps/two_blocks.csv",
    log:
        "logs/sweeps/two_blocks.log",
    shell:
        "python {input.script} {output} {input.chunks} > {log} 2>&1"
