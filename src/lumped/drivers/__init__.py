"""Layer 5, the drivers: what a user calls to run a problem.

* :mod:`~lumped.drivers.methods`: the one registry of methods;
* :mod:`~lumped.drivers.simulation`: :func:`~lumped.simulate`, one mass by
  any registered method;
* :mod:`~lumped.drivers.network` and :mod:`~lumped.drivers.one_mass`:
  :func:`~lumped.simulate_network`, a system file's network (checked here,
  marched by :mod:`lumped.solvers.backward_euler_network`);
* :mod:`~lumped.drivers.sweep`: many runs at once.
"""
