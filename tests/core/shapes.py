"""Analytic test curves shared by the core tests (plain numpy; also used by hypothesis)."""

import numpy as np


def circle(radius=1.0, n=200, centre=(0.0, 0.0), start=0.0):
    """Counter-clockwise circle without a repeated last point, shape (n, 2)."""
    t = start + np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    return np.c_[centre[0] + radius * np.cos(t), centre[1] + radius * np.sin(t)]


def polar_loop(coeffs, n=300, base=1.0):
    """Star-shaped loop r(theta) = base + sum a_k cos(k theta + b_k), shape (n, 2)."""
    t = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    r = np.full_like(t, base)
    for k, (a, b) in enumerate(coeffs, start=2):
        r += a * np.cos(k * t + b)
    return np.c_[r * np.cos(t), r * np.sin(t)]


def graph_stroke(height, coeffs=(), n=200):
    """Stroke y = f(x) over [0, 1] with f(0) = f(1) = 0, shape (n, 2).

    f = height * sin(pi x) + sum a_k sin((k + 1) pi x).
    """
    x = np.linspace(0.0, 1.0, n)
    return np.c_[x, graph_height(x, height, coeffs)]


def graph_height(x, height, coeffs=()):
    y = height * np.sin(np.pi * x)
    for k, a in enumerate(coeffs, start=2):
        y = y + a * np.sin(k * np.pi * x)
    return y


def graph_slope(x, height, coeffs=()):
    d = height * np.pi * np.cos(np.pi * x)
    for k, a in enumerate(coeffs, start=2):
        d = d + a * k * np.pi * np.cos(k * np.pi * x)
    return d


def distance_to_polyline(points, curve, closed):
    """Distance from each point to a polyline, shape (K,) (brute force, for tests)."""
    a = curve
    b = np.roll(curve, -1, axis=0) if closed else curve[1:]
    a = a[: len(b)]
    ab = b - a
    ap = points[:, None, :] - a[None, :, :]
    # A repeated vertex makes a zero-length segment: its closest point is the vertex itself.
    t = np.clip(np.einsum("kij,ij->ki", ap, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300), 0, 1)
    closest = a[None] + t[..., None] * ab[None]
    return np.linalg.norm(points[:, None, :] - closest, axis=2).min(axis=1)


def polar_tangent(points, coeffs, base=1.0, shift=(0.0, 0.0)):
    """Unit tangent of :func:`polar_loop` at points on it (by their polar angle), shape (K, 2)."""
    rel = points - np.asarray(shift)
    t = np.arctan2(rel[:, 1], rel[:, 0])
    r = np.full_like(t, base)
    dr = np.zeros_like(t)
    for k, (a, b) in enumerate(coeffs, start=2):
        r += a * np.cos(k * t + b)
        dr -= a * k * np.sin(k * t + b)
    tan = np.c_[dr * np.cos(t) - r * np.sin(t), dr * np.sin(t) + r * np.cos(t)]
    return tan / np.linalg.norm(tan, axis=1, keepdims=True)


def graph_min_curvature_radius(height, coeffs=(), n=2000):
    """Smallest radius of curvature of :func:`graph_stroke`'s curve (float)."""
    x = np.linspace(0.0, 1.0, n)
    d1 = graph_slope(x, height, coeffs)
    d2 = -height * np.pi**2 * np.sin(np.pi * x)
    for k, a in enumerate(coeffs, start=2):
        d2 = d2 - a * (k * np.pi) ** 2 * np.sin(k * np.pi * x)
    kappa = np.abs(d2) / (1 + d1**2) ** 1.5
    return 1.0 / max(kappa.max(), 1e-12)
