"""Layer 4, the solvers: one module per method, named after it.

* :mod:`~lumped.solvers.backward_euler`: Algorithm 1 (the ``backward-euler``
  method) and the generic backward-Euler loop for any law;
* :mod:`~lumped.solvers.schemes`: the ``theta`` and ``event-capturing`` schemes;
* :mod:`~lumped.solvers.exact`: the ``exact`` piecewise solution;
* :mod:`~lumped.solvers.event_driven`: the ``event-driven`` method (slip
  phases integrated, events located);
* :mod:`~lumped.solvers.textbook`: the ``sgn(0) = 0`` model of the textbooks;
* :mod:`~lumped.solvers.network_step`: backward Euler's step for a network
  (active set).
"""
