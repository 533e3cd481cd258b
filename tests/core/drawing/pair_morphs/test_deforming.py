"""Pairs that change shape where they lie (issue 38): the tangent-aligned route, chosen per pair."""

import numpy as np
import pytest
from shapes import circle, distance_to_polyline

from ballmorph_core.drawing.pair_morphs.deforming import DEFORMING_NOTE, similar_in_place
from ballmorph_core.drawing.pair_morphs.pipeline import PairMorph
from ballmorph_core.drawing.strokes import Route
from ballmorph_core.geometry.ragged import Ragged

#: An in-between within this fraction of the pair's size of the designer's (vertex-wise) blend.
BOLDER_TOLERANCE = 0.015


def _even(corners, n):
    """``n`` points evenly spaced along the closed polygon ``corners`` (K, 2)."""
    c = np.asarray(corners, dtype=float)
    edges = np.roll(c, -1, axis=0) - c
    lengths = np.linalg.norm(edges, axis=1)
    cum = np.r_[0.0, np.cumsum(lengths)]
    s = np.linspace(0.0, cum[-1], n, endpoint=False)
    k = np.searchsorted(cum, s, side="right") - 1
    return c[k] + ((s - cum[k]) / lengths[k])[:, None] * edges[k]


def rounded_l(stem, n, foot=0.6, height=1.0, radius=0.03):
    """An L-shaped outline (stem width ``stem``, corners rounded by ``radius``), ``n`` points."""
    c = np.array([(0, 0), (foot, 0), (foot, stem), (stem, stem), (stem, height), (0, height)], dtype=float)
    arcs = []
    for i, p in enumerate(c):
        u, v = c[i - 1] - p, c[(i + 1) % len(c)] - p
        p0, p1 = p + radius * u / np.linalg.norm(u), p + radius * v / np.linalg.norm(v)
        t = np.linspace(0.0, 1.0, 8)[:, None]
        arcs.append((1 - t) ** 2 * p0 + 2 * t * (1 - t) * p + t**2 * p1)
    return _even(np.concatenate(arcs), n)


def hausdorff(a, b, closed=True):
    return max(distance_to_polyline(a, b, closed).max(), distance_to_polyline(b, a, closed).max())


def test_an_outline_growing_bolder_in_place_slides_through_its_crossings():
    # Stem 0.08 -> 0.30 (the Thin and Black of a glyph's L), drawn with other point counts.
    morph = PairMorph(rounded_l(0.08, 400), rounded_l(0.30, 333), True)
    assert "tangent-aligned" in morph.used.morphs and not any("split at" in n for n in morph.notes), morph.notes
    for t in (0.25, 0.5, 0.75):
        truth = rounded_l(0.08 + t * 0.22, 3000)
        off = hausdorff(morph(t), truth)
        assert off <= BOLDER_TOLERANCE, f"t={t}: {off:.4f} from the vertex-wise blend (at most {BOLDER_TOLERANCE})"


def test_a_counter_shrinking_inside_its_thin_self_is_tangent_aligned():
    # A glyph's counter as its strokes grow bolder: a similar loop nested, no motion.
    thin = circle(0.5, 300) * (1.0, 1.3)
    black = circle(0.3, 240) * (1.0, 1.4) + (0.02, 0.0)
    morph = PairMorph(thin, black, True)
    assert morph.used.morphs == ("tangent-aligned",) and not morph.used.carrier, (morph.used, morph.notes)
    mid = morph(0.5)
    radii = np.abs(mid).max(axis=0)
    assert np.allclose(radii, [0.40 + 0.01, 0.5 * (0.65 + 0.42)], atol=0.01), f"mid box half-sizes {radii}"


def test_dissimilar_nested_loops_are_not_taken_for_a_shape_changing_in_place():
    # A notched disk inside a pear (the paper's configuration 1): no similarity explains it, so
    # the in-place screen leaves it to the ball-morph; the notch is where no ball-map follows
    # them, and only that sends the pair to the tangent-aligned correspondence, saying so.
    t = np.linspace(0, 2 * np.pi, 300, endpoint=False)
    notch = 1.0 - 0.6 * np.maximum(0, 1 - np.abs(np.angle(np.exp(1j * (t - 0.3)))) / 0.12)
    r = 1.6 + 0.25 * np.cos(t - np.pi / 2) + 0.1 * np.cos(2 * t)
    P, Q = notch[:, None] * np.c_[np.cos(t), np.sin(t)], np.c_[0.9 * r * np.cos(t), 1.2 * r * np.sin(t)]
    both = Ragged.from_list([P], [True]), Ragged.from_list([Q], [True])
    assert not similar_in_place(*both, np.array([True]))[0]
    morph = PairMorph(P, Q, True)
    assert morph.used.route == Route.TANGENT and any("not b-compatible" in n for n in morph.notes), morph.notes
    assert not any(n == DEFORMING_NOTE for n in morph.notes), morph.notes


def test_nested_loops_the_ball_map_follows_keep_the_ball_morph():
    # A disk inside a larger three-lobed blob, both smooth: b-compatible, the paper's ball-morph.
    t = np.linspace(0, 2 * np.pi, 300, endpoint=False)
    r = 2.0 + 0.4 * np.cos(3 * t)
    morph = PairMorph(circle(1.0, 300), np.c_[r * np.cos(t), r * np.sin(t)], True)
    assert morph.used.morphs == ("circular-ball",) and morph.used.route == Route.WHOLE, (morph.used, morph.notes)


@pytest.mark.parametrize("shift", [0.6, 1.5])
def test_a_loop_moving_across_its_old_position_keeps_its_carrier(shift):
    ring = circle(0.5, 200)
    morph = PairMorph(ring, ring * (1.2, 0.9) + (shift, 0.0), True)
    assert "tangent-aligned" not in morph.used.morphs and morph.used.carrier, (morph.used, morph.notes)


#: Squash and stretch stay within this fraction of the in-between's size of an ellipse.
ELLIPSE_TOLERANCE = 0.002

#: Dissimilar open strokes' in-betweens leave the keys' box by less than this fraction of its diagonal.
BOX_TOLERANCE = 0.02


def ellipse_gap(points):
    """Largest distance of ``points`` (K, 2) from their least-squares conic (first order:
    ``|F| / |grad F|``), as a fraction of their extent."""
    x, y = points[:, 0], points[:, 1]
    design = np.c_[x * x, x * y, y * y, x, y, np.ones_like(x)]
    a, b, c, d, e, _ = coef = np.linalg.svd(design)[2][-1]
    value = design @ coef
    gradient = np.hypot(2 * a * x + b * y + d, b * x + 2 * c * y + e)
    return float(np.max(np.abs(value) / gradient) / np.ptp(points, axis=0).max())


@pytest.mark.parametrize("move", [0.0, 1.5])
def test_a_ball_stretching_into_a_smear_stays_an_ellipse(move):
    ball = circle(0.25, 200)
    smear = np.c_[3.0 * ball[:, 0], ball[:, 1]] + (move, 0.0)
    morph = PairMorph(ball, smear, True)
    for t in np.linspace(0.1, 0.9, 9):
        gap = ellipse_gap(morph(t))
        assert gap <= ELLIPSE_TOLERANCE, f"move {move}, t={t:.1f}: {gap:.4%} off an ellipse ({morph.used})"


@pytest.mark.xfail(
    strict=True,
    raises=AssertionError,
    reason="a known limit (issue 38): in place, a loop drawn with other points than its key's "
    "takes the tangent-aligned route, whose straight paths between parts of equal direction "
    "leave an ellipse by up to 1.2 %; the stretch would keep ellipses, but taken for every "
    "loop a stretch explains it moved glyph counters off their designers' in-betweens "
    "(League Spartan's median Hausdorff 1.54 -> 1.63/1000 em)",
)
def test_a_ball_squashed_in_place_drawn_with_other_points_stays_an_ellipse():
    ball = circle(0.25, 120)
    t = np.linspace(0.0, 2.0 * np.pi, 173, endpoint=False)
    a = 0.5  # the squash's axis, radians
    squashed = np.c_[0.75 * np.cos(t), 0.25 * np.sin(t)] @ np.array([[np.cos(a), np.sin(a)], [-np.sin(a), np.cos(a)]])
    morph = PairMorph(ball, squashed, True)
    for time in np.linspace(0.1, 0.9, 9):
        gap = ellipse_gap(morph(time))
        assert gap <= ELLIPSE_TOLERANCE, f"t={time:.1f}: {gap:.4%} off an ellipse ({morph.used})"


def _box_excess(frame, keys):
    lo, hi = np.min([k.min(axis=0) for k in keys], axis=0), np.max([k.max(axis=0) for k in keys], axis=0)
    out = np.maximum(lo - frame, 0.0) + np.maximum(frame - hi, 0.0)
    return float(np.hypot(out[:, 0], out[:, 1]).max() / np.hypot(*(hi - lo)))


_S = np.linspace(0.0, 1.0, 150)
DISSIMILAR_STROKES = {
    # A 'c' drawn round against an 's'-like swing; a straight hook against a looped one.
    "c-against-s": (
        np.c_[0.5 * np.cos(0.4 + 5.5 * _S), 0.5 * np.sin(0.4 + 5.5 * _S)],
        np.c_[0.4 * np.sin(2 * np.pi * _S) * (1 - 0.3 * _S), 0.9 * (0.5 - _S)],
    ),
    "hook-against-loop": (
        np.c_[0.1 * np.sin(3 * _S), 1 - _S],
        np.c_[0.25 * np.sin(2 * np.pi * _S) + 0.05, 1 - _S - 0.2 * np.sin(np.pi * _S)],
    ),
}


@pytest.mark.parametrize("name", sorted(DISSIMILAR_STROKES))
def test_dissimilar_open_strokes_get_no_carrier_and_stay_clean(name):
    from ballmorph_core.geometry.intersections import simple_curves

    a, b = DISSIMILAR_STROKES[name]
    morph = PairMorph(a, b, False)
    assert not morph.used.carrier and "tangent-aligned" in morph.used.morphs, (morph.used, morph.notes)
    frames = [morph(t) for t in np.linspace(0.1, 0.9, 9)]
    worst = max(_box_excess(f, (a, b)) for f in frames)
    assert worst < BOX_TOLERANCE, f"{name}: leaves the keys' box by {worst:.2%}"
    simple = simple_curves(frames, np.zeros(len(frames), dtype=bool))
    assert simple.all(), f"{name}: in-betweens {np.flatnonzero(~simple)} of 9 cross themselves"


def rounded_rectangle(width, height, radius, per_corner, centre=(0.0, 0.0)):
    """A rounded rectangle's outline, ``per_corner`` points on each corner's quarter circle."""
    arcs = []
    for sx, sy, start in ((1, 1, 0), (-1, 1, 90), (-1, -1, 180), (1, -1, 270)):
        a = np.radians(np.linspace(start, start + 90, per_corner, endpoint=False))
        corner = (sx * (width / 2 - radius), sy * (height / 2 - radius))
        arcs.append(np.c_[corner[0] + radius * np.cos(a), corner[1] + radius * np.sin(a)])
    return np.concatenate(arcs) + centre


def best_turn(points, truth):
    """The turn (degrees) about the points' centroid that brings them closest (Hausdorff) to
    ``truth``, searched within 5 degrees by 0.05."""
    centre = points.mean(axis=0)
    angles = np.radians(np.arange(-5.0, 5.0001, 0.05))
    gaps = []
    for a in angles:
        c, s = np.cos(a), np.sin(a)
        gaps.append(hausdorff((points - centre) @ np.array([[c, s], [-s, c]]) + centre, truth))
    return abs(float(np.degrees(angles[int(np.argmin(gaps))])))


#: The dot changing proportions stays axis-aligned within this (degrees) ...
DOT_TURN = 1.0
#: ... and within this fraction of its size of the proportional in-between.
DOT_TOLERANCE = 0.01


def test_a_dot_changing_proportions_squashes_in_place_instead_of_turning():
    # The dot of an 'i' from a light weight (tall, narrow) to a heavy one (wide, flat): a turn
    # by 90 degrees fits it, a squash in place travels less.
    tall = rounded_rectangle(0.10, 0.30, 0.03, 20)
    wide = rounded_rectangle(0.32, 0.11, 0.03, 27, centre=(0.01, 0.0))
    morph = PairMorph(tall, wide, True)
    # Squashed in place: stretched without turn (the least travel here), or matched part to
    # part without a carrier; never turned.
    motion = morph.plans.motions
    assert not motion.moving[0] or abs(np.degrees(motion.theta[0])) < DOT_TURN, (morph.used, morph.notes)
    for t in (0.25, 0.5, 0.75):
        frame = morph(t)
        truth = rounded_rectangle(0.10 + 0.22 * t, 0.30 - 0.19 * t, 0.03, 200, centre=(0.01 * t, 0.0))
        turn, off = best_turn(frame, truth), hausdorff(frame, truth) / 0.32
        assert turn < DOT_TURN and off < DOT_TOLERANCE, (
            f"t={t}: turned {turn:.2f} deg, {off:.2%} off the proportional dot"
        )


def test_a_ball_landing_squashes_without_turning():
    # A tall ellipse falling onto the floor and landing wide: a stretch without turn explains
    # it exactly (the similarity turned it by 90 degrees: a diamond at the middle).
    tall = np.c_[
        0.18 * np.cos(np.linspace(0, 2 * np.pi, 120, endpoint=False)),
        0.33 * np.sin(np.linspace(0, 2 * np.pi, 120, endpoint=False)),
    ]
    wide = np.c_[0.36 * tall[:, 0] / 0.18, 0.15 * tall[:, 1] / 0.33] + (0.0, -0.6)
    morph = PairMorph(tall + (0.0, 0.3), wide, True)
    for t in (0.25, 0.5, 0.75):
        frame = morph(t)
        x, y = 0.18 + 0.18 * t, 0.33 - 0.18 * t
        a = np.linspace(0, 2 * np.pi, 400, endpoint=False)
        truth = np.c_[x * np.cos(a), y * np.sin(a) + 0.3 - 0.9 * t]
        turn, gap = best_turn(frame, truth), ellipse_gap(frame)
        assert turn < DOT_TURN and gap <= ELLIPSE_TOLERANCE, f"t={t}: turned {turn:.2f} deg, {gap:.3%} off an ellipse"


def test_a_loop_crossing_itself_that_changes_shape_in_place_is_tangent_aligned():
    # A contour that crosses itself (as a variable font's masters keep overlapping outlines)
    # widening in place: no motion explains it, so it slides through its crossings like any loop
    # that changes shape where it lies. Sending such loops to their carrier's ball route (they
    # cross themselves, so it falls back to aligned interpolation) took Inter Italic's median
    # Hausdorff from 11.84 to 12.75/1000 em, past its goal of 11.95.
    t = np.linspace(0.0, 2 * np.pi, 160, endpoint=False)

    def eight(width):
        return np.c_[width * np.sin(t), 0.5 * np.sin(2 * t)]

    morph = PairMorph(eight(1.0), eight(1.4), True)
    assert morph.used.morphs == ("tangent-aligned",) and not morph.used.carrier, (morph.used, morph.notes)
    middle = morph(0.5)
    off = distance_to_polyline(middle, eight(1.2), True).max()
    assert off <= BOLDER_TOLERANCE * 1.2, f"{off:.4f} off the proportional in-between"


def test_a_loop_stretched_in_place_along_a_diagonal_rides_its_stretch(monkeypatch):
    # Issue 38's squash along an oblique axis (the benchmark's deforming loops): a similarity
    # fits a turn of about 90 degrees; the stretch is exact, so it is the carrier (no turn,
    # no correspondence sought), and every point moves straight to its stretched image.
    from ballmorph_core.drawing.pair_morphs import deforming

    def sought(*args):
        raise AssertionError("a correspondence was sought for an exact stretch")

    monkeypatch.setattr(deforming, "_matched_travel", sought)
    t = np.linspace(0.0, 2.0 * np.pi, 240, endpoint=False)
    r = 0.3 * (1.0 + 0.12 * np.cos(2.0 * t) + 0.05 * np.cos(3.0 * t + 0.4))
    P = np.c_[1.1 * r * np.cos(t), r * np.sin(t)]
    a = np.radians(100.0)
    S = np.eye(2) + 0.4 * np.outer([np.cos(a), np.sin(a)], [np.cos(a), np.sin(a)])
    Q = P @ S.T
    morph = PairMorph(P, Q, True)
    motion = morph.plans.motions
    assert motion.moving[0] and abs(motion.theta[0]) < 1e-9, (morph.used, morph.notes)
    # The stretched P coincides with Q: the carrier alone, samples matched by arc length (no
    # ball-map between coincident curves).
    assert morph.used.route == Route.CARRIER and morph.used.morphs == ("arc-length",), morph.used
    for time in (0.25, 0.5, 0.75):
        off = hausdorff(morph(time), (1.0 - time) * P + time * Q)
        # Within the sampling's own chord error (a turned carrier's middle is 1e-2 off).
        assert off < 1e-3 * 0.3, f"t={time}: {off:.2e} off the stretch's in-between"
