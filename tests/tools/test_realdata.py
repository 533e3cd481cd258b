"""The pure functions of tools/realdata.py (the real-data benchmark, issue 11), in plain CPython.

Tests that read the Inter variable font skip when it is not installed.
"""

import os

import numpy as np
import pytest

from tools import realdata as rd


def square(side, n_per_side=1, start=0):
    """A square loop centred on the origin, counter-clockwise, ``n_per_side`` points per side."""
    h = side / 2.0
    corners = np.array([[-h, -h], [h, -h], [h, h], [-h, h]])
    pts = [
        corners[k] + (corners[(k + 1) % 4] - corners[k]) * f
        for k in range(4)
        for f in np.arange(n_per_side) / n_per_side
    ]
    return np.roll(np.array(pts), -start, axis=0)


def brute_distances(points, a, b):
    """Point-to-segments distance by the textbook formula, one pair at a time."""
    out = []
    for p in points:
        best = np.inf
        for s, e in zip(a, b):
            d = e - s
            u = 0.0 if not d.any() else min(1.0, max(0.0, float(np.dot(p - s, d) / np.dot(d, d))))
            best = min(best, float(np.linalg.norm(p - (s + u * d))))
        out.append(best)
    return np.array(out)


def brute_crossings(contours, closed):
    """Proper crossings by testing every pair of non-neighbouring segments."""
    a, b, contour, index, count = rd.drawing_segments(contours, closed)

    def orient(p, q, r):
        return np.sign((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]))

    found = []
    for i in range(len(a)):
        for j in range(i + 1, len(a)):
            gap = abs(index[i] - index[j])
            if contour[i] == contour[j] and (gap == 1 or gap == count[i] - 1):
                continue
            if (
                orient(a[i], b[i], a[j]) * orient(a[i], b[i], b[j]) < 0
                and orient(a[j], b[j], a[i]) * orient(a[j], b[j], b[i]) < 0
            ):
                found.append(tuple(sorted((contour[i], contour[j]))))
    return sorted(found)


# Flattening -------------------------------------------------------------------------------


def test_quadratic_segment_points():
    # B(u) = (1-u)^2 (0,0) + 2u(1-u) (1,2) + u^2 (2,0) = (2u, 4u(1-u))
    pts = rd.bezier_points([[0, 0], [1, 2], [2, 0]], 4)
    u = np.array([0.25, 0.5, 0.75, 1.0])
    np.testing.assert_allclose(pts, np.c_[2 * u, 4 * u * (1 - u)], atol=1e-12)


def test_flatten_contour_gives_each_segment_its_count():
    start = [0.0, 0.0]
    segments = [np.array([[10.0, 0.0]]), np.array([[10.0, 10.0], [0.0, 10.0]]), np.array([[0.0, 0.0]])]
    pts = rd.flatten_contour(start, segments, [3, 5, 3], closed=True)
    assert pts.shape == (1 + 3 + 5 + 3 - 1, 2)  # start, line, quadratic, closing line minus the repeated start
    np.testing.assert_allclose(pts[0], start)
    np.testing.assert_allclose(pts[1], [10.0 / 3, 0.0])
    np.testing.assert_allclose(pts[3], [10.0, 0.0])  # the first line's end
    np.testing.assert_allclose(pts[8], [0.0, 10.0])  # the quadratic's end
    assert rd.flatten_contour(start, segments, [3, 5, 3], closed=False).shape == (12, 2)


def test_segment_counts_are_shared_by_every_location():
    small = [
        ([0.0, 0.0], [np.array([[100.0, 0.0]]), np.array([[100.0, 100.0], [0.0, 100.0]]), np.array([[0.0, 0.0]])], True)
    ]
    large = [
        ([0.0, 0.0], [np.array([[300.0, 0.0]]), np.array([[300.0, 300.0], [0.0, 300.0]]), np.array([[0.0, 0.0]])], True)
    ]
    (counts,) = rd.segment_counts([small, large], spacing=10.0)
    # mean control-polygon lengths 200, 400 and 200 -> 20, 40, 20 points
    np.testing.assert_array_equal(counts, [20, 40, 20])
    (counts,) = rd.segment_counts([small], spacing=1000.0)
    np.testing.assert_array_equal(counts, [rd.MIN_POINTS[1], rd.MIN_POINTS[2], rd.MIN_POINTS[1]])


def test_drop_shared_duplicates_keeps_compatibility():
    thin = [np.array([[0.0, 0], [1, 0], [1, 0], [1, 1]])]
    black = [np.array([[0.0, 0], [2, 0], [2, 0], [2, 2]])]  # point 2 repeats point 1 in both: dropped
    other = [np.array([[0.0, 0], [2, 0], [3, 0], [2, 2]])]
    out = rd.drop_shared_duplicates([thin, black])
    assert [len(d[0]) for d in out] == [3, 3]
    out = rd.drop_shared_duplicates([thin, other])  # repeated in one drawing only: kept everywhere
    assert [len(d[0]) for d in out] == [4, 4]


# Distances --------------------------------------------------------------------------------


def test_point_segment_distances_match_brute_force():
    rng = np.random.default_rng(3)
    points = rng.normal(size=(40, 2)) * 5
    a = rng.normal(size=(25, 2)) * 5
    b = a + rng.normal(size=(25, 2))
    b[3] = a[3]  # a zero-length segment is a point
    expected = brute_distances(points, a, b)
    np.testing.assert_allclose(rd.point_segment_distances(points, a, b), expected, atol=1e-12)
    np.testing.assert_allclose(rd.point_segment_distances(points, a, b, chunk=7), expected, atol=1e-12)
    np.testing.assert_allclose(rd.point_segment_distances(points, a, b, block=4), expected, atol=1e-12)
    # points on the segments themselves (distance 0 up to rounding, at the runs' box edges)
    on = a + 0.3 * (b - a)
    np.testing.assert_allclose(rd.point_segment_distances(on, a, b, block=4), 0.0, atol=1e-12)


def test_hausdorff_and_mean_of_nested_squares():
    inner, outer = [square(2.0)], [square(4.0)]
    closed = np.array([True])
    h, m = rd.compare_drawings(rd.Reference.of(inner, closed, 0.001), rd.Reference.of(outer, closed, 0.001))
    assert h == pytest.approx(np.sqrt(2.0), abs=1e-3)  # outer corner to inner corner
    # inner -> outer: 1 everywhere; outer -> inner on a side x = 2: 1 for |y| <= 1, sqrt(1 + (|y| - 1)^2) beyond.
    arc = 0.5 * (np.sqrt(2.0) + np.arcsinh(1.0))  # integral of sqrt(1 + u^2) over [0, 1]
    assert m == pytest.approx(0.5 * (1.0 + (2.0 + 2.0 * arc) / 4.0), abs=1e-4)


def test_empty_drawing_is_infinitely_far():
    square_ref = rd.Reference.of([square(2.0)], [True])
    assert rd.compare_drawings(rd.Reference.of([], []), square_ref) == (np.inf, np.inf)


def test_sample_drawing_spacing():
    pts = rd.sample_drawing([square(2.0)], [True], spacing=0.5)
    assert len(pts) == 16
    steps = np.linalg.norm(np.diff(np.vstack([pts, pts[:1]]), axis=0), axis=1)
    assert steps.max() <= 0.5 + 1e-12


# Crossings --------------------------------------------------------------------------------


def test_crossing_counts_of_known_shapes():
    closed1, closed2 = np.array([True]), np.array([True, True])
    eight = [np.array([[0.0, 0], [1, 1], [1, 0], [0, 1]])]  # a bow tie crosses itself once
    assert rd.crossing_counts(eight, closed1) == (1, 0)
    assert rd.crossing_counts([square(2.0, 3)], closed1) == (0, 0)
    assert rd.crossing_counts([square(2.0), square(1.0)], closed2) == (0, 0)  # nested
    assert rd.crossing_counts([square(2.0), square(2.0) + 1.0], closed2) == (0, 1)  # overlapping
    assert rd.crossing_counts([np.array([[0.0, 0], [1, 1]]), np.array([[0.0, 1], [1, 0]])], [False, False]) == (0, 1)
    assert rd.crossing_counts([np.array([[0.0, 0], [1, 0], [2, 0]])], [False]) == (0, 0)  # neighbours touch


def test_crossing_sweep_matches_brute_force():
    rng = np.random.default_rng(7)
    for _ in range(5):
        contours = [rng.random((int(rng.integers(3, 15)), 2)) for _ in range(3)]
        closed = np.array([True, False, True])
        pairs = rd.crossing_pairs(contours, closed)
        assert sorted(tuple(sorted(p)) for p in pairs.tolist()) == brute_crossings(contours, closed)


# The routes --------------------------------------------------------------------------------


def test_baseline_resamples_from_the_first_point_and_blends():
    thin, black = [square(2.0)], [square(4.0, 2)]
    out = rd.baseline_inbetween(thin, black, [True], 0.5)
    assert out[0].shape == (8, 2)  # the larger point count
    np.testing.assert_allclose(out[0], square(3.0, 2), atol=1e-12)
    np.testing.assert_allclose(rd.baseline_inbetween(thin, black, [True], 0.0)[0], square(2.0, 2), atol=1e-12)


def test_baseline_follows_the_start_point():
    # The same square started one corner later: arc-length resampling from the first point
    # pairs corner k with corner k + 1, so the blend at 0.5 is the inscribed diamond.
    out = rd.baseline_inbetween([square(2.0)], [square(2.0, start=1)], [True], 0.5)
    np.testing.assert_allclose(np.abs(out[0]).sum(axis=1), 1.0)
    closed = np.array([True])
    h, _ = rd.compare_drawings(rd.Reference.of(out, closed, 0.001), rd.Reference.of([square(2.0)], closed, 0.001))
    assert h == pytest.approx(np.sqrt(0.5), abs=1e-3)


def test_fit_t_recovers_the_blend():
    thin, black = [square(2.0, 2)], [square(4.0, 2) + 0.3]
    t, residual = rd.fit_t(thin, black, rd.straight_blend(thin, black, 0.3))
    assert t == pytest.approx(0.3) and residual == pytest.approx(0.0, abs=1e-12)
    assert rd.fit_t(thin, black, rd.straight_blend(thin, black, 1.7))[0] == 1.0  # clipped


def test_score_beyond_truth():
    score = rd.Score(mean=1.0, hausdorff=2.0, self_crossing=1, pair_crossing=2)
    assert not score.crosses_beyond((1, 2))
    assert score.crosses_beyond((0, 2)) and score.crosses_beyond((1, 1))


# Command line -----------------------------------------------------------------------------


def test_command_line_arguments():
    args = rd.parse_args(["--glyphs", "aab&", "--method", "LINEAR_BALL", "--carrier", "none"])
    assert args.glyph_chars == "ab&"
    assert args.method == "linear-ball" and args.carrier.lower() == "none"
    assert rd.parse_args(["--quick"]).glyph_chars == rd.QUICK_GLYPHS
    for bad in (["--method", "nope"], ["--glyphs", "a b"], ["--jobs", "0"], ["--quick", "--glyphs", "a"]):
        with pytest.raises(SystemExit) as exc:
            rd.parse_args(bad)
        assert exc.value.code == 2
    with pytest.raises(SystemExit) as exc:  # the help text holds '%' (a glyph): argparse must not choke on it
        rd.parse_args(["--help"])
    assert exc.value.code == 0


def test_held_out_families_run_only_when_asked():
    held = tuple(f for f, *_ in rd.HELD_OUT_FAMILIES)
    assert rd.parse_args([]).families is None and rd.parse_args(["--held-out"]).families == held
    assert not set(held) & ({f for f, *_ in rd.STATIC_FAMILIES} | {f for f, _ in rd.FAMILIES})
    assert rd.family_list("Karla,Inter") == ("Karla", "Inter")  # a held-out family can be named


def test_missing_font_says_how_to_install(tmp_path):
    with pytest.raises(SystemExit, match="apt-get install fonts-inter-variable"):
        rd.find_fonts(str(tmp_path))


# On the font itself -----------------------------------------------------------------------

FONT = os.path.join(rd.FONT_DIR, rd.FAMILIES[0][1])
needs_font = pytest.mark.skipif(not os.path.isfile(FONT), reason=f"the Inter variable font is not installed ({FONT})")


@needs_font
def test_masters_are_point_compatible():
    pytest.importorskip("fontTools")
    masters = rd.load_glyph(rd.open_font(rd.FAMILIES[0][0], FONT), "o")
    assert len(masters.thin) == 2 and masters.closed.all()
    assert [len(c) for c in masters.thin] == [len(c) for c in masters.black] == [len(c) for c in masters.truths[400]]
    t, residual = rd.fit_t(masters.thin, masters.black, masters.truths[400])
    assert 0.2 < t < 0.6 and residual < 30.0  # thousandths of an em


@needs_font
def test_score_one_glyph():
    pytest.importorskip("fontTools")
    result = rd.score_glyph((rd.FAMILIES[0][0], FONT, "l", {}, 60.0))
    assert not result.error and len(result.weights) == len(rd.WEIGHTS)
    assert all(0.0 < w.t < 1.0 for w in result.weights)
    assert all(w.scores["floor"].mean < w.scores["baseline"].mean for w in result.weights)
    assert result.pairs and set(result.figure) >= {"ours", "baseline", "truth", "thin", "black"}
    missing = rd.score_glyph((rd.FAMILIES[0][0], FONT, "\u0f00", {}, 60.0))
    assert "not in" in missing.error
    raising = rd.score_glyph((rd.FAMILIES[0][0], FONT, "l", {"spacing": -1.0}, 60.0))  # the core refuses it
    assert raising.error.startswith("bm.inbetween raised") and not raising.weights


def test_pair_reasons_in_brief():
    reason = (
        "lens 1/4: not b-compatible, composite ball-morph used (not b-compatible: 17 of 18 disks (bifurcates); P s=1); "
        "lens 3/4: not b-compatible, composite ball-morph used (not b-compatible: 3 of (9 disks ...); "
        "lens 2/4: linear-interpolation used (the strokes are 'invalid'); "
        "split at 4 crossing/overlap pieces (crossing-loops)"
    )
    assert rd.short_reason(reason) == (
        "lens 1, 3 of 4: not b-compatible, composite ball-morph used; lens 2 of 4: linear-interpolation used; "
        "split at 4 crossing/overlap pieces (crossing-loops)"
    )
    assert rd.format_pair((0, None, "disappear", "")) == "0->- disappear"


def _contour(points, closed=True):
    """A contour of line segments through ``points`` (the font's start point first)."""
    pts = [np.asarray(p, dtype=np.float64) for p in points]
    return (pts[0], [p[None] for p in pts[1:]] + ([pts[0][None]] if closed else []), closed)


def test_static_instances_are_matched_to_their_neighbour():
    # Two contours: the heavier instance lists them the other way round and starts its square
    # two corners on; both are matched back (order, then the closest cyclic rotation).
    square = [(0, 0), (10, 0), (10, 10), (0, 10)]
    tri = [(20, 0), (30, 0), (25, 8)]
    light = [_contour(square), _contour(tri)]
    heavier_square = [(11, 11), (-1, 11), (-1, -1), (11, -1)]
    heavy = [_contour([(19, -1), (31, -1), (25, 9)]), _contour(heavier_square)]
    aligned = rd.align_outlines([light, heavy])
    assert rd.structure(aligned[1]) == rd.structure(light)
    starts = [tuple(c[0]) for c in aligned[1]]
    assert starts == [(-1.0, -1.0), (19.0, -1.0)], f"starts {starts}"


def test_static_instances_that_do_not_match_are_left_as_read():
    light = [_contour([(0, 0), (10, 0), (10, 10), (0, 10)])]
    other = [_contour([(0, 0), (10, 0), (5, 8)])]
    assert rd.align_outlines([light, other])[1] is other


def test_the_peer_follows_a_stem_grown_bolder_without_sliding_its_corners():
    # A rectangle growing wider: the peer's matched points keep the corners (tangent-aligned).
    thin = [np.array([[0, 0], [10, 0], [10, 100], [0, 100]], dtype=float)]
    black = [np.array([[0, 0], [60, 0], [60, 100], [0, 100]], dtype=float)]
    thin = [rd.flatten_contour(c[0], [p[None] for p in np.r_[c[1:], c[:1]]], [5] * 4) for c in thin]
    black = [rd.flatten_contour(c[0], [p[None] for p in np.r_[c[1:], c[:1]]], [5] * 4) for c in black]
    matched = rd.peer_correspondence(thin, black, np.array([True]))
    mid = rd.peer_inbetween(matched, 0.5)[0]
    truth = [rd.straight_blend(thin, black, 0.5)]
    h, _ = rd.compare_drawings(rd.Reference.of(mid[None], [True]), rd.Reference.of(truth[0], [True]))
    # Points 20 apart: knots of the two keys closer than 0.85 of that are merged (a corner may
    # give way to its neighbour on the other key).
    assert h < 3.0, f"peer's in-between of a widening stem is {h:.2f} from the straight blend"
