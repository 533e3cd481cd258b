"""Every bad input of issue 7 at the core boundary, one test each (see docs/reliability.md).

Each input is either handled (the test checks the documented result) or rejected with a
:class:`~ballmorph_core.BallMorphError` subclass whose message names the argument or stroke and
the reason. Tests marked ``xfail(strict=True)`` pin a known defect: they fail today and start
passing (turning the suite red as XPASS) once the core is fixed, so the marker must go then.

Resource tests run the call in a fresh interpreter whose address space is capped, so a memory
blow-up fails fast with a MemoryError instead of exhausting the machine.
"""

import json
import os
import re
import subprocess
import sys
import textwrap

import numpy as np
import pytest
from shapes import circle, distance_to_polyline

import ballmorph_core as bm
from ballmorph_core import StrokeSet, inbetween

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TIMES = [0.0, 0.25, 0.5, 0.75, 1.0]


# ---------------------------------------------------------------- shapes and helpers


def arc(height, n=60):
    """Stroke from (0, 0) to (1, 0) bulging to ``height``, shape (n, 2)."""
    x = np.linspace(0.0, 1.0, n)
    return np.c_[x, height * np.sin(np.pi * x)]


def figure_eight(height=1.0, n=120):
    """A self-crossing loop (lemniscate of Gerono), shape (n, 2)."""
    t = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    return np.c_[np.sin(t), height * np.sin(t) * np.cos(t)]


def curl(radius=0.3, n=120):
    """A stroke that loops over itself twice (a cursive 'l'), shape (n, 2)."""
    x = np.linspace(0.0, 1.0, n)
    return np.c_[x + radius * np.sin(4 * np.pi * x), radius * (np.cos(4 * np.pi * x) - 1)]


def key(*strokes, cyclic=None):
    """A StrokeSet on the XZ canvas from 2D strokes."""
    return StrokeSet.from_strokes(list(strokes), cyclic=cyclic)


def replace(strokes, **changes):
    """A copy of a StrokeSet with some arrays replaced (bypassing from_strokes' defaults)."""
    fields = dict(
        positions=strokes.positions,
        offsets=strokes.offsets,
        cyclic=strokes.cyclic,
        material_index=strokes.material_index,
        radius=strokes.radius,
        opacity=strokes.opacity,
        vertex_color=strokes.vertex_color,
    )
    fields.update(changes)
    return StrokeSet(**fields)


def xz(points3d):
    """The XZ-canvas coordinates of 3D points, shape (N, 2)."""
    return np.asarray(points3d)[:, [0, 2]]


def stroke_xy(strokes, i):
    return xz(strokes.positions[strokes.points(i)])


def all_finite(result):
    return all(
        np.all(np.isfinite(f.positions))
        and np.all(np.isfinite(f.radius))
        and np.all(np.isfinite(f.opacity))
        and np.all(np.isfinite(f.vertex_color))
        for f in result.frames
    )


def warnings_about(result, stroke_a, stroke_b):
    # Messages number strokes as the animator counts them, from 1.
    return [m for m in result.messages if m.level == "WARNING" and f"stroke {stroke_a + 1} -> {stroke_b + 1}" in m.text]


def _ball_map(P, Q, closed):
    return bm.ball_map(P, Q, closed=closed)


def _classify(P, Q, closed):
    return bm.classify(P, Q, closed=closed)


def _morph(method):
    def call(P, Q, closed):
        return bm.make_morph(P, Q, method, closed=closed)(0.5)

    return call


ENTRY_POINTS = [
    pytest.param(_ball_map, id="ball_map"),
    pytest.param(_classify, id="classify"),
    *(pytest.param(_morph(m), id=f"make_morph-{m}") for m in bm.METHODS),
]


_BOUNDED = """
import json, sys, time, tracemalloc
import numpy as np
sys.path.insert(0, {repo!r})
import ballmorph_core as bm
from ballmorph_core import StrokeSet, inbetween

try:  # Linux: cap the address space (elsewhere only the time limit and the traced peak apply)
    import resource
    with open("/proc/self/status") as status:
        size = next(int(line.split()[1]) * 1024 for line in status if line.startswith("VmSize:"))
    limit = size + {headroom_mib} * 2**20
    resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
except (ImportError, OSError, StopIteration):
    pass
{setup}
tracemalloc.start()
start = time.perf_counter()
{call}
seconds = time.perf_counter() - start
peak = tracemalloc.get_traced_memory()[1]
print(json.dumps(dict(seconds=seconds, peak_mib=peak / 2**20, info=info)))
"""


def run_bounded(setup, call, headroom_mib, timeout):
    """Run ``call`` (which sets ``info``) in a fresh Python capped at ``headroom_mib`` of extra
    address space; return its time (s, printed, never asserted: a loaded machine is slow), peak
    traced memory (MiB) and ``info``. ``timeout`` only catches a hang.

    Fails the test with the child's last error line on a crash (e.g. MemoryError) or timeout.
    """
    code = _BOUNDED.format(
        repo=REPO, headroom_mib=headroom_mib, setup=textwrap.dedent(setup), call=textwrap.dedent(call)
    )
    try:
        proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        pytest.fail(f"did not finish within {timeout} s")
    if proc.returncode != 0:
        last = (proc.stderr.strip().splitlines() or ["(no output)"])[-1]
        pytest.fail(f"crashed within {headroom_mib} MiB of extra address space: {last}")
    return json.loads(proc.stdout.strip().splitlines()[-1])


# ---------------------------------------------------------------- malformed curves (core)


@pytest.mark.parametrize("value", [np.nan, np.inf, -np.inf], ids=["nan", "inf", "-inf"])
@pytest.mark.parametrize("which", ["P", "Q"])
@pytest.mark.parametrize("entry", ENTRY_POINTS)
def test_non_finite_coordinate_is_rejected_naming_curve_and_point(entry, which, value):
    P, Q = arc(0.3), arc(-0.3)
    bad = P if which == "P" else Q
    bad[7, 1] = value
    with pytest.raises(bm.InvalidCurveError, match=rf"^{which}: point 7 is not finite"):
        entry(P, Q, False)


@pytest.mark.parametrize("entry", ENTRY_POINTS)
def test_empty_curve_is_rejected(entry):
    with pytest.raises(bm.InvalidCurveError, match=r"^P: the curve has no points"):
        entry(np.zeros((0, 2)), arc(0.3), False)


@pytest.mark.parametrize("entry", ENTRY_POINTS)
def test_single_point_is_rejected(entry):
    with pytest.raises(bm.InvalidCurveError, match=r"^Q: a stroke needs at least 2 distinct points, got 1"):
        entry(arc(0.3), np.array([[0.5, 0.5]]), False)


@pytest.mark.parametrize("entry", ENTRY_POINTS)
def test_zero_length_stroke_is_rejected(entry):
    dot = np.tile([[0.2, 0.1]], (25, 1))
    with pytest.raises(bm.InvalidCurveError, match=r"^P: a stroke needs at least 2 distinct points, got 1"):
        entry(dot, arc(0.3), False)


@pytest.mark.parametrize("entry", ENTRY_POINTS)
def test_loop_with_two_distinct_points_is_rejected(entry):
    flat = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [0.0, 0.0]])
    with pytest.raises(bm.InvalidCurveError, match=r"^P: a loop needs at least 3 distinct points, got 2"):
        entry(flat, circle(2.0, 40), True)


@pytest.mark.parametrize(
    "bad",
    [np.zeros((5, 3)), np.zeros(10), [[0.0, 0.0], [1.0]], [["a", "b"], ["c", "d"]], None],
    ids=["3-columns", "flat", "ragged", "strings", "none"],
)
@pytest.mark.parametrize("entry", ENTRY_POINTS)
def test_wrong_shape_or_type_is_rejected_naming_the_curve(entry, bad):
    with pytest.raises(bm.InvalidCurveError, match=r"^P: "):
        entry(bad, arc(0.3), False)


# ---------------------------------------------------------------- degenerate but well-formed curves


def test_duplicate_points_are_dropped_and_change_nothing():
    P, Q = arc(0.3, 40), arc(-0.3, 50)
    dup = np.repeat(P, [1, 3] * 20, axis=0)  # every other point three times
    ref, got = bm.ball_map(P, Q), bm.ball_map(dup, Q)
    np.testing.assert_array_equal(got.p, ref.p)
    np.testing.assert_array_equal(got.q, ref.q)
    for method in bm.METHODS:
        try:
            expected = bm.make_morph(P, Q, method)(0.5)
        except bm.IncompatibleCurvesError:
            with pytest.raises(bm.IncompatibleCurvesError):
                bm.make_morph(dup, Q, method)
            continue
        np.testing.assert_array_equal(bm.make_morph(dup, Q, method)(0.5), expected, err_msg=method)


def test_loop_repeating_its_first_point_is_the_same_loop():
    P, Q = circle(1.0, 60), circle(2.0, 90, start=0.3)
    ref = bm.ball_map(P, Q, closed=True)
    got = bm.ball_map(np.vstack([P, P[:1]]), np.vstack([Q, Q[:1]]), closed=True)
    np.testing.assert_array_equal(got.p, ref.p)
    np.testing.assert_array_equal(got.radii, ref.radii)


@pytest.mark.parametrize(
    "P,Q,closed,config",
    [
        (curl(0.3), arc(-0.4, 80), False, "strokes"),
        (figure_eight(), circle(3.0, 100), True, "loops"),
    ],
    ids=["stroke", "loop"],
)
def test_self_intersecting_input_is_invalid_for_ball_morphs(P, Q, closed, config):
    assert bm.classify(P, Q, closed=closed) == "invalid"
    for method in ("circular-ball", "linear-ball", "parabolic-ball", "hat-ball", "tangent-ball", "composite-ball"):
        with pytest.raises(bm.IncompatibleCurvesError, match=rf"the {config} are 'invalid'"):
            bm.make_morph(P, Q, method, closed=closed)
    # The methods that need no configuration still morph it, finitely, from P to Q.
    for method in ("linear-interpolation", "curvature-interpolation", "laplace-blending"):
        morph = bm.make_morph(P, Q, method, closed=closed)
        frames = morph.frames([0.0, 0.5, 1.0])
        assert np.all(np.isfinite(frames)), method
        assert distance_to_polyline(frames[0], P, closed).max() < 0.05, method
        assert distance_to_polyline(frames[-1], Q, closed).max() < 0.05, method


def test_nearly_parallel_thin_lens_is_morphed_inside_the_gap():
    # Q is a bump of height 1e-6 over the straight P: every edge pair is parallel to ~1e-6 rad.
    P = np.c_[np.linspace(0.0, 1.0, 80), np.zeros(80)]
    Q = arc(1e-6, 70)
    corr = bm.ball_map(P, Q)
    assert np.all(np.isfinite(corr.radii)) and corr.radii.max() <= 1e-6
    for method in ("circular-ball", "linear-ball", "parabolic-ball"):
        morph = bm.make_morph(P, Q, method)
        mid = morph(0.5)
        assert np.all(np.isfinite(mid))
        # Half-way in-betweens stay inside the lens.
        assert mid[:, 1].min() >= -1e-12 and mid[:, 1].max() <= 1e-6 * (1 + 1e-6)
        assert distance_to_polyline(morph(1.0), Q, False).max() < 1e-9


def stadium(half_length, radius, n_side=40, n_cap=40):
    """Counter-clockwise stadium (two parallel sides joined by half circles), shape (N, 2)."""
    side = np.linspace(-half_length, half_length, n_side, endpoint=False)
    cap = np.linspace(-np.pi / 2, np.pi / 2, n_cap, endpoint=False)
    return np.concatenate(
        [
            np.c_[side, np.full(n_side, -radius)],
            np.c_[half_length + radius * np.cos(cap), radius * np.sin(cap)],
            np.c_[-side, np.full(n_side, radius)],
            np.c_[-half_length - radius * np.cos(cap), -radius * np.sin(cap)],
        ]
    )


def test_exactly_parallel_opposite_edges_take_the_parallel_branch():
    # Nested stadiums: each straight side of Q faces the same way as P's normal on the other
    # side (1 - n.N = 0, the singular case of paper eq. 4), which must be skipped, not divided by.
    P, Q = stadium(1.0, 0.5), stadium(1.0, 1.5, n_cap=60)
    corr = bm.ball_map(P, Q, closed=True)
    assert np.all(np.isfinite(corr.radii))
    # The gap is 1 everywhere, so every maximal disk has radius 1/2.
    np.testing.assert_allclose(corr.radii, 0.5, atol=2e-3)


#: A thin lens (gap ~1e-3) between two coarse 13-point strokes with a sharp bend, found by the
#: fuzz target (tests/fuzz, relation 'shared-endpoints').
BENT_LENS_P = [
    [0.16641440401515495, 0.37285728985306954],
    [0.1459466457511686, 0.33497762218091776],
    [0.13190444579003877, 0.3092659219699416],
    [0.1187465349706694, 0.2855501265516546],
    [0.11860888502933868, 0.2853044445638676],
    [0.09567001910412097, 0.24524159415861327],
    [0.02637836630646168, 0.13959967241698895],
    [0.0129947372320664, 0.12262008160530186],
    [0.00724568822364938, 0.11571347015108652],
    [0.00066141524621763, 0.10809616422666729],
    [-0.4288089628014754, 0.21639231990380287],
    [-0.4957888628839985, 0.29518149641568653],
    [-0.503952814260977, 0.3049448336197959],
]
BENT_LENS_Q = [
    [0.16641440401515495, 0.37285728985306954],
    [0.1454954878267639, 0.33522245794467664],
    [0.1310356659587363, 0.30974401432227394],
    [0.11752026889301441, 0.28623054766542594],
    [0.11711830184797091, 0.28615779903730365],
    [0.09405135051284602, 0.2462662046886186],
    [0.0247339408185583, 0.14070839582040395],
    [0.01149954961591895, 0.12381771624871242],
    [0.00593646893346674, 0.11682522413831727],
    [0.00097690756166132, 0.10946260704807226],
    [-0.4284592732307651, 0.21732025734607635],
    [-0.4953974769590699, 0.295513618504287],
    [-0.503952814260977, 0.3049448336197959],
]


def test_every_contact_lies_on_its_disk_at_a_sharp_bend_of_a_thin_lens():
    P, Q = np.array(BENT_LENS_P), np.array(BENT_LENS_Q)
    try:
        corr = bm.ball_map(P, Q)
    except bm.IncompatibleCurvesError:
        return  # reporting the place as not b-compatible is a valid answer too
    for contact in (corr.p, corr.q):
        gap = np.abs(np.linalg.norm(corr.centers - contact, axis=1) - corr.radii)
        assert gap.max() <= 1e-6 * corr.radii.max()


def test_nearly_coincident_curves_below_the_overlap_tolerance_are_static():
    P = arc(0.3, 60)
    Q = P + [0.0, 1e-12]
    corr = bm.ball_map(P, Q)
    assert corr.report.configuration == "coincident"
    np.testing.assert_array_equal(corr.radii, 0.0)


@pytest.mark.parametrize("method", bm.METHODS)
@pytest.mark.parametrize("closed", [False, True], ids=["stroke", "loop"])
def test_coincident_curves_give_a_still_morph(method, closed):
    P = circle(1.0, 90) * [1.0, 0.6] if closed else arc(0.4, 70)
    morph = bm.make_morph(P, P.copy(), method, closed=closed)
    first = morph(0.0)
    for t in (0.3, 0.5, 1.0):
        # Closest projection re-projects onto Q's spline: still to ~1e-5 of the size.
        np.testing.assert_allclose(morph(t), first, atol=1e-5, err_msg=f"t={t}")
    assert distance_to_polyline(first, P, closed).max() < 1e-3


def test_coincident_curves_ball_map_is_the_identity():
    P = arc(0.4, 70)
    for Q in (P.copy(), P[::-1].copy()):
        corr = bm.ball_map(P, Q)
        assert corr.report.configuration == "coincident"
        np.testing.assert_array_equal(corr.p, corr.q)
        np.testing.assert_array_equal(corr.radii, 0.0)


def test_classify_names_coincident_curves_as_crossing():
    # Documented: classify has no 'coincident' class; a curve overlapping itself everywhere is in
    # the crossing configuration (paper section 3.2: overlapping portions stay static).
    assert bm.classify(arc(0.4), arc(0.4)) == "crossing-strokes"
    assert bm.classify(circle(1.0, 50), circle(1.0, 50), closed=True) == "crossing-loops"


@pytest.mark.parametrize("scale", [1e-20, 1e-6, 1e6, 1e38])
def test_extreme_but_representable_scales_morph_the_same(scale):
    # Down to 1e-20 (below, curves._catmull_rom's absolute 1e-12 knot floor makes the spline
    # uniform instead of centripetal: still finite, 1e-5 off) and up to float32's maximum.
    P, Q = arc(0.3), arc(-0.3)
    ref = bm.make_morph(P, Q, "circular-ball")(0.5)
    got = bm.make_morph(P * scale, Q * scale, "circular-ball")(0.5)
    np.testing.assert_allclose(got / scale, ref, atol=1e-9)


def test_coordinates_too_large_to_square_are_rejected():
    with pytest.raises(bm.InvalidCurveError, match=r"^P: "):
        bm.make_morph(arc(0.3) * 1e160, arc(-0.3) * 1e160, "circular-ball")


# ---------------------------------------------------------------- found by the fuzz target
# Nested loops: a coarse random loop Q = centre + scale * (P - centre) (fuzz relation 'scaled').
# The failures depend on the exact floats (recentring the loops hides them), so the points are
# kept as found.

SCALED_LOOPS = {
    "degenerate-stretch": (
        2.2989552591314864,
        [
            [-29563.85943503567, 41068.03712495386],
            [-29582.100840440093, 41078.33524237379],
            [-29620.772492727512, 41070.35292990663],
            [-29621.753989873672, 41069.880385711986],
            [-29621.904841483392, 41069.80643059629],
            [-29627.19817377064, 41066.97208094249],
            [-29647.06036406293, 41048.755741471614],
            [-29648.402454785093, 41046.07362913778],
            [-29649.761682383356, 41041.33277083679],
            [-29645.561317726242, 41030.00292363756],
            [-29643.69744304053, 41028.6032684519],
            [-29585.814847209505, 41035.95647470242],
            [-29570.829055866816, 41047.616092282544],
            [-29563.60058104234, 41059.63190229123],
        ],
    ),
    "one-sample-frames": (
        2.6075025431847285,
        [
            [-1331.7734291379447, -3740.3107375147497],
            [-1332.7024315206743, -3740.73749711517],
            [-1333.8147076564958, -3741.170793555244],
            [-1333.953788951003, -3743.4599066690366],
            [-1334.174715774422, -3744.9518433415815],
            [-1334.7386651569755, -3747.2884897435592],
            [-1333.8782705901417, -3748.0693681736566],
            [-1332.9068712549972, -3747.943734393048],
            [-1331.9159155853831, -3747.478734203439],
            [-1331.1631267818218, -3745.835671160993],
            [-1331.0234334364402, -3744.0677415577684],
            [-1330.7294368896248, -3742.377566754457],
            [-1330.6239386170826, -3740.102356544523],
        ],
    ),
    "huge-bridge-disk": (
        2.133315905563917,
        [
            [3.7753338806844132, 1.2254202130344118],
            [3.775542502261205, 1.2253854360096503],
            [3.772542172337932, 1.2294659430132018],
            [3.7725411851637656, 1.2294521747340592],
            [3.77360615271141, 1.226372101091144],
            [3.7736615580513027, 1.2263167789818246],
            [3.7737535025344875, 1.226230114686246],
            [3.774082553913864, 1.2259652952539537],
            [3.7745334015073992, 1.2256953554234287],
            [3.774695073525847, 1.2256203649993018],
            [3.7748536970796516, 1.225556803650926],
            [3.775199822783054, 1.2254502468936703],
        ],
    ),
}


def scaled_loops(name):
    """The loop pair ``name`` of :data:`SCALED_LOOPS`: P (N, 2) and Q (N, 2)."""
    scale, points = SCALED_LOOPS[name]
    P = np.array(points)
    centre = P.mean(axis=0)
    return P, centre + scale * (P - centre)


def assert_composite_contract(P, Q):
    """A finite composite ball-morph of loops (>= 3 samples per frame), or IncompatibleCurvesError."""
    try:
        morph = bm.make_morph(P, Q, "composite-ball", closed=True)
    except bm.IncompatibleCurvesError:
        return
    frames = morph.frames([0.0, 0.5, 1.0])
    assert frames.shape[1] >= 3 and np.all(np.isfinite(frames))


def test_composite_ball_of_nested_loops_with_a_degenerate_stretch():
    assert_composite_contract(*scaled_loops("degenerate-stretch"))


def test_composite_ball_of_nested_loops_keeps_its_samples():
    assert_composite_contract(*scaled_loops("one-sample-frames"))


def test_composite_ball_bridge_disk_stays_bounded():
    P, Q = scaled_loops("huge-bridge-disk")
    out = run_bounded(
        f"P, Q = np.array({P.tolist()!r}), np.array({Q.tolist()!r})",
        """
        try:
            frames = bm.make_morph(P, Q, "composite-ball", closed=True).frames([0.0, 0.5, 1.0])
            info = dict(samples=frames.shape[1], finite=bool(np.all(np.isfinite(frames))))
        except bm.IncompatibleCurvesError:
            info = dict(samples=3, finite=True)
        """,
        headroom_mib=512,
        timeout=60,
    )
    assert out["info"]["samples"] >= 3 and out["info"]["finite"]


# ---------------------------------------------------------------- options of the core


@pytest.mark.parametrize("spacing", [0.0, -1.0, np.nan, np.inf])
def test_non_positive_or_non_finite_spacing_is_rejected(spacing):
    with pytest.raises(bm.InvalidCurveError, match="spacing"):
        bm.ball_map(arc(0.3), arc(-0.3), spacing=spacing)
    with pytest.raises(bm.InvalidCurveError, match="spacing"):
        bm.make_morph(arc(0.3), arc(-0.3), "circular-ball", spacing=spacing)


def test_non_numeric_spacing_is_rejected():
    with pytest.raises(bm.InvalidCurveError, match="spacing"):
        bm.ball_map(arc(0.3), arc(-0.3), spacing="fine")


def test_spacing_far_below_the_curve_size_is_rejected_or_bounded():
    run_bounded(
        "x = np.linspace(0, 1, 60)\nP, Q = np.c_[x, np.zeros(60)], np.c_[x, 0.3 * np.sin(np.pi * x)]",
        """
        try:
            info = len(bm.ball_map(P, Q, spacing=1e-7))
        except bm.InvalidCurveError as exc:
            info = str(exc)
        """,
        headroom_mib=512,
        timeout=60,
    )


def test_unknown_method_and_sampling_are_rejected_listing_valid_values():
    with pytest.raises(bm.InvalidCurveError, match="method='spline' is not valid; expected one of 'circular-ball'"):
        bm.make_morph(arc(0.3), arc(-0.3), "spline")
    with pytest.raises(bm.InvalidCurveError, match="sampling='both' is not valid"):
        bm.ball_map(arc(0.3), arc(-0.3), sampling="both")


# ---------------------------------------------------------------- size and cost


BIG_STROKES = """
n = 100_000
x = np.linspace(0.0, 1.0, n)
P = np.c_[x, 0.3 * np.sin(np.pi * x)]
Q = np.c_[x, 0.4 * np.sin(np.pi * x)]
"""

#: A hand-drawn wiggle (20 waves of 1 % of the size) on P: the pair is not b-compatible, so the
#: pipeline splits it and uses the composite ball-morph, its most expensive path.
WIGGLE = "P = np.c_[x, 0.3 * np.sin(np.pi * x) + 0.01 * np.sin(40 * np.pi * x)]\n"

BIG_LOOPS = """
n = 100_000
t = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
P = np.c_[np.cos(t), np.sin(t)] * (1 + 0.05 * np.cos(5 * t))[:, None]
Q = 1.3 * np.c_[np.cos(t + 0.2), 0.8 * np.sin(t + 0.2)] + [0.1, 0.0]
"""

INBETWEEN_100K = """
r = inbetween(A, B, np.linspace(0.0, 1.0, 7))
first = r.frames[0].positions[:, [0, 2]]
info = dict(
    finite=bool(all(np.all(np.isfinite(f.positions)) for f in r.frames)),
    points=len(first),
    method=r.pairs[0].method,
    # The first frame is key A (P is a graph over x for strokes, a star-shaped loop otherwise).
    on_a=float(np.abs(radial(first) - np.interp(angle(first), angle(P), radial(P), period=2 * np.pi)).max())
    if CLOSED
    else float(np.abs(np.interp(first[:, 0], P[:, 0], P[:, 1]) - first[:, 1]).max()),
)
"""


def _inbetween_100k(setup, closed, headroom_mib=2048, timeout=180):
    keys = (
        f"CLOSED = {closed}\n"
        "A = StrokeSet.from_strokes([P], cyclic=[CLOSED])\n"
        "B = StrokeSet.from_strokes([Q], cyclic=[CLOSED])\n"
        "angle = lambda c: np.arctan2(c[:, 1], c[:, 0])\n"
        "radial = lambda c: np.hypot(c[:, 0], c[:, 1])\n"
    )
    return run_bounded(setup + keys, INBETWEEN_100K, headroom_mib=headroom_mib, timeout=timeout)


@pytest.mark.parametrize("shape", ["strokes", "loops"])
def test_inbetween_of_100k_point_keys_is_bounded(shape):
    out = _inbetween_100k(BIG_STROKES if shape == "strokes" else BIG_LOOPS, shape == "loops")
    print(f"inbetween 100k {shape}: {out}")
    assert out["info"]["finite"] and out["info"]["points"] >= 1000
    assert out["info"]["on_a"] < 1e-3
    assert out["peak_mib"] < 256.0


def test_inbetween_of_a_100k_point_hand_drawn_stroke_is_bounded():
    # Memory is the bound asserted; the timeout only catches a hang (timings are the
    # benchmark's business, not a test's).
    out = _inbetween_100k(BIG_STROKES + WIGGLE, False, headroom_mib=512, timeout=120)
    print(f"inbetween 100k wiggly stroke: {out}")
    assert out["info"]["finite"] and out["info"]["points"] >= 1000
    assert out["info"]["on_a"] < 1e-3
    assert out["peak_mib"] < 256.0


def test_ball_map_of_100k_point_loops_is_bounded():
    out = run_bounded(
        BIG_LOOPS,
        """
        corr = bm.ball_map(P, 2.5 * np.c_[np.cos(t), np.sin(t)], closed=True)
        info = dict(samples=len(corr), finite=bool(np.all(np.isfinite(corr.radii))))
        """,
        headroom_mib=1024,
        timeout=60,
    )
    print(f"ball_map 100k loops: {out}")
    assert out["info"]["finite"] and out["info"]["samples"] >= 1000
    assert out["peak_mib"] < 256.0


@pytest.mark.parametrize("method", bm.METHODS)
def test_make_morph_of_100k_point_strokes_is_bounded(method):
    out = run_bounded(
        BIG_STROKES,
        f"""
        frame = bm.make_morph(P, Q, {method!r})(0.5)
        info = dict(points=len(frame), finite=bool(np.all(np.isfinite(frame))))
        """,
        headroom_mib=1024,
        timeout=60,
    )
    print(f"make_morph 100k {method}: {out}")
    assert out["info"]["finite"] and out["info"]["points"] >= 1000
    assert out["peak_mib"] < 512.0


def test_crossing_coarse_polygons_stay_cheap():
    out = run_bounded(
        """
        A = StrokeSet.from_strokes([[[0, 0], [1, 0], [1, 1], [0, 1.0]]], cyclic=[True])
        B = StrokeSet.from_strokes([[[0.5, -0.2], [1.2, 0.5], [0.5, 1.2], [-0.2, 0.5]]], cyclic=[True])
        """,
        "info = inbetween(A, B, [0.0, 0.5, 1.0], carrier='NONE').pairs[0].method",
        headroom_mib=384,
        timeout=60,
    )
    assert out["peak_mib"] < 100.0


def test_scribble_stroke_stays_cheap():
    out = run_bounded(
        """
        rng = np.random.default_rng(1)
        a = rng.random((100, 2))
        A, B = StrokeSet.from_strokes([a]), StrokeSet.from_strokes([a + 0.01 * rng.standard_normal((100, 2))])
        """,
        "info = inbetween(A, B, [0.0, 0.5, 1.0]).pairs[0].method",
        headroom_mib=1024,
        timeout=60,
    )
    assert out["peak_mib"] < 256.0


def test_long_scribble_stroke_stays_cheap():
    # 2,000 random points: long edges that all cross each other (~10^6 crossings). Nothing
    # enumerates them: is_simple stops at the first, find_events at its crossing budget, and
    # the sliding fit's nearest-edge search looks at pieces of edges near each sample.
    out = run_bounded(
        """
        rng = np.random.default_rng(1)
        a = rng.random((2000, 2))
        A, B = StrokeSet.from_strokes([a]), StrokeSet.from_strokes([a + 0.01 * rng.standard_normal((2000, 2))])
        """,
        "info = inbetween(A, B, [0.0, 0.5, 1.0]).pairs[0].method",
        headroom_mib=256,
        timeout=30,
    )
    assert out["peak_mib"] < 64.0


def test_strokes_crossing_too_often_fall_back_saying_so():
    # Two simple combs whose teeth all cross: more crossings than any lens cutting could use,
    # so they are not all enumerated and the note says why.
    x, y = np.linspace(0, 1, 60), np.tile([0.0, 1.0], 30)
    A, B = StrokeSet.from_strokes([np.c_[x, y]]), StrokeSet.from_strokes([np.c_[y, x]])
    report = inbetween(A, B, [0.0, 0.5, 1.0]).pairs[0]
    assert report.method == "aligned-interpolation"
    assert re.search(r"meet more than \d+ times, more than lenses between their points allow", report.reason)


# ---------------------------------------------------------------- malformed drawings (inbetween)


@pytest.mark.parametrize("value", [np.nan, np.inf])
def test_non_finite_positions_are_rejected_naming_key_and_stroke(value):
    good = key(arc(0.3), arc(0.5) + [0, 1])
    pos = good.positions.copy()
    pos[70, 2] = value  # the second stroke: stroke 2 as the animator counts
    with pytest.raises(bm.InvalidCurveError, match=r"^key_b: stroke\(s\) \[2\] have NaN or infinite"):
        inbetween(key(arc(0.35), arc(0.55) + [0, 1]), replace(good, positions=pos), TIMES)


@pytest.mark.parametrize("attribute", ["radius", "opacity", "vertex_color"])
def test_non_finite_attributes_are_rejected_or_repaired(attribute):
    good = key(arc(0.3))
    values = getattr(good, attribute).copy()
    values[5] = np.nan
    try:
        result = inbetween(replace(good, **{attribute: values}), key(arc(0.5)), TIMES)
    except bm.InvalidCurveError as exc:
        assert attribute in str(exc)
        return
    assert all_finite(result)


@pytest.mark.parametrize(
    "offsets",
    [[0, 70, 60], [1, 60], [0, 50], [0, 80]],
    ids=["decreasing", "not-from-zero", "short", "past-the-end"],
)
def test_inconsistent_offsets_are_rejected(offsets):
    good = key(arc(0.3))
    with pytest.raises(bm.InvalidCurveError, match=r"^offsets: must rise from 0 to the point count 60"):
        StrokeSet(
            good.positions,
            offsets,
            [False] * (len(offsets) - 1),
            [0] * (len(offsets) - 1),
            good.radius,
            good.opacity,
            good.vertex_color,
        )


@pytest.mark.parametrize("attribute,size", [("radius", 59), ("opacity", 61), ("vertex_color", 3), ("cyclic", 2)])
def test_attribute_of_the_wrong_length_is_rejected(attribute, size):
    good = key(arc(0.3))
    bad = np.zeros((size, 4)) if attribute == "vertex_color" else np.zeros(size)
    expected = 1 if attribute == "cyclic" else 60
    with pytest.raises(bm.InvalidCurveError, match=rf"^{attribute}: expected {expected} values"):
        replace(good, **{attribute: bad})


def test_key_that_is_not_a_strokeset_is_rejected():
    with pytest.raises(bm.InvalidCurveError, match="key_a"):
        inbetween(arc(0.3), key(arc(0.5)), TIMES)


def test_empty_keys_give_empty_or_appearing_frames():
    result = inbetween(StrokeSet.empty(), StrokeSet.empty(), TIMES)
    assert [len(f) for f in result.frames] == [0] * len(TIMES) and result.pairs == []
    result = inbetween(StrokeSet.empty(), key(arc(0.3)), TIMES)
    assert [len(f) for f in result.frames] == [0, 0, 1, 1, 1]
    assert [p.method for p in result.pairs] == ["appear"]
    assert any(m.level == "WARNING" and "stroke 1 of the second key has no partner" in m.text for m in result.messages)
    np.testing.assert_array_equal(result.frames[-1].positions, key(arc(0.3)).positions)


def test_stroke_with_no_points_is_dropped_and_reported():
    result = inbetween(key(np.zeros((0, 2)), arc(0.3)), key(arc(0.35)), TIMES)
    for frame in result.frames:
        assert np.all(frame.sizes > 0)
    assert any("stroke 1 " in m.text and "no point" in m.text for m in result.messages)


@pytest.mark.parametrize(
    "a",
    [np.array([[0.5, 0.2]]), np.tile([[0.5, 0.2]], (12, 1))],
    ids=["single-point", "zero-length"],
)
def test_strokes_with_fewer_than_two_distinct_points_move_straight(a):
    b = np.array([[0.6, 0.3], [0.6, 0.3]])
    result = inbetween(key(a), key(b), TIMES, matching="INDEX")
    assert [p.method for p in result.pairs] == ["straight point motion"]
    assert warnings_about(result, 0, 0), "the fallback must be a warning naming the stroke"
    for t, frame in zip(TIMES, result.frames):
        np.testing.assert_allclose(
            xz(frame.positions), np.broadcast_to((1 - t) * a[0] + t * b[0], (len(frame.positions), 2))
        )


def test_cyclic_stroke_with_two_points_moves_straight_with_a_warning():
    """Not "morphed as open" (what docs/reliability.md said until issue 41): its two points move
    straight, and the warning says a loop needs three."""
    a, b = np.array([[0.0, 0.0], [1.0, 0.0]]), np.array([[0.0, 0.1], [1.0, 0.1]])
    result = inbetween(key(a, cyclic=[True]), key(b, cyclic=[True]), TIMES, matching="INDEX")
    assert all_finite(result)
    assert result.pairs[0].method == "straight point motion"
    assert [m.text for m in result.messages] == [
        "stroke 1 -> 1: too few distinct points (P: a loop needs at least 3 distinct points, got 2)"
    ]
    for t, frame in zip(TIMES, result.frames):
        np.testing.assert_allclose(xz(frame.positions)[:, 1], 0.1 * t, atol=1e-12)


@pytest.mark.parametrize(
    "a,b,cyclic,method",
    [
        (curl(0.3), curl(0.2) * [1.0, 1.3], False, "aligned-interpolation"),
        # A loop crossing itself that changes shape where it lies slides through its crossing
        # like any such loop (issue 38; a variable font's overlapping contours): no fallback.
        (figure_eight(1.0), figure_eight(0.6), True, "tangent-aligned"),
    ],
    ids=["curl-stroke", "figure-eight"],
)
def test_self_intersecting_strokes_fall_back_with_a_warning(a, b, cyclic, method):
    result = inbetween(key(a, cyclic=[cyclic]), key(b, cyclic=[cyclic]), TIMES)
    assert all_finite(result)
    assert method in result.pairs[0].method
    assert bool(warnings_about(result, 0, 0)) == (method == "aligned-interpolation")
    # The end frames are the keys, resampled on the spline through their points.
    assert distance_to_polyline(stroke_xy(result.frames[0], 0), a, cyclic).max() < 2e-3
    assert distance_to_polyline(stroke_xy(result.frames[-1], 0), b, cyclic).max() < 2e-3


def test_self_intersecting_stroke_warning_says_it_crosses_itself():
    result = inbetween(key(curl(0.3)), key(curl(0.2) * [1.0, 1.3]), TIMES)
    assert any("itself" in m.text or "self-intersect" in m.text for m in warnings_about(result, 0, 0))


@pytest.mark.parametrize("cyclic", [False, True], ids=["stroke", "loop"])
def test_keys_of_very_different_sizes_keep_their_shape(cyclic):
    a = circle(1.0, 64) if cyclic else arc(0.3, 64)
    b = a / 100 + [3.0, 0.0]  # the same shape, far away and 100 times smaller
    result = inbetween(key(a, cyclic=[cyclic]), key(b, cyclic=[cyclic]), TIMES, matching="INDEX")
    assert all_finite(result)
    first = stroke_xy(result.frames[0], 0)
    assert len(first) >= 32
    # The first in-between is key A: every drawn point is on it.
    assert distance_to_polyline(a, first, cyclic).max() < 1e-2


@pytest.mark.parametrize("cyclic", [False, True], ids=["stroke", "loop"])
def test_identical_keys_give_still_in_betweens(cyclic):
    a = circle(1.0, 80) * [1.0, 0.5] if cyclic else curl(0.3)
    result = inbetween(key(a, cyclic=[cyclic]), key(a.copy(), cyclic=[cyclic]), TIMES)
    assert all_finite(result)
    first = stroke_xy(result.frames[0], 0)
    for frame in result.frames[1:]:
        np.testing.assert_allclose(stroke_xy(frame, 0), first, atol=1e-9)
    assert distance_to_polyline(first, a, cyclic).max() < 1e-3


def test_non_finite_times_are_rejected():
    with pytest.raises(bm.InvalidCurveError, match=r"^times: "):
        inbetween(key(arc(0.3)), key(arc(0.5)), [0.5, np.nan])


def test_times_outside_the_unit_interval_are_rejected_or_clamped():
    a = key(arc(0.3))
    b = replace(key(arc(0.5)), radius=np.full(60, 0.05))
    try:
        result = inbetween(a, b, [-1.0, 2.0])
    except bm.InvalidCurveError as exc:
        assert "times" in str(exc)
        return
    clamped = inbetween(a, b, [0.0, 1.0])
    for got, ref in zip(result.frames, clamped.frames):
        np.testing.assert_allclose(got.positions, ref.positions)
        np.testing.assert_allclose(got.radius, ref.radius)


def test_non_numeric_times_are_rejected():
    with pytest.raises(bm.InvalidCurveError, match=r"^times: "):
        inbetween(key(arc(0.3)), key(arc(0.5)), ["half"])


def test_no_times_give_no_frames():
    result = inbetween(key(arc(0.3)), key(arc(0.5)), [])
    assert result.frames == []


@pytest.mark.parametrize(
    "option,value",
    [("method", "spline"), ("carrier", "AFFINE"), ("matching", "NEAREST"), ("unmatched", "DROP")],
)
def test_unknown_inbetween_option_is_rejected_listing_valid_values(option, value):
    with pytest.raises(bm.InvalidCurveError, match=rf"^{option}='{value}' is not valid; expected one of '"):
        inbetween(key(arc(0.3)), key(arc(0.5)), TIMES, **{option: value})


@pytest.mark.parametrize("spacing", [0.0, -1.0, np.nan])
def test_bad_inbetween_spacing_is_rejected(spacing):
    with pytest.raises(bm.InvalidCurveError, match="spacing"):
        inbetween(key(arc(0.3)), key(arc(0.5)), TIMES, spacing=spacing)


def test_non_planar_keys_are_morphed_in_the_best_plane_with_a_warning():
    a = key(arc(0.3))
    pos = a.positions.copy()
    pos[:, 1] = 0.2 * np.sin(np.linspace(0, 6, len(pos)))  # off the XZ canvas
    result = inbetween(replace(a, positions=pos), key(arc(0.5)), TIMES)
    assert all_finite(result)
    assert any(m.level == "WARNING" and "not flat" in m.text for m in result.messages)
    # The first frame is key A, off-plane offsets included.
    assert distance_to_polyline(result.frames[0].positions, pos, False).max() < 1e-3


def test_keys_drawn_on_a_tilted_plane_are_morphed_in_that_plane():
    angle = 0.7
    rot = np.array([[1.0, 0.0, 0.0], [0.0, np.cos(angle), -np.sin(angle)], [0.0, np.sin(angle), np.cos(angle)]])
    a, b = key(arc(0.3)), key(arc(0.6))
    ta, tb = replace(a, positions=a.positions @ rot.T), replace(b, positions=b.positions @ rot.T)
    result = inbetween(ta, tb, TIMES)
    flat = inbetween(a, b, TIMES)
    assert not any(m.level == "WARNING" for m in result.messages)
    for got, ref in zip(result.frames, flat.frames):
        np.testing.assert_allclose(got.positions, ref.positions @ rot.T, atol=1e-9)


def test_keys_are_never_modified():
    a, b = key(curl(0.3), arc(0.2), cyclic=[False, False]), key(arc(0.5), np.zeros((4, 2)))
    before = [np.array(getattr(k, f), copy=True) for k in (a, b) for f in ("positions", "radius", "offsets")]
    inbetween(a, b, TIMES)
    after = [getattr(k, f) for k in (a, b) for f in ("positions", "radius", "offsets")]
    for x, y in zip(before, after):
        np.testing.assert_array_equal(x, y)
