"""Ball-map correspondence: analytic cases, invariants, property-based checks (issue 2)."""

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from shapes import (
    circle,
    distance_to_polyline,
    graph_min_curvature_radius,
    graph_slope,
    graph_stroke,
    polar_loop,
    polar_tangent,
)

import ballmorph_core as bm
from ballmorph_core.ballmap import candidates, check
from ballmorph_core.ballmap.candidates import tangent_disks
from ballmorph_core.ballmap.topology import classify_pairs, orient_pair, orient_pairs
from ballmorph_core.geometry.intersections import is_simple
from ballmorph_core.geometry.polyline import vertex_normals

# ---------------------------------------------------------------- analytic cases


@pytest.mark.parametrize("sampling", ["symmetric", "P", "Q"])
@pytest.mark.parametrize("inner,outer", [(1.0, 3.0), (2.0, 2.5)])
def test_concentric_circles_map_radially_with_half_gap(sampling, inner, outer):
    corr = bm.ball_map(circle(inner, 180), circle(outer, 240), closed=True, sampling=sampling)
    ang_p = np.arctan2(corr.p[:, 1], corr.p[:, 0])
    ang_q = np.arctan2(corr.q[:, 1], corr.q[:, 0])
    assert np.abs(np.angle(np.exp(1j * (ang_p - ang_q)))).max() < 1e-5
    np.testing.assert_allclose(corr.radii, (outer - inner) / 2, rtol=1e-5)
    np.testing.assert_allclose(np.linalg.norm(corr.centers, axis=1), (outer + inner) / 2, rtol=1e-5)


def test_concentric_circles_all_ball_morphs_coincide():
    P, Q = circle(1.0, 150), circle(2.0, 150)
    morphs = [bm.make_morph(P, Q, m, closed=True) for m in ("circular-ball", "linear-ball", "parabolic-ball")]
    for t in (0.0, 0.25, 0.5, 0.8, 1.0):
        frames = [m(t) for m in morphs]
        np.testing.assert_allclose(np.linalg.norm(frames[0], axis=1), 1.0 + t, atol=1e-6)
        np.testing.assert_allclose(frames[1], frames[0], atol=1e-6)
        np.testing.assert_allclose(frames[2], frames[0], atol=1e-6)


def test_parallel_segments_with_shared_endpoint_caps():
    # P is the segment from (0,0) to (4,0); Q goes up, across at height 1, and down again.
    P = np.c_[np.linspace(0, 4, 81), np.zeros(81)]
    Q = np.concatenate(
        [
            np.c_[np.zeros(20), np.linspace(0, 1, 20, endpoint=False)],
            np.c_[np.linspace(0, 4, 80, endpoint=False), np.ones(80)],
            np.c_[np.full(21, 4.0), np.linspace(1, 0, 21)],
        ]
    )
    corr = bm.ball_map(P, Q, sampling="P", spacing=0.05)
    middle = (corr.p[:, 0] > 0.6) & (corr.p[:, 0] < 3.4)
    assert middle.sum() > 40
    # Between the caps the disk touches the parallel side straight above, radius half the gap.
    np.testing.assert_allclose(corr.radii[middle], 0.5, atol=1e-9)
    np.testing.assert_allclose(corr.q[middle, 0], corr.p[middle, 0], atol=1e-9)
    np.testing.assert_allclose(corr.q[middle, 1], 1.0, atol=1e-9)
    # Near a cap the disk is tangent to both the cap and the base: r = x for x < 0.5.
    near = (corr.p[:, 0] > 0.05) & (corr.p[:, 0] < 0.45)
    np.testing.assert_allclose(corr.radii[near], corr.p[near, 0], atol=1e-6)
    # Ends map to the shared endpoints with zero radius.
    assert corr.radii[0] == 0 and corr.radii[-1] == 0


def test_mirror_symmetric_lens_maps_each_point_to_its_mirror():
    x = np.linspace(0, 1, 150)
    P = np.c_[x, 0.3 * np.sin(np.pi * x)]
    Q = np.c_[x, -0.3 * np.sin(np.pi * x)]
    corr = bm.ball_map(P, Q)
    np.testing.assert_allclose(corr.q[:, 0], corr.p[:, 0], atol=1e-4)
    np.testing.assert_allclose(corr.q[:, 1], -corr.p[:, 1], atol=1e-4)
    np.testing.assert_allclose(corr.centers[:, 1], 0.0, atol=1e-4)


def test_reversed_stroke_and_counter_clockwise_loop_are_oriented():
    P = graph_stroke(0.3)
    Q = graph_stroke(-0.2)[::-1]
    corr = bm.ball_map(P, Q)
    assert corr.setup.reversed_q
    np.testing.assert_allclose(corr.q[0], P[0], atol=1e-12)
    loop = bm.ball_map(circle(1.0)[::-1], circle(2.0), closed=True)
    assert not loop.setup.reversed_p and loop.setup.reversed_q


def test_input_is_not_mutated():
    P, Q = graph_stroke(0.3), graph_stroke(-0.2)
    P0, Q0 = P.copy(), Q.copy()
    bm.make_morph(P, Q, "circular-ball")(0.5)
    np.testing.assert_array_equal(P, P0)
    np.testing.assert_array_equal(Q, Q0)


# ---------------------------------------------------------------- configurations


def test_classify_one_example_per_configuration():
    c = circle(1.0, 100)
    assert bm.classify(c, 2 * c, closed=True) == "disjoint-loops"
    assert bm.classify(c, c + [0.6, 0.0], closed=True) == "crossing-loops"
    assert bm.classify(c, c + [3.0, 0.0], closed=True) == "invalid"  # insides do not overlap
    assert bm.classify(graph_stroke(0.3), graph_stroke(-0.3), closed=False) == "quasi-disjoint-strokes"
    wavy = graph_stroke(0.0, (0.2,))
    assert bm.classify(graph_stroke(0.1), wavy, closed=False) == "crossing-strokes"
    assert bm.classify(graph_stroke(0.1), graph_stroke(0.1) + [0, 1], closed=False) == "invalid"
    figure8 = np.c_[
        np.sin(np.linspace(0, 2 * np.pi, 100, endpoint=False)),
        np.sin(2 * np.linspace(0, 2 * np.pi, 100, endpoint=False)),
    ]
    assert bm.classify(figure8, 3 * c, closed=True) == "invalid"


def _pairs_of_every_configuration():
    c = circle(1.0, 100)
    wavy = graph_stroke(0.0, (0.2,))
    figure8 = np.c_[np.sin(np.linspace(0, 2 * np.pi, 100, endpoint=False)), np.sin(2 * np.linspace(0, 2 * np.pi, 100))]
    return [
        (c, 2 * c, True),
        (c[::-1].copy(), 2 * c, True),  # counter-clockwise: oriented
        (c, c + [0.6, 0.0], True),
        (c, c + [3.0, 0.0], True),
        (graph_stroke(0.3), graph_stroke(-0.3), False),
        (graph_stroke(0.3), graph_stroke(-0.3)[::-1].copy(), False),  # reversed: oriented
        (graph_stroke(0.1), wavy, False),
        (graph_stroke(0.1), graph_stroke(0.1) + [0, 1], False),
        (figure8, 3 * c, True),
        (c, c.copy(), True),  # coincident
        (graph_stroke(0.2), graph_stroke(0.2), False),
    ]


def test_classify_and_orient_pairs_in_one_batch_answer_each_pair_as_alone():
    pairs = _pairs_of_every_configuration()
    assert classify_pairs(pairs) == [bm.classify(P, Q, closed) for P, Q, closed in pairs]
    assert set(classify_pairs(pairs)) == set(bm.ballmap.CONFIGURATIONS)
    for (P, Q, closed), got in zip(pairs, orient_pairs(pairs)):
        try:
            want = orient_pair(P, Q, closed)
        except bm.IncompatibleCurvesError as exc:
            assert isinstance(got, bm.IncompatibleCurvesError) and str(got) == str(exc)
            continue
        assert not isinstance(got, Exception)
        for name in ("P", "Q"):
            np.testing.assert_array_equal(getattr(got, name), getattr(want, name))
        for name in ("closed", "side_p", "side_q", "reversed_p", "reversed_q", "coincident"):
            assert getattr(got, name) == getattr(want, name)
    assert classify_pairs([]) == [] and orient_pairs([]) == []


def test_crossing_loops_with_two_intersection_components_are_invalid():
    # A long thin ellipse crossing a ring-like bean twice on each side: i(P) & i(Q) splits.
    t = np.linspace(0, 2 * np.pi, 400, endpoint=False)
    bean = np.c_[np.cos(t), 0.25 * np.sin(t) + 0.6 * np.cos(t) ** 2 - 0.3]
    bar = np.c_[0.2 * np.cos(t), 1.2 * np.sin(t)] + [0.0, 0.05]
    # Two separate overlaps would make it invalid; a single lens keeps it valid.
    config = bm.classify(bean, bar, closed=True)
    assert config in ("crossing-loops", "invalid")
    u = np.c_[np.cos(t), np.sin(t)] * [1.0, 0.3]
    v = np.c_[np.cos(t), np.sin(t)] * [0.3, 1.0]
    # Two crossed ellipses meet at 4 points; i(P) & i(Q) is one square-ish region: valid.
    assert bm.classify(u, v, closed=True) == "crossing-loops"


def test_incompatible_pair_is_rejected_naming_where():
    t = np.linspace(0, 2 * np.pi, 300, endpoint=False)
    P = circle(1.0, 300)
    bump = 3.0 - 1.7 * np.exp(-(np.angle(np.exp(1j * t)) ** 2) / 0.005)
    Q = np.c_[bump * np.cos(t), bump * np.sin(t)]
    with pytest.raises(bm.IncompatibleCurvesError) as err:
        bm.ball_map(P, Q, closed=True)
    report = err.value.report
    assert not report.compatible and report.violations
    # The violations are next to the bump (angle 0), and the message gives coordinates.
    angles = [abs(np.arctan2(v.p[1], v.p[0])) for v in report.violations]
    assert max(angles) < 0.8
    assert "not b-compatible" in str(err.value) and "near P(" in str(err.value)
    # Without the check the map is still produced and carries the report.
    corr = bm.ball_map(P, Q, closed=True, check=False)
    assert corr.report.violations


def test_strokes_without_shared_endpoints_are_rejected():
    with pytest.raises(bm.IncompatibleCurvesError, match="share both endpoints"):
        bm.ball_map(graph_stroke(0.3), graph_stroke(-0.3) + [0.1, 0.0])


@pytest.mark.parametrize(
    "bad,match",
    [
        (np.zeros((0, 2)), "no points"),
        (np.array([[0.0, 0.0]]), "at least 2"),
        (np.array([[0.0, 0.0], [0.0, 0.0], [0.0, 0.0]]), "at least 2"),
        (np.array([[0.0, 0.0], [np.nan, 1.0]]), "not finite"),
        (np.zeros((4, 3)), "shape"),
    ],
)
def test_malformed_input_raises_value_error_naming_argument(bad, match):
    with pytest.raises(ValueError, match=match) as err:
        bm.ball_map(bad, graph_stroke(0.3))
    assert str(err.value).startswith("P:")
    assert isinstance(err.value, bm.BallMorphError)


def test_bad_option_lists_valid_values():
    with pytest.raises(ValueError, match="'symmetric', 'p', 'q'"):
        bm.ball_map(graph_stroke(0.3), graph_stroke(-0.3), sampling="both")
    with pytest.raises(ValueError, match="circular-ball"):
        bm.make_morph(graph_stroke(0.3), graph_stroke(-0.3), method="spline")


# ---------------------------------------------------------------- random b-compatible pairs

small_coef = st.floats(-0.015, 0.015)


@st.composite
def stroke_pairs(draw):
    """Strokes y = f(x) above and below [0, 1], b-compatible with a margin: the largest maximal
    disk is at most 0.8 of either curve's smallest radius of curvature (near the boundary of
    b-compatibility, at focal points, the smooth ball-map itself degenerates)."""
    hp = draw(st.floats(0.08, 0.3))
    hq = -draw(st.floats(0.08, 0.3))
    cp = tuple(draw(st.lists(small_coef, min_size=0, max_size=2)))
    cq = tuple(draw(st.lists(small_coef, min_size=0, max_size=2)))
    n_p, n_q = draw(st.integers(60, 240)), draw(st.integers(60, 240))
    # Largest disk: at most half the largest vertical gap.
    gap = (graph_stroke(hp, cp, 400)[:, 1] - graph_stroke(hq, cq, 400)[:, 1]).max()
    assume(gap / 2 < 0.8 * min(graph_min_curvature_radius(hp, cp), graph_min_curvature_radius(hq, cq)))
    return (hp, cp, n_p), (hq, cq, n_q)


@st.composite
def loop_pairs(draw):
    cp = [(draw(st.floats(-0.05, 0.05)), draw(st.floats(0, 6.28))) for _ in range(draw(st.integers(0, 3)))]
    cq = [(draw(st.floats(-0.08, 0.08)), draw(st.floats(0, 6.28))) for _ in range(draw(st.integers(0, 3)))]
    gap = draw(st.floats(0.3, 1.2))
    shift = (draw(st.floats(-0.15, 0.15)), draw(st.floats(-0.15, 0.15)))
    P = polar_loop(cp, n=draw(st.integers(80, 300)))
    Q = polar_loop(cq, n=draw(st.integers(80, 300)), base=1.0 + gap) + np.array(shift)
    return P, Q, (cp, 1.0, (0.0, 0.0)), (cq, 1.0 + gap, shift)


def _check_contact_invariants(P, Q, closed, corr, slope_p=None, slope_q=None):
    r = corr.radii
    np.testing.assert_allclose(np.linalg.norm(corr.centers - corr.p, axis=1), r, rtol=1e-4, atol=1e-9)
    np.testing.assert_allclose(np.linalg.norm(corr.centers - corr.q, axis=1), r, rtol=1e-4, atol=1e-9)
    # Contacts lie on the curves (on the smooth curve through the vertices: within a fraction
    # of an edge of the polyline, the sagitta of a coarse polyline).
    edge = max(np.linalg.norm(np.diff(P, axis=0), axis=1).max(), np.linalg.norm(np.diff(Q, axis=0), axis=1).max())
    assert distance_to_polyline(corr.p, P, closed).max() < 0.1 * edge
    assert distance_to_polyline(corr.q, Q, closed).max() < 0.1 * edge
    # Maximality: no point of P or Q inside any disk, beyond the documented slack (a disk may be
    # entered by DISK_PENETRATION dense spacings near its contacts, NONLOCAL_* farther away).
    fine_p = bm.geometry.polyline.resample(P, closed, count=4 * len(P))
    fine_q = bm.geometry.polyline.resample(Q, closed, count=4 * len(Q))
    pts = np.concatenate([fine_p, fine_q])
    d = np.linalg.norm(pts[None, :, :] - corr.centers[:, None, :], axis=2).min(axis=1)
    slack = check.NONLOCAL_RELATIVE * r + check.NONLOCAL_PENETRATION * corr.spacing
    assert np.all(d >= r - slack - 1e-9)
    # m - p is normal to P at p and m - q normal to Q at q.
    big = r > 0.2 * r.max()
    for pts_, slope in ((corr.p, slope_p), (corr.q, slope_q)):
        v = corr.centers[big] - pts_[big]
        v /= np.linalg.norm(v, axis=1, keepdims=True)
        if slope is not None:
            tangent = np.c_[np.ones(big.sum()), slope(pts_[big, 0])]
            tangent /= np.linalg.norm(tangent, axis=1, keepdims=True)
            assert np.abs(np.einsum("ij,ij->i", v, tangent)).max() < 2e-2


@given(stroke_pairs())
def test_random_stroke_pairs_contact_invariants(pair):
    (hp, cp, n_p), (hq, cq, n_q) = pair
    P, Q = graph_stroke(hp, cp, n_p), graph_stroke(hq, cq, n_q)
    try:
        corr = bm.ball_map(P, Q)
    except bm.IncompatibleCurvesError:
        assume(False)
    _check_contact_invariants(
        P,
        Q,
        False,
        corr,
        lambda x: graph_slope(x, hp, cp),
        lambda x: graph_slope(x, hq, cq),
    )


@given(loop_pairs())
def test_random_loop_pairs_contact_invariants(pair):
    P, Q, shape_p, shape_q = pair
    try:
        corr = bm.ball_map(P, Q, closed=True)
    except bm.IncompatibleCurvesError:
        assume(False)
    _check_contact_invariants(P, Q, True, corr)
    # m - p is normal to P at p, m - q normal to Q at q (analytic tangents of the polar curves).
    for pts, shape in ((corr.p, shape_p), (corr.q, shape_q)):
        v = (corr.centers - pts) / corr.radii[:, None]
        tangent = polar_tangent(pts, *shape)
        assert np.abs(np.einsum("ij,ij->i", v, tangent)).max() < 2e-2


@given(stroke_pairs())
def test_swapping_p_and_q_gives_the_inverse_correspondence(pair):
    (hp, cp, n_p), (hq, cq, n_q) = pair
    P, Q = graph_stroke(hp, cp, n_p), graph_stroke(hq, cq, n_q)
    try:
        fwd = bm.ball_map(P, Q)
        bwd = bm.ball_map(Q, P)
    except bm.IncompatibleCurvesError:
        assume(False)
    # Symmetric sampling: the same contact pairs, roles swapped. (Where a forward and a
    # backward contact tie exactly, e.g. mirror-symmetric curves, either may be kept: they agree
    # to the discretisation error, far below the spacing.)
    assert len(bwd) == len(fwd)
    np.testing.assert_allclose(bwd.p, fwd.q, atol=1e-2 * fwd.spacing)
    np.testing.assert_allclose(bwd.q, fwd.p, atol=1e-2 * fwd.spacing)
    # Asymmetric sampling: the backward pairs still lie on the forward correspondence graph
    # (distance in the (s_p, s_q) plane; the graph may be steep where a fan leaves a point).
    back = bm.ball_map(Q, P, sampling="P")
    graph = np.c_[fwd.s_p, fwd.s_q]
    assert distance_to_polyline(np.c_[back.s_q, back.s_p], graph, False).max() < fwd.spacing


@given(loop_pairs())
def test_swapping_loops_gives_the_inverse_correspondence(pair):
    P, Q = pair[:2]
    try:
        fwd = bm.ball_map(P, Q, closed=True, sampling="P")
        bwd = bm.ball_map(Q, P, closed=True, sampling="P")
    except bm.IncompatibleCurvesError:
        assume(False)
    # Every backward pair (q -> p) is also a pair of the forward map.
    d = np.linalg.norm(fwd.p[None] - bwd.q[:, None], axis=2)
    nearest = np.argmin(d, axis=1)
    # p of the backward map lies between two forward samples, so compare its image.
    gap = np.linalg.norm(fwd.q[nearest] - bwd.p, axis=1)
    assert gap.max() < 3 * fwd.spacing * max(1.0, fwd.radii.max())


@pytest.mark.parametrize("kind", ["circular", "parabolic", "linear"])
@given(pair=stroke_pairs())
def test_random_morph_endpoints_orthogonality_speed_and_simplicity(kind, pair):
    (hp, cp, n_p), (hq, cq, n_q) = pair
    P, Q = graph_stroke(hp, cp, n_p), graph_stroke(hq, cq, n_q)
    try:
        morph = bm.make_morph(P, Q, f"{kind}-ball")
    except bm.IncompatibleCurvesError:
        assume(False)
    corr = morph.correspondence
    np.testing.assert_allclose(morph(0.0), corr.p, atol=1e-12)
    assert distance_to_polyline(morph(1.0), Q, False).max() < 1e-3
    ts = np.linspace(0, 1, 101)
    frames = morph.frames(ts)
    # Uniform arc-length speed along each trajectory (chords of 1/100 of a path differ from
    # its arc by far less than the tolerance).
    steps = np.linalg.norm(np.diff(frames, axis=0), axis=2)
    moving = steps.mean(axis=0) > 1e-6
    rel = (steps.max(axis=0) - steps.min(axis=0))[moving] / steps.mean(axis=0)[moving]
    assert rel.max() < 1e-3
    # Circular and parabolic paths leave P and reach Q at right angles.
    if kind != "linear":
        big = corr.radii > 0.2 * corr.radii.max()
        start = morph(1e-4)[big] - morph(0.0)[big]
        end = morph(1.0)[big] - morph(1 - 1e-4)[big]
        n_p, n_q = corr.normal_p[big], corr.normal_q[big]
        cos_p = np.einsum("ij,ij->i", start, n_p) / np.linalg.norm(start, axis=1)
        cos_q = np.einsum("ij,ij->i", end, -n_q) / np.linalg.norm(end, axis=1)
        assert cos_p.min() > 0.999 and cos_q.min() > 0.999
    # In-between frames of a b-compatible pair do not self-intersect.
    for frame in frames[1:-1:10]:
        assert is_simple(frame, False)


@given(loop_pairs())
def test_random_loop_morph_frames_are_simple_and_closed_end_on_q(pair):
    P, Q = pair[:2]
    try:
        morph = bm.make_morph(P, Q, "circular-ball", closed=True)
    except bm.IncompatibleCurvesError:
        assume(False)
    edge = max(np.linalg.norm(np.diff(P, axis=0), axis=1).max(), np.linalg.norm(np.diff(Q, axis=0), axis=1).max())
    assert distance_to_polyline(morph(0.0), P, True).max() < 0.1 * edge
    assert distance_to_polyline(morph(1.0), Q, True).max() < 0.1 * edge
    for t in (0.2, 0.5, 0.8):
        assert is_simple(morph(t), True)


def test_vertex_normals_are_unit_and_orthogonal_on_a_circle():
    c = circle(2.0, 64)
    n = vertex_normals(c, True)
    np.testing.assert_allclose(np.linalg.norm(n, axis=1), 1.0)
    # Left normals of a counter-clockwise circle point inwards.
    np.testing.assert_allclose(n, -c / 2.0, atol=1e-12)


def test_tangent_disks_are_the_smallest_disk_touching_each_edge():
    # Random samples and edges (coordinate rows): the radius is the least of the edge's
    # tangent disk (contact on the edge) and its two vertices' disks, and the disk touches.
    rng = np.random.default_rng(5)
    k = 400
    x, a, b = rng.uniform(-1, 1, (3, 2, k))
    n = rng.normal(size=(2, k))
    n /= np.linalg.norm(n, axis=0)
    N = np.array([a[1] - b[1], b[0] - a[0]]) * rng.choice([-1.0, 1.0], k)  # the edges' normals
    N /= np.linalg.norm(N, axis=0)
    r, u = tangent_disks(x, n, a, b, N, 1e-12)
    for i in range(k):
        xi, ni, ai, bi, Ni = x[:, i], n[:, i], a[:, i], b[:, i], N[:, i]
        radii = [np.inf]
        den = 1.0 - ni @ Ni
        r_e = (xi - ai) @ Ni / den if den > 1e-12 else np.inf
        if np.isfinite(r_e) and r_e >= 0:
            f = (xi + r_e * (ni - Ni) - ai) @ (bi - ai) / ((bi - ai) @ (bi - ai))
            radii.append(r_e if -1e-9 <= f <= 1 + 1e-9 else np.inf)
        for v in (ai, bi):
            dv = v - xi
            radii.append(dv @ dv / (2.0 * dv @ ni) if dv @ ni > 0 else np.inf)
        assert r[i] == pytest.approx(min(radii), rel=1e-9)
        if np.isfinite(r[i]):
            contact = ai + u[i] * (bi - ai)
            assert np.linalg.norm(xi + r[i] * ni - contact) == pytest.approx(r[i], rel=1e-6, abs=1e-9)


# ---------------------------------------------------------------- the disk check's search


def _per_disk(query, point, n):
    """Each disk's vertices in the order they were reported."""
    return [point[query == k].tolist() for k in range(n)]


@pytest.mark.parametrize("seed", range(12))
def test_disks_asked_in_runs_find_the_vertices_each_disk_finds(seed):
    # Three chains of two wavy curves each; disks walk along each chain's gap a little apart,
    # small ones (empty: their runs are cleared at once) and some reaching the curves.
    from ballmorph_core.geometry.spatial import CurveTree

    rng = np.random.default_rng(seed)
    curves, disks = [], []
    for c in range(3):
        x = np.linspace(0, 1, rng.integers(20, 120))
        wave = 0.02 * np.sin(rng.uniform(3, 12) * x + rng.uniform(0, 6))
        curves.append((np.c_[x, wave + 0.1] + c, np.c_[x, wave - 0.1] + c))
        k = rng.integers(1, 60)
        centre = np.c_[np.sort(rng.uniform(0, 1, k)), rng.normal(0, 0.01, k)] + c
        radius = np.where(rng.random(k) < 0.15, rng.uniform(0.1, 0.3, k), rng.uniform(0.0, 0.07, k))
        disks.append((centre, radius, np.full(k, c)))
    pts = np.concatenate([p for p, _ in curves] + [q for _, q in curves])
    sizes = [len(p) for p, _ in curves] + [len(q) for _, q in curves]
    tree = CurveTree(pts, np.r_[0, np.cumsum(sizes)])
    centres, radii, chain = (np.concatenate(v) for v in zip(*disks))
    own = np.c_[chain, chain + 3]
    want = _per_disk(*tree.within(centres, radii, own, first_only=True), len(centres))
    got = _per_disk(*check._entered(tree, centres, radii, own, chain), len(centres))
    assert got == want
    # Both kinds of disk occur: empty ones and ones a curve enters.
    assert any(want) and not all(want)


def _plain_tangent_disks(x, n, a, b, N, eps):
    """tangent_disks as plain expressions (its first version): the in-place one must match it bit for bit."""
    (xx, xy), (nx, ny), (ax, ay), (Nx, Ny) = x, n, a, N
    dx, dy = b[0] - ax, b[1] - ay
    len2 = dx * dx + dy * dy
    num = (xx - ax) * Nx + (xy - ay) * Ny
    den = 1.0 - (nx * Nx + ny * Ny)
    with np.errstate(divide="ignore", invalid="ignore"):
        r_e = np.where(den > 1e-12, num / den, np.inf)
    r_e = np.where(r_e >= -eps, np.maximum(r_e, 0.0), np.inf)
    step = np.where(np.isfinite(r_e), r_e, 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        u = ((xx + step * (nx - Nx) - ax) * dx + (xy + step * (ny - Ny) - ay) * dy) / len2
    r_e = np.where((u >= -1e-9) & (u <= 1 + 1e-9), r_e, np.inf)
    u = np.clip(np.nan_to_num(u), 0.0, 1.0)
    best_r, best_u = r_e, u
    for (vx, vy), uu in ((a, 0.0), (b, 1.0)):
        ex, ey = vx - xx, vy - xy
        dist2 = ex * ex + ey * ey
        den_v = 2.0 * (ex * nx + ey * ny)
        with np.errstate(divide="ignore", invalid="ignore"):
            r_v = np.where(den_v > 0, dist2 / den_v, np.inf)
        r_v = np.where(dist2 <= eps * eps, 0.0, r_v)
        better = r_v < best_r
        best_r = np.where(better, r_v, best_r)
        best_u = np.where(better, uu, best_u)
    return best_r, best_u


@pytest.mark.parametrize("seed", range(4))
def test_tangent_disks_are_bitwise_the_plain_expressions(seed):
    # Random samples and edges, with the special cases mixed in: zero-length edges, edges
    # facing the normal (parallel), samples on a vertex or on the edge's line.
    rng = np.random.default_rng(seed)
    k = 3000
    x, a, b = rng.uniform(-1, 1, (3, 2, k))
    n = rng.normal(size=(2, k))
    n /= np.linalg.norm(n, axis=0)
    b[:, ::17] = a[:, ::17]
    x[:, 5::19] = a[:, 5::19]
    x[:, 7::23] = a[:, 7::23] + rng.uniform(0, 1, len(range(7, k, 23))) * (b - a)[:, 7::23]
    N = np.array([a[1] - b[1], b[0] - a[0]]) * rng.choice([-1.0, 1.0], k)
    with np.errstate(invalid="ignore"):
        N /= np.linalg.norm(N, axis=0)
    N = np.nan_to_num(N)
    N[:, 3::29] = n[:, 3::29]
    # NaN and infinite coordinates and normals: NaN denominators, infinite distances.
    x[0, 11::31], n[1, 13::37], N[0, 15::41], b[1, 17::43] = np.nan, np.nan, np.nan, np.nan
    x[1, 19::47], b[0, 21::53] = np.inf, -np.inf
    for eps in (1e-12, 1e-3):
        with np.errstate(all="ignore"):
            got, want = tangent_disks(x, n, a, b, N, eps), _plain_tangent_disks(x, n, a, b, N, eps)
        for g, w in zip(got, want):
            np.testing.assert_array_equal(g.view(np.int64), w.view(np.int64))


@pytest.mark.parametrize("seed", range(6))
def test_first_minima_of_groups_match_group_argmin(seed):
    # Groups of every size (empty ones too), values with many ties and a few NaNs (the last
    # group's one value too: no minimum after the last one found).
    from ballmorph_core.ballmap.lacing import _first_minima
    from ballmorph_core.geometry.ragged import group_argmin, ragged_arange

    rng = np.random.default_rng(seed)
    counts = rng.integers(0, 6, 200)
    counts[:2], counts[-1] = [0, 3], 1
    owner, _ = ragged_arange(counts)
    values = rng.integers(0, 4, len(owner)).astype(float)
    values[rng.random(len(owner)) < 0.03] = np.nan
    values[-1] = np.nan
    want = group_argmin(values, owner, len(counts))
    np.testing.assert_array_equal(_first_minima(values, counts), want)
    np.testing.assert_array_equal(_first_minima(values, counts, np.cumsum(counts)), want)
    # Without the empty groups (the lacing's case: every group filled, none masked out).
    filled = counts[counts > 0]
    owner, _ = ragged_arange(filled)
    np.testing.assert_array_equal(_first_minima(values, filled), group_argmin(values, owner, len(filled)))


@pytest.mark.parametrize("closed", [False, True])
def test_local_depths_are_the_nearest_vertex_of_the_window_round_each_contact(closed):
    # Brute force, row by row: the vertices LOCAL_WINDOW before to LOCAL_WINDOW + 1 after the
    # contact's edge (wrapping round a loop, stopping at a stroke's ends), the nearest one.
    from ballmorph_core.ballmap.sides import Sides

    rng = np.random.default_rng(3)
    curves = [circle(1.0 + c, 40 + 30 * c)[: None if closed else 25 + 20 * c] for c in range(3)]
    side = Sides(curves, np.full(3, closed), np.ones(3), np.full(3, 0.05))
    rg = side.rg
    chain = np.sort(rng.integers(0, 3, 300))
    s = rng.uniform(-0.1, 1.1, 300) * rg.length[chain]
    centres, radii = rng.uniform(-2, 2, (300, 2)), rng.uniform(0, 1, 300)
    start = check._window_starts(side, chain, s)
    depth = check._local_depths(side, start, centres, radii)
    witness = check._nearest_vertices(side, start, centres)
    edge, _ = rg.locate(chain, s)
    for k, c in enumerate(chain):
        local = edge[k] - rg.offsets[c] + np.arange(-check.LOCAL_WINDOW, check.LOCAL_WINDOW + 2)
        local = local % rg.n[c] if closed else np.clip(local, 0, rg.n[c] - 1)
        g = rg.offsets[c] + local
        d = np.linalg.norm(rg.pts[g] - centres[k], axis=1)
        assert witness[k] == g[np.argmin(d)]
        assert depth[k] == pytest.approx(radii[k] - d.min(), abs=1e-12)


@pytest.mark.parametrize("closed", [False, True])
@pytest.mark.parametrize("repeated", [False, True])
def test_vertex_window_starts_are_the_windows_located_at_the_vertices(closed, repeated):
    # Curves of every size (a dot, two points), as the window starts found by locating every
    # vertex's own arc length; with repeated vertices (edges of no length, a curve of no
    # length: arc lengths not strictly increasing) the vertices are located as such.
    from types import SimpleNamespace

    from ballmorph_core.geometry.ragged import Ragged

    rng = np.random.default_rng(7)
    curves = [rng.uniform(-1, 1, (k, 2)) for k in (5, 1, 2, 17, 3)]
    if repeated:
        curves[3][6] = curves[3][5]
        curves.append(np.zeros((3, 2)) + 0.5)
    side = SimpleNamespace(rg=Ragged.from_list(curves, closed))
    rg = side.rg
    if not closed:
        # Summed edge by edge, a stroke's last arc length may overshoot its length (located
        # at the length: still on the last edge).
        last = rg.offsets[1:-1:2] - 1
        rg.s[last] = np.nextafter(rg.length[: len(last) * 2 : 2], np.inf)
    assert np.all(np.diff(rg.global_s()[0]) > 0) != repeated
    want = check._window_starts(side, rg.owner, rg.s)
    np.testing.assert_array_equal(check._vertex_window_starts(side), want)


@pytest.mark.parametrize("seed", range(4))
def test_thinning_steps_and_picks_are_the_plain_ones(seed):
    # The larger steps are np.diff's (prepended, first rows zeroed), bit for bit, infinite
    # positions too; the picks' unique values are np.unique's, in order or not.
    from ballmorph_core.ballmap import thinning

    rng = np.random.default_rng(seed)
    sp_, sq_ = np.cumsum(rng.exponential(1.0, (2, 300)), axis=1) * rng.choice([1.0, -1.0], 2)[:, None]
    sp_[rng.integers(0, 300, 3)] = np.inf
    starts = np.unique(np.r_[0, rng.integers(0, 300, 7)])
    with np.errstate(invalid="ignore"):
        want = np.maximum(np.abs(np.diff(sp_, prepend=sp_[:1])), np.abs(np.diff(sq_, prepend=sq_[:1])))
        want[starts] = 0.0
        got = thinning._larger_steps(sp_, sq_, starts)
    np.testing.assert_array_equal(got.view(np.int64), want.view(np.int64))
    picks = np.sort(rng.integers(0, 50, 200))
    for p in (picks, rng.permutation(picks), picks[:0], picks[:1]):
        got = thinning._sorted_unique(p)
        np.testing.assert_array_equal(got, np.unique(p))
        assert got.dtype == np.unique(p).dtype


def _wavy_sides(rng, count, shift):
    """Sides of a few open wavy strokes (gap above), shifted by ``shift``."""
    from ballmorph_core.ballmap.sides import Sides

    curves = []
    for c in range(count):
        x = np.linspace(0, 1, 50)
        curves.append(np.c_[x, 0.05 * np.sin(rng.uniform(2, 9) * x + rng.uniform(0, 6))] + [0, shift + 3 * c])
    return Sides(curves, np.zeros(count, bool), np.full(count, 1.0), np.full(count, rng.uniform(0.003, 0.02)))


@pytest.mark.parametrize("seed", range(8))
def test_pruned_search_finds_what_the_whole_window_finds(seed):
    # Samples above wavy strokes (some exactly on them: zero disks), searched over random wide
    # windows with good and bad guesses of the contact: bit for bit the unpruned search.
    from ballmorph_core.ballmap import lacing

    rng = np.random.default_rng(seed)
    dst = _wavy_sides(rng, 3, 0.0)
    src = _wavy_sides(rng, 3, rng.uniform(0.01, 0.2))
    rg = src.rg
    k = rng.integers(0, len(rg.pts), 400)
    chain = rg.owner[k]
    x, n = rg.pts[k].copy(), src.vnormals[k]
    on = rng.random(400) < 0.1
    x[on] = dst.rg.pts[np.minimum(k[on], dst.rg.offsets[chain[on] + 1] - 1)]
    n_e = dst.rg.n_edges[chain]
    e_lo = rng.integers(0, n_e // 2)
    e_hi = np.minimum(e_lo + rng.integers(0, n_e), n_e - 1)
    good = (k - rg.offsets[chain]) * n_e / np.maximum(rg.n[chain] - 1, 1)
    x, n = np.ascontiguousarray(x.T), np.ascontiguousarray(n.T)
    for guess in (good, rng.uniform(0, n_e)):
        want = lacing._search(x, n, dst, chain, e_lo, e_hi, 1e-9)
        got = lacing._search(x, n, dst, chain, e_lo, e_hi, 1e-9, guess)
        assert (e_hi - e_lo + 1 > lacing.WIDE_WINDOW).sum() > 100
        for g, w in zip(got, want):
            np.testing.assert_array_equal(g.view(np.int64), w.view(np.int64))


@pytest.mark.parametrize("seed", range(4))
def test_contacts_and_refinements_of_strokes_are_those_of_a_batch_with_a_loop(seed):
    # Open strokes alone take the route without laps; with a loop in the batch (after them:
    # the strokes' arrays are the same) the contacts and refinements of the strokes' samples
    # are bit for bit the same.
    from ballmorph_core.ballmap import lacing
    from ballmorph_core.ballmap.sides import Sides

    rng = np.random.default_rng(seed)
    curves = [
        np.c_[x, 0.05 * np.sin(rng.uniform(2, 9) * x)] + [0, 3 * c] for c, x in enumerate([np.linspace(0, 1, 50)] * 3)
    ]
    h = np.full(4, 0.01)
    alone = Sides(curves, np.zeros(3, bool), np.ones(3), h[:3])
    mixed = Sides(curves + [circle(0.5, 60, (5.0, 5.0))], np.r_[False, False, False, True], np.ones(4), h)
    src = _wavy_sides(rng, 3, 0.05)
    k = rng.integers(0, len(src.rg.pts), 300)
    chain = src.rg.owner[k]
    pos = rng.uniform(0, 1.0, 300) * alone.rg.n_edges[chain]
    pos[::7] = np.floor(pos[::7])
    r = rng.uniform(0.0, 0.3, 300)
    x, n = src.rg.pts[k], src.vnormals[k]
    loop = np.full(20, 3)
    both = (np.r_[chain, loop], np.r_[pos, rng.uniform(0, 120, 20)])
    for got, want in (
        (lacing.contacts(alone, chain, pos), lacing.contacts(mixed, *both)),
        (
            lacing.refine(x, n, alone, chain, pos, r, 1e-9),
            lacing.refine(np.r_[x, x[:20]], np.r_[n, n[:20]], mixed, *both, np.r_[r, r[:20]], 1e-9),
        ),
    ):
        for g, w in zip(got, want):
            np.testing.assert_array_equal(g, w[:300])
            if g.dtype.kind == "f":
                np.testing.assert_array_equal(g.view(np.int64), w[:300].view(np.int64))


def test_same_lap_without_loops_keeps_the_positions():
    from ballmorph_core.ballmap.lacing import same_lap

    rng = np.random.default_rng(1)
    s_new, s_ref, length = rng.uniform(0, 10, (3, 50))
    for closed in (np.zeros(50, bool), rng.random(50) < 0.5):
        want = np.where(closed, s_new + length * np.round((s_ref - s_new) / length), s_new)
        got = same_lap(s_new, s_ref, length, closed)
        np.testing.assert_array_equal(got.view(np.int64), want.view(np.int64))
        assert got is not s_new


def test_edge_blocks_hold_their_edges():
    from ballmorph_core.ballmap.sides import EDGE_BLOCK

    side = _wavy_sides(np.random.default_rng(2), 3, 0.0)
    (x, y), (ex, ey) = side.columns[0], side.columns[1]
    x0, y0, x1, y1, longest = side.blocks
    b = side.block_of(np.arange(len(x)))
    for px, py in ((x, y), (x + ex, y + ey)):
        assert np.all((x0[b] <= px) & (px <= x1[b]) & (y0[b] <= py) & (py <= y1[b]))
    assert np.all(np.hypot(ex, ey) <= longest[b] * (1 + 1e-15))
    assert len(longest) == -(-len(x) // EDGE_BLOCK)


def test_one_tree_answers_both_directions_as_a_tree_of_their_own_would():
    # Disks between two sides, asked from P to Q, then from Q to P of the same shared tree:
    # each direction gets the vertices (numbered source first) a tree of its own finds.
    from ballmorph_core.geometry.spatial import CurveTree

    rng = np.random.default_rng(4)
    sp, sq = _wavy_sides(rng, 3, 0.0), _wavy_sides(rng, 3, 0.08)
    trees = check._Trees()
    for src, dst in ((sp, sq), (sq, sp)):
        k = np.sort(rng.integers(0, len(src.rg.pts), 300))
        chain = src.rg.owner[k]
        centres = src.rg.pts[k] + rng.normal(0, 0.03, (300, 2))
        radii = rng.uniform(0, 0.08, 300)
        n_src = len(src.rg.pts)
        own_tree = CurveTree(
            np.concatenate([src.rg.pts, dst.rg.pts]), np.r_[src.rg.offsets, dst.rg.offsets[1:] + n_src]
        )
        want = own_tree.within(centres, radii, np.c_[chain, chain + 3], first_only=True)
        got = trees.entered(src, dst, centres, radii, chain)
        assert _per_disk(*got, 300) == _per_disk(*want, 300)
        assert any(_per_disk(*want, 300))
    assert len(trees._built) == 1


def test_sides_densify_exactly_the_coarse_curves():
    # Coarse polygons (subdivided first) among dense curves, loops and strokes: the dense
    # curves are those of every curve handed to densify, bit for bit.
    from ballmorph_core.ballmap.sides import Sides
    from ballmorph_core.geometry.ragged import Ragged
    from ballmorph_core.geometry.spline import densify

    curves = [circle(1.0, 6), circle(2.0, 300), graph_stroke(0.2, (), 5), graph_stroke(0.1, (0.01,), 200)]
    closed = np.array([True, True, False, False])
    spacing = np.array([0.02, 0.05, 0.01, 0.03])
    side = Sides(curves, closed, np.ones(4), spacing)
    raw = Ragged.from_list([densify(c, cl, h) for c, cl, h in zip(curves, closed, spacing)], closed)
    want = raw.resample(np.round(raw.length / spacing).astype(np.int64) + np.where(closed, 0, 1))
    assert len(raw.pts) > sum(len(c) for c in curves)  # the coarse ones were subdivided
    np.testing.assert_array_equal(side.rg.pts, want.pts)
    np.testing.assert_array_equal(side.rg.offsets, want.offsets)


@pytest.mark.parametrize("seed", range(6))
def test_chain_order_is_lexsort_by_chain_then_key(seed):
    # Two runs of chains (as both one-way maps come), keys with many ties, signed zeros,
    # infinities (and NaNs): the very permutation of np.lexsort.
    from ballmorph_core.ballmap.thinning import chain_order

    rng = np.random.default_rng(seed)
    chain = np.concatenate([np.sort(rng.integers(0, 30, 400)), np.sort(rng.integers(0, 30, 300))])
    key = rng.integers(-3, 4, len(chain)).astype(float)
    key[rng.random(len(chain)) < 0.2] = -0.0
    key[rng.random(len(chain)) < 0.05] = rng.choice([np.inf, -np.inf])
    if seed >= 4:
        key[rng.random(len(chain)) < 0.05] = np.nan
    if seed % 2:
        rng.shuffle(chain)
    np.testing.assert_array_equal(chain_order(chain, key), np.lexsort((key, chain)))


def _bisected_disks(ends, edges, windows, eps, iterations):
    """disk_between as plain bisection, one level per evaluation (the reference)."""
    x0, n0, x1, n1 = ends
    lo, hi = np.zeros(len(x0)), np.ones(len(x0))

    def evaluate(lam):
        x = x0 + lam[:, None] * (x1 - x0)
        n = n0 + lam[:, None] * (n1 - n0)
        n /= np.linalg.norm(n, axis=1, keepdims=True)
        return x, n, [candidates._smallest_in_windows(x, n, edges, w, eps) for w in windows]

    for _ in range(iterations):
        mid = (lo + hi) / 2
        _, _, ((ra, _), (rb, _)) = evaluate(mid)
        lo, hi = np.where(ra < rb, mid, lo), np.where(ra < rb, hi, mid)
    x, n, ((ra, qa), (rb, qb)) = evaluate((lo + hi) / 2)
    return x, n, np.minimum(ra, rb), qa, qb


@given(st.integers(0, 2**32 - 1), st.sampled_from([1, 4, 5, 7, 40]))
@settings(max_examples=30, deadline=None)
def test_disk_between_decides_several_levels_at_once_like_plain_bisection(seed, iterations):
    """Bridging disks: every midpoint of the next levels evaluated at once gives bit for bit
    what bisecting one level at a time gives, for rows of their own windows."""
    rng = np.random.default_rng(seed)
    rows = int(rng.integers(1, 4))
    other = np.cumsum(rng.normal(size=(30, 2)), axis=0) + [0.0, 4.0]
    a, b = other[:-1], other[1:]
    N = np.c_[-(b - a)[:, 1], (b - a)[:, 0]]
    N /= np.linalg.norm(N, axis=1, keepdims=True)
    x0, x1 = rng.normal(size=(rows, 2)), rng.normal(size=(rows, 2))
    n0, n1 = (rng.normal(size=(rows, 2)) + [0.0, 2.0] for _ in range(2))
    n0, n1 = (v / np.linalg.norm(v, axis=1, keepdims=True) for v in (n0, n1))
    windows = tuple(
        [np.sort(rng.choice(29, int(rng.integers(1, 12)), replace=False)) for _ in range(rows)] for _ in range(2)
    )
    ends = (x0, n0, x1, n1)
    got = candidates.disk_between(ends, (a, b, N), windows, 1e-9, iterations=iterations)
    want = _bisected_disks(ends, (a, b, N), windows, 1e-9, iterations)
    for g, w in zip(got, want):
        np.testing.assert_array_equal(g, w)
