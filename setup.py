"""Build the optional compiled kernel; everything else is in pyproject.toml.

If the C compiler is missing, the extension is skipped (``optional=True``) and
``lumped`` runs the pure-Python loop, which gives the same numbers.
"""

from setuptools import Extension, setup

setup(
    ext_modules=[
        Extension(
            "lumped._kernel",
            ["src/lumped/_kernel.c"],
            extra_compile_args=["-O2", "-ffp-contract=off", "-fno-fast-math"],
            optional=True,
        )
    ]
)
