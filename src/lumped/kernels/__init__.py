"""Layer 3, the compiled kernels and their Python bindings.

The C sources sit here: ``_kernel.c`` (Algorithm 1's loop), ``_batch_kernel.c``
with its vector loop ``_batch_lanes.h`` (many parameter sets at once) and
``_network_kernel.c`` (the network step on a forest of links, with the
element graphs in ``_network_elements.h`` and the elimination in
``_network_forest.h``) and ``_friction_kernel.c`` (backward Euler for one mass
with a friction contact, the block on a belt).  They share ``_stick.h`` (the stick test and
corrector, once in C), ``_sine.h`` (the project's sine) and
``_binding_checks.h``; ``_batch_block.h`` is the batched kernel's block of
trajectories, read by its scalar code and its vector loop alike.  No header
uses a name defined by the file that includes it.  :mod:`~lumped.kernels.batched`,
:mod:`~lumped.solvers.network_compiled` and :mod:`~lumped.solvers.friction_compiled`
call them, each with a NumPy or Python twin that gives the same numbers when the
compiler is missing (the friction loop's twin is the network's Python step).
"""
