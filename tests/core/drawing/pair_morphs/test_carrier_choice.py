"""Which pairs get a carrier (drawing/carrier_choice.py)."""

import numpy as np
import pytest
from shapes import circle, polar_loop

from ballmorph_core.drawing.pair_morphs import carrier_choice
from ballmorph_core.drawing.pair_morphs.pipeline import PairMorph
from ballmorph_core.drawing.pair_morphs.registration import Fits
from ballmorph_core.geometry.ragged import Ragged


def _lumpy(n=300):
    """r = 1.1 + 0.3 cos(3 theta): crosses the unit circle six times, mostly around it."""
    return polar_loop([(0.0, 0.0), (0.3, 0.0)], n=n, base=1.1)


def _turned(xy, degrees, shift):
    a = np.radians(degrees)
    return xy @ np.array([[np.cos(a), np.sin(a)], [-np.sin(a), np.cos(a)]]) + shift


def test_closest_distance_of_concentric_circles_is_their_gap_whatever_their_starts():
    P = Ragged.from_list([circle(1.0, 400), circle(1.0, 400)], [True, True])
    Q = Ragged.from_list([circle(2.0, 400), circle(2.0, 400, start=2.0)], [True, True])
    d = carrier_choice.closest_distance(P, Q)
    np.testing.assert_allclose(d, 1.0, atol=2e-4)
    assert abs(d[0] - d[1]) < 1e-4


def test_a_loop_changing_shape_where_it_lies_gets_no_carrier_and_says_why():
    morph = PairMorph(circle(1.0, 300), _lumpy(), True)
    assert morph.used.carrier == "", morph.used
    note = [n for n in morph.notes if n.startswith("no carrier")]
    assert note and "change shape" in note[0], morph.notes


def test_the_same_change_while_the_loop_moves_and_turns_keeps_its_carrier():
    morph = PairMorph(circle(1.0, 300), _turned(_lumpy(), 40.0, (0.9, 0.4)), True)
    assert morph.used.carrier == "similarity", morph.used
    assert not any(n.startswith("no carrier") for n in morph.notes)


@pytest.mark.parametrize("apart, changed", [(0.0, True), (3.0, False)])
def test_only_overlapping_loops_count_as_changing_shape(apart, changed):
    # A registration that explains nothing (the identity, its residual the samples' own):
    # loops lying over each other change shape; loops side by side still need the carrier.
    P = Ragged.from_list([circle(1.0, 300)], [True])
    Q = Ragged.from_list([_lumpy() + [apart, 0.0]], [True])
    fits = Fits(np.eye(2)[None], np.zeros((1, 2)), np.array([np.inf]))
    got, kept = carrier_choice.shape_changes(P, Q, fits, np.array([True]))
    assert got[0] == changed
    assert kept[0] == pytest.approx(1.0)


def _oblique_stretch(factor, degrees):
    """The symmetric map stretching by ``factor`` along the axis at ``degrees``, shape (2, 2)."""
    a = np.radians(degrees)
    axis = np.array([np.cos(a), np.sin(a)])
    return np.eye(2) + (factor - 1.0) * np.outer(axis, axis)


def test_a_registration_that_explains_the_change_is_screened_out_before_any_distance(monkeypatch):
    # An affine fit that is exact: the registered loop is Q. P's uniform samples moved by it
    # sit off Q's (the stretch shares arc length out anew: 30 % of the distance as drawn),
    # the registered loop's own do not; no closest-point distance is measured.
    A = _oblique_stretch(1.6, 35.0)
    P = Ragged.from_list([_lumpy()], [True])
    Q = Ragged.from_list([_lumpy() @ A.T + [0.2, 0.0]], [True])
    fits = Fits(A[None], np.array([[0.2, 0.0]]), np.array([np.inf]))

    def measured(*args):
        raise AssertionError("the screen let an exact fit through")

    monkeypatch.setattr(carrier_choice, "closest_distances", measured)
    got, kept = carrier_choice.shape_changes(P, Q, fits, np.array([True]))
    assert not got[0] and np.isnan(kept[0])


def test_open_strokes_whose_registration_explains_little_are_shape_changes():
    # Issue 38: an open stroke's carrier that explains nothing of the pair (here the identity)
    # is not used, whatever the overlap (strokes have no inside).
    P = Ragged.from_list([circle(1.0, 300)[:200]], [False])
    Q = Ragged.from_list([_lumpy()[:200]], [False])
    fits = Fits(np.eye(2)[None], np.zeros((1, 2)), np.array([np.inf]))
    got, kept = carrier_choice.shape_changes(P, Q, fits, np.array([True]))
    assert got[0] and kept[0] == pytest.approx(1.0), f"kept {kept[0]:.3f} of the distance"


class _Astray:
    """A stand-in composite ball-morph whose middle frames leave the chains far behind."""

    def __init__(self, P, reach):
        self.P, self.reach = P, reach

    def frames(self, ts):
        return np.stack([self.P + [0.0, -self.reach] for _ in ts])


@pytest.mark.parametrize("reach, followed", [(0.0, True), (0.2, True), (1.0, False)])
def test_a_composite_ball_morph_that_strays_far_outside_its_chains_falls_back(monkeypatch, reach, followed):
    from ballmorph_core.drawing.pair_morphs import fallbacks

    P = np.c_[np.linspace(0.0, 1.0, 20), np.zeros(20)]
    Q = np.c_[np.linspace(0.0, 1.0, 20), np.full(20, 0.5)]
    monkeypatch.setattr(fallbacks, "composite_morphs", lambda pairs, kind: [_Astray(P_, reach) for P_, *_ in pairs])
    morph, note = fallbacks.chain_fallbacks([fallbacks.FailingChain(P, Q, False, 0.05, "lens 1/2", "why")], "circular")[
        0
    ]
    # The box's diagonal is 1.118: a reach of 0.2 is 0.18 of it, 1.0 is 0.89.
    assert isinstance(morph, _Astray) == followed, note
    assert ("composite ball-morph used" in note) == followed
    if not followed:
        assert "leave the chains' box by 0.89 of its diagonal" in note and "aligned-interpolation used" in note


class _Crossing:
    """A stand-in composite ball-morph whose in-between at t = 1/8 (only) crosses itself."""

    def __init__(self, P, Q):
        self.P, self.Q = P, Q

    def frames(self, ts):
        out = [0.5 * (self.P + self.Q) for _ in ts]
        out[0] = out[0].copy()
        out[0][[5, 12]] = out[0][[12, 5]] + [0.0, 0.1]  # two samples swapped: the line loops back
        return np.stack(out)


def test_a_composite_ball_morph_whose_in_between_crosses_itself_falls_back(monkeypatch):
    from ballmorph_core.drawing.pair_morphs import fallbacks

    x = np.linspace(0.0, 1.0, 20)
    P, Q = np.c_[x, np.zeros(20)], np.c_[x, np.full(20, 0.5)]
    monkeypatch.setattr(fallbacks, "composite_morphs", lambda pairs, kind: [_Crossing(P_, Q_) for P_, Q_, *_ in pairs])
    morph, note = fallbacks.chain_fallbacks([fallbacks.FailingChain(P, Q, False, 0.05, "lens 1/2", "why")], "circular")[
        0
    ]
    assert not isinstance(morph, _Crossing)
    assert "cross themselves where neither chain does" in note and "aligned-interpolation used" in note, note


def test_handled_directly_are_nested_loops_and_strokes_sharing_their_ends():
    x = np.linspace(0.0, 1.0, 30)
    loops = [circle(1.0, 80), circle(0.5, 80, centre=(0.2, 0.1)), circle(1.0, 80), circle(1.0, 80)]
    others = [circle(0.5, 80, centre=(0.2, 0.1)), circle(1.0, 80), circle(1.0, 80) + [0.5, 0], circle(1.0, 80) + [3, 0]]
    P = Ragged.from_list(loops + [np.c_[x, x * 0], np.c_[x, x * 0]], [True] * 4 + [False] * 2)
    Q = Ragged.from_list(others + [np.c_[x, np.sin(np.pi * x)], np.c_[x, x * 0] + [0, 1]], P.closed)
    got = carrier_choice.handled_directly(P, Q, np.ones(6))
    # Inside either way; crossing; side by side; sharing both ends; sharing none.
    np.testing.assert_array_equal(got, [True, True, False, False, True, False])


def test_closest_distance_in_batches_is_the_same(monkeypatch):
    # Pairs are measured a few hundred at a time (memory): each pair's distance is its own, up to
    # round-off (the projection's search takes another path for a smaller batch: 4e-15 here).
    loops = [circle(1.0 + 0.1 * k, 40) for k in range(7)]
    P = Ragged.from_list(loops, [True] * 7)
    Q = Ragged.from_list([loop * (1.2, 0.9) + (0.05 * k, 0.0) for k, loop in enumerate(loops)], [True] * 7)
    whole = carrier_choice.closest_distance(P, Q)
    monkeypatch.setattr(carrier_choice, "CLOSEST_BATCH", 3)
    np.testing.assert_allclose(carrier_choice.closest_distance(P, Q), whole, rtol=1e-12, atol=0)
