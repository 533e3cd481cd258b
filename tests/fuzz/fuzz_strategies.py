"""Hypothesis strategies for the fuzz target: random curve pairs and drawings.

Curves are built in numpy from a few drawn parameters (shape, sampling density, noise, a
similarity transform) and then edited by random degenerate edits, so every example is either
something an animator could draw or one of the bad inputs the core must answer cleanly.
Noise comes from a drawn integer seed: examples replay exactly, at the cost of coarser
shrinking of the noise itself.
"""

import os

import numpy as np
from hypothesis import HealthCheck, settings
from hypothesis import strategies as st

#: The profile the fuzz tests run with: ``fuzz`` (thousands of examples) when
#: HYPOTHESIS_PROFILE=fuzz, else the short CI profile ``fuzz-ci`` (see conftest.py).
PROFILE = "fuzz" if os.environ.get("HYPOTHESIS_PROFILE") == "fuzz" else "fuzz-ci"


def fuzz_settings(test):
    """Decorator applied to every fuzz test: the profile ``PROFILE`` (registered by conftest.py).

    Explicit, so the core suite's global profile and this one never leak into each other when
    both directories run in one pytest process; resolved when the test is decorated, so this
    module also imports on its own (to replay a failing example by hand).
    """
    chosen = settings(
        settings.get_profile(PROFILE),
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much, HealthCheck.data_too_large],
    )
    return chosen(test)


#: Sampling densities: very coarse hand-placed polylines up to densely drawn strokes.
DENSITIES = st.one_of(st.integers(3, 12), st.integers(13, 120), st.integers(121, 600))

#: Hand jitter, relative to the curve's size (0: a clean curve).
NOISE = st.sampled_from([0.0, 0.0, 1e-9, 1e-5, 1e-3, 1e-2, 5e-2])

EDITS = (
    "none",
    "duplicate-points",
    "repeat-first-at-end",
    "reverse",
    "collapse-to-point",
    "two-points",
    "single-point",
    "spike",
    "collinear",
    "flatten-run",
    "zigzag-run",
)

#: Half the curves are left as drawn; the rest get one edit.
EDIT = st.one_of(st.just("none"), st.sampled_from(EDITS))

RELATIONS = (
    "independent",
    "deformed",
    "same",
    "same-reversed",
    "resampled",
    "offset-tiny",
    "offset-nearly-parallel",
    "scaled",
    "shared-endpoints",
    "crossing",
)

#: Half the pairs are what an animator's next key looks like (deformed, scaled, bent between the
#: same endpoints); the rest are spread over every relation.
RELATION = st.one_of(st.sampled_from(["deformed", "scaled", "shared-endpoints"]), st.sampled_from(RELATIONS))


def _parameters(n, rng, uneven):
    """Curve parameters in [0, 1]: uniform, or with random (uneven) spacing."""
    if not uneven:
        return np.linspace(0.0, 1.0, n)
    steps = rng.gamma(0.5, size=n - 1) + 1e-3
    return np.concatenate([[0.0], np.cumsum(steps) / steps.sum()])


def smooth_loop(n, rng, harmonics, wobble, uneven):
    """A random closed Fourier curve (simple when ``wobble`` is small), shape (n, 2)."""
    s = _parameters(n + 1, rng, uneven)[:-1] * 2 * np.pi
    r = np.ones_like(s)
    for k in range(2, 2 + harmonics):
        r += wobble * rng.uniform(-1, 1) / k * np.cos(k * s + rng.uniform(0, 2 * np.pi))
    aspect = rng.uniform(0.3, 1.0)
    return np.c_[r * np.cos(s), aspect * r * np.sin(s)]


def smooth_stroke(n, rng, harmonics, wobble, uneven):
    """A random open curve from (0, 0) to (1, 0) with smooth bumps, shape (n, 2)."""
    s = _parameters(n, rng, uneven)
    y = rng.uniform(-0.5, 0.5) * np.sin(np.pi * s)
    x = s.copy()
    for k in range(2, 2 + harmonics):
        y += wobble * rng.uniform(-1, 1) / k * np.sin(k * np.pi * s)
        x += wobble * rng.uniform(-1, 1) / (2 * k * k) * np.sin(k * np.pi * s)
    return np.c_[x, y]


def normals(curve, closed):
    """Unit left normals at the vertices (central differences), shape (N, 2)."""
    if len(curve) < 2:
        return np.zeros_like(curve)
    if closed:
        d = np.roll(curve, -1, axis=0) - np.roll(curve, 1, axis=0)
    else:
        d = np.gradient(curve, axis=0)
    n = np.c_[-d[:, 1], d[:, 0]]
    length = np.linalg.norm(n, axis=1, keepdims=True)
    return np.divide(n, length, out=np.zeros_like(n), where=length > 0)


def similarity(curve, rng, big):
    """Random rotation, scale (10^-3..10^3 when ``big``) and translation."""
    angle = rng.uniform(0, 2 * np.pi)
    scale = 10 ** rng.uniform(-3, 3) if big else rng.uniform(0.5, 2.0)
    rot = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    shift = rng.uniform(-1, 1, 2) * (1000.0 if big else 1.0) * scale
    return scale * curve @ rot.T + shift


def _spike(c, closed, rng, size):
    k = int(rng.integers(0, len(c) - 1))
    return np.concatenate([c[: k + 1], [c[k] + rng.uniform(-1, 1, 2) * size], c[k:]])


def _collinear(c, closed, rng, size):
    direction = rng.standard_normal(2)
    direction /= max(np.linalg.norm(direction), 1e-12)
    return np.outer(c @ direction, direction)


def _flatten_run(c, closed, rng, size):
    a, b = sorted(rng.choice(len(c), 2, replace=False))
    t = np.linspace(0.0, 1.0, b - a + 1)[:, None]
    c[a : b + 1] = (1 - t) * c[a] + t * c[b]
    return c


def _zigzag_run(c, closed, rng, size):
    a, b = sorted(rng.choice(len(c), 2, replace=False))
    c[a:b:2] += 0.05 * size * normals(c, closed)[a:b:2]
    return c


#: Degenerate edits: name -> (fewest points it needs, edit(curve, closed, rng, size)).
_EDITS_BY_NAME = {
    "duplicate-points": (1, lambda c, closed, rng, size: np.repeat(c, rng.integers(1, 4, size=len(c)), axis=0)),
    "repeat-first-at-end": (1, lambda c, closed, rng, size: np.concatenate([c, c[:1]])),
    "reverse": (0, lambda c, closed, rng, size: c[::-1].copy()),
    "collapse-to-point": (1, lambda c, closed, rng, size: np.repeat(c[:1], len(c), axis=0)),
    "two-points": (2, lambda c, closed, rng, size: c[[0, -1]].copy()),
    "single-point": (1, lambda c, closed, rng, size: c[:1].copy()),
    "spike": (2, _spike),
    "collinear": (1, _collinear),
    "flatten-run": (4, _flatten_run),
    "zigzag-run": (4, _zigzag_run),
}


def apply_edit(curve, edit, closed, rng):
    """One degenerate edit (a new array; the input is left alone)."""
    c = np.array(curve, dtype=np.float64, copy=True)
    size = float(np.ptp(c, axis=0).max()) if len(c) else 1.0
    fewest, edit_curve = _EDITS_BY_NAME.get(edit, (np.inf, None))
    return edit_curve(c, closed, rng, size) if len(c) >= fewest else c


@st.composite
def curves(draw, closed=None):
    """One random curve: (points (N, 2), closed)."""
    closed = draw(st.booleans()) if closed is None else closed
    n = draw(DENSITIES)
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    harmonics = draw(st.integers(0, 6))
    wobble = draw(st.sampled_from([0.0, 0.1, 0.3, 0.8, 2.0]))
    uneven = draw(st.booleans())
    maker = smooth_loop if closed else smooth_stroke
    c = maker(n, rng, harmonics, wobble, uneven)
    noise = draw(NOISE)
    if noise:
        c = c + noise * rng.standard_normal(c.shape)
    c = similarity(c, rng, draw(st.booleans()))
    return c, closed


def related(P, closed, relation, rng):
    """A second key curve standing in ``relation`` to P, shape (M, 2)."""
    size = max(float(np.linalg.norm(np.ptp(P, axis=0))), 1e-300)
    centre = P.mean(axis=0)
    if relation == "same":
        return P.copy()
    if relation == "same-reversed":
        return P[::-1].copy()
    if relation == "resampled":
        s = np.linspace(0.0, 1.0, len(P) + (1 if closed else 0))
        u = np.linspace(0.0, 1.0, max(3, int(len(P) * rng.uniform(0.3, 3.0))), endpoint=not closed)
        loop = np.concatenate([P, P[:1]]) if closed else P
        return np.c_[np.interp(u, s, loop[:, 0]), np.interp(u, s, loop[:, 1])]
    if relation == "offset-tiny":
        return P + 10 ** rng.uniform(-12, -6) * size * normals(P, closed)
    if relation == "offset-nearly-parallel":
        bump = np.sin(np.linspace(0.0, np.pi, len(P)))[:, None]
        return P + 1e-3 * size * (1.0 + 1e-9 * bump) * normals(P, closed)
    if relation == "scaled":
        return centre + rng.uniform(1.1, 3.0) * (P - centre)
    if relation == "shared-endpoints" and not closed:
        bump = np.sin(np.linspace(0.0, np.pi, len(P)))[:, None]
        return P + rng.uniform(-0.5, 0.5) * size * bump * normals(P, closed)
    if relation == "crossing":
        return P + rng.uniform(-0.3, 0.3) * size * np.sin(np.linspace(0.0, 3 * np.pi, len(P)))[:, None] * normals(
            P, closed
        )
    if relation == "deformed":
        t = np.linspace(0.0, 2 * np.pi, len(P))
        wave = np.c_[np.sin(2 * t + rng.uniform(0, 6)), np.cos(3 * t + rng.uniform(0, 6))]
        angle = rng.uniform(-0.5, 0.5)
        rot = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
        return centre + rng.uniform(0.7, 1.4) * (P - centre) @ rot.T + 0.1 * size * wave + rng.normal(0, 0.2, 2) * size
    return None  # independent


@st.composite
def curve_pairs(draw, allow_nonfinite=False):
    """(P, Q, closed, edits): two key curves of one kind, possibly edited into bad input."""
    P, closed = draw(curves())
    relation = draw(RELATION)
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    Q = related(P, closed, relation, rng)
    if Q is None:
        Q, _ = draw(curves(closed=closed))
    edit_p, edit_q = draw(EDIT), draw(EDIT)
    P, Q = apply_edit(P, edit_p, closed, rng), apply_edit(Q, edit_q, closed, rng)
    if allow_nonfinite and draw(st.integers(0, 9)) == 0:
        target = P if draw(st.booleans()) else Q
        if len(target):
            target[int(rng.integers(0, len(target))), int(rng.integers(0, 2))] = draw(
                st.sampled_from([np.nan, np.inf, -np.inf])
            )
    return P, Q, closed, (relation, edit_p, edit_q)


def distinct_count(points, closed, rel=1e-6):
    """Points left after dropping consecutive near-duplicates (and a loop's repeated start)."""
    pts = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    if len(pts) == 0:
        return 0
    size = max(float(np.ptp(pts, axis=0).max()), 1e-300)
    keep = np.r_[True, np.linalg.norm(np.diff(pts, axis=0), axis=1) > rel * size]
    pts = pts[keep]
    if closed and len(pts) > 1 and np.linalg.norm(pts[-1] - pts[0]) <= rel * size:
        pts = pts[:-1]
    return len(pts)


@st.composite
def drawings(draw, max_strokes=4):
    """A pair of keys for ``inbetween``: lists of (points (N, 3), cyclic) per key.

    The second key mostly reuses the first key's strokes moved and deformed (as an animator's
    next key would), sometimes in another order, sometimes with strokes added or removed.
    """
    strokes_a = draw(st.lists(curves(), min_size=0, max_size=max_strokes))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    strokes_b = []
    for pts, closed in strokes_a:
        relation = draw(RELATION)
        q = related(pts, closed, relation, rng)
        strokes_b.append((pts if q is None else q, closed))
    if draw(st.booleans()) and strokes_b:
        strokes_b = [strokes_b[i] for i in rng.permutation(len(strokes_b))]
    strokes_b += draw(st.lists(curves(), min_size=0, max_size=1))
    if draw(st.booleans()) and strokes_b:
        strokes_b.pop(int(rng.integers(0, len(strokes_b))))
    keys = []
    for key in (strokes_a, strokes_b):
        out = []
        for pts, closed in key:
            pts = apply_edit(pts, draw(EDIT), closed, rng)
            depth = draw(st.sampled_from([0.0, 0.0, 1e-6, 1e-2]))
            out.append((np.c_[pts[:, 0], depth * rng.standard_normal(len(pts)), pts[:, 1]], closed))
        keys.append(out)
    return keys[0], keys[1]


#: How a pair of keys degenerates (issue 41): a stroke drawn again in place, every stroke about
#: one centroid, one stroke far from the rest (up to a million times the drawing's size).
DEGENERACIES = ("duplicated-in-place", "same-centroid", "one-far")


def _degenerate(strokes, degeneracy, rng):
    """``strokes`` ([(points (N, 2), closed)]) made degenerate in place of a new list."""
    out = [(p.copy(), c) for p, c in strokes]
    if not out:
        return out
    if degeneracy == "duplicated-in-place":
        k = int(rng.integers(0, len(out)))
        out += [(out[k][0].copy(), out[k][1]) for _ in range(int(rng.integers(1, 3)))]
    elif degeneracy == "same-centroid":
        out = [(p - p.mean(axis=0) + out[0][0].mean(axis=0), c) for p, c in out]
    else:
        size = max(float(np.linalg.norm(np.ptp(np.concatenate([p for p, _ in out]), axis=0))), 1.0)
        k = int(rng.integers(0, len(out)))
        out[k] = (out[k][0] + size * 10 ** rng.uniform(2, 6) * rng.standard_normal(2), out[k][1])
    return out


def _rounded(points, single):
    """``points`` (float64), rounded to float32 first when ``single``."""
    return points.astype(np.float32).astype(np.float64) if single else points


@st.composite
def degenerate_drawings(draw, max_strokes=3):
    """A pair of keys as :func:`drawings` gives them, made degenerate: each key by one of
    ``DEGENERACIES`` (or left alone), and perhaps both rounded to float32 (Blender's storage).

    The overflow of issue 41 is one of them: key A a stroke drawn twice in place, key B that
    stroke moved and one more far away.
    """
    strokes_a = draw(st.lists(curves(), min_size=1, max_size=max_strokes))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    strokes_b = []
    for pts, closed in strokes_a:
        q = related(pts, closed, draw(RELATION), rng)
        strokes_b.append((pts if q is None else q, closed))
    strokes_b += draw(st.lists(curves(), min_size=0, max_size=1))
    keys = [_degenerate(key, draw(st.sampled_from(("none", *DEGENERACIES))), rng) for key in (strokes_a, strokes_b)]
    single = draw(st.booleans())
    return tuple([(_rounded(np.c_[p[:, 0], np.zeros(len(p)), p[:, 1]], single), c) for p, c in key] for key in keys)
