"""The six quality measures (paper section 6): known values, invariants, fairness of sampling."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from shapes import circle, graph_stroke

import ballmorph_core as bm
from ballmorph_core.morphs.base import PathMorph
from ballmorph_core.morphs.paths import BallPaths
from ballmorph_core.study.measures import (
    MEASURES,
    accelerations,
    distortions,
    mean_curvature_sq,
    measure_frames,
    sample_weights,
    stretches,
    strip_mesh,
    travel_distances,
)


def ellipse(a, b, n):
    t = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    return np.c_[a * np.cos(t), b * np.sin(t)]


def similarity_frames(curve, steps, rotation=0.0, scale=1.0, shift=(0.0, 0.0), centre=(0.0, 0.0)):
    """A steady similarity motion: z_t = c + a^t (z - c) + t shift (complex a), shape (T + 1, K, 2)."""
    z = curve[:, 0] + 1j * curve[:, 1]
    c = complex(*centre)
    t = np.linspace(0.0, 1.0, steps + 1)[:, None]
    a_t = np.exp(t * (np.log(scale) + 1j * rotation))
    zt = c + a_t * (z[None, :] - c) + t * complex(*shift)
    return np.stack([zt.real, zt.imag], axis=-1)


SEGMENT = np.c_[np.linspace(0.0, 1.0, 41), np.zeros(41)]
WAVE = graph_stroke(0.3, (0.1,), n=60)

# ---------------------------------------------------------------- known values


@pytest.mark.parametrize(
    "method", ["circular-ball", "linear-ball", "parabolic-ball", "hat-ball", "linear-interpolation"]
)
def test_concentric_circles_travel_the_radius_gap(method):
    scores = bm.measure(circle(1.0, 160), circle(2.5, 220), method, closed=True, steps=10)
    assert scores["travel_distance"] == pytest.approx(1.5, rel=1e-5)
    # Radial motion is along the normal: no distortion; a cone is smooth: finite curvature.
    assert scores["distortion"] < 1e-4
    assert 0 < scores["mean_curvature_sq_avg"] < 1.0


def test_travel_polyline_equals_exact_lengths_for_straight_paths():
    morph = bm.make_morph(circle(1.0, 120), ellipse(1.7, 1.3, 150), "linear-ball", closed=True)
    frames = morph.frames(np.linspace(0, 1, 7))
    np.testing.assert_allclose(travel_distances(frames), morph.paths.lengths(), rtol=1e-9)
    # Curved paths: the polyline through T + 1 points is shorter than the arc, and converges to it.
    morph = bm.make_morph(circle(1.0, 120), ellipse(1.7, 1.3, 150), "circular-ball", closed=True)
    exact = morph.paths.lengths()
    coarse = travel_distances(morph.frames(np.linspace(0, 1, 3)))
    fine = travel_distances(morph.frames(np.linspace(0, 1, 81)))
    assert np.all(coarse <= exact + 1e-12)
    np.testing.assert_allclose(fine, exact, rtol=1e-3)


def test_circular_ball_morph_between_segments_is_a_rotation_without_distortion():
    # Paper Fig. 19: P on the x axis, Q at 50 degrees, meeting at O. The maximal disk tangent to
    # P at (s, 0) is centred on the bisector; it touches Q at the mirror image of p; the
    # circular path's centre is where the tangents meet: O. So every frame is P rotated about O.
    angle = np.deg2rad(50.0)
    s = np.linspace(0.05, 1.0, 40)
    p = np.c_[s, np.zeros_like(s)]
    m = np.c_[s, s * np.tan(angle / 2)]
    q = np.c_[s * np.cos(angle), s * np.sin(angle)]
    morph = PathMorph("circular-ball", False, BallPaths(p, m, q, "circular"), s, s)
    frames = morph.frames(np.linspace(0, 1, 21))
    np.testing.assert_allclose(np.linalg.norm(frames, axis=2), np.broadcast_to(s, (21, 40)), atol=1e-12)
    np.testing.assert_allclose(distortions(frames, False), 0.0, atol=1e-12)
    np.testing.assert_allclose(accelerations(frames, False), 0.0, atol=1e-9)
    # The linear ball-morph between the same segments cuts the corner: it distorts.
    linear = PathMorph("linear-ball", False, BallPaths(p, m, q, "linear"), s, s)
    assert distortions(linear.frames(np.linspace(0, 1, 21)), False).min() > 0.1


def test_sliding_along_the_curve_is_full_distortion():
    frames = similarity_frames(SEGMENT, 8, shift=(0.5, 0.0))
    np.testing.assert_allclose(distortions(frames, False), 1.0, atol=1e-12)
    # ... and moving along the normal is none.
    frames = similarity_frames(SEGMENT, 8, shift=(0.0, 0.5))
    np.testing.assert_allclose(distortions(frames, False), 0.0, atol=1e-12)


@pytest.mark.parametrize("closed", [False, True])
def test_translation_has_no_stretch_and_no_acceleration(closed):
    curve = circle(1.0, 50) if closed else WAVE
    frames = similarity_frames(curve, 12, shift=(0.7, -0.3))
    np.testing.assert_allclose(stretches(frames, closed), 0.0, atol=1e-12)
    np.testing.assert_allclose(accelerations(frames, closed), 0.0, atol=1e-9)


def test_uniform_scaling_stretch():
    # A loop scaled from length a to 2a: every edge changes by |b - a| in total; normalised by
    # the mean length: 2 |b - a| / (a + b) = 2/3.
    frames = similarity_frames(circle(1.0, 64), 10, scale=2.0)
    w = sample_weights(frames[0], frames[-1], True)
    assert np.dot(w, stretches(frames, True, w)) / w.sum() == pytest.approx(2.0 / 3.0, rel=1e-12)


@pytest.mark.parametrize("closed", [False, True])
def test_steady_similarity_spirals_have_no_acceleration(closed):
    curve = circle(1.0, 40, centre=(0.3, 0.1)) if closed else WAVE
    frames = similarity_frames(curve, 16, rotation=1.1, scale=1.8, centre=(2.0, -1.0))
    np.testing.assert_allclose(accelerations(frames, closed), 0.0, atol=1e-8)


def test_unsteady_motion_has_acceleration():
    # Linear interpolation between a circle and an ellipse: straight paths at constant speed
    # whose local frame shears as the curve changes: not steady.
    morph = bm.make_morph(circle(1.0, 120), ellipse(2.0, 1.2, 150), "linear-interpolation", closed=True)
    acc = accelerations(morph.frames(np.linspace(0, 1, 21)), True)
    assert acc.max() > 1e-3
    # The frames move with the neighbours: a common change of speed (easing a rigid motion)
    # is not unsteadiness in this sense.
    t = np.linspace(0, 1, 11)[:, None, None] ** 2
    eased = SEGMENT[None] + t * np.array([0.0, 1.0])
    np.testing.assert_allclose(accelerations(eased, False), 0.0, atol=1e-9)


def test_cylinder_mean_curvature():
    # A static circle stacked along z is a cylinder: H = 1 / (2 R).
    radius = 0.8
    frames = np.broadcast_to(circle(radius, 120), (31, 120, 2))
    avg, peak = mean_curvature_sq(frames, True, height=2.0)
    assert avg == pytest.approx(1.0 / (4 * radius**2), rel=2e-3)
    assert peak == pytest.approx(1.0 / (4 * radius**2), rel=2e-3)


def test_plane_has_no_mean_curvature():
    # A segment translating steadily sweeps a plane.
    frames = similarity_frames(SEGMENT, 10, shift=(0.2, 1.0))
    avg, peak = mean_curvature_sq(frames, False, height=1.0)
    assert peak < 1e-20 and avg < 1e-20


def test_strip_mesh_topology():
    frames = similarity_frames(circle(1.0, 10), 4, scale=1.5)
    vertices, tri, interior = strip_mesh(frames, True, 3.0)
    assert vertices.shape == (50, 3) and tri.shape == (2 * 4 * 10, 3)
    np.testing.assert_allclose(vertices[-10:, 2], 3.0)
    interior_count = interior.sum()
    assert interior_count == 30

    def euler_and_edge_use(triangles, n_vertices):
        pairs = np.sort(np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]]), axis=1)
        _, uses = np.unique(pairs, axis=0, return_counts=True)
        return n_vertices - len(uses) + len(triangles), uses.max()

    # A loop's frames make a tube (Euler characteristic 0), a stroke's a disk (1); every edge
    # belongs to at most two triangles.
    assert euler_and_edge_use(tri, 50) == (0, 2)
    _, tri_open, interior_open = strip_mesh(frames[:, :6], False, 1.0)
    assert len(tri_open) == 2 * 4 * 5 and interior_open.sum() == 3 * 4
    assert euler_and_edge_use(tri_open, 30) == (1, 2)


def test_weights_sum_to_the_mean_length():
    p, q = WAVE, graph_stroke(-0.2, n=60)
    w = sample_weights(p, q, False)
    mean_length = 0.5 * (
        np.linalg.norm(np.diff(p, axis=0), axis=1).sum() + np.linalg.norm(np.diff(q, axis=0), axis=1).sum()
    )
    assert w.sum() == pytest.approx(mean_length, rel=1e-12)
    assert w[0] == pytest.approx((np.linalg.norm(p[1] - p[0]) + np.linalg.norm(q[1] - q[0])) / 4)
    c1, c2 = circle(1.0, 30), circle(2.0, 30)
    assert sample_weights(c1, c2, True).sum() == pytest.approx(1.5 * 30 * 2 * np.sin(np.pi / 30), rel=1e-12)


# ---------------------------------------------------------------- fairness of the measure


@pytest.mark.parametrize("method", ["circular-ball", "linear-interpolation"])
@pytest.mark.parametrize("closed", [True, False])
def test_measures_do_not_depend_on_input_density(method, closed):
    # Stated tolerance: 1e-3 relative for the trajectory measures, 1e-2 for the average squared
    # mean curvature, 0.1 for its maximum (a single vertex of the mesh).
    if closed:
        coarse = (circle(1.0, 150), ellipse(1.6, 1.2, 170))
        dense = (circle(1.0, 700), ellipse(1.6, 1.2, 900))
    else:
        coarse = (graph_stroke(0.3, n=120), graph_stroke(-0.2, (0.05,), n=90))
        dense = (graph_stroke(0.3, n=600), graph_stroke(-0.2, (0.05,), n=800))
    a = bm.measure(*coarse, method, closed=closed, steps=16)
    b = bm.measure(*dense, method, closed=closed, steps=16)
    for name in MEASURES[:4]:
        assert a[name] == pytest.approx(b[name], rel=1e-3), name
    assert a["mean_curvature_sq_avg"] == pytest.approx(b["mean_curvature_sq_avg"], rel=1e-2)
    assert a["mean_curvature_sq_max"] == pytest.approx(b["mean_curvature_sq_max"], rel=0.1)


@pytest.mark.parametrize("closed", [True, False])
def test_travel_is_symmetric_in_P_and_Q(closed):
    if closed:
        P, Q = circle(1.0, 200), ellipse(1.8, 1.3, 240)
    else:
        P, Q = graph_stroke(0.3, n=150), graph_stroke(-0.2, (0.05,), n=120)
    for method in ("circular-ball", "linear-ball"):
        forward = bm.measure(P, Q, method, closed=closed, steps=8)
        backward = bm.measure(Q, P, method, closed=closed, steps=8)
        assert forward["travel_distance"] == pytest.approx(backward["travel_distance"], rel=1e-6)
        assert forward["stretch"] == pytest.approx(backward["stretch"], rel=1e-6)


def test_linear_ball_travels_least_and_circular_distorts_least():
    # Paper section 8 on a nested pair: the straight path is the shortest between the same
    # contacts; the circular path leaves and reaches the curves along their normals.
    P, Q = circle(1.0, 200), ellipse(1.8, 1.15, 240)
    scores = {m: bm.measure(P, Q, m, closed=True, steps=16) for m in bm.METHODS[:3]}
    scores["linear-interpolation"] = bm.measure(P, Q, "linear-interpolation", closed=True, steps=16)
    travel = {m: s["travel_distance"] for m, s in scores.items()}
    assert min(travel, key=travel.get) == "linear-ball"
    assert scores["circular-ball"]["distortion"] < 0.25 * scores["linear-ball"]["distortion"]
    assert scores["circular-ball"]["distortion"] < 0.1 * scores["linear-interpolation"]["distortion"]


def test_result_keys_and_values():
    scores = bm.measure(graph_stroke(0.3, n=80), graph_stroke(-0.2, n=80), steps=6)
    assert tuple(scores) == MEASURES
    assert all(isinstance(v, float) and np.isfinite(v) and v >= 0 for v in scores.values())


def test_measure_frames_matches_measure():
    P, Q = circle(1.0, 100), circle(1.6, 100)
    spacing, height = 0.05, 2.0
    parts = []
    for sampling in ("P", "Q"):
        morph = bm.make_morph(P, Q, "parabolic-ball", closed=True, spacing=spacing, sampling=sampling)
        frames = morph.frames(np.linspace(0, 1, 9))
        parts.append(measure_frames(frames, True, height, morph.paths.lengths()))
    scores = bm.measure(P, Q, "parabolic-ball", closed=True, spacing=spacing, steps=8, height=height)
    for name in MEASURES:
        assert scores[name] == pytest.approx(0.5 * (parts[0][name] + parts[1][name]), rel=1e-12)


# ---------------------------------------------------------------- invariants


@given(
    angle=st.floats(-np.pi, np.pi),
    scale=st.floats(0.05, 20.0),
    dx=st.floats(-50, 50),
    dy=st.floats(-50, 50),
    closed=st.booleans(),
)
def test_measures_are_similarity_invariant(angle, scale, dx, dy, closed):
    # Moving the whole animation by a similarity keeps the dimensionless measures, scales travel
    # by s and the squared curvature by 1 / s^2 (with the surface's height scaled too).
    if closed:
        frames = similarity_frames(ellipse(1.3, 0.8, 40), 6, rotation=0.4, scale=1.7, shift=(0.2, 0.1))
    else:
        frames = np.stack([WAVE + [0, 0.1 * k] + 0.05 * k**2 * np.c_[np.zeros(60), WAVE[:, 0] ** 2] for k in range(7)])
    c, s = np.cos(angle), np.sin(angle)
    moved = scale * frames @ np.array([[c, s], [-s, c]]) + np.array([dx, dy])
    a = measure_frames(frames, closed, 1.0)
    b = measure_frames(moved, closed, scale)
    for name in ("distortion", "stretch", "acceleration"):
        assert b[name] == pytest.approx(a[name], rel=1e-6, abs=1e-9), name
    assert b["travel_distance"] == pytest.approx(scale * a["travel_distance"], rel=1e-9)
    for name in ("mean_curvature_sq_avg", "mean_curvature_sq_max"):
        assert b[name] == pytest.approx(a[name] / scale**2, rel=1e-6, abs=1e-12), name


# ---------------------------------------------------------------- errors


def test_bad_arguments_are_reported():
    P, Q = circle(1.0, 40), circle(2.0, 40)
    with pytest.raises(ValueError, match="steps"):
        bm.measure(P, Q, closed=True, steps=1)
    with pytest.raises(ValueError, match="steps"):
        bm.measure(P, Q, closed=True, steps=2.5)
    with pytest.raises(ValueError, match="height"):
        bm.measure(P, Q, closed=True, height=-1.0)
    with pytest.raises(ValueError, match="height"):
        bm.measure(P, Q, closed=True, height="tall")
    with pytest.raises(ValueError, match="method"):
        bm.measure(P, Q, "no-such-morph", closed=True)
    with pytest.raises(ValueError, match="frames"):
        distortions(np.zeros((3, 5)), False)
    with pytest.raises(ValueError, match="frames"):
        accelerations(np.full((3, 5, 2), np.nan), False)


def test_incompatible_pair_raises():
    # S-shaped strokes whose gap is wider than their bends are tight: the maximal disks touch a
    # curve twice, the ball-morph does not apply (the evaluation shows "n/a").
    x = np.linspace(0.0, 1.0, 300)
    P = np.c_[x, 0.22 * np.sin(np.pi * x) + 0.17 * np.sin(2 * np.pi * x)]
    Q = np.c_[x, -0.22 * np.sin(np.pi * x) + 0.17 * np.sin(2 * np.pi * x)]
    with pytest.raises(bm.IncompatibleCurvesError):
        bm.measure(P, Q, steps=4)
