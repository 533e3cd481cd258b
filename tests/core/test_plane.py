"""The drawing plane: projecting keys to 2D and lifting in-betweens back to 3D."""

import numpy as np
import pytest

from ballmorph_core.geometry.plane import fit_plane


def _tilted(points_2d, depth, angle):
    """Points on a plane turned by ``angle`` about the x then the z axis, ``depth`` off it."""
    c, s = np.cos(angle), np.sin(angle)
    u = np.array([c, s * 0.6, s * 0.8])
    v = np.cross([0.3, -0.8, 0.5], u)
    v /= np.linalg.norm(v)
    n = np.cross(u, v)
    return np.array([0.4, -1.0, 2.0]) + points_2d[:, :1] * u + points_2d[:, 1:] * v + depth[:, None] * n


@pytest.mark.parametrize("angle", [0.0, 0.7])
def test_lifting_undoes_projecting_with_and_without_offsets(angle):
    rng = np.random.default_rng(3)
    xy, depth = rng.normal(size=(200, 2)), 1e-3 * rng.normal(size=200)
    points = _tilted(xy, depth, angle)
    plane = fit_plane(points)
    coords, offsets = plane.to_2d(points)
    np.testing.assert_allclose(plane.to_3d(coords, offsets), points, atol=1e-12)
    # Without offsets: the foot of each point on the plane.
    feet = plane.to_3d(coords)
    np.testing.assert_allclose(feet + offsets[:, None] * plane.normal, points, atol=1e-12)
    np.testing.assert_allclose((feet - plane.origin) @ plane.normal, 0.0, atol=1e-12)


def test_the_front_canvas_maps_to_x_and_z():
    """Blender's front view draws on XZ: the plane is that world frame, coordinates are (x, z)."""
    rng = np.random.default_rng(4)
    points = np.c_[rng.normal(size=50), np.zeros(50), rng.normal(size=50)]
    plane = fit_plane(points)
    coords, offsets = plane.to_2d(points)
    np.testing.assert_allclose(np.abs(plane.normal), [0.0, 1.0, 0.0])
    np.testing.assert_allclose(offsets, 0.0, atol=1e-12)
    np.testing.assert_allclose(plane.to_3d(coords, offsets), points, atol=1e-12)
