"""Snakemake script: write the effective configuration (config/config.yaml after
any ``--config`` overrides) to the rule's output, for the notebooks to read via
``$LUMPED_CONFIG``.

The rule passes the configuration, checked and written as canonical YAML by
``rules/common.smk``, as a parameter, so Snakemake's ``params`` rerun trigger
reruns it (and everything downstream) only when a value changes.
"""

from pathlib import Path

snakemake = globals()["snakemake"]  # injected by Snakemake's script directive
target = Path(snakemake.output[0])
text = snakemake.params.text
header = "# Written by the Snakemake rule effective_config; do not edit.\n"
target.write_text(header + text, encoding="utf-8")
Path(snakemake.log[0]).write_text(f"wrote {target}:\n{text}", encoding="utf-8")
