"""Heat-propagation morph (paper section 2, its reference [35]): in-betweens are the iso-contours
of a harmonic field between the curves, and each sample travels along the field's gradient.

The field ``u`` solves the Laplace equation in the gap (between nested loops, or inside the loop
formed by P and Q reversed for strokes sharing their endpoints), with ``u = 0`` on P and
``u = 1`` on Q. It has no critical point in the gap: a conformal map ``f`` takes the gap onto a
round annulus (loops, ``u = log|f| / log R``) or onto a strip (strokes, ``u = Im f``), and
``f' != 0``; so every gradient line runs from P to Q.

**Grid.** ``grid`` cells along the longer side of the pair's bounding box. Nodes are inside the
gap by the even-odd rule along each grid row, using the same crossings that cut grid edges, so
the mask and the boundary always agree. The curves cut grid edges between nodes; the symmetric
second-order discretisation of Gibou, Fedkiw, Cheng and Kang (2002) puts the Dirichlet value at
the cut, a fraction ``theta`` of the edge away, which keeps the matrix symmetric positive
definite. It is solved by conjugate gradients with a Jacobi preconditioner, started from the
solution on a grid half as fine (recursively), all in numpy. Values are extended a few nodes
past the curves by linear extrapolation through the cut, so bilinear interpolation and central
differences work right up to the curves.

**Trajectories.** From each sample ``x(0)`` on P the path solves ``dx/du = grad u / |grad u|^2``
(RK4, all samples at once), so it reaches level ``u`` at time ``u``, then each point is pulled
back onto its level by one Newton step. The paths are stored at ``levels + 1`` uniform levels,
shape (K, S, 2), and frames interpolate between levels (:class:`LevelPaths`): **time is the
level, not the arc length**, so frame ``t`` is the ``t`` iso-contour (:class:`SampledPaths`
would re-parameterise by arc length). Each path's end is moved onto Q exactly (the few-ulp to
O(cell^2) miss is spread along the path in proportion to the level), so ``morph(1)`` lies on Q.

**Where the curves are close** (the paper's known weakness, section 8): a sample closer to the
other curve than ``HEAT_THIN_GAP`` cells, and any path that fails (leaves the extended field,
stalls, ends away from Q), moves straight to its closest point instead; ``morph.fallback`` says
which. Shared stroke endpoints stay put. Nothing non-finite reaches the frames.
"""

import numpy as np

from ..ballmap.topology import orient_pair
from ..errors import InvalidCurveError
from ..geometry.polyline import resample, resolve_spacing, reverse
from ..geometry.ragged import ragged_arange
from .base import PathMorph, register
from .closest import Projector
from .paths import LevelPaths

__all__ = ["HeatField", "HeatMorph", "conjugate_gradient"]

#: Heat propagation: default grid cells along the longer side of the pair's bounding box, and
#: stored levels per trajectory (frames interpolate linearly between levels).
HEAT_GRID = 256
HEAT_LEVELS = 64
#: Heat propagation: empty cells around the curves' bounding box (room for the extension past
#: the curves), and how many node layers the field is extended by past the first ghost layer.
HEAT_GRID_PAD = 6
HEAT_EXTENSION_LAYERS = 3
#: Heat propagation: the solve starts from the solution on a grid half as fine, recursively
#: down to this many cells (the smallest grid accepted).
HEAT_COARSEST_GRID = 16
#: Heat propagation: conjugate gradients stop at this relative residual, or after this many
#: iterations per grid cell along the longer side.
HEAT_CG_RTOL = 1e-9
HEAT_CG_MAX_ITER_PER_CELL = 8
#: Heat propagation: a curve cutting a grid edge closer than this fraction of the edge to a node
#: is put at this fraction (keeps the Dirichlet weight 1/theta finite).
HEAT_MIN_THETA = 1e-3
#: Heat propagation: a gradient smaller than this (times 1 / extent of the pair) is a stall.
HEAT_MIN_GRADIENT = 1e-6
#: Heat propagation: a tracing step longer than this fraction of the pair's extent is a failure.
HEAT_MAX_STEP = 0.25
#: Heat propagation: a traced path ending farther than this many cells from the other curve
#: failed; samples closer than HEAT_THIN_GAP cells to the other curve are not traced. Both move
#: straight to their closest point instead.
HEAT_END_MISS_CELLS = 2.0
HEAT_THIN_GAP = 1.5


def conjugate_gradient(apply, b, diag, x0, rtol, max_iter):
    """Jacobi-preconditioned conjugate gradients for a symmetric positive definite operator.

    Parameters
    ----------
    apply : callable
        ``apply(x) -> A x`` on arrays shaped like ``b``.
    b, diag, x0 : ndarray, same shape
        Right-hand side, the operator's diagonal (all positive), and the first guess.
    rtol : float
        Stop when ``|b - A x| <= rtol |b|``.
    max_iter : int

    Returns
    -------
    x : ndarray
    iterations : int
    residual : float
        Final ``|b - A x| / |b|``.

    Examples
    --------
    >>> import numpy as np
    >>> a = np.array([[4.0, 1.0], [1.0, 3.0]])
    >>> x, _, _ = conjugate_gradient(lambda v: a @ v, np.array([1.0, 2.0]), np.diag(a), np.zeros(2), 1e-12, 10)
    >>> np.allclose(a @ x, [1.0, 2.0])
    True
    """
    x = x0.copy()
    r = b - apply(x)
    norm_b = float(np.linalg.norm(b)) or 1.0
    z = r / diag
    p = z.copy()
    rz = float(np.vdot(r, z))
    it = 0
    res = float(np.linalg.norm(r)) / norm_b
    while res > rtol and it < max_iter:
        ap = apply(p)
        pap = float(np.vdot(p, ap))
        if not pap > 0:
            break
        alpha = rz / pap
        x += alpha * p
        r -= alpha * ap
        it += 1
        res = float(np.linalg.norm(r)) / norm_b
        z = r / diag
        rz_new = float(np.vdot(r, z))
        p = z + (rz_new / rz) * p
        rz = rz_new
    return x, it, res


class _Cuts:
    """Where the curves cut the grid edges along one axis.

    For axis 0 (rows: horizontal grid edges) ``near_lo[i, j]`` is the fraction of the edge from
    node ``(i, j)`` to node ``(i, j + 1)`` at which the cut nearest to ``(i, j)`` lies, and
    ``val_lo`` its boundary value; ``near_hi``/``val_hi`` the same seen from ``(i, j + 1)``;
    ``count`` the number of cuts on each edge. Axis 1 (columns) is the transpose.
    """

    def __init__(self, a, b, values, origin, h, shape, axis):
        # Work in (along, across) coordinates: for axis 0 a grid line is y = const (across = y)
        # and the cut position runs along x.
        al, ac = (0, 1) if axis == 0 else (1, 0)
        n_lines, n_nodes = (shape[0], shape[1]) if axis == 0 else (shape[1], shape[0])
        lo_c, hi_c = np.minimum(a[:, ac], b[:, ac]), np.maximum(a[:, ac], b[:, ac])
        first = np.floor((lo_c - origin[ac]) / h).astype(np.int64)
        last = np.ceil((hi_c - origin[ac]) / h).astype(np.int64)
        seg, local = ragged_arange(np.maximum(last - first + 1, 0))
        line = first[seg] + local
        y = origin[ac] + line * h
        ya, yb = a[seg, ac], b[seg, ac]
        # Half-open rule (as in points_in_loop), so a vertex on a grid line is counted once.
        hit = ((ya > y) != (yb > y)) & (line >= 0) & (line < n_lines)
        seg, line, y = seg[hit], line[hit], y[hit]
        xa, xb, ya, yb = a[seg, al], b[seg, al], a[seg, ac], b[seg, ac]
        xc = xa + (y - ya) * (xb - xa) / (yb - ya)
        pos = (xc - origin[al]) / h
        edge = np.clip(np.floor(pos).astype(np.int64), 0, n_nodes - 2)
        frac = np.clip(pos - edge, 0.0, 1.0)
        key = line * n_nodes + edge
        size = n_lines * n_nodes
        self.count = np.bincount(key, minlength=size).reshape(n_lines, n_nodes)
        self.near_lo, self.val_lo = self._nearest(key, frac, values[seg], size, (n_lines, n_nodes))
        self.near_hi, self.val_hi = self._nearest(key, 1.0 - frac, values[seg], size, (n_lines, n_nodes))
        if axis == 1:
            for name in ("count", "near_lo", "val_lo", "near_hi", "val_hi"):
                setattr(self, name, getattr(self, name).T)

    @staticmethod
    def _nearest(key, dist, vals, size, shape):
        near = np.full(size, np.inf)
        val = np.zeros(size)
        order = np.lexsort((dist, key))
        ks = key[order]
        first = order[np.r_[True, ks[1:] != ks[:-1]]] if len(ks) else order
        near[key[first]] = dist[first]
        val[key[first]] = vals[first]
        return near.reshape(shape), val.reshape(shape)


class HeatField:
    """The harmonic field between two curves on a grid (see the module docstring).

    Parameters
    ----------
    a, b : ndarray, shape (E, 2)
        Start and end points of every boundary segment (both curves).
    values : ndarray, shape (E,)
        Dirichlet value on each segment (0 on P, 1 on Q).
    lo, hi : ndarray, shape (2,)
        Bounding box of the curves.
    cells : int
        Grid cells along the longer side.
    nearest_value : callable
        ``nearest_value(points) -> values``: the boundary value of the curve nearest to each
        point, for the rare node where the mask changes along a column without a cut (a curve
        through a node exactly).

    Attributes
    ----------
    origin : ndarray, shape (2,)
    h : float
        Cell size.
    u : ndarray, shape (ny, nx)
        Values on the nodes (``u[i, j]`` at ``origin + (j h, i h)``); NaN beyond the extension.
    inside : ndarray of bool, shape (ny, nx)
        Nodes in the gap.
    iterations : int
        Conjugate-gradient iterations on this grid.
    residual : float
    """

    def __init__(self, a, b, values, lo, hi, cells, nearest_value):
        self.extent = extent = float(max(hi - lo))
        self.h = h = extent / cells
        pad = HEAT_GRID_PAD
        self.origin = lo - pad * h
        nx = int(np.ceil((hi[0] - lo[0]) / h)) + 2 * pad + 1
        ny = int(np.ceil((hi[1] - lo[1]) / h)) + 2 * pad + 1
        shape = (ny, nx)
        rows = _Cuts(a, b, values, self.origin, h, shape, 0)
        cols = _Cuts(a, b, values, self.origin, h, shape, 1)
        before = np.zeros(shape, dtype=np.int64)
        before[:, 1:] = np.cumsum(rows.count[:, :-1], axis=1)
        self.inside = inside = (before % 2) == 1
        self._assemble(rows, cols, nearest_value)
        coarse = cells // 2
        if coarse >= HEAT_COARSEST_GRID:
            guess = HeatField(a, b, values, lo, hi, coarse, nearest_value).value(self.nodes()[inside])
            x0 = np.zeros(shape)
            x0[inside] = np.where(np.isfinite(guess), guess, 0.5)
        else:
            x0 = np.where(inside, 0.5, 0.0)
        x, self.iterations, self.residual = conjugate_gradient(
            self._apply, self._rhs, self._diag, x0, HEAT_CG_RTOL, HEAT_CG_MAX_ITER_PER_CELL * cells
        )
        u = np.full(shape, np.nan)
        u[inside] = x[inside]
        self.u = self._extend(u)
        self._grad = self._gradient(self.u)

    def nodes(self):
        """Coordinates of every node, shape (ny, nx, 2)."""
        ny, nx = self.inside.shape
        gx = self.origin[0] + self.h * np.arange(nx)
        gy = self.origin[1] + self.h * np.arange(ny)
        return np.stack(np.meshgrid(gx, gy), axis=-1)

    def _assemble(self, rows, cols, nearest_value):
        """Diagonal, couplings and right-hand side of the h^2-scaled symmetric discretisation."""
        ins = self.inside
        shape = ins.shape
        diag = np.zeros(shape)
        rhs = np.zeros(shape)
        # For each axis: the edge between node n (lo side) and its next node (hi side).
        self._couple = []
        for axis, cuts in ((1, rows), (0, cols)):
            lo = [slice(None), slice(None)]
            hi = [slice(None), slice(None)]
            lo[axis], hi[axis] = slice(None, -1), slice(1, None)
            lo, hi = tuple(lo), tuple(hi)
            cut_edge = [slice(None), slice(None)]
            cut_edge[axis] = slice(None, -1)
            cut_edge = tuple(cut_edge)
            count = cuts.count[cut_edge]
            in_lo, in_hi = ins[lo], ins[hi]
            coupled = in_lo & in_hi & (count == 0)
            self._couple.append((axis, lo, hi, coupled.astype(np.float64)))
            theta_lo, val_lo = cuts.near_lo[cut_edge], cuts.val_lo[cut_edge]
            theta_hi, val_hi = cuts.near_hi[cut_edge], cuts.val_hi[cut_edge]
            # A mask change without a cut (a curve exactly through a node): cut at the far node.
            lonely = (in_lo != in_hi) & (count == 0)
            if lonely.any():
                far = np.where(in_lo, 1, 0)  # the outside node of each lonely edge
                idx = np.argwhere(lonely)
                out_nodes = idx.copy()
                out_nodes[:, axis] += far[lonely]
                guess = nearest_value(self.nodes()[out_nodes[:, 0], out_nodes[:, 1]])
                theta_lo, val_lo = theta_lo.copy(), val_lo.copy()
                theta_hi, val_hi = theta_hi.copy(), val_hi.copy()
                theta_lo[lonely], theta_hi[lonely] = 1.0, 1.0
                val_lo[lonely], val_hi[lonely] = guess, guess
            bound_lo = in_lo & ~coupled
            bound_hi = in_hi & ~coupled
            t_lo = np.maximum(np.where(bound_lo, theta_lo, 1.0), HEAT_MIN_THETA)
            t_hi = np.maximum(np.where(bound_hi, theta_hi, 1.0), HEAT_MIN_THETA)
            diag[lo] += np.where(coupled, 1.0, 0.0) + np.where(bound_lo, 1.0 / t_lo, 0.0)
            diag[hi] += np.where(coupled, 1.0, 0.0) + np.where(bound_hi, 1.0 / t_hi, 0.0)
            rhs[lo] += np.where(bound_lo, val_lo / t_lo, 0.0)
            rhs[hi] += np.where(bound_hi, val_hi / t_hi, 0.0)
            # Remember the cuts for the extension past the curves.
            setattr(self, f"_cut{axis}", (t_lo, val_lo, t_hi, val_hi, bound_lo, bound_hi, lo, hi))
        self._diag = np.where(ins, diag, 1.0)
        self._rhs = np.where(ins, rhs, 0.0)

    def _apply(self, x):
        out = self._diag * x
        for _, lo, hi, c in self._couple:
            out[lo] -= c * x[hi]
            out[hi] -= c * x[lo]
        return out

    def _extend(self, u):
        """Fill nodes past the curves: first by extrapolating through each cut, then outwards."""
        total = np.zeros_like(u)
        weight = np.zeros_like(u)
        for axis in (1, 0):
            t_lo, val_lo, t_hi, val_hi, bound_lo, bound_hi, lo, hi = getattr(self, f"_cut{axis}")
            # Inside node at lo, cut at t_lo towards hi: the line through (0, u_lo), (t_lo, val)
            # gives the value at the hi node (if it is outside).
            out_hi = bound_lo & ~self.inside[hi]
            ghost = np.where(out_hi, u[lo] + (val_lo - u[lo]) / t_lo, 0.0)
            total[hi] += np.where(out_hi, ghost, 0.0)
            weight[hi] += out_hi
            out_lo = bound_hi & ~self.inside[lo]
            ghost = np.where(out_lo, u[hi] + (val_hi - u[hi]) / t_hi, 0.0)
            total[lo] += np.where(out_lo, ghost, 0.0)
            weight[lo] += out_lo
        known = np.isfinite(u)
        fill = ~known & (weight > 0)
        u = u.copy()
        u[fill] = total[fill] / weight[fill]
        for _ in range(HEAT_EXTENSION_LAYERS):
            known = np.isfinite(u)
            total = np.zeros_like(u)
            weight = np.zeros_like(u)
            v = np.where(known, u, 0.0)
            for axis in (0, 1):
                for step in (1, -1):
                    n1 = np.roll(v, step, axis=axis)
                    k1 = np.roll(known, step, axis=axis)
                    n2 = np.roll(v, 2 * step, axis=axis)
                    k2 = np.roll(known, 2 * step, axis=axis)
                    est = np.where(k2, 2.0 * n1 - n2, n1)
                    total += np.where(k1, est, 0.0)
                    weight += k1
            fill = ~known & (weight > 0)
            u[fill] = total[fill] / weight[fill]
        # np.roll wraps around the grid, harmlessly: the padding (HEAT_GRID_PAD cells) is wider
        # than the extension, so the border nodes stay unknown and never feed the other side.
        return u

    def _gradient(self, u):
        """Central differences (one-sided next to unknown nodes), shape (ny, nx, 2)."""
        g = np.full(u.shape + (2,), np.nan)
        for comp, axis in ((0, 1), (1, 0)):
            fwd = (np.roll(u, -1, axis=axis) - u) / self.h
            bwd = (u - np.roll(u, 1, axis=axis)) / self.h
            both = 0.5 * (fwd + bwd)
            g[..., comp] = np.where(np.isfinite(both), both, np.where(np.isfinite(fwd), fwd, bwd))
        return g

    def _bilinear(self, grid, x):
        ny, nx = self.inside.shape
        f = (x - self.origin) / self.h
        j = np.clip(np.floor(f[:, 0]).astype(np.int64), 1, nx - 3)
        i = np.clip(np.floor(f[:, 1]).astype(np.int64), 1, ny - 3)
        fx = np.clip(f[:, 0] - j, 0.0, 1.0)
        fy = np.clip(f[:, 1] - i, 0.0, 1.0)
        if grid.ndim == 3:
            fx, fy = fx[:, None], fy[:, None]
        return (1 - fy) * ((1 - fx) * grid[i, j] + fx * grid[i, j + 1]) + fy * (
            (1 - fx) * grid[i + 1, j] + fx * grid[i + 1, j + 1]
        )

    def value(self, x):
        """Bilinearly interpolated field at points, shape (K,) (NaN where unknown)."""
        return self._bilinear(self.u, np.asarray(x, dtype=np.float64).reshape(-1, 2))

    def gradient(self, x):
        """Bilinearly interpolated gradient at points, shape (K, 2) (NaN where unknown)."""
        return self._bilinear(self._grad, np.asarray(x, dtype=np.float64).reshape(-1, 2))


def _velocity(field, x, sign):
    """``sign * grad u / |grad u|^2`` and whether it is usable, for all points."""
    g = field.gradient(x)
    g2 = np.sum(g * g, axis=1)
    ok = np.isfinite(g2) & (g2 > (HEAT_MIN_GRADIENT / field.extent) ** 2)
    v = np.where(ok[:, None], sign * g / np.where(ok, g2, 1.0)[:, None], 0.0)
    return v, ok


def _trace(field, start, u0, u1, levels):
    """Follow the gradient from ``start`` (at level u0) to level u1, shape (K, levels + 1, 2).

    Also returns a mask of paths that stayed usable all the way.
    """
    sign = 1.0 if u1 > u0 else -1.0
    dt = abs(u1 - u0) / levels
    path = np.empty((len(start), levels + 1, 2))
    path[:, 0] = start
    x = start.copy()
    ok = np.ones(len(start), dtype=bool)
    max_step = HEAT_MAX_STEP * field.extent
    for j in range(levels):
        k1, ok1 = _velocity(field, x, sign)
        k2, ok2 = _velocity(field, x + 0.5 * dt * k1, sign)
        k3, ok3 = _velocity(field, x + 0.5 * dt * k2, sign)
        k4, ok4 = _velocity(field, x + dt * k3, sign)
        step = dt / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        x = x + step
        # Newton step back onto the level this point should have reached.
        level = u0 + sign * dt * (j + 1)
        g = field.gradient(x)
        g2 = np.sum(g * g, axis=1)
        miss = level - field.value(x)
        good = np.isfinite(g2) & (g2 > 0) & np.isfinite(miss)
        x = x + np.where(good[:, None], miss[:, None] * g / np.where(good, g2, 1.0)[:, None], 0.0)
        ok &= ok1 & ok2 & ok3 & ok4 & good & (np.linalg.norm(step, axis=1) <= max_step)
        ok &= np.all(np.isfinite(x), axis=1)
        x = np.where(np.isfinite(x), x, path[:, j])
        path[:, j + 1] = x
    return path, ok


class HeatMorph(PathMorph):
    """A heat-propagation morph: trajectories along the gradient of the harmonic field.

    Attributes
    ----------
    paths : LevelPaths
        Indexed by level: frame ``t`` is the ``t`` iso-contour.
    field : HeatField or None
        The solved field (None when P and Q coincide: the morph is static).
    fallback : ndarray of bool, shape (K,)
        Samples that move straight to their closest point instead of along the gradient
        (too close to the other curve for the grid, or a failed trace).
    """

    def __init__(self, closed, paths, u_p, u_q, field, fallback):
        super().__init__("heat-propagation", closed, paths, u_p, u_q, field)
        self.field = field
        self.fallback = fallback


def _straight(start, end, levels):
    w = np.linspace(0.0, 1.0, levels + 1)[None, :, None]
    return (1 - w) * start[:, None, :] + w * end[:, None, :]


@register("heat-propagation")
def build(P, Q, closed, spacing, sampling, grid=None, levels=None):
    """Heat-propagation morph (see the module docstring).

    Parameters
    ----------
    P, Q, closed, spacing : see :func:`~ballmorph_core.morphs.make_morph`
    sampling : {'symmetric', 'p', 'q'}
        ``'P'`` and ``'symmetric'`` trace from uniform samples of P; ``'Q'`` traces backwards
        from uniform samples of Q. Samples are ordered along P as given.
    grid : int, optional
        Cells along the longer side of the bounding box (default ``HEAT_GRID``).
    levels : int, optional
        Stored levels per path, minus one (default ``HEAT_LEVELS``).

    Raises
    ------
    IncompatibleCurvesError
        If the curves are not in configuration 1 or 2.
    """
    grid = HEAT_GRID if grid is None else grid
    levels = HEAT_LEVELS if levels is None else levels
    for name, value, least in (("grid", grid, HEAT_COARSEST_GRID), ("levels", levels, 1)):
        if not (isinstance(value, (int, np.integer)) and value >= least):
            raise InvalidCurveError(f"{name} must be an integer >= {least}, got {value!r}")
    spacing = resolve_spacing(P, Q, closed, spacing)
    setup = orient_pair(P, Q, closed)
    flip = setup.reversed_p != setup.reversed_q
    proj = {"P": Projector(P, closed, spacing), "Q": Projector(reverse(Q, closed) if flip else Q, closed, spacing)}
    src, dst = ("Q", "P") if sampling == "q" else ("P", "Q")
    curves = {"P": P, "Q": Q}
    start = resample(curves[src], closed, spacing)
    if flip and src == "Q":  # follow P's direction
        start = reverse(start, closed)
    near = proj[dst].project(start)
    field = None
    if setup.coincident:
        paths = _straight(start, start, levels)
        fallback = np.ones(len(start), dtype=bool)
    else:
        field = _field(setup, closed, int(grid), proj)
        u0, u1 = (1.0, 0.0) if src == "Q" else (0.0, 1.0)
        paths, ok = _trace(field, start, u0, u1, levels)
        # Land exactly on the other curve; spread the miss along the path by level.
        end = proj[dst].project(paths[:, -1])
        miss = np.linalg.norm(end.foot - paths[:, -1], axis=1)
        ok &= miss <= HEAT_END_MISS_CELLS * field.h
        w = np.linspace(0.0, 1.0, levels + 1)[None, :, None]
        paths = paths + w * (end.foot - paths[:, -1])[:, None, :]
        thin = near.dist <= HEAT_THIN_GAP * field.h
        fallback = thin | ~ok | ~np.all(np.isfinite(paths), axis=(1, 2))
        paths[fallback] = _straight(start[fallback], near.foot[fallback], levels)
        near.pos = np.where(fallback, near.pos, end.pos)
    u_src = np.arange(len(start)) / (len(start) if closed else len(start) - 1)
    if flip and src == "Q":
        u_src = np.mod(1.0 - u_src, 1.0) if closed else 1.0 - u_src
    u_dst = proj[dst].fraction(near.pos)
    if flip and dst == "Q":
        u_dst = np.mod(1.0 - u_dst, 1.0) if closed else 1.0 - u_dst
    if src == "Q":
        paths = paths[:, ::-1]
        u_p, u_q = u_dst, u_src
    else:
        u_p, u_q = u_src, u_dst
    return HeatMorph(closed, LevelPaths(paths), u_p, u_q, field, fallback)


def _field(setup, closed, cells, proj):
    """The harmonic field for an oriented pair (u = 0 on P, 1 on Q)."""
    P, Q = setup.P, setup.Q
    if closed:
        ends_p, ends_q = np.roll(P, -1, axis=0), np.roll(Q, -1, axis=0)
        a = np.concatenate([P, Q])
        b = np.concatenate([ends_p, ends_q])
        values = np.r_[np.zeros(len(P)), np.ones(len(Q))]
    else:
        # The loop P then Q backwards; the joins at the shared endpoints are (nearly) empty.
        a = np.concatenate([P[:-1], [P[-1]], Q[:-1], [Q[0]]])
        b = np.concatenate([P[1:], [Q[-1]], Q[1:], [P[0]]])
        values = np.r_[np.zeros(len(P)), np.ones(len(Q))]
    both = np.concatenate([P, Q])
    lo, hi = both.min(axis=0), both.max(axis=0)

    def nearest_value(points):
        return (proj["Q"].project(points).dist < proj["P"].project(points).dist).astype(np.float64)

    return HeatField(a, b, values, lo, hi, cells, nearest_value)
