"""The compiled kernels' bindings refuse every bad argument with a one-line ``ValueError``.

``_kernel.bingham_block``, ``_network_kernel.network_block`` and
``_network_kernel.network_solve`` are private (the drivers build their
arrays), but a wrong count, length or item type would make the C loops read
or write past a buffer (``save_every = 0`` divided by zero, a short output
buffer was written past).  Each case below starts from arguments the drivers
would pass (checked to run), changes one, and requires a ``ValueError`` whose
one-line message names that argument.  Every call runs in a forked child, so
that a crash (SIGSEGV, SIGFPE) or a hang is reported as this test failing,
not as the end of the test run.
"""

from __future__ import annotations

import math
import os
import select
import signal

import numpy as np
import pytest
from test_network_kernel import tree

from lumped.solvers.backward_euler_network import _graphs, _sigma
from lumped.solvers import backward_euler
from lumped.solvers import network_compiled as kernel

_kernel = pytest.importorskip("lumped.kernels._kernel")
_network_kernel = pytest.importorskip("lumped.kernels._network_kernel")

#: How long a child may take (the valid calls take milliseconds).
TIMEOUT = 60.0


def outcome(call) -> tuple[str, str]:  # noqa: ANN001
    """Run ``call()`` in a forked child: ``("ok", "")``, ``(exception type, message)``,
    ``("signal", name)`` if the child died of a signal, or ``("timeout", "")``."""
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:  # the child: report and leave at once (no atexit, no pytest teardown)
        os.close(read)
        try:
            call()
            text = "ok\n"
        except BaseException as err:  # noqa: BLE001 (reported to the parent)
            text = f"{type(err).__name__}\n{err}"
        os.write(write, text.encode())
        os._exit(0)
    os.close(write)
    ready, _, _ = select.select([read], [], [], TIMEOUT)
    data = os.read(read, 1 << 16) if ready else b""
    if not ready:
        os.kill(pid, signal.SIGKILL)
    os.close(read)
    _, status = os.waitpid(pid, 0)
    if os.WIFSIGNALED(status) and ready:
        return "signal", signal.Signals(os.WTERMSIG(status)).name
    if not ready:
        return "timeout", ""
    kind, _, message = data.decode().partition("\n")
    return kind, message


def assert_refused(call, name: str) -> None:  # noqa: ANN001
    kind, message = outcome(call)
    assert (kind, name in message) == ("ValueError", True), (kind, message)
    assert "\n" not in message and message.startswith(name), message


# -- _kernel.bingham_block ------------------------------------------------------------
def block_args(**change: object) -> dict[str, object]:
    """Arguments of one block of 10 steps, all saved: released at x0 = 0.5 m, forced."""
    args: dict[str, object] = dict(
        m=1.0,
        k=100.0,
        dt=1e-3,
        tau=1.0,
        c=1.0,
        n_first=1,
        n_last=10,
        n_steps=10,
        save_every=1,
        amp=2.0,
        omega=3.0,
        phase=0.0,
        until=math.inf,
        force_values=np.empty(0),
        state=np.array([50.0, 0.0, 0.0]),
        counters=np.array([1, 0, 0, 0], dtype=np.int64),
        out=np.zeros((11, 6)),
    )
    args.update(change)
    return args


BLOCK_CASES = {  # case: (changed arguments, the name the message begins with)
    "save_every-0": (dict(save_every=0), "save_every"),
    "save_every-negative": (dict(save_every=-3), "save_every"),
    "n_first-negative": (dict(n_first=-1), "n_first"),
    "n_last-before-n_first": (dict(n_last=0), "n_last"),
    "n_steps-before-n_last": (dict(n_steps=5), "n_steps"),
    "m-0": (dict(m=0.0), "m"),
    "k-negative": (dict(k=-100.0), "k"),
    "dt-nan": (dict(dt=math.nan), "dt"),
    "tau-negative": (dict(tau=-1.0), "tau"),
    "c-inf": (dict(c=math.inf), "c"),
    "amp-nan": (dict(amp=math.nan), "amp"),
    "omega-inf": (dict(omega=math.inf), "omega"),
    "phase-nan": (dict(phase=math.nan), "phase"),
    "until-nan": (dict(until=math.nan), "until"),
    "force_values-length": (dict(force_values=np.ones(3)), "force_values"),
    "force_values-float32": (dict(force_values=np.ones(10, dtype=np.float32)), "force_values"),
    "state-length": (dict(state=np.zeros(2)), "state"),
    "state-int64": (dict(state=np.zeros(3, dtype=np.int64)), "state"),
    "state-read-only": (dict(state=np.broadcast_to(np.zeros(1), (3,))), "state"),
    "counters-length": (dict(counters=np.zeros(3, dtype=np.int64)), "counters"),
    "counters-float64": (dict(counters=np.array([1.0, 0, 0, 0])), "counters"),
    "counters-row-negative": (dict(counters=np.array([-5, 0, 0, 0], dtype=np.int64)), "counters"),
    "out-rows-from-row": (dict(counters=np.array([5, 0, 0, 0], dtype=np.int64)), "out"),
    "out-too-short": (dict(n_last=10**7, n_steps=10**7, out=np.zeros((11, 6))), "out"),
    "out-columns": (dict(out=np.zeros((11, 5))), "out"),
    "out-float32": (dict(out=np.zeros((11, 6), dtype=np.float32)), "out"),
    "out-not-contiguous": (dict(out=np.zeros((11, 12))[:, ::2]), "out"),
}


def test_the_valid_block_runs_as_the_python_loop() -> None:
    """The starting point of the cases is a valid call: it fills ``out`` as the Python twin does."""
    compiled, python = block_args(), block_args()
    assert outcome(lambda: _kernel.bingham_block(*compiled.values())) == ("ok", "")
    _kernel.bingham_block(*compiled.values())
    backward_euler._python_block(*python.values())
    assert np.array_equal(compiled["out"], python["out"]) and compiled["counters"][0] == 11


@pytest.mark.parametrize("case", list(BLOCK_CASES))
def test_bingham_block_refuses(case: str) -> None:
    change, name = BLOCK_CASES[case]
    args = block_args(**change)
    assert_refused(lambda: _kernel.bingham_block(*args.values()), name)


# -- _network_kernel ------------------------------------------------------------------
NET, DT, STEPS = tree(), 1e-3, 10


def block(**change: object) -> dict[str, object]:
    """Arguments of ``network_block`` for the first 10 steps of ``tree()``, as ``integrate._run_compiled``
    builds them; ``change`` replaces arguments, or items of the tuples (``topology_kind``, ...)."""
    net, n_mass, n_el = NET, len(NET.masses), len(NET.elements)
    loaded = np.array(net.loaded_masses(), dtype=np.int64)
    inertia = np.array([m.mass / DT for m in net.masses])
    rows = STEPS + 1
    args: dict[str, object] = dict(
        topology=[*kernel.plan(net), inertia, _sigma(net, inertia, DT), loaded],
        marching=[
            np.array([m.x0 for m in net.masses]),
            np.array([m.v0 for m in net.masses]),
            np.zeros(n_el),
            np.full(n_el, -1, dtype=np.int64),
            np.zeros(n_mass, dtype=np.int64),
            np.array([1, 0, 0, 0]),
        ],
        record=[
            np.zeros(rows),
            np.zeros((rows, n_mass)),
            np.zeros((rows, n_mass)),
            np.zeros((rows, n_el)),
            np.zeros((rows, n_el)),
            np.zeros((rows, n_el), dtype=np.uint8),
            np.empty(0),
            np.empty(0),
        ],
        table=net.load_table(np.arange(1, STEPS + 1) * DT, loaded),
        dt=DT,
        n_first=1,
        n_last=STEPS,
        n_steps=STEPS,
        save_every=1,
    )
    return _changed(args, change)


def solve(**change: object) -> dict[str, object]:
    """Arguments of ``network_solve`` for the initial forces' problem of ``tree()``."""
    net, n_el = NET, len(NET.elements)
    inertia = np.array([m.mass for m in net.masses])
    graphs = _graphs(net, [0.0] * n_el, None, np.zeros(n_el))
    pieces = np.zeros((n_el, 5, 5))
    for e, graph in enumerate(graphs):
        pieces[e, : len(graph)] = graph
    args: dict[str, object] = dict(
        topology=[*kernel.plan(net), inertia, _sigma(net, inertia, 1.0), np.empty(0, dtype=np.int64)],
        pieces=pieces,
        counts=np.array([len(g) for g in graphs], dtype=np.int64),
        rhs=np.ones(len(net.masses)),
        solution=[
            np.empty(inertia.size),
            np.empty(n_el),
            np.empty(n_el),
            np.full(n_el, -1, dtype=np.int64),
            np.zeros(n_el, dtype=np.uint8),
        ],
    )
    return _changed(args, change)


TUPLES = {
    "topology": "kind par first second order parent link_start link_el sign inertia sigma load_mass".split(),
    "marching": "x v state modes rest counters".split(),
    "record": "t x v force state rigid low high".split(),
    "solution": "v w f modes rigid".split(),
}


def _changed(args: dict[str, object], change: dict[str, object]) -> dict[str, object]:
    for key, value in change.items():
        group, _, item = key.partition("_")
        if group in TUPLES and item in TUPLES[group]:
            args[group][TUPLES[group].index(item)] = value(args[group][TUPLES[group].index(item)])  # type: ignore[index]
        else:
            args[key] = value
    return {k: tuple(v) if isinstance(v, list) else v for k, v in args.items()}


def _set(index: int, value: int):  # noqa: ANN202
    """A change of an int64 array: a copy with ``[index] = value``."""

    def change(a: np.ndarray) -> np.ndarray:
        a = a.copy()
        a[index] = value
        return a

    return change


N_PT = len(NET.masses) + 1
N_EL = len(NET.elements)
# A bad argument of the topology, refused by both bindings: (change, the name in the message).
TOPOLOGY_CASES = {
    "topology-count": (dict(topology=lambda: None), "topology"),
    "kind-code-6": (dict(topology_kind=_set(0, 6)), "topology[0] (kind)"),
    "kind-code-negative": (dict(topology_kind=_set(1, -1)), "topology[0] (kind)"),
    "kind-float64": (dict(topology_kind=lambda a: a.astype(float)), "topology[0] (kind)"),
    "par-length": (dict(topology_par=lambda a: a.ravel()[:-1]), "topology[1] (par)"),
    "first-length": (dict(topology_first=lambda a: a[:-1]), "topology[2] (first)"),
    "first-index": (dict(topology_first=_set(0, N_PT)), "topology[2] (first)"),
    "second-index": (dict(topology_second=_set(2, -1)), "topology[3] (second)"),
    "order-length": (dict(topology_order=lambda a: a[:-1]), "topology[4] (order)"),
    "order-index": (dict(topology_order=_set(1, N_PT + 5)), "topology[4] (order)"),
    "order-repeats": (dict(topology_order=lambda a: np.append(a[:-1], a[0])), "topology[4] (order)"),
    "parent-index": (dict(topology_parent=_set(0, N_PT)), "topology[5] (parent)"),
    "parent-after-child": (dict(topology_parent=lambda a: np.where(a == N_PT - 1, 2, a)), "topology[5] (parent)"),
    "link_start-length": (dict(topology_link_start=lambda a: a[:-1]), "topology[6] (link_start)"),
    "link_start-past-link_el": (dict(topology_link_start=_set(-1, 100)), "topology[6] (link_start)"),
    "link_start-decreasing": (dict(topology_link_start=_set(2, 0)), "topology[6] (link_start)"),
    "link_el-index": (dict(topology_link_el=_set(0, N_EL)), "topology[7] (link_el)"),
    "sign-length": (dict(topology_sign=lambda a: a[:-1]), "topology[8] (sign)"),
    "inertia-float32": (dict(topology_inertia=lambda a: a.astype(np.float32)), "topology[9] (inertia)"),
    "sigma-length": (dict(topology_sigma=lambda a: a[:2]), "topology[10] (sigma)"),
    "load_mass-index": (dict(topology_load_mass=lambda a: np.array([0, 99])), "topology[11] (load_mass)"),
}
BLOCK_ONLY = {
    "marching-count": (dict(marching=lambda: (1, 2)), "marching"),
    "x-length": (dict(marching_x=lambda a: a[:-1]), "marching[0] (x)"),
    "v-float32": (dict(marching_v=lambda a: a.astype(np.float32)), "marching[1] (v)"),
    "state-length": (dict(marching_state=lambda a: a[:1]), "marching[2] (state)"),
    "state-read-only": (dict(marching_state=lambda a: np.broadcast_to(a[:1], a.shape)), "marching[2] (state)"),
    "modes-length": (dict(marching_modes=lambda a: a[:-1]), "marching[3] (modes)"),
    "modes-piece": (dict(marching_modes=_set(1, 3)), "marching[3] (modes)"),  # a Bingham band has 3 pieces
    "rest-int32": (dict(marching_rest=lambda a: a.astype(np.int32)), "marching[4] (rest)"),
    "counters-length": (dict(marching_counters=lambda a: a[:3]), "marching[5] (counters)"),
    "counters-row-negative": (dict(marching_counters=_set(0, -4)), "counters[0]"),
    "record-count": (dict(record=lambda: ()), "record"),
    "t-rows": (dict(record=lambda: tuple(a[:5] for a in block()["record"])), "record[0] (t)"),
    "t-rows-from-row": (dict(marching_counters=_set(0, 3)), "record[0] (t)"),
    "t-rows-long-run": (
        dict(n_last=lambda: 10**6, n_steps=lambda: 10**6, table=lambda: np.zeros((10**6, 2))),
        "record[0] (t)",
    ),
    "x-rows": (dict(record_x=lambda a: a[:-1]), "record[1] (x)"),
    "v-rows": (dict(record_v=lambda a: a[:-1]), "record[2] (v)"),
    "force-not-contiguous": (
        dict(record_force=lambda a: np.zeros((a.shape[0], 2 * a.shape[1]))[:, ::2]),
        "record[3] (force)",
    ),
    "state-rows": (dict(record_state=lambda a: a[:-2]), "record[4] (state)"),
    "rigid-float64": (dict(record_rigid=lambda a: a.astype(float)), "record[5] (rigid)"),
    "table-length": (dict(table=lambda: np.zeros((3, 2))), "table"),
    "dt-0": (dict(dt=lambda: 0.0), "dt"),
    "dt-nan": (dict(dt=lambda: math.nan), "dt"),
    "save_every-0": (dict(save_every=lambda: 0), "save_every"),
    "n_first-negative": (dict(n_first=lambda: -1), "n_first"),
    "n_last-before-n_first": (dict(n_last=lambda: 0), "n_last"),
    "n_steps-before-n_last": (dict(n_steps=lambda: 4), "n_steps"),
}
SOLVE_ONLY = {
    "pieces-length": (dict(pieces=lambda: np.zeros((N_EL, 5, 4))), "pieces"),
    "counts-length": (dict(counts=lambda: np.ones(N_EL - 1, dtype=np.int64)), "counts"),
    "counts-0": (dict(counts=lambda: np.zeros(N_EL, dtype=np.int64)), "counts"),
    "counts-6": (dict(counts=lambda: np.full(N_EL, 6, dtype=np.int64)), "counts"),
    "rhs-length": (dict(rhs=lambda: np.ones(2)), "rhs"),
    "solution-count": (dict(solution=lambda: (1,)), "solution"),
    "v-length": (dict(solution_v=lambda a: a[:-1]), "solution[0] (v)"),
    "w-length": (dict(solution_w=lambda a: a[:-1]), "solution[1] (w)"),
    "f-int64": (dict(solution_f=lambda a: np.zeros(a.shape, np.int64)), "solution[2] (f)"),
    "modes-piece": (dict(solution_modes=_set(0, 5)), "solution[3] (modes)"),  # no graph has 6 pieces
    "rigid-length": (dict(solution_rigid=lambda a: a[:-1]), "solution[4] (rigid)"),
}


def _apply(builder, change: dict[str, object]) -> dict[str, object]:  # noqa: ANN001
    """``builder`` with each change applied (scalars and whole tuples given as functions of nothing)."""
    base = builder()
    resolved = {}
    for key, value in change.items():
        if key in base:
            resolved[key] = value()  # type: ignore[operator]
        else:
            resolved[key] = value
    return builder(**resolved)


@pytest.mark.parametrize("call", ["network_block", "network_solve"])
def test_the_valid_network_calls_run(call: str) -> None:
    """The starting points of the cases are valid calls; the block saves every row it is given."""
    args = (block if call == "network_block" else solve)()
    assert outcome(lambda: getattr(_network_kernel, call)(*args.values())) == ("ok", "")
    getattr(_network_kernel, call)(*args.values())
    if call == "network_block":
        assert args["marching"][5][0] == STEPS + 1 and np.all(args["record"][0][1:] > 0)
    assert _network_kernel.network_solve(*solve().values()) > 0


@pytest.mark.parametrize("call", ["network_block", "network_solve"])
@pytest.mark.parametrize("case", list(TOPOLOGY_CASES))
def test_network_bindings_refuse_a_bad_topology(call: str, case: str) -> None:
    change, name = TOPOLOGY_CASES[case]
    args = _apply(block if call == "network_block" else solve, change)
    assert_refused(lambda: getattr(_network_kernel, call)(*args.values()), name)


@pytest.mark.parametrize("case", list(BLOCK_ONLY))
def test_network_block_refuses(case: str) -> None:
    change, name = BLOCK_ONLY[case]
    args = _apply(block, change)
    assert_refused(lambda: _network_kernel.network_block(*args.values()), name)


@pytest.mark.parametrize("case", list(SOLVE_ONLY))
def test_network_solve_refuses(case: str) -> None:
    change, name = SOLVE_ONLY[case]
    args = _apply(solve, change)
    assert_refused(lambda: _network_kernel.network_solve(*args.values()), name)
