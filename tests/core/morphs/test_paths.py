"""The five ball-morph paths and the midpoint loci (paper section 4.2)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from shapes import circle

import ballmorph_core as bm
from ballmorph_core.morphs.base import PathMorph
from ballmorph_core.morphs.paths import KINDS, BallPaths, LevelPaths, LinearPaths, SampledPaths

# A right-angle contact: p on the x axis, m above it, q to the right of m (r = 1, psi = 90 deg).
P1, M1, Q1 = np.array([[0.0, 0.0]]), np.array([[0.0, 1.0]]), np.array([[1.0, 1.0]])


@pytest.mark.parametrize(
    "kind,length",
    [
        ("hat", 2.0),  # p -> m -> q
        ("linear", np.sqrt(2.0)),  # the chord
        ("tangent", np.pi / 2),  # a quarter of the disk's boundary
        ("circular", np.pi / 2),  # centre (1, 0), radius 1: a quarter circle
    ],
)
def test_path_lengths_on_a_right_angle_contact(kind, length):
    paths = BallPaths(P1, M1, Q1, kind)
    assert paths.lengths()[0] == pytest.approx(length, rel=1e-12)
    np.testing.assert_allclose(paths.at(0.0), P1, atol=1e-12)
    np.testing.assert_allclose(paths.at(1.0), Q1, atol=1e-12)


def test_parabolic_path_is_the_quadratic_bezier_and_its_length():
    paths = BallPaths(P1, M1, Q1, "parabolic")
    # Midpoint of a symmetric quadratic Bezier: (p + 2m + q) / 4.
    np.testing.assert_allclose(paths.at(0.5), (P1 + 2 * M1 + Q1) / 4, atol=1e-9)
    # Its length, by fine chords.
    s = np.linspace(0, 1, 20001)[:, None]
    curve = (1 - s) ** 2 * P1 + 2 * s * (1 - s) * M1 + s**2 * Q1
    assert paths.lengths()[0] == pytest.approx(np.linalg.norm(np.diff(curve, axis=0), axis=1).sum(), rel=1e-6)


def test_circular_path_degenerates_to_the_segment_when_tangents_are_parallel():
    p = np.array([[0.0, 0.0], [2.0, 0.0]])
    m = np.array([[0.0, 1.0], [2.0, 0.5]])
    q = np.array([[0.0, 2.0], [2.0, 1.0]])  # p, m, q collinear: the disk's diameter
    paths = BallPaths(p, m, q, "circular")
    for t in (0.0, 0.3, 0.5, 1.0):
        np.testing.assert_allclose(paths.at(t), p + t * (q - p), atol=1e-15)
    np.testing.assert_allclose(paths.lengths(), np.linalg.norm(q - p, axis=1))
    # Nearly collinear: continuous, no blow-up of sin(phi t) / sin(phi).
    q2 = q + np.array([[1e-9, 0.0], [0.0, 0.0]])
    np.testing.assert_allclose(BallPaths(p, m, q2, "circular").at(0.5), paths.at(0.5), atol=1e-8)


@pytest.mark.parametrize("kind", KINDS)
def test_every_kind_is_traversed_at_constant_speed(kind):
    rng = np.random.default_rng(3)
    p = rng.normal(size=(20, 2))
    n = rng.normal(size=(20, 2))
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    r = rng.uniform(0.2, 2.0, 20)
    m = p + r[:, None] * n
    # q on the disk at angle psi from p seen from m, psi in [30, 170] degrees (sharper spikes make
    # a 1/400 chord cut the parabola's tip: a measuring error, not a speed error).
    psi = rng.uniform(0.5, 3.0, 20) * rng.choice([-1.0, 1.0], 20)
    d = -n
    q = m + r[:, None] * np.stack(
        [np.cos(psi) * d[:, 0] - np.sin(psi) * d[:, 1], np.sin(psi) * d[:, 0] + np.cos(psi) * d[:, 1]], axis=1
    )
    paths = BallPaths(p, m, q, kind)
    ts = np.linspace(0, 1, 1601)  # fine enough that chords measure arc length to 1e-5
    pts = np.stack([paths.at(t) for t in ts])
    steps = np.linalg.norm(np.diff(pts, axis=0), axis=2)
    np.testing.assert_allclose(steps.sum(axis=0), paths.lengths(), rtol=1e-4)
    rel = (steps.max(axis=0) - steps.min(axis=0)) / steps.mean(axis=0)
    assert rel.max() < (1e-2 if kind == "hat" else 1e-4)  # the hat's corner cuts one chord


def test_midpoint_loci_of_concentric_circles_are_the_middle_circle():
    corr = bm.ball_map(circle(1.0, 120), circle(3.0, 160), closed=True)
    # (The tangent path is not unique for antipodal contacts: either half of the disk's boundary.)
    for kind in ("linear", "circular", "parabolic", "hat"):
        locus = bm.midpoint_locus(corr.p, corr.centers, corr.q, kind)
        # The hat's midpoint is m itself: the medial axis M.
        np.testing.assert_allclose(np.linalg.norm(locus, axis=1), 2.0, atol=1e-6)
    np.testing.assert_allclose(bm.midpoint_locus(corr.p, corr.centers, corr.q, "hat"), corr.centers, atol=1e-12)


def test_midpoint_loci_differ_on_a_tilted_contact():
    loci = {k: bm.midpoint_locus(P1, M1, Q1, k)[0] for k in KINDS}
    np.testing.assert_allclose(loci["hat"], M1[0])  # M
    np.testing.assert_allclose(loci["linear"], [0.5, 0.5])  # L (Asada-Brady)
    np.testing.assert_allclose(loci["tangent"], M1[0] + np.sqrt(0.5) * np.array([1.0, -1.0]))  # T (PISA)
    t = loci["tangent"]
    assert np.linalg.norm(t - M1[0]) == pytest.approx(1.0)  # T lies on the disk's boundary
    n = loci["circular"]
    assert np.linalg.norm(n - np.array([1.0, 0.0])) == pytest.approx(1.0)  # N on the circular path
    assert len({tuple(np.round(v, 9)) for v in loci.values()}) == 5


def test_sampled_and_level_paths():
    pts = np.array([[[0.0, 0.0], [1.0, 0.0], [1.0, 3.0]]])  # an L: lengths 1 then 3
    sampled, level = SampledPaths(pts), LevelPaths(pts)
    np.testing.assert_allclose(sampled.at(0.25), [[1.0, 0.0]])  # a quarter of the length
    np.testing.assert_allclose(level.at(0.5), [[1.0, 0.0]])  # the middle level
    np.testing.assert_allclose(sampled.lengths(), [4.0])
    np.testing.assert_allclose(level.lengths(), [4.0])
    np.testing.assert_allclose(sampled.end, [[1.0, 3.0]])


@pytest.mark.parametrize("kind", KINDS)
def test_paths_written_into_a_buffer_are_the_paths_bit_for_bit(kind):
    """``at(t, out=)`` (the layout's work columns, a transposed view) gives exactly ``at(t)``,
    call after call (the circular paths keep their work buffers from one call to the next)."""
    rng = np.random.default_rng(3)
    p, q = rng.normal(size=(50, 2)), rng.normal(size=(50, 2))
    m = 0.5 * (p + q) + 0.3 * rng.normal(size=(50, 2))
    m[:5] = 0.5 * (p[:5] + q[:5])  # collinear contacts: straight circular paths
    p[5:8] = q[5:8] = m[5:8]  # a contact that does not move
    paths = BallPaths(p, m, q, kind)
    columns = np.zeros((2, 60))
    for t in (0.7, 0.0, 0.25, 1.0, 0.7):
        out = columns[:, 10:].T  # rows 10: of a column-major buffer
        assert paths.at(t, out=out) is out
        np.testing.assert_array_equal(out, paths.at(t))
        np.testing.assert_array_equal(out, BallPaths(p, m, q, kind).at(t))  # no state kept between calls
    assert not columns[:, :10].any()


def test_linear_paths_written_into_a_buffer_are_the_paths_bit_for_bit():
    from ballmorph_core.morphs.paths import LinearPaths

    rng = np.random.default_rng(4)
    paths = LinearPaths(rng.normal(size=(30, 2)), rng.normal(size=(30, 2)))
    columns = np.empty((2, 30))
    for t in (0.3, 1.0, 0.0, 0.55):
        np.testing.assert_array_equal(paths.at(t, out=columns.T), paths.at(t))
        np.testing.assert_array_equal(columns.T, paths.p + t * (paths.q - paths.p))


@pytest.mark.parametrize("bound", [0.0, 1e-6, 0.01, 0.144, 0.5, np.pi / 4, 1.0, 2.0, np.pi])
def test_circular_paths_sines_and_cosines_are_numpys_to_round_off(bound):
    """The circular paths' own sin and cos (polynomials, with angle doublings for large angles;
    faster than numpy's float64 loops) agree with np.sin and np.cos over [-bound, bound], the
    fewer terms the smaller the bound, are exact at 0 and stay on the unit circle."""
    from ballmorph_core.morphs.paths import _sincos, _sincos_terms

    x = np.r_[np.linspace(-bound, bound, 200_001), 0.0, 1e-300, -1e-12 * bound, np.nextafter(bound, 0)]
    sin, cos, work = np.empty_like(x), np.empty_like(x), np.empty_like(x)
    _sincos(x.copy(), sin, cos, work, bound)
    assert np.abs(sin - np.sin(x)).max() <= 1e-15
    assert np.abs(cos - np.cos(x)).max() <= 1e-15
    assert np.abs(sin**2 + cos**2 - 1).max() <= 4e-15
    assert (sin[-4], cos[-4]) == (0.0, 1.0)
    assert sin[-3] == 1e-300 and cos[-3] == 1.0  # tiny angles keep their sine
    doublings, sin_terms, cos_terms = _sincos_terms(bound)
    assert doublings == (0 if bound <= np.pi / 4 else 1 if bound <= np.pi / 2 else 2)
    assert len(sin_terms) + len(cos_terms) <= (3 if bound <= 1e-6 else 11 if bound <= 0.144 else 18)


def test_parabolic_paths_are_the_plain_formulas_bit_for_bit():
    """The parabolic paths' speeds, arc lengths and positions (column by column, in place)
    against the plain expressions they stand for: |B'(s)| = 2 np.linalg.norm(a + s b), L(s) as
    the table below s plus the Gauss-Legendre rule, four Newton steps from the table's guess.
    Contacts of every kind: turning, collinear, not moving, p = m, tiny and huge."""
    from ballmorph_core.morphs.paths import _GAUSS3, ARC_TABLE_SAMPLES

    rng = np.random.default_rng(8)
    p = rng.normal(size=(3000, 2)) * 10.0 ** rng.integers(-6, 6, (3000, 1))
    m = p + rng.normal(size=(3000, 2)) * 10.0 ** rng.integers(-9, 1, (3000, 1)) * np.abs(p).max(axis=1, keepdims=True)
    q = m + rng.normal(size=(3000, 2)) * np.linalg.norm(m - p, axis=1, keepdims=True)
    m[:50] = 0.5 * (p[:50] + q[:50])  # collinear: a straight path
    p[50:80] = m[50:80] = q[50:80]  # a contact that does not move
    m[80:120] = p[80:120]  # the path leaves p along the chord
    paths = BallPaths(p, m, q, "parabolic")
    a, b = (m - p)[:, None, :], (q - 2 * m + p)[:, None, :]

    def speed(s):
        return 2.0 * np.linalg.norm(a + s[..., None] * b, axis=-1)

    n = ARC_TABLE_SAMPLES
    s = rng.uniform(size=(3000, n))
    np.testing.assert_array_equal(paths._speed(s), speed(s))
    np.testing.assert_array_equal(paths._speed(s[:, 3]), speed(s[:, 3:4])[:, 0])
    for t in (0.0, 0.2, 0.5, 1 / 3, 0.99, 1.0):
        f = t * n
        j = min(int(f), n - 1)
        u = (1 - (f - j)) * paths._tau_nodes[j] + (f - j) * paths._tau_nodes[j + 1]
        for _ in range(4):
            node = np.clip(np.floor(u * n).astype(np.int64), 0, n - 1)
            half, total = 0.5 * (u - node / n), np.zeros_like(u)
            for x, w in _GAUSS3:
                total += w * speed((node / n + half + half * x)[:, None])[:, 0]
            length = np.take_along_axis(paths._L, node[:, None], 1)[:, 0] + half * total
            np.testing.assert_array_equal(paths._arc_length(u), length)
            v = speed(u[:, None])[:, 0]
            u = np.clip(u - np.divide(length - t * paths._par_len, v, out=np.zeros_like(u), where=v > 0), 0.0, 1.0)
        np.testing.assert_array_equal(paths._parabola_parameter(t), u)
        u = u[:, None]
        np.testing.assert_array_equal(paths.at(t), (1 - u) ** 2 * p + 2 * u * (1 - u) * m + u**2 * q)


@pytest.mark.parametrize("shape", [(1, 2, 1), (7, 3, 5), (500, 17, 17), (300, 40, 1)])
def test_inverted_tables_reach_their_levels(shape):
    """``_invert_rows`` (parabolic arc-length tables, sampled paths' frames): the table read at
    the fractional index it gives is the level, on rows rising with flat stretches (a path
    that stops) and rows that never rise (every level at the start or the end)."""
    from ballmorph_core.morphs.paths import _invert_rows

    k, s, j = shape
    rng = np.random.default_rng(k)
    rise = rng.exponential(size=(k, s - 1)) * (rng.random((k, s - 1)) < 0.7)
    cum = np.concatenate([np.zeros((k, 1)), np.cumsum(rise, axis=1)], axis=1)
    total = cum[:, -1:]
    table = np.divide(cum, total, out=np.zeros_like(cum), where=total > 0)
    table[total[:, 0] == 0, -1] = 1.0  # a row that rises only at its end
    levels = np.linspace(0.0, 1.0, j) if j > 1 else np.array([0.37])
    f = _invert_rows(table, levels)
    assert f.shape == (k, j) and np.all((f >= 0) & (f <= s - 1))
    for row, fractions in zip(table, f):
        np.testing.assert_allclose(np.interp(fractions, np.arange(s), row), levels, atol=1e-12)


@given(st.integers(0, 2**32 - 1), st.sampled_from(KINDS + ("line",)))
@settings(max_examples=40)
def test_frames_at_many_times_are_those_of_each_time(seed, kind):
    """A morph's frames at many times, in one pass where its paths can (circular and straight
    paths), are bitwise the frames time by time; times outside [0, 1] are clamped as one by one."""
    rng = np.random.default_rng(seed)
    k = int(rng.integers(1, 40))
    p, m, q = (rng.normal(size=(k, 2)) for _ in range(3))
    m[: k // 3] = 0.5 * (p[: k // 3] + q[: k // 3])  # straight paths (phi 0) among them
    paths = LinearPaths(p, q) if kind == "line" else BallPaths(p, m, q, kind)
    morph = PathMorph("test", False, paths, np.linspace(0, 1, k), np.linspace(0, 1, k))
    ts = np.r_[rng.random(int(rng.integers(0, 30))), 0.0, 1.0, -0.5, 1.5]
    want = np.stack([morph(t) for t in ts])
    np.testing.assert_array_equal(morph.frames(ts), want)
    np.testing.assert_array_equal(morph.frames(0.25), morph(0.25)[None])
    assert morph.frames([]).shape == (0, k, 2)


def test_circular_paths_hold_their_points_once_after_the_first_evaluation():
    """Evaluated, the circular paths keep u and p as the contiguous columns every frame reads
    and p as a view of them (not a second copy): the same positions, start and lengths."""
    rng = np.random.default_rng(5)
    p, m, q = rng.normal(size=(3, 40, 2))
    paths = BallPaths(p, m, q, "circular")
    lengths = paths.lengths()
    first = [paths.at(t) for t in (0.0, 0.3, 1.0)]
    assert np.shares_memory(paths.p, paths._columns[1]) and paths._u is None
    np.testing.assert_array_equal(paths.start, p)
    np.testing.assert_array_equal(paths.lengths(), lengths)
    for t, want in zip((0.0, 0.3, 1.0), first):
        got = paths.at(t)
        np.testing.assert_array_equal(got, want)
        assert got.flags.c_contiguous
    np.testing.assert_array_equal(paths.at_times([0.0, 0.3, 1.0]), np.stack(first))
