"""The six quality measures of a morph (paper section 6), for a fair comparison of methods.

:func:`measure` is the entry point. Every measure is the average of two weighted averages: one
over samples spaced uniformly (geodesic spacing ``u``) on P and mapped forward by the morph
(``make_morph(..., sampling='p')``), one over samples spaced uniformly on Q and mapped
backward (``sampling='q'``). Sample ``i`` is weighted by the mean of its four adjacent edge
lengths on P and on Q (paper section 6)::

    w_i = (|p_{i-1} p_i| + |q_{i-1} q_i| + |p_i p_{i+1}| + |q_i q_{i+1}|) / 4

At a stroke's ends the missing edges count as zero length (trapezoid weights: they sum to the
mean length of the two sampled curves). Time is sampled at ``T + 1`` instants ``t_k = k eps``,
``eps = 1 / T``.

The functions below the entry point take the sampled frames directly, an array of shape
``(T + 1, K, 2)`` whose row ``k`` is the in-between curve at ``t_k`` (sample ``i`` is the same
material point in every row), so any morph or a synthetic motion can be measured. Every choice
the paper leaves open is made once here and is the same for every method.
"""

import numpy as np

from .. import tolerances as tol
from ..errors import InvalidCurveError
from ..geometry.polyline import as_curve, curve_length, scale_of
from ..morphs import make_morph

__all__ = [
    "MEASURES",
    "measure",
    "measure_frames",
    "sample_weights",
    "travel_distances",
    "distortions",
    "stretches",
    "accelerations",
    "mean_curvature_sq",
    "strip_mesh",
]

#: Default number of time steps ``T`` (``eps = 1 / T``) at which the quality measures sample a
#: morph (paper section 6).
MEASURE_STEPS = 40

#: Default sample count of the quality measures along the longer curve (their geodesic spacing
#: is its length over this), independent of how densely the input was drawn.
MEASURE_SAMPLES = 200

#: Acceleration measure: a local frame triangle (sample, neighbour now, neighbour next) whose
#: sine of its angle at the sample is below this is degenerate (the neighbour does not move, or
#: moves along the edge) and gives no barycentric coordinates.
DEGENERATE_FRAME = 1e-6

#: The keys of :func:`measure`'s result, in the paper's order (smaller is better for each).
MEASURES = (
    "travel_distance",
    "distortion",
    "stretch",
    "acceleration",
    "mean_curvature_sq_avg",
    "mean_curvature_sq_max",
)


def _unit(v):
    n = np.linalg.norm(v, axis=-1, keepdims=True)
    return np.divide(v, n, out=np.zeros_like(v), where=n > 0)


def _cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _edges(frames, closed):
    """Edge vectors of every frame, shape (T + 1, E, 2): ``E = K`` for loops, ``K - 1`` strokes."""
    nxt = np.roll(frames, -1, axis=1) if closed else frames[:, 1:]
    return nxt - (frames if closed else frames[:, :-1])


def _per_sample(edge_values, closed):
    """Values on the edges before and after each sample, shape (..., K) each.

    A stroke's end has no edge on one side: that side reads 0.
    """
    if closed:
        return np.roll(edge_values, 1, axis=-1), edge_values
    pad = np.zeros(edge_values.shape[:-1] + (1,))
    return np.concatenate([pad, edge_values], axis=-1), np.concatenate([edge_values, pad], axis=-1)


def _check_frames(frames, closed):
    frames = np.asarray(frames, dtype=np.float64)
    if frames.ndim != 3 or frames.shape[2] != 2:
        raise InvalidCurveError(f"frames: expected shape (T + 1, K, 2), got {frames.shape}")
    if frames.shape[0] < 2 or frames.shape[1] < (3 if closed else 2):
        raise InvalidCurveError(f"frames: need at least 2 times and {3 if closed else 2} samples, got {frames.shape}")
    if not np.all(np.isfinite(frames)):
        raise InvalidCurveError("frames: contains NaN or infinite coordinates")
    return frames


def sample_weights(p, q, closed):
    """Integration weight of each sample (paper section 6).

    Parameters
    ----------
    p, q : ndarray, shape (K, 2)
        The samples on P and their images on Q.
    closed : bool

    Returns
    -------
    ndarray, shape (K,)
        ``(|p_{i-1} p_i| + |q_{i-1} q_i| + |p_i p_{i+1}| + |q_i q_{i+1}|) / 4``; at a stroke's
        ends the missing edges count as zero, so the weights sum to the mean of the two
        polylines' lengths.
    """
    pair = np.stack([p, q])
    lengths = np.linalg.norm(_edges(pair, closed), axis=2).sum(axis=0)  # (E,): |p edge| + |q edge|
    before, after = _per_sample(lengths, closed)
    return (before + after) / 4.0


def travel_distances(frames, lengths=None):
    """Travel distance of every sample: arc length of its trajectory.

    Parameters
    ----------
    frames : ndarray, shape (T + 1, K, 2)
    lengths : ndarray, shape (K,), optional
        Exact path lengths when the morph knows them (``morph.paths.lengths()``); used as given.

    Returns
    -------
    ndarray, shape (K,)
        Length of the polyline through the ``T + 1`` positions (or ``lengths``).
    """
    if lengths is not None:
        return np.asarray(lengths, dtype=np.float64)
    return np.linalg.norm(np.diff(np.asarray(frames, dtype=np.float64), axis=0), axis=2).sum(axis=0)


def distortions(frames, closed):
    """Distortion of every sample: how much it moves along the curve rather than across it.

    For each time step ``[t, t + eps]`` and sample ``p``: ``L`` is the unit tangent of the
    evolving curve at ``p``, the normalised sum of the unit directions of the sample's two
    edges at ``t`` and at ``t + eps`` (the paper's ``1/2 (L(p, t) + L(p, t + eps))``, made
    per sample instead of per edge: the paper's ``1/2 (V(p, t) + V(p', t))`` then reduces to
    the sample's own ``V``); ``V`` is the unit direction of travel ``p_t -> p_{t + eps}``
    (zero for a step shorter than ``tolerances.COINCIDENT`` times the frames' size). The
    distortion is ``eps * sum_t |L . V|``: the **absolute value** counts sliding either way
    along the curve, and the factor ``eps`` makes it the time average of ``|cos|`` of the angle
    between travel and tangent, in [0, 1] and independent of ``T`` (the paper's bare sum is
    ``T`` times this). 0 when every point moves along the curve's normal (pure rotation between
    segments, paper Fig. 19); 1 when it slides along the curve the whole time.

    Parameters
    ----------
    frames : ndarray, shape (T + 1, K, 2)
    closed : bool

    Returns
    -------
    ndarray, shape (K,)
    """
    frames = _check_frames(frames, closed)
    u = _unit(_edges(frames, closed))
    before, after = (np.moveaxis(a, -1, 1) for a in _per_sample(np.moveaxis(u, 1, -1), closed))
    tangent = before + after  # (T + 1, K, 2); a stroke's end uses its one edge
    L = _unit(tangent[:-1] + tangent[1:])
    step = np.diff(frames, axis=0)
    moving = np.linalg.norm(step, axis=2) > tol.COINCIDENT * scale_of(frames.reshape(-1, 2))
    V = np.where(moving[..., None], _unit(step), 0.0)
    return np.abs(np.einsum("tki,tki->tk", L, V)).mean(axis=0)


def stretches(frames, closed, weights=None):
    """Stretch of every sample: how much the curve's length changes around it over time.

    The paper sums ``|L(p, t + eps) - L(p, t)|`` over time steps and edges ``(p, p')``. Each
    edge's total is split half to each of its two samples, and divided by the sample's weight
    ``w_i``, so that the weighted average ``sum w_i m_i / sum w_i`` equals the paper's double
    sum **normalised by** ``sum w_i`` (the mean length of the sampled P and Q): a
    dimensionless total variation of the local stretch factor, independent of the sample
    count. 0 for any length-preserving motion (rigid, or a bending that keeps edge lengths);
    ``2 |b - a| / (a + b)`` for a curve scaled uniformly from length ``a`` to ``b``.

    Parameters
    ----------
    frames : ndarray, shape (T + 1, K, 2)
    closed : bool
    weights : ndarray, shape (K,), optional
        :func:`sample_weights` of the first and last frames (computed if not given).

    Returns
    -------
    ndarray, shape (K,)
    """
    frames = _check_frames(frames, closed)
    if weights is None:
        weights = sample_weights(frames[0], frames[-1], closed)
    lengths = np.linalg.norm(_edges(frames, closed), axis=2)  # (T + 1, E)
    per_edge = np.abs(np.diff(lengths, axis=0)).sum(axis=0)  # (E,)
    before, after = _per_sample(per_edge, closed)
    return np.divide(0.5 * (before + after), weights, out=np.zeros_like(weights), where=weights > 0)


def _frame_coordinates(edge, neighbour_step, velocity):
    """Barycentric coordinates of a velocity in the triangle (p_t, n_t, n_{t+eps}).

    ``edge = n_t - p_t``, ``neighbour_step = n_{t+eps} - n_t``; all shape (T, K, 2). Returns
    the coordinate vectors (T, K, 3) of ``velocity`` as a displacement (they sum to 0) and
    whether the triangle is non-degenerate (T, K).
    """
    a = edge
    b = edge + neighbour_step
    det = _cross(a, b)
    ok = np.abs(det) > DEGENERATE_FRAME * np.linalg.norm(a, axis=2) * np.linalg.norm(b, axis=2)
    safe = np.where(ok, det, 1.0)
    x = np.where(ok, _cross(velocity, b) / safe, 0.0)
    y = np.where(ok, _cross(a, velocity) / safe, 0.0)
    return np.stack([-x - y, x, y], axis=-1), ok


def accelerations(frames, closed):
    """Acceleration (lack of steadiness) of every sample (paper section 6, Fig. 18).

    The velocity of sample ``p`` over a step is ``v_t = p_{t + eps} - p_t``. It is expressed in
    barycentric coordinates of two triangles of the evolving curve, built from the sample and
    one neighbour at ``t`` and ``t + eps``:

    * left: ``L_t = (p_t, a_t, a_{t + eps})`` with ``a`` the previous sample;
    * right: ``R_t = (p_t, b_t, b_{t + eps})`` with ``b`` the next sample;

    i.e. ``v_t = x (n_t - p_t) + y (n_{t + eps} - p_t)`` for the neighbour ``n``, coordinate
    vector ``B(v_t) = (-x - y, x, y)``. The corresponding vertices of the two triangles are
    mirror images, so a motion symmetric about the sample gives equal left and right
    coordinates.

    The paper defines acceleration as "the derivative of the expression of velocity in the
    local, time-evolving frame", and writes
    ``g_t = 1/2 |B_L(v_in) - B_R(v_in)| + 1/2 |B_L(v_out) - B_R(v_out)|``. Taken literally
    (left minus right, one instant) that is a spatial difference: it does not vanish for a
    steady rigid rotation and it grows with ``T``. We read it as the derivative it names: in
    each frame, the incoming velocity ``v_in = v_{t - eps}`` (in ``L_{t - eps}``) against the
    outgoing ``v_out = v_t`` (in ``L_t``)::

        g_t = 1/2 |B_{L_t}(v_out) - B_{L_{t-eps}}(v_in)| + 1/2 |B_{R_t}(v_out) - B_{R_{t-eps}}(v_in)|

    and the measure is ``sum_t g_t`` over the interior instants. ``g`` is exactly 0 for a
    steady motion, one whose every time step applies the same affine map (steady translation,
    rotation, similarity spiral ``c + a^t (z - c)``), because barycentric coordinates are
    affine invariant. Because the frames move with the neighbours, it sees how a sample's
    motion departs from its neighbours' over time; a common change of speed of the whole
    neighbourhood (easing a rigid motion) is not unsteadiness in this sense. For a smooth
    morph the coordinates differ from the trivial ``(0, -1, 1)`` by ``O(u)`` (how the normal
    speed varies along the curve) and ``O(eps)`` (how the velocity turns along the curve), so
    the measure behaves like ``u A + eps B`` with ``A, B`` continuous unsteadiness terms: it
    stays bounded as ``T`` grows, and like the paper's it is a discrete quantity, to be
    compared between morphs at the same ``u`` and ``T``.

    A triangle whose sine of its angle at ``p_t`` is below ``DEGENERATE_FRAME`` (the
    neighbour does not move, or moves along the edge) has no frame: the other side's term
    counts in full, and if neither side has a frame at both steps the term is 0. A stroke's end
    has only one side. Just above that threshold the frame is ill-conditioned: where a morph
    slides points almost along the curve with small steps (uniform arc-length morphs where the
    curves are close), single samples can dominate the average.

    Parameters
    ----------
    frames : ndarray, shape (T + 1, K, 2)
        The morph at times ``0, eps, ..., 1``.
    closed : bool

    Returns
    -------
    ndarray, shape (K,)
        The measure of each sample's trajectory.
    """
    frames = _check_frames(frames, closed)
    v = np.diff(frames, axis=0)  # (T, K, 2)
    e = _edges(frames[:-1], closed)  # (T, E, 2): e_i = x_{i+1} - x_i at time t
    if closed:
        to_prev, to_next = -np.roll(e, 1, axis=1), e
        step_prev, step_next = np.roll(v, 1, axis=1), np.roll(v, -1, axis=1)
    else:
        zero = np.zeros_like(e[:, :1])
        to_prev = np.concatenate([zero, -e], axis=1)
        to_next = np.concatenate([e, zero], axis=1)
        step_prev = np.concatenate([np.zeros_like(v[:, :1]), v[:, :-1]], axis=1)
        step_next = np.concatenate([v[:, 1:], np.zeros_like(v[:, :1])], axis=1)
    total = np.zeros(frames.shape[1])
    if len(v) < 2:
        return total
    terms = []
    for edge, step in ((to_prev, step_prev), (to_next, step_next)):
        coords, ok = _frame_coordinates(edge, step, v)
        change = np.linalg.norm(coords[1:] - coords[:-1], axis=2)  # (T - 1, K)
        terms.append((change, ok[1:] & ok[:-1]))
    (c_left, ok_left), (c_right, ok_right) = terms
    both = ok_left & ok_right
    g = np.where(both, 0.5 * (c_left + c_right), np.where(ok_left, c_left, np.where(ok_right, c_right, 0.0)))
    return g.sum(axis=0)


def strip_mesh(frames, closed, height):
    """Stack the frames along z and triangulate consecutive frames into a strip.

    Frame ``k`` is lifted to ``z = t_k * height``. Samples correspond across frames, so the
    quads between samples ``i, i + 1`` and frames ``k, k + 1`` are split into two triangles
    along their **shorter diagonal** (the better-shaped split; a fixed diagonal would bias the
    curvature with the morph's shear).

    Parameters
    ----------
    frames : ndarray, shape (T + 1, K, 2)
    closed : bool
        Loops wrap around (a tube); strokes give an open strip.
    height : float
        z extent (the same for every morph of a test case).

    Returns
    -------
    vertices : ndarray, shape ((T + 1) K, 3)
        Vertex ``k K + i`` is sample ``i`` at time ``t_k``.
    triangles : ndarray of int, shape (2 T E, 3)
        Counter-clockwise seen from the same side for every quad.
    interior : ndarray of bool, shape ((T + 1) K,)
        Vertices not on the mesh boundary (not in the first or last frame, not a stroke's end).
    """
    frames = _check_frames(frames, closed)
    n_t, k = frames.shape[:2]
    z = np.linspace(0.0, float(height), n_t)
    vertices = np.concatenate([frames, np.broadcast_to(z[:, None, None], (n_t, k, 1))], axis=2).reshape(-1, 3)
    cols = np.arange(k if closed else k - 1)
    rows = np.arange(n_t - 1)
    a = (rows[:, None] * k + cols[None, :]).ravel()
    b = (rows[:, None] * k + (cols[None, :] + 1) % k).ravel()
    c, dd = b + k, a + k
    first = np.linalg.norm(vertices[a] - vertices[c], axis=1) <= np.linalg.norm(vertices[b] - vertices[dd], axis=1)
    tri1 = np.where(first[:, None], np.c_[a, b, c], np.c_[a, b, dd])
    tri2 = np.where(first[:, None], np.c_[a, c, dd], np.c_[b, c, dd])
    interior = np.zeros((n_t, k), dtype=bool)
    interior[1:-1, :] = True
    if not closed:
        interior[:, [0, -1]] = False
    return vertices, np.concatenate([tri1, tri2]), interior.ravel()


def mean_curvature_sq(frames, closed, height):
    """Squared mean curvature of the stacked-frames surface (paper section 6.1).

    The strip mesh of :func:`strip_mesh`; at each interior vertex the mean-curvature normal is
    the cotangent Laplacian ``K_i = 1/(2 A_i) sum_j (cot a_ij + cot b_ij) (x_i - x_j)``
    (Meyer et al. 2003), the mean curvature is ``|K_i| / 2`` and ``A_i`` is the barycentric
    area (a third of the adjacent triangles' areas). The average is weighted by ``A_i``.

    Parameters
    ----------
    frames : ndarray, shape (T + 1, K, 2)
    closed : bool
    height : float

    Returns
    -------
    average, maximum : float
        Area-weighted average and maximum of the squared mean curvature over interior
        vertices (units: 1 / length^2; they depend on ``height``).
    """
    vertices, tri, interior = strip_mesh(frames, closed, height)
    x0, x1, x2 = (vertices[tri[:, j]] for j in range(3))
    normal = np.cross(x1 - x0, x2 - x0)
    double_area = np.linalg.norm(normal, axis=1)
    ok = double_area > tol.COINCIDENT * scale_of(vertices[:, :2]) ** 2
    lap = np.zeros_like(vertices)
    area = np.zeros(len(vertices))
    corners = ((x0, x1, x2), (x1, x2, x0), (x2, x0, x1))
    for j, (xa, xb, xc) in enumerate(corners):
        # cot of the angle at corner a weighs the opposite edge (b, c).
        cot = np.divide(np.einsum("ij,ij->i", xb - xa, xc - xa), double_area, out=np.zeros(len(tri)), where=ok)
        ib, ic = tri[:, (j + 1) % 3], tri[:, (j + 2) % 3]
        np.add.at(lap, ib, cot[:, None] * (xb - xc))
        np.add.at(lap, ic, cot[:, None] * (xc - xb))
        np.add.at(area, tri[:, j], double_area / 6.0)
    inner = interior & (area > 0)
    mean_curv = np.linalg.norm(lap[inner], axis=1) / (4.0 * area[inner])
    h2 = mean_curv**2
    if len(h2) == 0:
        return 0.0, 0.0
    return float(np.sum(area[inner] * h2) / np.sum(area[inner])), float(h2.max())


def measure_frames(frames, closed, height, lengths=None):
    """The six measures of one sampled morph (one direction of :func:`measure`).

    Parameters
    ----------
    frames : ndarray, shape (T + 1, K, 2)
    closed : bool
    height : float
        z extent of the stacked surface.
    lengths : ndarray, shape (K,), optional
        Exact trajectory lengths (see :func:`travel_distances`).

    Returns
    -------
    dict
        ``{name: float}`` for every name in :data:`MEASURES`: the weighted averages of the
        per-sample measures with :func:`sample_weights`, and the two mesh measures.
    """
    frames = _check_frames(frames, closed)
    w = sample_weights(frames[0], frames[-1], closed)
    total = w.sum()

    def average(values):
        return float(np.dot(w, values) / total) if total > 0 else 0.0

    avg, peak = mean_curvature_sq(frames, closed, height)
    return {
        "travel_distance": average(travel_distances(frames, lengths)),
        "distortion": average(distortions(frames, closed)),
        "stretch": average(stretches(frames, closed, w)),
        "acceleration": average(accelerations(frames, closed)),
        "mean_curvature_sq_avg": avg,
        "mean_curvature_sq_max": peak,
    }


def measure(
    P,
    Q,
    method="circular-ball",
    closed=False,
    spacing=None,
    steps=MEASURE_STEPS,
    height=None,
    **options,
):
    """The paper's six quality measures of a morph from P to Q (section 6).

    Parameters
    ----------
    P, Q : array_like, shape (N, 2) and (M, 2)
        The key curves (not modified).
    method : str
        One of ``METHODS``.
    closed : bool
    spacing : float, optional
        Geodesic spacing ``u`` of the samples on P (forward) and on Q (backward), the same for
        both. Default: the longer curve's length over ``MEASURE_SAMPLES``, so the
        result does not depend on how densely the input curves were drawn. The acceleration
        and the maximum squared mean curvature depend on ``u`` and ``steps`` (discrete
        quantities, as in the paper): compare methods at the same values.
    steps : int
        Number ``T`` of time steps (``eps = 1 / T``).
    height : float, optional
        z extent of the stacked surface for the mean-curvature measures; default the diagonal
        of the curves' bounding box. Pass the same value for every morph of a comparison.
    **options
        Passed to the morph's builder.

    Returns
    -------
    dict
        ``{name: float}`` with the keys of :data:`MEASURES`, each the mean of the measure over
        the P-sampled and the Q-sampled morph (for the maximum of the squared mean curvature:
        the mean of the two meshes' maxima). Smaller is better for every measure.

    Raises
    ------
    InvalidCurveError
        Malformed curves or parameters.
    IncompatibleCurvesError
        The method cannot morph this pair.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 2 * np.pi, 120, endpoint=False)
    >>> c = np.c_[np.cos(t), np.sin(t)]
    >>> scores = measure(c, 2 * c, "linear-ball", closed=True, steps=8)
    >>> round(scores["travel_distance"], 6)  # every point moves radially by 1
    1.0
    """
    P = as_curve(P, "P", closed)
    Q = as_curve(Q, "Q", closed)
    if isinstance(steps, bool) or not isinstance(steps, (int, np.integer)) or steps < 2:
        raise InvalidCurveError(f"steps must be an integer >= 2, got {steps!r}")
    if spacing is None:
        spacing = max(curve_length(P, closed), curve_length(Q, closed)) / MEASURE_SAMPLES
    if height is None:
        height = scale_of(P, Q)
    if not (isinstance(height, (int, float, np.number)) and np.isfinite(height) and height > 0):
        raise InvalidCurveError(f"height must be a positive finite number, got {height!r}")
    ts = np.linspace(0.0, 1.0, steps + 1)
    results = []
    for sampling in ("p", "q"):
        morph = make_morph(P, Q, method, closed=closed, spacing=spacing, sampling=sampling, **options)
        paths = getattr(morph, "paths", None)
        lengths = paths.lengths() if paths is not None and hasattr(paths, "lengths") else None
        results.append(measure_frames(morph.frames(ts), morph.closed, height, lengths))
    return {name: 0.5 * (results[0][name] + results[1][name]) for name in MEASURES}
