"""Build the optional compiled kernels and the packaged copy of the paper's values.

Everything else is in pyproject.toml.  The kernels are Algorithm 1's loop
(``_kernel.c``), the same loop over many parameter sets at once
(``_batch_kernel.c``, with OpenMP), the network step on a forest of links
or one loop of links (``_network_kernel.c``) and backward Euler for one mass
with a friction contact (``_friction_kernel.c``).  If the C compiler is missing, the extensions are
skipped (``optional=True``) and ``lumped`` runs the pure-Python loops:
Algorithm 1's gives the same numbers, the network step's the same up to the
rounding of its linear solve, the friction loop's the same up to its root solve.

``config/config.yaml`` stays the one file holding the paper's values (the
Snakefile and the users edit it); :class:`build_py` copies it into the built
package as ``lumped/paper_config.yaml``, which ``lumped.studies.config.load()`` reads
when the package is installed without its checkout.  MANIFEST.in puts the file
into the sdist, so a wheel built from the sdist carries it too.
"""

import os

from setuptools import Extension, setup
from setuptools.command.build_py import build_py as _build_py

CONFIG = os.path.join("config", "config.yaml")
PACKAGED = os.path.join("lumped", "studies", "paper_config.yaml")


class build_py(_build_py):
    """``build_py`` that also copies ``config/config.yaml`` into the package."""

    def run(self) -> None:
        super().run()
        if self.editable_mode:  # an editable install reads the checkout's file
            return
        if not os.path.isfile(CONFIG):
            raise FileNotFoundError(f"{CONFIG} is missing: the package must carry the paper's values")
        self.copy_file(CONFIG, os.path.join(self.build_lib, PACKAGED))

    def get_outputs(self, include_bytecode: bool = True) -> list[str]:
        extra = [] if self.editable_mode else [os.path.join(self.build_lib, PACKAGED)]
        return super().get_outputs(include_bytecode) + extra


setup(
    cmdclass={"build_py": build_py},
    ext_modules=[
        Extension(
            f"lumped.kernels.{name}",
            [f"src/lumped/kernels/{name}.c"],
            depends=depends,
            extra_compile_args=["-O2", "-ffp-contract=off", "-fno-fast-math"],
            optional=True,
        )
        for name, depends in (
            (
                "_kernel",
                ["src/lumped/kernels/_binding_checks.h", "src/lumped/kernels/_sine.h", "src/lumped/kernels/_stick.h"],
            ),
            ("_friction_kernel", ["src/lumped/kernels/_binding_checks.h", "src/lumped/kernels/_slip_curve.h"]),
            (
                "_network_kernel",
                [
                    "src/lumped/kernels/_binding_checks.h",
                    "src/lumped/kernels/_network_curve.h",
                    "src/lumped/kernels/_network_elements.h",
                    "src/lumped/kernels/_network_forest.h",
                    "src/lumped/kernels/_network_loop.h",
                    "src/lumped/kernels/_network_sparse.h",
                    "src/lumped/kernels/_network_active_set.h",
                    "src/lumped/kernels/_slip_curve.h",
                    "src/lumped/kernels/_stick.h",
                ],
            ),
        )
    ]
    + [
        # the batched Algorithm 1: both cores through OpenMP, and -O3 for the
        # vectorised loop over trajectories; still no contraction (bit-identity)
        Extension(
            "lumped.kernels._batch_kernel",
            ["src/lumped/kernels/_batch_kernel.c"],
            depends=[  # its block layout, its vector loop (once per instruction set), the sine, the stick test
                "src/lumped/kernels/_batch_block.h",
                "src/lumped/kernels/_batch_lanes.h",
                "src/lumped/kernels/_sine.h",
                "src/lumped/kernels/_stick.h",
            ],
            extra_compile_args=["-O3", "-fopenmp", "-ffp-contract=off", "-fno-fast-math", "-Wno-psabi"],
            extra_link_args=["-fopenmp"],
            optional=True,
        )
    ],
)
