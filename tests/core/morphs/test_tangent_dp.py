"""The tangent-aligned correspondence (issue 38): analytic cases of the turning-function warp."""

import numpy as np
import pytest

from ballmorph_core.geometry.ragged import Ragged
from ballmorph_core.morphs import tangent_dp
from ballmorph_core.morphs.tangent_aligned import tangent_morph
from ballmorph_core.morphs.tangent_dp import POSITION, STRETCH, tangent_warp, tangent_warps

#: The warps of these tests run on 128 edges a curve: one cell, as a fraction of a curve.
SAMPLES = 128
CELL = 1.0 / SAMPLES


def circle(n=200, phase=0.0, r=1.0, c=(0.0, 0.0)):
    a = np.linspace(0.0, 2.0 * np.pi, n, endpoint=False) + phase
    return np.c_[c[0] + r * np.cos(a), c[1] + r * np.sin(a)]


def rectangle(w, h, per_side=40):
    """A rectangle's outline (counter-clockwise from its lower left corner), ``per_side`` points a side."""
    s = np.linspace(0.0, 1.0, per_side, endpoint=False)[:, None]
    corners = np.array([[-w, -h], [w, -h], [w, h], [-w, h]]) / 2
    return np.concatenate([a + s * (b - a) for a, b in zip(corners, np.roll(corners, -1, axis=0))])


def cyclic_gap(a, b):
    return abs((a - b + 0.5) % 1.0 - 0.5)


def test_circle_against_itself_rotated_gives_the_rotation():
    for phase in (0.3, 1.9, 4.0):
        warp = tangent_warp(circle(), circle(phase=phase), True, samples=SAMPLES)
        expected = (-phase / (2 * np.pi)) % 1.0
        gap = cyclic_gap(warp.start, expected)
        assert gap <= CELL, f"phase {phase}: start {warp.start:.4f}, expected {expected:.4f} ({gap / CELL:.2f} cells)"
        # Every point goes to the same point: the warp is the identity after the start.
        inner = np.interp(np.linspace(0, 1, 50), warp.u_p, warp.u_q)
        assert np.max(np.abs(inner - np.linspace(0, 1, 50))) <= 2 * CELL, f"phase {phase}: warp not the identity"
        assert warp.cost < 1e-3, f"phase {phase}: cost {warp.cost:.2e}"


def test_square_against_rectangle_maps_corners_to_corners():
    # Sides 1, 1 against 2, 0.5: the rectangle's corners are at fractions 0.4, 0.5, 0.9 of its
    # outline (from the same lower left corner), the square's at 0.25, 0.5, 0.75.
    warp = tangent_warp(rectangle(1.0, 1.0), rectangle(2.0, 0.5), True, samples=SAMPLES)
    assert cyclic_gap(warp.start, 0.0) <= CELL, f"start {warp.start:.4f}"
    for corner_p, corner_q in ((0.25, 0.4), (0.5, 0.5), (0.75, 0.9)):
        got = (warp.start + np.interp(corner_p, warp.u_p, warp.u_q)) % 1.0
        assert cyclic_gap(got, corner_q) <= 2 * CELL, f"square corner {corner_p} -> {got:.3f}, expected {corner_q}"


def test_open_strokes_keep_their_ends_and_warps_are_monotone():
    x = np.linspace(0.0, 1.0, 60)
    P = np.c_[x, 0.2 * np.sin(3 * x)]
    Q = np.c_[x**1.5, 0.3 * np.sin(3 * x**1.5)]
    warp = tangent_warp(P, Q, False)
    assert warp.start == 0.0 and warp.u_p[0] == warp.u_q[0] == 0.0 and warp.u_p[-1] == warp.u_q[-1] == 1.0
    assert np.all(np.diff(warp.u_p) >= 0) and np.all(np.diff(warp.u_q) >= 0)


def test_a_batch_gives_each_pair_its_own_warp():
    pairs = [(circle(), circle(phase=1.0), True), (rectangle(1, 1), rectangle(2, 0.5), True)]
    batch = tangent_warps(*zip(*pairs))
    for (P, Q, closed), got in zip(pairs, batch):
        alone = tangent_warp(P, Q, closed)
        assert got.start == alone.start and np.array_equal(got.u_q, alone.u_q)


@pytest.mark.parametrize("closed", [True, False])
def test_the_morph_runs_straight_between_the_keys(closed):
    P, Q = rectangle(1.0, 1.0), rectangle(1.6, 0.7)
    if not closed:
        P, Q = P[:100], Q[:100]
    morph = tangent_morph(P, Q, closed)
    start, end = morph(0.0), morph(1.0)
    mid = morph(0.5)
    assert np.allclose(mid, (start + end) / 2) and np.isfinite(mid).all()
    # The ends lie on their keys' outlines: the corners of both keys are kept (to a sample).
    assert np.abs(np.abs(end).max(axis=0) - [0.8, 0.35]).max() < 0.02, f"end box {np.abs(end).max(axis=0)}"


def _reference_warp(P, Q, closed, k, start):
    """The warp from ``start`` cell by cell, as the module docstring states it: edges of uniform
    samples, ``1 - cos`` plus the position term, a diagonal step counting its cell twice, a step
    along one curve paying ``STRETCH`` more, the first of equal steps in the order (both, along
    P, along Q). Returns (total, cells i, cells j)."""
    edges = []
    for curve in (P, Q):
        pts = Ragged.from_list([curve], [closed]).resample(np.array([k if closed else k + 1]), smooth=False).pts
        nxt = np.roll(pts, -1, axis=0) if closed else pts[1:]
        pts = pts if closed else pts[:-1]
        d = nxt - pts
        edges.append((d / np.maximum(np.linalg.norm(d, axis=1, keepdims=True), 1e-300), (pts + nxt) / 2))
    (tp, mp), (tq, mq) = edges
    both = np.concatenate([mp, mq])
    size = max(np.sqrt(np.mean(np.sum(np.square(both - both.mean(axis=0)), axis=1))), 1e-300)
    cost = 1.0 - np.einsum("id,jd->ij", tp, tq) + POSITION * np.sum(np.square(mp[:, None] - mq[None]), axis=2) / size**2
    total = np.full((k + 1, k + 1), np.inf)  # cell (i, j) at [i + 1, j + 1]
    total[0, 0] = 0.0
    step = np.zeros((k, k), dtype=int)
    for i in range(k):
        for j in range(k):
            c = cost[i, (start + j) % k]
            options = (total[i, j] + 2.0 * c, total[i, j + 1] + c + STRETCH, total[i + 1, j] + c + STRETCH)
            total[i + 1, j + 1] = min(options)
            step[i, j] = options.index(total[i + 1, j + 1])
    path, i, j = [], k - 1, k - 1
    while True:
        path.append((i, j))
        if i == j == 0:
            break
        i, j = i - (step[i, j] != 2), j - (step[i, j] != 1)
    cells = np.array(path[::-1]).T
    return total[k, k], cells[0], cells[1]


def _blob(n, phase, stretch=1.0, turn=0.0):
    t = np.linspace(0.0, 2.0 * np.pi, n, endpoint=False)
    r = 1.0 + 0.2 * np.cos(2 * t + phase) + 0.07 * np.cos(3 * t + 2 * phase)
    pts = np.c_[stretch * r * np.cos(t), r * np.sin(t)]
    c, s = np.cos(turn), np.sin(turn)
    return pts @ np.array([[c, -s], [s, c]]).T


@pytest.mark.parametrize(
    "P, Q",
    [
        (_blob(90, 0.4), _blob(70, 0.4, stretch=1.25, turn=0.3)),
        (rectangle(1.0, 1.0, 15), rectangle(2.0, 0.5, 12)),
        (circle(60), circle(80, phase=2.0, r=1.3)),
    ],
    ids=["blob-stretched", "square-rectangle", "circles"],
)
def test_the_warp_is_the_cell_by_cell_dynamic_programme(P, Q):
    """Every start on a small table (all are tried there): the same start, total and cells as
    the cell-by-cell programme, bit for bit (the vectorised sweep only reorders the work)."""
    k = 24
    warp = tangent_warp(P, Q, True, samples=k)
    totals = [_reference_warp(P, Q, True, k, s)[0] for s in range(k)]
    best = int(np.argmin(totals))
    total, i, j = _reference_warp(P, Q, True, k, best)
    assert warp.start == best / k
    assert warp.cost == total / (2 * len(i))
    assert np.array_equal(warp.u_p, np.r_[0.0, (i + 1) / k]) and np.array_equal(warp.u_q, np.r_[0.0, (j + 1) / k])


@pytest.mark.parametrize("closed", [True, False])
def test_a_fine_warp_is_the_cell_by_cell_programme_from_its_start(closed):
    """On 160 edges (a loop's start chosen on coarser tables): the warp from its start is the
    cell-by-cell programme's."""
    P, Q = _blob(150, 1.1), _blob(170, 1.1, stretch=1.3, turn=-0.2)
    if not closed:
        P, Q = P[:120], Q[:130]
    k = 160
    warp = tangent_warp(P, Q, closed, samples=k)
    total, i, j = _reference_warp(P, Q, closed, k, int(round(warp.start * k)))
    assert warp.cost == total / (2 * len(i))
    assert np.array_equal(warp.u_p, np.r_[0.0, (i + 1) / k]) and np.array_equal(warp.u_q, np.r_[0.0, (j + 1) / k])


def test_pairs_warped_one_table_at_a_time_get_the_same_warps(monkeypatch):
    pairs = [(_blob(150, 0.3 * b), _blob(130, 0.3 * b, stretch=1.2, turn=0.1 * b), b % 2 == 0) for b in range(5)]
    together = tangent_warps(*zip(*pairs))
    monkeypatch.setattr(tangent_dp, "TABLE_CELLS", 1)  # every pair a group of its own
    for got, want in zip(tangent_warps(*zip(*pairs)), together):
        assert (got.start, got.cost) == (want.start, want.cost)
        assert np.array_equal(got.u_p, want.u_p) and np.array_equal(got.u_q, want.u_q)
