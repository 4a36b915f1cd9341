"""Study "the Burridge-Knopoff chain" (notebook 17, ``results/studies/burridge_knopoff.csv``): Carlson and Langer's
uniform chain of blocks on a velocity-weakening floor, run by backward Euler, and its catalogue of slip events.

The model (Carlson and Langer, Phys. Rev. Lett. 62 (1989) 2632; Phys. Rev. A 40 (1989) 6470), in their
dimensionless variables (time in units of ``1/omega_p``, ``omega_p = sqrt(k_p/m)``; displacement in units of
``D_0 = F_0/k_p``, ``F_0`` the static friction force)::

    U_j'' = l^2 (U_{j+1} - 2 U_j + U_{j-1}) - U_j - phi(2 alpha (nu + U_j'))

with ``U_j = X_j - nu t`` block ``j``'s displacement from its leaf spring's point on the plate, ``l^2 = k_c/k_p``
(coupling over leaf stiffness), ``nu`` the plate speed and ``phi`` the friction over ``F_0``: ``phi(0) = 1`` at
rest (a stuck block holds any force up to 1) and, sliding, ``phi(y) = sign(y)/(1 + |y|)`` in ``y = 2 alpha v``.
What was read, and what is recalled (notebook 17 quotes them): the PRA's first page (the chain "in contact with
a moving rough surface", so that the friction sees ``nu + U_j'``; size distributions "consistent with the
Gutenberg-Richter law"); the Clark University teaching page (``l``, ``alpha``, ``nu``, the defaults
``l = 10, alpha = 2.5, nu = 0.01``, and that the 1989 PRA's friction "allows the block to move in both
directions", a drop ``sigma`` from the static to the dynamic friction and motion in one direction only coming
with their 1991 PRA); and a public teaching code (github ``larashores/burridgeknopoffsimulator``, read in code),
which sums exactly the three terms above with ``phi(y) = sign(y)/(1 + |y|)``.  Recalled, not read: the 1991
law's form ``phi(y) = (1 - sigma)/(1 + y/(1 - sigma))``, the moment's definition, CL's exponent and boundary
condition.

In this repository's units (:class:`Parameters`): ``m``, ``k_p`` and ``F_0`` are given (1 kg, 1 N/m, 1 N by
default, so that the units are CL's), the coupling springs are ``k_c = l^2 k_p``, the plate (a
:class:`~lumped.model.network.Driver`) moves at ``V = nu D_0 omega_p`` and each block's floor contact is a
:class:`~lumped.laws.Friction` with ``static = F_0``, ``kinetic = 0``, ``decay = "rational"`` (``1/(1 + x)``)
and ``stribeck_velocity = F_0 omega_p/(2 alpha k_p)``.  That is exactly the law the teaching code uses (the
velocity unit ``D_0 omega_p`` turns ``2 alpha v`` into ``v/v_s``), symmetric as the teaching page says the 1989
law is (whether that law had a drop could not be read); the 1991 law's
drop ``sigma > 0`` has no place in ``Friction`` (its sliding force starts at ``static``) and its ban on backward
slip none either, so this study runs ``sigma = 0`` and counts the steps with a block moving backwards
(:attr:`Catalogue.back_steps`).  And backward Euler (first order, dissipative at ``omega dt`` of order one)
stands for their integrator, as notebook 17 says.

The catalogue (:func:`catalogue`): a block *slips* in step ``n`` when its velocity ``v_n`` is not zero (backward
Euler's stuck contacts give exactly zero); an *event* is a connected cluster of slipping (block, step) cells,
neighbours being the same block in consecutive steps and adjacent blocks (across the ends for a periodic chain)
in the same step -- a burst that starts where some block breaks away and ends where every block of it has stuck
again, and two bursts far apart in the chain at the same time are two events.  For each event: ``blocks`` (the
number of distinct blocks that slipped), ``moment`` (CL's as recalled: the sum over the event's blocks of their
slips, in units of ``D_0``; here the sum of ``x_n - x_{n-1}`` over its cells), ``duration`` (its number of steps times
``dt``, in units of ``1/omega_p``) and where and when it started.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import NamedTuple

import numpy as np
from scipy import ndimage

from lumped.drivers.simulation import solve
from lumped.laws import Friction, Spring
from lumped.model.network import Driver, Mass, Network
from lumped.model.problem import Problem
from lumped.numerics import validate
from lumped.numerics.roots import brentq
from lumped.numerics.union_find import UnionFind
from lumped.studies import read_csv

__all__ = [
    "COLUMNS",
    "ENDS",
    "Catalogue",
    "Cataloguer",
    "Parameters",
    "PowerLaw",
    "Run",
    "catalogue",
    "catalogue_table",
    "chain",
    "fit_power_law",
    "initial_positions",
    "read_catalogue",
    "run",
    "run_facts",
]

#: The catalogue file's columns, in order (``*_block`` and ``blocks`` are integers).
COLUMNS = ("start_time", "plate", "first_block", "blocks", "moment", "duration")
#: The chain's ends: ``free`` (the end blocks have one coupling spring) or ``periodic`` (a ring).
ENDS = ("free", "periodic")


@dataclass(frozen=True)
class Parameters:
    """Carlson and Langer's chain (see the module docstring for the mapping).

    Parameters
    ----------
    blocks : int
        ``N >= 1``.
    ell : float
        ``l = sqrt(k_c/k_p)`` (> 0).
    alpha : float
        The friction's decay, ``phi = 1/(1 + 2 alpha v)`` in CL's velocity unit (> 0).
    nu : float
        The plate's speed in CL's velocity unit ``D_0 omega_p`` (> 0).
    mass : float, kg
    leaf : float, N/m
        ``k_p``, the leaf spring to the plate.
    static : float, N
        ``F_0``, the friction force a stuck block holds.
    ends : str
        One of :data:`ENDS`.
    """

    blocks: int = 1000
    ell: float = 10.0
    alpha: float = 2.5
    nu: float = 0.01
    mass: float = 1.0
    leaf: float = 1.0
    static: float = 1.0
    ends: str = "free"

    def __post_init__(self) -> None:
        object.__setattr__(self, "blocks", validate.positive_int("blocks", self.blocks))
        for name in ("ell", "alpha", "nu", "mass", "leaf", "static"):
            object.__setattr__(self, name, validate.positive(name, getattr(self, name)))
        if self.ends not in ENDS:
            raise ValueError(f"ends must be one of {', '.join(ENDS)}, not {self.ends!r:.40}")

    @property
    def omega(self) -> float:
        """``omega_p = sqrt(k_p/m)`` (rad/s): CL's time unit is ``1/omega_p``."""
        return math.sqrt(self.leaf / self.mass)

    @property
    def length(self) -> float:
        """``D_0 = F_0/k_p`` (m), CL's displacement unit."""
        return self.static / self.leaf

    @property
    def coupling(self) -> float:
        """``k_c = l^2 k_p`` (N/m)."""
        return self.ell**2 * self.leaf

    @property
    def plate_speed(self) -> float:
        """``V = nu D_0 omega_p`` (m/s)."""
        return self.nu * self.length * self.omega

    @property
    def stribeck_velocity(self) -> float:
        """``v_s = D_0 omega_p/(2 alpha)`` (m/s): ``1/(1 + v/v_s)`` is CL's ``1/(1 + 2 alpha v)``."""
        return self.length * self.omega / (2.0 * self.alpha)


def chain(p: Parameters, x0: np.ndarray, v0: np.ndarray | None = None) -> Network:
    """The chain as a :class:`Network`: blocks ``b0..b{N-1}`` at ``x0`` (m) with ``v0`` (m/s), the plate ``"plate"``.

    Block ``j`` has a leaf spring ``leaf{j}`` to the plate and a friction contact ``floor{j}`` to the ground;
    ``c{j}`` joins ``b{j}`` to ``b{j+1}`` (and ``b{N-1}`` to ``b0`` for a periodic chain of 3 or more blocks).
    """
    n = p.blocks
    x0 = np.broadcast_to(np.asarray(x0, dtype=float), (n,))
    v0 = np.zeros(n) if v0 is None else np.broadcast_to(np.asarray(v0, dtype=float), (n,))
    masses = [Mass(f"b{j}", p.mass, float(x0[j]), float(v0[j])) for j in range(n)]
    elements = []
    for j in range(n):
        elements.append(Spring(f"leaf{j}", ("plate", f"b{j}"), p.leaf))
        elements.append(
            Friction(
                f"floor{j}",
                ("ground", f"b{j}"),
                static=p.static,
                kinetic=0.0,
                stribeck_velocity=p.stribeck_velocity,
                decay="rational",
            )
        )
    pairs = [(j, j + 1) for j in range(n - 1)] + ([(n - 1, 0)] if p.ends == "periodic" and n >= 3 else [])
    elements += [Spring(f"c{i}", (f"b{i}", f"b{j}"), p.coupling) for i, j in pairs]
    return Network(masses, elements, drivers=[Driver("plate", p.plate_speed)])


@dataclass(frozen=True)
class Catalogue:
    """Slip events, one entry per event in order of their start (arrays of equal length).

    Attributes
    ----------
    start_time : ndarray, s
        The time of the step before the event's first (its blocks all stuck).
    first_block : ndarray of int
        The lowest-numbered block slipping in the event's first step.
    blocks : ndarray of int
        Distinct blocks that slipped.
    moment : ndarray, m
        Sum of the event's slips (``x_n - x_{n-1}`` over its cells).
    duration : ndarray, s
        Steps of the event times ``dt``.
    unfinished : int
        Events still slipping at the end of the data (left out of the arrays).
    back_steps : int
        (block, step) cells with a negative velocity (backward slip: the 1989 law allows it, the 1991 law forbids it).
    slip_steps : int
        (block, step) cells with a velocity other than zero.
    """

    start_time: np.ndarray
    first_block: np.ndarray
    blocks: np.ndarray
    moment: np.ndarray
    duration: np.ndarray
    unfinished: int = 0
    back_steps: int = 0
    slip_steps: int = 0

    def __len__(self) -> int:
        return len(self.blocks)


def _labels(slipping: np.ndarray, periodic: bool) -> tuple[np.ndarray, int]:
    """Connected clusters of ``slipping`` (steps x blocks), 4-neighbours, joined across the ends if ``periodic``."""
    labels, count = ndimage.label(slipping)
    if not (periodic and slipping.shape[1] >= 3 and count):
        return labels, count
    sets = UnionFind(count + 1)
    for a, b in zip(labels[:, 0], labels[:, -1]):
        ra, rb = sets.find(int(a)), sets.find(int(b))
        if a and b and ra != rb:
            sets.attach(max(ra, rb), min(ra, rb))
    final = np.array([sets.find(a) for a in range(count + 1)])
    _, relabel = np.unique(final, return_inverse=True)
    labels = relabel[labels]
    return labels, int(relabel.max())


class _Scan:
    """The events of one buffer of rows: those complete inside it, and the first row an open one needs.

    ``seen``: the buffer's rows before it were scanned already (a buffer kept from ``keep_from`` of the last
    one): an event that ends before it was counted then.  No other event touches the buffer's first row
    except one that began before the data (the argument is in notebook 17).
    """

    def __init__(self, t: np.ndarray, x: np.ndarray, v: np.ndarray, periodic: bool, seen: int = 0) -> None:
        labels, _ = _labels(v != 0, periodic)
        self.table: dict[str, list] = {c: [] for c in COLUMNS if c != "plate"}
        self.keep_from = len(t) - 1  # the row the next buffer starts at (the last one when nothing is open)
        self.left_out = 0  # events slipping in the first row: they began before the data
        self.open = 0  # events still slipping in the last row
        for k, box in enumerate(ndimage.find_objects(labels), start=1):
            rows, cols = box
            mine = labels[box] == k
            first, last = rows.start, rows.stop - 1  # the event's first and last slipping rows
            if last < seen:  # complete in the rows scanned before: already counted
                continue
            if first == 0:
                self.left_out += 1
                continue
            if last == len(t) - 1:
                self.keep_from = min(self.keep_from, first - 1)
                self.open += 1
                continue
            dx = np.diff(x[first - 1 : last + 1, cols], axis=0)
            self.table["start_time"].append(t[first - 1])
            self.table["first_block"].append(cols.start + int(np.argmax(mine[0])))
            self.table["blocks"].append(int(mine.any(axis=0).sum()))
            self.table["moment"].append(float(dx[mine].sum()))
            self.table["duration"].append(t[last] - t[first - 1])


def catalogue(t: np.ndarray, x: np.ndarray, v: np.ndarray, periodic: bool = False) -> Catalogue:
    """The slip events of a trajectory sampled at every step: ``t`` (S,), ``x`` and ``v`` (S, N).

    The first row is the state before the first step.  An event slipping in the first row (it started before
    the data) or in the last (it ends after them) is unfinished and left out of the arrays.
    """
    t, x, v = np.asarray(t, float), np.asarray(x, float), np.asarray(v, float)
    scan = _Scan(t, x, v, periodic)
    return _as_catalogue(scan.table, scan.left_out + scan.open, int((v[1:] < 0).sum()), int((v[1:] != 0).sum()))


def _as_catalogue(table: Mapping[str, list], unfinished: int, back_steps: int, slip_steps: int) -> Catalogue:
    """The events of ``table`` in order of their start (ties by first block)."""
    start, block = np.asarray(table["start_time"], float), np.asarray(table["first_block"], int)
    order = np.lexsort((block, start))
    return Catalogue(
        start_time=start[order],
        first_block=block[order],
        blocks=np.asarray(table["blocks"], int)[order],
        moment=np.asarray(table["moment"], float)[order],
        duration=np.asarray(table["duration"], float)[order],
        unfinished=unfinished,
        back_steps=back_steps,
        slip_steps=slip_steps,
    )


def initial_positions(p: Parameters, seed: int = 0, roughness: float = 1e-3) -> np.ndarray:
    """Blocks at rest behind their leaf springs' points by ``roughness D_0`` times a uniform number in [0, 1).

    The chain is uniform, so without this small disorder every block would move as one; ``roughness`` must
    leave every block stuck (``l^2 roughness < 1/2`` is enough).
    """
    roughness = validate.positive("roughness", roughness)
    if p.ell**2 * roughness >= 0.5:
        raise ValueError(f"roughness must be below 1/(2 l^2) = {0.5 / p.ell**2:g}, not {roughness!r}")
    return -p.length * roughness * np.random.default_rng(seed).random(p.blocks)


class Run(NamedTuple):
    """A run of the chain: its :class:`Catalogue`, its steps, end time (s) and final state (m from the plate's point, m/s)."""

    catalogue: Catalogue
    steps: int
    t_end: float
    positions: np.ndarray
    velocities: np.ndarray


class Cataloguer:
    """The catalogue of a trajectory given in pieces (:meth:`add`), holding only the rows an open event needs.

    After each piece, the events complete in the rows held are counted (those that end before the rows
    scanned at the last piece were counted then) and the rows before the first open event's start dropped.
    """

    def __init__(self, t0: float, x0: np.ndarray, v0: np.ndarray, periodic: bool = False) -> None:
        self.t, self.x, self.v = np.array([t0], float), np.array(x0, float)[None, :], np.array(v0, float)[None, :]
        self.periodic, self.seen, self.back, self.slips, self.open, self.left_out = periodic, 0, 0, 0, 0, 0
        self.table: dict[str, list] = {c: [] for c in COLUMNS if c != "plate"}

    def add(self, t: np.ndarray, x: np.ndarray, v: np.ndarray) -> None:
        """The rows after those given so far: ``t`` (S,), ``x`` and ``v`` (S, N)."""
        self.t = np.concatenate([self.t, t])
        self.x, self.v = np.vstack([self.x, x]), np.vstack([self.v, v])
        self.back += int((np.asarray(v) < 0).sum())
        self.slips += int((np.asarray(v) != 0).sum())
        scan = _Scan(self.t, self.x, self.v, self.periodic, self.seen)
        for c, values in scan.table.items():
            self.table[c] += values
        self.t, self.x, self.v = self.t[scan.keep_from :], self.x[scan.keep_from :], self.v[scan.keep_from :]
        self.seen, self.open, self.left_out = len(self.t) - 1, scan.open, self.left_out + scan.left_out

    def catalogue(self) -> Catalogue:
        """The events complete so far; those still slipping are counted as ``unfinished``."""
        return _as_catalogue(self.table, self.open + self.left_out, self.back, self.slips)


def run(p: Parameters, travel: float, dt: float, *, x0: np.ndarray | None = None, segment: int | None = None) -> Run:
    """Run the chain by backward Euler while the plate travels ``travel`` (in ``D_0``), and catalogue its events.

    The run is cut into pieces of ``segment`` steps (by default about 10^6 block-steps), each a
    :func:`lumped.solve` of the chain restarted from the last state with every position taken from the plate's
    (the chain is invariant under a common shift, so only rounding differs from one long run), so that
    the memory stays bounded; the events are found across the cuts (:class:`Cataloguer`).  ``x0`` (m, from
    the plate's point at ``t = 0``) defaults to :func:`initial_positions`.
    """
    travel = validate.positive("travel", travel)
    steps = validate.step_count(travel * p.length / p.plate_speed, dt)
    segment = max(100, 1_000_000 // p.blocks) if segment is None else validate.positive_int("segment", segment)
    x = initial_positions(p) if x0 is None else np.asarray(x0, float)
    v, done = np.zeros(p.blocks), 0
    events = Cataloguer(0.0, x, v, p.ends == "periodic")
    while done < steps:
        shift = p.plate_speed * done * dt
        piece = solve(Problem(chain(p, x - shift, v), min(segment, steps - done) * dt), dt, method="backward-euler")
        n = len(piece.t) - 1
        x, v = piece.positions[-1] + shift, piece.velocities[-1]
        # times from step numbers, so that the cuts leave them be
        events.add(dt * np.arange(done + 1, done + n + 1), piece.positions[1:] + shift, piece.velocities[1:])
        done += n
    return Run(events.catalogue(), done, done * dt, x - p.plate_speed * done * dt, v)


def catalogue_table(p: Parameters, events: Catalogue) -> dict[str, np.ndarray]:
    """The catalogue as the columns of :data:`COLUMNS`, in CL's units (``1/omega_p``, ``D_0``)."""
    return {
        "start_time": events.start_time * p.omega,
        "plate": events.start_time * p.plate_speed / p.length,
        "first_block": events.first_block,
        "blocks": events.blocks,
        "moment": events.moment / p.length,
        "duration": events.duration * p.omega,
    }


def read_catalogue(path: str | Path) -> dict[str, np.ndarray]:
    """A catalogue file written by the pipeline (:data:`COLUMNS`), ``first_block`` and ``blocks`` as integers."""
    table = read_csv(path, COLUMNS)
    return {c: table[c].astype(np.int64) if c in ("first_block", "blocks") else table[c] for c in COLUMNS}


def run_facts(p: Parameters, travel: float, dt: float, result: Run) -> dict[str, float | int | str]:
    """What a catalogue file does not say about its run: the parameters, the events left out, back steps."""
    return {
        "blocks": p.blocks,
        "ell": p.ell,
        "alpha": p.alpha,
        "nu": p.nu,
        "ends": p.ends,
        "travel": travel,
        "dt": dt,
        "steps": result.steps,
        "events": len(result.catalogue),
        "unfinished": result.catalogue.unfinished,
        "back_steps": result.catalogue.back_steps,
        "slip_steps": result.catalogue.slip_steps,
    }


class PowerLaw(NamedTuple):
    """A power law ``p(s) ~ s^-exponent`` on ``[low, high]`` fitted by maximum likelihood to ``count`` sizes.

    ``stderr`` is the standard error from the Fisher information (``1/sqrt(count Var[ln s])`` at the estimate).
    """

    exponent: float
    stderr: float
    count: int
    low: float
    high: float


def _log_moments(beta: float, width: float) -> tuple[float, float]:
    """Mean and variance of ``y`` with density ``~ exp(-beta y)`` on ``[0, width]`` (``width`` may be inf)."""
    if math.isinf(width):
        return 1.0 / beta, 1.0 / beta**2
    z = beta * width
    if abs(z) < 1e-4:  # series: the closed form loses digits to cancellation
        return width * (0.5 - z / 12.0), width**2 * (1.0 / 12.0 - z**2 / 720.0)
    e = math.expm1(z)
    return 1.0 / beta - width / e, 1.0 / beta**2 - width**2 * (e + 1.0) / e**2


def fit_power_law(sizes: Iterable[float], low: float, high: float = math.inf) -> PowerLaw:
    """The maximum-likelihood exponent of a power law for the ``sizes`` in ``[low, high]``.

    With ``y = ln(s/low)`` the law is an exponential of rate ``beta = exponent - 1`` truncated to
    ``[0, ln(high/low)]``; the likelihood's maximum is where its mean equals the sample's mean of ``y``
    (Brent's method; without ``high``, Hill's ``beta = 1/mean(y)``).
    """
    low = validate.positive("low", low)
    high = validate.positive_or_inf("high", high)
    if high <= low:
        raise ValueError(f"high = {high!r} must exceed low = {low!r}")
    s = np.asarray(list(sizes), float)
    y = np.log(s[(s >= low) & (s <= high)] / low)
    if y.size < 2 or not y.any():
        raise ValueError(f"fewer than 2 distinct sizes in [{low!r}, {high!r}]: no exponent")
    width, mean = math.log(high / low), float(y.mean())
    if math.isinf(width):
        beta = 1.0 / mean
    else:
        if not 0.0 < mean < width:
            raise ValueError("the sizes sit on an end of the range: no exponent")
        f = lambda b: _log_moments(b, width)[0] - mean  # decreasing in b
        lo, hi = -1.0, 1.0
        while f(lo) < 0:
            lo *= 2
        while f(hi) > 0:
            hi *= 2
        beta = brentq(f, lo, hi, xtol=1e-14)
    return PowerLaw(1.0 + beta, 1.0 / math.sqrt(y.size * _log_moments(beta, width)[1]), int(y.size), low, high)
