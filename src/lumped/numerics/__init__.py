"""Layer 0, numerics that know nothing of mechanics.

* :mod:`~lumped.numerics.validate`: the checks of every user input, each
  failing with one line;
* :mod:`~lumped.numerics.sine`: the project's sine, the twin of the compiled
  kernels' ``_sine.h`` (the same bits on every machine);
* :mod:`~lumped.numerics.roots`: the one root finder (Brent's method) and its
  tolerances;
* :mod:`~lumped.numerics.dop853` and :mod:`~lumped.numerics.dop853_tableau`:
  the Dormand-Prince 8(5,3) integrator of the slip phases;
* :mod:`~lumped.numerics.arclength`: the predictor of pseudo-arclength
  continuation (the forced orbits' and the limit cycles').
"""
