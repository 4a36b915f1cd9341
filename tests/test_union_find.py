"""The one union-find (:mod:`lumped.numerics.union_find`) against independent references."""

from __future__ import annotations

import numpy as np
import pytest

from lumped.numerics.union_find import UnionFind


def _components(n: int, edges: list[tuple[int, int]]) -> list[set[int]]:
    """Connected components by breadth-first search (no union-find)."""
    adjacent: dict[int, list[int]] = {i: [] for i in range(n)}
    for a, b in edges:
        adjacent[a].append(b)
        adjacent[b].append(a)
    seen, out = set(), []
    for start in range(n):
        if start in seen:
            continue
        part, queue = {start}, [start]
        while queue:
            for nxt in adjacent[queue.pop()]:
                if nxt not in part:
                    part.add(nxt)
                    queue.append(nxt)
        seen |= part
        out.append(part)
    return out


@pytest.mark.parametrize("seed", range(5))
def test_sets_are_the_connected_components(seed: int) -> None:
    """``union`` returns False exactly for an edge that closes a cycle, and the sets are the components."""
    rng = np.random.default_rng(seed)
    n = 30
    edges = [tuple(int(i) for i in rng.integers(0, n, 2)) for _ in range(25)]
    sets = UnionFind(n)
    closing = [not sets.union(a, b) for a, b in edges]
    for k, (a, b) in enumerate(edges):  # a cycle-closing edge joins points the earlier edges already join
        assert closing[k] == any(a in c and b in c for c in _components(n, edges[:k]))
    by_root: dict[int, set[int]] = {}
    for i in range(n):
        by_root.setdefault(sets.find(i), set()).add(i)
    assert sorted(map(sorted, by_root.values())) == sorted(map(sorted, _components(n, edges)))


def test_offsets_sum_along_the_path_and_the_root_is_the_callers() -> None:
    """Offsets are dyadic (exact in binary), so the sums along any path are exact: asserted with ``==``."""
    sets = UnionFind(5)
    sets.attach(1, 0, 0.5)
    sets.attach(2, 1, 0.25)
    sets.attach(3, 2, -2.0)
    assert sets.locate(3) == (0, -1.25)
    assert sets.locate(2) == (0, 0.75)  # after the path was compressed
    assert sets.parent[3] == 0 and sets.locate(0) == (0, 0.0)
    sets.attach(4, 3, 1.0)  # below a non-root: the offset adds to 3's
    assert sets.locate(4) == (0, -0.25)
