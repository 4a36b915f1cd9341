"""Layer 2, the model: what a problem is, independent of how it is solved.

* :mod:`~lumped.model.oscillator`: the paper's system (one mass, a spring, a
  dashpot) and the magnitude checks every method shares;
* :mod:`~lumped.model.network`: masses, loads and the :class:`Network` of
  elements, with its well-posedness check;
* :mod:`~lumped.model.forcing`: the loads (sine, constant, table, sums);
* :mod:`~lumped.model.tables`: load histories read from CSV files;
* :mod:`~lumped.model.parameters`: every parameter's name, default, unit,
  range and help, in one table;
* :mod:`~lumped.model.files`: system files (TOML); :mod:`~lumped.model.repeated`: their
  ``count = N`` tables;
* :mod:`~lumped.model.problem`: :class:`Problem`, a system over a span, which every
  method takes, and the one-mass form of a network;
* :mod:`~lumped.model.trajectory`: what every run returns, for one mass or many,
  with the events.
"""
