"""The benchmark's drawings (tools/benchmark.py), in plain numpy: no bpy, so the core's tests and
profiling scripts draw the same keys the benchmark times.

Kinds: ``loops`` (star-shaped blobs), ``open`` (gentle arcs), ``jagged`` (wavy strokes
retraced with a tremor, whose lenses take the fallback step) and ``deforming`` (the loops'
blobs changing shape where they lie: each of key B is key A's stretched 1.25x along one axis
about its own centre, overlapping and crossing it); see :func:`make_keys`.
"""

import math

import numpy as np

KINDS = ("loops", "open", "jagged", "deforming")

#: The deforming drawing: each loop of key B is key A's stretched this much along one axis.
STRETCH = 1.25


def _normals(points, closed):
    """Unit normals of a polyline by central differences, shape (n, 2)."""
    if closed:
        d = np.roll(points, -1, axis=0) - np.roll(points, 1, axis=0)
    else:
        d = np.gradient(points, axis=0)
    n = np.c_[-d[:, 1], d[:, 0]]
    return n / np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-12)


def _rotation(angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s], [s, c]])


def make_keys(kind, n_strokes, n_points, seed=6):
    """Key A and key B of a drawing, on a unit grid (one stroke per cell).

    Loops are star-shaped blobs, open strokes gentle arcs; key B moves the whole drawing a little,
    then every stroke by its own small move, turn (up to 8 degrees) and scale (up to 8 %), plus a
    smooth wobble along its normal (3 random harmonics, up to 6 % of its size). Jagged redraws
    are wavy strokes 0.6 long drawn twice over the same line, moved by (0.01, 0.005), each time
    with a tremor (normal noise of 0.01 at every point): the two drawings cross each other
    again and again.

    Returns
    -------
    key_a, key_b : list of ndarray, shape (n_points, 2)
        (x, z) points on Blender's front (XZ) canvas.
    """
    rng = np.random.default_rng([seed, KINDS.index(kind), n_strokes, n_points])
    cols = math.ceil(math.sqrt(n_strokes))
    drift = np.array([0.15, 0.05])
    key_a, key_b = [], []
    if kind == "jagged":
        return _jagged_keys(rng, n_strokes, n_points, cols)
    if kind == "deforming":
        return _deforming_keys(n_strokes, n_points, seed)
    for i in range(n_strokes):
        centre = np.array([i % cols, -(i // cols)], dtype=float) + rng.uniform(-0.08, 0.08, 2)
        spin = rng.uniform(0, 2 * np.pi)
        if kind == "loops":
            t = np.linspace(0, 2 * np.pi, n_points, endpoint=False)
            phases = rng.uniform(0, 2 * np.pi, 2)
            r = (
                0.3
                * rng.uniform(0.85, 1.15)
                * (
                    1
                    + rng.uniform(0, 0.15) * np.cos(2 * t + phases[0])
                    + rng.uniform(0, 0.05) * np.cos(3 * t + phases[1])
                )
            )
            shape = np.c_[rng.uniform(0.8, 1.2) * r * np.cos(t), r * np.sin(t)]
            size, s = 0.3, t / (2 * np.pi)
        else:
            s = np.linspace(0, 1, n_points)
            length = rng.uniform(0.5, 0.8)
            shape = np.c_[
                length * (s - 0.5),
                rng.uniform(-0.2, 0.2) * np.sin(np.pi * s) + rng.uniform(-0.06, 0.06) * np.sin(2 * np.pi * s + 0.5),
            ]
            size = length
        a = shape @ _rotation(spin).T + centre
        # Key B: wobble along the normal (periodic for loops), then move, turn and scale.
        closed = kind == "loops"
        harmonics = np.arange(1, 4) * (2 * np.pi if closed else np.pi)
        wobble = (rng.uniform(-1, 1, 3)[None, :] * np.sin(s[:, None] * harmonics + rng.uniform(0, 6.3, 3))).sum(1)
        b = a + (0.06 * size / 3) * wobble[:, None] * _normals(a, closed)
        turn = _rotation(np.radians(rng.uniform(-8, 8))) * rng.uniform(0.92, 1.08)
        b = (b - centre) @ turn.T + centre + drift + rng.uniform(-0.06, 0.06, 2)
        key_a.append(a)
        key_b.append(b)
    return key_a, key_b


def _jagged_keys(rng, n_strokes, n_points, cols):
    """Key A and key B of a jagged drawing (see :func:`make_keys`)."""
    key_a, key_b = [], []
    s = np.linspace(0.0, 1.0, n_points)
    for i in range(n_strokes):
        corner = np.array([i % cols, -(i // cols)], dtype=float)
        line = np.c_[0.6 * s, 0.15 * np.sin(np.pi * s * rng.uniform(0.5, 2.0))] + corner
        key_a.append(line + rng.normal(0.0, 0.01, line.shape))
        key_b.append(line + [0.01, 0.005] + rng.normal(0.0, 0.01, line.shape))
    return key_a, key_b


def _deforming_keys(n_strokes, n_points, seed):
    """Key A and key B of a deforming drawing (see :func:`make_keys`): key A is the loops
    drawing's, each loop of key B key A's stretched ``STRETCH`` times along its own axis (the
    loop's turn) about its centre, in place."""
    key_a, _ = make_keys("loops", n_strokes, n_points, seed)
    rng = np.random.default_rng([seed, KINDS.index("deforming"), n_strokes, n_points])
    key_b = []
    for a in key_a:
        centre = a.mean(axis=0)
        axis = _rotation(rng.uniform(0, np.pi))
        stretch = axis @ np.diag([STRETCH, 1.0]) @ axis.T
        key_b.append((a - centre) @ stretch.T + centre)
    return key_a, key_b
