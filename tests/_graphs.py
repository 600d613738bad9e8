"""Oracles over an explored graph for the tests, written apart from the explorer's own bookkeeping."""

from collections import deque


def bfs_distances(g) -> list[int]:
    """Each state's distance from the initial state, by a breadth-first walk of the arcs (-1: unreached),
    so that a trace can be checked to be shortest without the explorer's BFS parents."""
    dist = [-1] * g.n_states
    dist[0] = 0
    queue = deque([0])
    while queue:
        u = queue.popleft()
        for _, v in g.out_arcs(u):
            if dist[v] < 0:
                dist[v] = dist[u] + 1
                queue.append(v)
    return dist
