"""The drawing plane: projecting keys to 2D and lifting in-betweens back to 3D."""

import numpy as np
import pytest

from ballmorph_core.geometry import plane
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


def test_lifting_sums_origin_u_v_and_normal_terms_in_that_order():
    """to_3d skips zero terms and writes the first with the origin: the same numbers, bit for
    bit, as origin + u x + v y + n d summed in that order (a tilted plane: every term)."""
    from ballmorph_core.geometry.plane import Plane

    rng = np.random.default_rng(5)
    normal = np.array([0.3, -0.8, 0.52])
    normal /= np.linalg.norm(normal)
    u = np.cross(normal, [0.0, 0.0, 1.0])
    u /= np.linalg.norm(u)
    plane = Plane(np.array([0.4, -1.2, 2.5]), u, np.cross(normal, u), normal)
    coords, depth = rng.normal(size=(40, 2)), rng.normal(size=40) * 1e-3
    want = np.empty((40, 3))
    for axis in range(3):
        column = np.full(40, plane.origin[axis])
        column += plane.u[axis] * coords[:, 0]
        column += plane.v[axis] * coords[:, 1]
        column += plane.normal[axis] * depth
        want[:, axis] = column
    np.testing.assert_array_equal(plane.to_3d(coords, depth), want)
    front = fit_plane(np.c_[coords[:, 0], np.zeros(40), coords[:, 1]])  # XZ: one axis has no term
    lifted = front.to_3d(coords)
    np.testing.assert_array_equal(lifted[:, 1], np.full(40, front.origin[1]))
    np.testing.assert_array_equal(lifted[:, 0], coords[:, 0] + front.origin[0])


def _nudged(points, axis):
    """The points with one of them a rounding off the axis plane they lie on: no longer exactly
    on it, so fit_plane takes its SVD (and snaps a normal this close to the axis)."""
    off = points.copy()
    off[7, axis] = np.nextafter(off[7, axis], np.inf)
    return off


@pytest.mark.parametrize("axis", [0, 1, 2])
@pytest.mark.parametrize("spread", [1.0, 1e-2, 1e-4, 1e-9, 0.0])
@pytest.mark.parametrize("offset", [0.0, 0.37])
def test_points_on_an_axis_plane_get_the_frame_of_points_a_rounding_off_it(axis, spread, offset):
    # Exactly on an axis plane, however thin their spread across it (down to collinear): the
    # frame is the very one of the same points with one a rounding off the plane (which the
    # SVD fits), bit for bit; only the origin moves, by that rounding.
    rng = np.random.default_rng(axis)
    pts = rng.normal(size=(500, 3)) * [3.0, 1.0, 1.0]
    pts[:, (axis + 2) % 3] = spread * pts[:, (axis + 2) % 3] + 0.5 * pts[:, (axis + 1) % 3]
    pts[:, axis] = offset
    for options in ({}, {"axis_tolerance": 1e-9}):
        got, nudged = fit_plane(pts, **options), fit_plane(_nudged(pts, axis), **options)
        for name in ("u", "v", "normal"):
            assert np.array_equal(getattr(got, name), getattr(nudged, name)), (name, options)
        np.testing.assert_allclose(got.origin, nudged.origin, rtol=0.0, atol=1e-17)
        if spread > 0.0:  # spread across the plane: its own axis frame
            assert abs(got.normal[axis]) == 1.0


def test_the_axis_plane_shortcut_takes_exact_axis_planes_of_spread_points_only():
    pts = np.random.default_rng(1).normal(size=(50, 3))
    pts[:, 1] = 2.0
    assert plane._on_axis_plane(pts, pts.mean(axis=0)) == 1
    pts[7, 1] = np.nextafter(2.0, 3.0)  # one point off the plane
    assert plane._on_axis_plane(pts, pts.mean(axis=0)) is None
    pts[:, 1], pts[:, 2] = 2.0, pts[:, 0] * 0.3  # collinear
    assert plane._on_axis_plane(pts, pts.mean(axis=0)) is None


@pytest.mark.parametrize("tilt", [0.0, 1e-5, 0.3])
def test_the_farthest_point_is_the_projections_farthest_bit_for_bit(tilt):
    # Points a little off the front canvas (its frame, or a tilted fit): the largest distance
    # read off the axis is the projection's.
    rng = np.random.default_rng(3)
    pts = rng.normal(size=(300, 3)) * [2.0, 1e-4, 1.0]
    pts[:, 1] += tilt * pts[:, 0] + 0.25
    pts[7, 1] = -0.0
    p = fit_plane(pts)
    assert p.farthest(pts) == float(np.abs(p.to_2d(pts)[1]).max())
    assert (np.flatnonzero(p.normal).size == 1) == (tilt < 1e-3)  # both routes taken
