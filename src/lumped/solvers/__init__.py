"""Layer 4, the solvers: one module per method, named after it.

* :mod:`~lumped.solvers.backward_euler`: Algorithm 1 (the ``backward-euler``
  method) and the generic backward-Euler loop for any law;
* :mod:`~lumped.solvers.theta`: the ``theta`` method (the θ-method);
* :mod:`~lumped.solvers.event_capturing`: the ``event-locating`` scheme;
* :mod:`~lumped.solvers.grid`: what those two fixed-step schemes share (the
  grid's checks);
* :mod:`~lumped.solvers.exact`: the ``exact`` piecewise solution, with its
  closed-form slip phases in :mod:`~lumped.solvers.closed_form` (and
  :mod:`~lumped.solvers.closed_form_belt`, the closed-form stick-slip cycle
  of a block on a belt that ``exact`` and backward Euler are tested against);
* :mod:`~lumped.solvers.event_driven`: the ``event-driven`` method (slip
  phases integrated, events located);
* :mod:`~lumped.solvers.events`: the one event machinery (events, phases,
  switching rules, the march through phases) of the last three;
* :mod:`~lumped.solvers.textbook`: the ``sgn(0) = 0`` model of the textbooks;
* :mod:`~lumped.solvers.network_step`: backward Euler's step for a network
  (active set), and :mod:`~lumped.solvers.backward_euler_network` its time
  loop (in Python, or block by block in the compiled kernel).
"""
