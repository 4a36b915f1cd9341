"""Snakemake script: write the effective configuration (config/config.yaml after
any ``--config`` overrides) to the rule's output, for the notebooks to read via
``$LUMPED_CONFIG``.

The rule passes the configuration as a parameter, so Snakemake's ``params``
rerun trigger reruns it (and everything downstream) only when a value changes.
"""

from pathlib import Path

import yaml

snakemake = globals()["snakemake"]  # injected by Snakemake's script directive
target = Path(snakemake.output[0])
values = dict(snakemake.params.values)
header = "# Written by the Snakemake rule effective_config; do not edit.\n"
target.write_text(header + yaml.safe_dump(values, sort_keys=True), encoding="utf-8")
Path(snakemake.log[0]).write_text(f"wrote {target}: {values}\n", encoding="utf-8")
