"""Layer 5, the drivers: what a user calls to run a problem.

* :mod:`~lumped.drivers.methods`: the one registry of methods;
* :mod:`~lumped.drivers.simulation`: :func:`~lumped.solve`, the one entry
  point (any problem by any registered method), and its shims
  :func:`~lumped.simulate` and :func:`~lumped.simulate_network`;
* :mod:`~lumped.drivers.network` and :mod:`~lumped.drivers.one_mass`:
  backward Euler on any network (checked here, marched by
  :mod:`lumped.solvers.backward_euler_network`), and a one-mass run written
  back on its network;
* :mod:`~lumped.drivers.sweep`: many runs at once.
"""
