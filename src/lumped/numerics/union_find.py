"""Disjoint sets (union-find), the one copy the package uses.

Four places group things by it: a network's closed loops
(:func:`lumped.model.network.rigid_loop`), the free groups of an exact phase
(:func:`lumped.solvers.network_phase.groups`), the chords whose cycles share an
element (:mod:`lumped.solvers.loop_forces`) and the clusters of rigid elements,
which also carry each point's velocity offset from its cluster's root
(:func:`lumped.solvers.rigid_clusters.loop_clusters`).  The offsets are the
one extra: a plain grouping leaves them 0.

Which member becomes a set's root depends only on the calls to :meth:`UnionFind.attach`
(the caller names the new parent), never on the path compression, so the
callers that number their groups by root get the same numbers whatever the
compression does.
"""

from __future__ import annotations

__all__ = ["UnionFind"]


class UnionFind:
    """The sets of the members ``0 .. n - 1``, each at first alone.

    ``offset[i]`` is member ``i``'s offset from its parent; :meth:`locate` sums
    them along the path to the root (``value_i = value_root + offset``).
    """

    def __init__(self, n: int) -> None:
        self.parent = list(range(n))
        self.offset = [0.0] * n

    def locate(self, i: int) -> tuple[int, float]:
        """``i``'s root and its offset from it; the path walked is compressed."""
        parent, off = self.parent, self.offset
        path = []
        while parent[i] != i:
            path.append(i)
            i = parent[i]
        total = 0.0
        for node in reversed(path):
            total = off[node] + total
            off[node], parent[node] = total, i
        return i, (off[path[0]] if path else 0.0)

    def find(self, i: int) -> int:
        """``i``'s root."""
        return self.locate(i)[0]

    def attach(self, root: int, to: int, offset: float = 0.0) -> None:
        """Hang the set whose root is ``root`` below ``to`` (a member of another set), ``offset`` from it."""
        self.parent[root], self.offset[root] = to, offset

    def union(self, a: int, b: int) -> bool:
        """Join the sets of ``a`` and ``b``, ``a``'s root below ``b``'s; False if they were one set already."""
        ra, rb = self.find(a), self.find(b)
        if ra == rb:
            return False
        self.attach(ra, rb)
        return True
