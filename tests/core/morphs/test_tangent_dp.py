"""The tangent-aligned correspondence (issue 38): analytic cases of the turning-function warp."""

import numpy as np
import pytest

from ballmorph_core.morphs.tangent_aligned import tangent_morph
from ballmorph_core.morphs.tangent_dp import tangent_warp, tangent_warps

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
