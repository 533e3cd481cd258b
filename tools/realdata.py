#!/usr/bin/env python3
"""Real-data benchmark (issue 11): in-between glyph outlines of the variable font Inter.

Each glyph is a drawing whose contours are closed strokes. The keys are the font's Thin and
Black masters (the ends of its weight axis); the ground truth is the font's own instance at
weights 300 to 700. Three masters (Thin, Regular, Black) bend the designer's path at Regular,
so for each glyph and weight the tool fits the time t at which the designer's straight blend
``(1 - t) * Thin + t * Black`` (point by point: masters are point-compatible) is closest to the
instance, then scores three routes at that t against the instance:

- ours: ``bm.inbetween`` (default options unless ``--method`` / ``--carrier`` say otherwise);
- baseline: Blender-like, every contour of both keys resampled by arc length from its first
  point to the same count and blended linearly, contours paired by index;
- floor: the designer's straight blend (the best a morph between two keys can hope for).

Scores are the symmetric Hausdorff and the mean distance between drawings, in thousandths of
an em, and the number of in-betweens whose contours cross (themselves or each other) where the
instance's do not. The report (``--write docs/realdata.md``) documents every choice.

Usage::

    tools/realdata.py --write docs/realdata.md     # make realdata: every glyph, three families
    tools/realdata.py --quick                      # a dozen glyphs, report on stdout
    tools/realdata.py --glyphs 'ag&' --method linear-ball --carrier none

fontTools reads the fonts here, in the development environment only: the add-on never does.
"""

import argparse
import datetime
import glob
import os
import platform
import re
import signal
import subprocess
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field
from functools import cache
from math import comb

import numpy as np

TOOLS = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(TOOLS)
sys.path.insert(0, ROOT)

import ballmorph_core as bm  # noqa: E402

FONT_DIR = os.environ.get("INTER_FONT_DIR", "/usr/share/fonts/truetype/inter-vf")
FONT_PACKAGE = "fonts-inter-variable"
FAMILIES = (
    ("Inter", "Inter-roman.var.ttf"),
    ("Inter Italic", "Inter-italic.var.ttf"),
    ("Inter Display", "InterDisplay-roman.var.ttf"),
)
#: Families of static instances of one interpolable design (Debian packages): family, package,
#: directory, files (every weight's instance; the lightest and heaviest are the keys).
STATIC_FAMILIES = (
    ("Dosis", "fonts-dosis", "/usr/share/fonts/opentype/dosis", "Dosis-*.otf"),
    ("League Spartan", "fonts-league-spartan", "/usr/share/fonts/opentype/league-spartan", "LeagueSpartan-*.otf"),
    ("JetBrains Mono", "fonts-jetbrains-mono", "/usr/share/fonts/truetype/jetbrains-mono", "JetBrainsMono-*[!c].ttf"),
    ("Manrope", "fonts-manrope", "/usr/share/fonts/truetype/manrope", "Manrope-*.ttf"),
)
#: Families held back (issue 38's follow-up): static instances from other designers (Debian
#: packages), kept out of ``make realdata`` so that rules are not chosen on them; ``--held-out``
#: runs them (docs/realdata-heldout.md). Karla's 'B', 'D' and 's' showed that loops no ball-map
#: follows fare better tangent-aligned than composite (pipeline._loops_off_the_ball): it is no
#: longer unseen; the other seven were never used to choose a rule or a constant.
HELD_OUT_FAMILIES = (
    ("Fira Code", "fonts-firacode", "/usr/share/fonts/truetype/firacode", "FiraCode-*.ttf"),
    ("Lato", "fonts-lato", "/usr/share/fonts/truetype/lato", "Lato-*[!c].ttf"),
    ("Open Sans", "fonts-open-sans", "/usr/share/fonts/truetype/open-sans", "OpenSans-[!C]*[!c].ttf"),
    ("Quicksand", "fonts-quicksand", "/usr/share/fonts/truetype/quicksand", "Quicksand-*.ttf"),
    ("Roboto", "fonts-roboto-unhinted", "/usr/share/fonts/truetype/roboto/unhinted/RobotoTTF", "Roboto-*[!c].ttf"),
    ("Yrsa", "fonts-yrsa-rasa", "/usr/share/fonts/truetype/fonts-yrsa-rasa", "Yrsa-*[!c].ttf"),
    ("Karla", "fonts-karla", "/usr/share/fonts/truetype/karla", "Karla-*[!c].otf"),
    ("Cantarell", "fonts-cantarell", "/usr/share/fonts/opentype/cantarell", "Cantarell-*.otf"),
)
WEIGHTS = (300, 400, 500, 600, 700)
GLYPHS = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789&@%ß$"
QUICK_GLYPHS = "aegksABQR8&@"
FIGURE_GLYPHS = (("Inter", "g"), ("Inter Italic", "&"), ("Inter Display", "ß"))
FIGURE_WEIGHT = 400

POINT_SPACING = 10.0  # thousandths of an em between the points of a flattened outline (about)
MIN_POINTS = {1: 1, 2: 2, 3: 3}  # points at least per line / quadratic / cubic segment
SAMPLE_SPACING = 1.0  # thousandths of an em between the samples the distances are taken at
DUPLICATE = 1e-9  # thousandths of an em: a point this close to its predecessor everywhere is dropped
BLOCK = 16  # segments per run of the distance search
CHUNK = 2048  # points per block of the distance search
GOAL_RATIO, GOAL_MARGIN = 1.1, 1.5  # issue 38: median Hausdorff <= max(1.1 x floor, floor + 1.5)
DEFAULT_TIMEOUT = 120.0  # seconds for one glyph's bm.inbetween call
ROADS = ("ours", "peer", "baseline", "floor")


class GlyphError(Exception):
    """A glyph that cannot be benchmarked (reported, not fatal)."""


# --------------------------------------------------------------------------------------------
# Reading the font: contours as Bézier segments, flattened point-compatibly
# --------------------------------------------------------------------------------------------


def bezier_points(control, n):
    """Points of one Bézier segment at parameters ``1/n, 2/n, ..., 1`` (its start left out).

    Parameters
    ----------
    control : ndarray, shape (d + 1, 2)
        Control points, the segment's start first (d = 1 line, 2 quadratic, 3 cubic).
    n : int
        Number of points (>= 1).

    Returns
    -------
    ndarray, shape (n, 2)
    """
    control = np.asarray(control, dtype=np.float64)
    d = len(control) - 1
    t = np.arange(1, n + 1, dtype=np.float64)[:, None] / n
    basis = np.hstack([comb(d, k) * t**k * (1.0 - t) ** (d - k) for k in range(d + 1)])
    return basis @ control


def flatten_contour(start, segments, counts, closed=True):
    """A contour's polyline: its start, then ``counts[k]`` points along segment k.

    Parameters
    ----------
    start : array_like, shape (2,)
    segments : list of array_like, each shape (d, 2)
        Each segment's control points after its start (1: line, 2: quadratic, 3: cubic).
    counts : sequence of int, length len(segments)
        Points per segment (its end included, its start not).
    closed : bool
        A closed contour's last segment ends at ``start``: that repeated point is dropped.

    Returns
    -------
    ndarray, shape (1 + sum(counts) - closed, 2)
    """
    pts = [np.asarray(start, dtype=np.float64).reshape(1, 2)]
    for seg, n in zip(segments, counts):
        seg = np.asarray(seg, dtype=np.float64).reshape(-1, 2)
        pts.append(bezier_points(np.vstack([pts[-1][-1:], seg]), int(n)))
    out = np.vstack(pts)
    return out[:-1] if closed and len(out) > 1 else out


def control_lengths(start, segments):
    """Each segment's control polygon length (an upper bound of its arc length), shape (len(segments),)."""
    ends = [np.asarray(start, dtype=np.float64).reshape(1, 2)] + [np.asarray(g).reshape(-1, 2) for g in segments]
    return np.array(
        [
            np.sum(np.linalg.norm(np.diff(np.vstack([ends[k][-1:], ends[k + 1]]), axis=0), axis=1))
            for k in range(len(segments))
        ]
    )


def segment_counts(outlines, spacing=POINT_SPACING):
    """Points per segment, the same for every location: about one per ``spacing`` of length.

    A segment's length is its control polygon's, averaged over the given outlines (the two
    keys): a drawing flattened with these counts is about evenly spaced, as a drawn stroke is,
    and every location of the glyph flattens to the same point counts.

    Parameters
    ----------
    outlines : list of list of (start, segments, closed)
        The same glyph at several locations (see :func:`read_outline`), of one structure.
    spacing : float

    Returns
    -------
    list of ndarray of int
        Per contour, the count of each of its segments (at least :data:`MIN_POINTS`).
    """
    counts = []
    for contour in zip(*outlines):
        length = np.mean([control_lengths(start, segments) for start, segments, _ in contour], axis=0)
        least = np.array([MIN_POINTS[len(seg)] for seg in contour[0][1]], dtype=np.int64)
        counts.append(np.maximum(least, np.rint(length / spacing).astype(np.int64)))
    return counts


def _segment_pen_class():
    """The fontTools pen recording contours as segments (fontTools imported only when reading fonts)."""
    from fontTools.pens.basePen import BasePen

    class SegmentPen(BasePen):
        """Records each contour as ``(start, segments, closed)``; components are decomposed.

        BasePen splits TrueType quadratic strings at their implied on-curve points. A closed
        contour whose last segment does not end at its start gets the implied closing line.
        """

        def __init__(self, glyph_set):
            super().__init__(glyph_set)
            self.contours = []

        def _moveTo(self, pt):
            self._start, self._segments = np.asarray(pt, dtype=np.float64), []

        def _lineTo(self, pt):
            self._segments.append(np.array([pt], dtype=np.float64))

        def _qCurveToOne(self, pt1, pt2):
            self._segments.append(np.array([pt1, pt2], dtype=np.float64))

        def _curveToOne(self, pt1, pt2, pt3):
            self._segments.append(np.array([pt1, pt2, pt3], dtype=np.float64))

        def _closePath(self):
            if not self._segments or not np.array_equal(self._segments[-1][-1], self._start):
                self._segments.append(self._start[None].copy())
            self.contours.append((self._start, self._segments, True))

        def _endPath(self):
            self.contours.append((self._start, self._segments, False))

    return SegmentPen


@dataclass
class Font:
    """One variable font, with its glyph sets opened at every location used.

    Attributes
    ----------
    family : str
    path : str
    scale : float
        Thousandths of an em per font unit (1000 / unitsPerEm).
    thin, black : float
        The weight axis' ends: the key masters.
    cmap : dict
        Character code -> glyph name.
    glyph_sets : dict
        Weight -> fontTools glyph set at that weight (other axes at their defaults).
    truth_weights : tuple of float
        The weights between the keys whose instances are the truth.
    static : bool
        Static instances (one file per weight): their contours' order and start points are
        matched between weights (:func:`align_outlines`).
    """

    family: str
    path: str
    scale: float
    thin: float
    black: float
    cmap: dict
    glyph_sets: dict
    truth_weights: tuple = WEIGHTS
    static: bool = False


@cache
def open_font(family, path):
    """Open ``path`` once per process: a variable font whose weight axis covers :data:`WEIGHTS`,
    or (a tuple of paths) the static instances of one design (:func:`open_static`).

    Returns
    -------
    Font
    """
    from fontTools.ttLib import TTFont

    if not isinstance(path, str):
        return open_static(family, path)
    tt = TTFont(path)
    axes = {a.axisTag: a for a in tt["fvar"].axes} if "fvar" in tt else {}
    if "wght" not in axes:
        raise SystemExit(f"realdata: {path} has no weight axis (wght): not the variable Inter")
    wght = axes["wght"]
    if not wght.minValue <= min(WEIGHTS) <= max(WEIGHTS) <= wght.maxValue:
        raise SystemExit(f"realdata: {path}: weight axis {wght.minValue}-{wght.maxValue} does not cover {WEIGHTS}")
    weights = (wght.minValue, wght.maxValue, *WEIGHTS)
    glyph_sets = {w: tt.getGlyphSet(location={"wght": w}) for w in weights}
    return Font(
        family, path, 1000.0 / tt["head"].unitsPerEm, wght.minValue, wght.maxValue, tt.getBestCmap(), glyph_sets
    )


def open_static(family, paths):
    """The static instances ``paths`` of one design as a Font keyed by their OS/2 weight class:
    the lightest and heaviest are the keys, the others the truth.

    Returns
    -------
    Font
    """
    from fontTools.ttLib import TTFont

    fonts = {}
    for path in paths:
        tt = TTFont(path)
        fonts.setdefault(float(tt["OS/2"].usWeightClass), tt)
    weights = sorted(fonts)
    if len(weights) < 3:
        raise SystemExit(f"realdata: {family}: fewer than three weights in {', '.join(paths)}")
    first = fonts[weights[0]]
    return Font(
        family,
        ", ".join(os.path.basename(p) for p in paths),
        1000.0 / first["head"].unitsPerEm,
        weights[0],
        weights[-1],
        first.getBestCmap(),
        {w: tt.getGlyphSet() for w, tt in fonts.items()},
        tuple(weights[1:-1]),
        True,
    )


def _ends(segments):
    """A contour's on-curve points (each segment's end), shape (len(segments), 2)."""
    return np.array([np.asarray(seg, dtype=np.float64).reshape(-1, 2)[-1] for seg in segments])


def rotated(contour, r):
    """A closed contour ``(start, segments, closed)`` started at its segment ``r``'s start."""
    start, segments, closed = contour
    if not closed or r == 0:
        return contour
    return (np.asarray(segments[r - 1], dtype=np.float64).reshape(-1, 2)[-1], segments[r:] + segments[:r], closed)


def _best_rotation(ref, cur):
    """The rotation of contour ``cur`` whose segment kinds match ``ref``'s, on-curve points
    closest (summed squared distance): ``(cost, r)``, cost inf when none matches."""
    kinds_ref, kinds_cur = [len(s) for s in ref[1]], [len(s) for s in cur[1]]
    if ref[2] != cur[2] or len(kinds_ref) != len(kinds_cur):
        return np.inf, 0
    a, b = _ends(ref[1]), _ends(cur[1])
    best = (np.inf, 0)
    for r in range(len(kinds_cur)) if cur[2] else (0,):
        if kinds_cur[r:] + kinds_cur[:r] == kinds_ref:
            # Segment r of cur becomes the first: its ends shift by r.
            best = min(best, (float(np.sum(np.square(a - np.roll(b, -r, axis=0)))), r))
    return best


def align_outlines(outlines):
    """Static instances' outlines with each contour matched to its lighter neighbour's: the
    same contour order and start point (the closest cyclic rotation whose segment kinds agree).

    Parameters
    ----------
    outlines : list of list of (start, segments, closed)
        The glyph at every weight, lightest first (see :func:`read_outline`).

    Returns
    -------
    list of list of (start, segments, closed)
        The same contours, reordered and rotated; an instance whose contours cannot all be
        matched is left as read (:func:`load_glyph` then reports the glyph).
    """
    out = [outlines[0]]
    for cur in outlines[1:]:
        ref = out[-1]
        if len(cur) != len(ref):
            out.append(cur)
            continue
        costs = np.array([[_best_rotation(a, b) for b in cur] for a in ref])  # (n, n, 2)
        order, free = [None] * len(ref), set(range(len(cur)))
        # Greedy by cost: the contours of a glyph lie apart, the closest match is the right one.
        for flat in np.argsort(costs[..., 0], axis=None, kind="stable"):
            i, j = divmod(int(flat), len(cur))
            if order[i] is None and j in free and np.isfinite(costs[i, j, 0]):
                order[i] = rotated(cur[j], int(costs[i, j, 1]))
                free.discard(j)
        out.append(order if all(o is not None for o in order) else cur)
    return out


def read_outline(font, glyph_name, weight):
    """A glyph's contours at one weight as Bézier segments, in thousandths of an em.

    Returns
    -------
    list of (ndarray (2,), list of ndarray (d, 2), bool)
        Per contour, in the font's order: its start point (the font's), its segments' control
        points after their starts, and whether it is closed.
    """
    pen = _segment_pen_class()(font.glyph_sets[weight])
    font.glyph_sets[weight][glyph_name].draw(pen)
    return [(start * font.scale, [seg * font.scale for seg in segs], closed) for start, segs, closed in pen.contours]


def structure(outline):
    """What must agree between locations: per contour, its closed flag and its segments' kinds."""
    return [(closed, tuple(len(seg) for seg in segs)) for _, segs, closed in outline]


def drop_shared_duplicates(drawings):
    """Drop the points that repeat their predecessor in every one of point-compatible drawings.

    A zero-length segment in every master (a doubled on-curve point) says nothing; one that is
    zero-length in some masters only is kept, so the drawings stay point-compatible.

    Parameters
    ----------
    drawings : list of list of ndarray
        The same glyph at several locations: ``drawings[k][i]`` is contour i at location k,
        shape (n_i, 2) for every k.

    Returns
    -------
    list of list of ndarray
        The same structure, with the shared duplicates removed.
    """
    out = [[] for _ in drawings]
    for i in range(len(drawings[0])):
        stack = np.stack([d[i] for d in drawings])  # (K, n_i, 2)
        step = np.linalg.norm(stack - np.roll(stack, 1, axis=1), axis=2)
        keep = ~np.all(step <= DUPLICATE, axis=0)
        keep[0] = True
        for k, d in enumerate(drawings):
            out[k].append(d[i][keep])
    return out


@dataclass
class GlyphMasters:
    """One glyph's keys and ground truth, point-compatible.

    Attributes
    ----------
    thin, black : list of ndarray, each shape (n_i, 2)
        The key masters' contours (thousandths of an em).
    truths : dict
        Weight -> list of contours of the instance at that weight, shape (n_i, 2) each.
    closed : ndarray of bool, shape (S,)
    """

    thin: list
    black: list
    truths: dict
    closed: np.ndarray


def load_glyph(font, char):
    """Read one glyph at the two key weights and every benchmark weight, point-compatibly.

    Raises
    ------
    GlyphError
        The character is not in the font, has no contour, or its contours differ between
        locations (another count, closed flag or segment kind).
    """
    name = font.cmap.get(ord(char))
    if name is None:
        raise GlyphError(f"{char!r} is not in {os.path.basename(font.path)}")
    weights = (font.thin, font.black, *font.truth_weights)
    outlines = [read_outline(font, name, w) for w in weights]
    if not outlines[0]:
        raise GlyphError("no contours")
    if font.static:
        # Lightest to heaviest, each matched to its neighbour, then back in the order above.
        by_weight = sorted(range(len(weights)), key=lambda k: weights[k])
        aligned = align_outlines([outlines[k] for k in by_weight])
        outlines = [aligned[by_weight.index(k)] for k in range(len(weights))]
    for w, outline in zip(weights, outlines):
        if structure(outline) != structure(outlines[0]):
            raise GlyphError(f"contours differ between weights {weights[0]:g} and {w:g}")
    counts = segment_counts(outlines[:2])
    drawings = [[flatten_contour(*c[:2], n, c[2]) for c, n in zip(outline, counts)] for outline in outlines]
    drawings = drop_shared_duplicates(drawings)
    closed = np.array([c for _, _, c in outlines[0]], dtype=bool)
    return GlyphMasters(drawings[0], drawings[1], dict(zip(font.truth_weights, drawings[2:])), closed)


# --------------------------------------------------------------------------------------------
# Geometry of drawings: polylines, distances, crossings
# --------------------------------------------------------------------------------------------


def drawing_segments(contours, closed):
    """Every segment of a drawing (closing segments of closed contours included).

    Parameters
    ----------
    contours : list of ndarray, each shape (n_i, 2)
    closed : array_like of bool, shape (S,)

    Returns
    -------
    a, b : ndarray, shape (M, 2)
        Segment ends.
    contour : ndarray of int, shape (M,)
        Which contour each segment belongs to.
    index : ndarray of int, shape (M,)
        The segment's index along its contour.
    count : ndarray of int, shape (M,)
        Segments on its contour.
    """
    parts = []
    for i, (c, cyc) in enumerate(zip(contours, closed)):
        c = np.asarray(c, dtype=np.float64)
        b = np.roll(c, -1, axis=0) if cyc else c[1:]
        a = c if cyc else c[:-1]
        m = len(a)
        parts.append((a, b, np.full(m, i), np.arange(m), np.full(m, m)))
    if not parts:
        return np.zeros((0, 2)), np.zeros((0, 2)), *(np.zeros(0, np.int64) for _ in range(3))
    return tuple(np.concatenate(p) for p in zip(*parts))


def _segment_blocks(a, b, block):
    """Segments grouped in runs of ``block`` (the last run padded with its last segment).

    Returns
    -------
    a, b : ndarray, shape (K, block, 2)
        The segments' ends, K = ceil(M / block).
    lo, hi : ndarray, shape (K, 2)
        Each run's bounding box.
    """
    pad = -len(a) % block
    a = np.concatenate([a, np.repeat(a[-1:], pad, axis=0)]).reshape(-1, block, 2)
    b = np.concatenate([b, np.repeat(b[-1:], pad, axis=0)]).reshape(-1, block, 2)
    return a, b, np.minimum(a.min(axis=1), b.min(axis=1)), np.maximum(a.max(axis=1), b.max(axis=1))


def _squared_distances(px, py, ax, ay, bx, by):
    """Squared distances from points to segments, elementwise over broadcast coordinate arrays."""
    dx, dy = bx - ax, by - ay
    rx, ry = px - ax, py - ay
    dd = dx * dx + dy * dy
    u = np.clip((rx * dx + ry * dy) / np.where(dd > 0, dd, 1.0), 0.0, 1.0)
    rx -= u * dx
    ry -= u * dy
    return rx * rx + ry * ry


def _run_distances(p, which, run, ra, rb):
    """Squared distances from points ``p[which]`` to every segment of runs ``run``, shape (C, block)."""
    sa, sb = ra[run], rb[run]
    return _squared_distances(p[which, :1], p[which, 1:], sa[..., 0], sa[..., 1], sb[..., 0], sb[..., 1])


def point_segment_distances(points, a, b, block=BLOCK, chunk=CHUNK):
    """Distance from each point to the nearest of the segments ``a[j] b[j]`` (exact).

    Segments are grouped in runs of ``block`` consecutive ones (runs along a contour are
    compact). For each point, the distance to a run's first vertex bounds its answer from
    above and the distance to a run's bounding box bounds that run's segments from below: only
    the runs whose lower bound is within the upper bound are searched, segment by segment.

    Parameters
    ----------
    points : ndarray, shape (N, 2)
    a, b : ndarray, shape (M, 2)
        Segment ends (zero-length segments are points), M >= 1.
    block : int
        Segments per run.
    chunk : int
        Points per block of work.

    Returns
    -------
    ndarray, shape (N,)
    """
    points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    ra, rb, lo, hi = _segment_blocks(np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64), block)
    out = np.empty(len(points))
    for start in range(0, len(points), chunk):
        p = points[start : start + chunk]
        outside = np.maximum(np.maximum(lo[None] - p[:, None], p[:, None] - hi[None]), 0.0)  # (n, K, 2)
        lower = np.sum(outside * outside, axis=2)
        nearest = np.argmin(lower, axis=1)  # the run whose box is nearest: its distance bounds from above
        upper = np.min(_run_distances(p, np.arange(len(p)), nearest, ra, rb), axis=1)
        search = lower <= upper[:, None]
        search[np.arange(len(p)), nearest] = True  # so rounding never leaves a point without a run
        which, run = np.nonzero(search)  # grouped by point
        best = np.min(_run_distances(p, which, run, ra, rb), axis=1)
        firsts = np.flatnonzero(np.r_[True, which[1:] != which[:-1]])
        out[start : start + len(p)] = np.minimum.reduceat(best, firsts)
    return np.sqrt(out)


def points_at_arclength(contour, closed, s):
    """Points at arc lengths ``s`` along a polyline from its first point.

    Parameters
    ----------
    contour : ndarray, shape (n, 2)
    closed : bool
        Include the closing segment (s runs around the loop).
    s : ndarray, shape (K,)
        Arc lengths in [0, length].

    Returns
    -------
    ndarray, shape (K, 2)
    """
    pts = np.vstack([contour, contour[:1]]) if closed else np.asarray(contour)
    cum = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
    return np.column_stack([np.interp(s, cum, pts[:, 0]), np.interp(s, cum, pts[:, 1])])


def polyline_length(contour, closed):
    """Arc length of a polyline (closing segment included when ``closed``)."""
    pts = np.vstack([contour, contour[:1]]) if closed else np.asarray(contour)
    return float(np.sum(np.linalg.norm(np.diff(pts, axis=0), axis=1)))


def sample_drawing(contours, closed, spacing=SAMPLE_SPACING):
    """Points every ``spacing`` along every contour (a contour's vertices are not added).

    Returns
    -------
    ndarray, shape (K, 2)
    """
    out = [np.zeros((0, 2))]
    for c, cyc in zip(contours, closed):
        length = polyline_length(c, cyc)
        n = max(1, int(np.ceil(length / spacing)) + (0 if cyc else 1))
        s = np.linspace(0.0, length, n, endpoint=not cyc)
        out.append(points_at_arclength(c, cyc, s))
    return np.vstack(out)


@dataclass
class Reference:
    """A drawing prepared for comparisons: its samples and its segments."""

    samples: np.ndarray
    a: np.ndarray
    b: np.ndarray

    @classmethod
    def of(cls, contours, closed, spacing=SAMPLE_SPACING):
        """Prepare ``contours`` (list of (n_i, 2) arrays) with their ``closed`` flags (S,)."""
        a, b = drawing_segments(contours, closed)[:2]
        return cls(sample_drawing(contours, closed, spacing), a, b)


def compare_drawings(x, y):
    """Symmetric Hausdorff and mean distance between two drawings.

    Each is measured from the samples of one drawing to the other's polylines (exact
    point-to-segment distances), both ways: the Hausdorff distance is the larger of the two
    maxima, the mean distance the average of the two means. Sampling at spacing h makes the
    Hausdorff distance at most h / 2 short.

    Parameters
    ----------
    x, y : Reference

    Returns
    -------
    hausdorff, mean : float
    """
    if not (len(x.a) and len(y.a)):  # an empty drawing (every stroke gone) is infinitely far
        return float("inf"), float("inf")
    dxy = point_segment_distances(x.samples, y.a, y.b)
    dyx = point_segment_distances(y.samples, x.a, x.b)
    return float(max(dxy.max(), dyx.max())), float(0.5 * (dxy.mean() + dyx.mean()))


def _candidate_pairs(a, b):
    """Segment pairs whose x ranges overlap, by a sweep over the segments sorted by x.

    Returns
    -------
    i, j : ndarray of int, shape (K,)
        Segment indices, each pair once.
    """
    lo, hi = np.minimum(a[:, 0], b[:, 0]), np.maximum(a[:, 0], b[:, 0])
    order = np.argsort(lo, kind="stable")
    lo_sorted = lo[order]
    end = np.searchsorted(lo_sorted, hi[order], side="right")
    count = np.maximum(end - np.arange(len(a)) - 1, 0)
    first = np.repeat(np.arange(len(a)), count)
    offset = np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)
    return order[first], order[first + 1 + offset]


def _orient(p, q, r):
    """Sign of the turn p -> q -> r, per row (shapes (K, 2) -> (K,))."""
    return np.sign((q[:, 0] - p[:, 0]) * (r[:, 1] - p[:, 1]) - (q[:, 1] - p[:, 1]) * (r[:, 0] - p[:, 0]))


def crossing_pairs(contours, closed):
    """Segment pairs of a drawing that cross properly (neighbours along a contour excluded).

    Candidates come from a sweep over x (:func:`_candidate_pairs`), are kept when their y
    ranges overlap too, and cross when each segment's ends lie strictly on both sides of the
    other's line. Touching, collinear overlaps and crossings exactly through a vertex are not
    counted.

    Returns
    -------
    ndarray of int, shape (K, 2)
        Contour indices of the two segments of each crossing.
    """
    a, b, contour, index, count = drawing_segments(contours, closed)
    i, j = _candidate_pairs(a, b)
    y_overlap = np.maximum(np.minimum(a[i, 1], b[i, 1]), np.minimum(a[j, 1], b[j, 1])) <= np.minimum(
        np.maximum(a[i, 1], b[i, 1]), np.maximum(a[j, 1], b[j, 1])
    )
    gap = np.abs(index[i] - index[j])
    neighbours = (contour[i] == contour[j]) & ((gap == 1) | (gap == count[i] - 1))
    i, j = i[y_overlap & ~neighbours], j[y_overlap & ~neighbours]
    cross = (_orient(a[i], b[i], a[j]) * _orient(a[i], b[i], b[j]) < 0) & (
        _orient(a[j], b[j], a[i]) * _orient(a[j], b[j], b[i]) < 0
    )
    return np.column_stack([contour[i[cross]], contour[j[cross]]])


def crossing_counts(contours, closed):
    """How many contours cross themselves, and how many pairs of contours cross each other.

    Returns
    -------
    self_crossing, pair_crossing : int
    """
    pairs = crossing_pairs(contours, closed)
    same = pairs[:, 0] == pairs[:, 1]
    between = np.unique(np.sort(pairs[~same], axis=1), axis=0)
    return int(len(np.unique(pairs[same, 0]))), int(len(between))


# --------------------------------------------------------------------------------------------
# The three routes
# --------------------------------------------------------------------------------------------


def fit_t(thin, black, truth):
    """The t in [0, 1] at which the straight blend of the masters is closest to ``truth``.

    Closest in the least-squares sense, point by point (the masters and the instance are
    point-compatible): the 1-D minimisation of ``sum |(1 - t) A + t B - C|^2`` has the closed
    form ``t = <B - A, C - A> / |B - A|^2``, clipped to [0, 1].

    Parameters
    ----------
    thin, black, truth : list of ndarray, each shape (n_i, 2)

    Returns
    -------
    t : float
    residual : float
        Root mean square distance (per point) between the blend at t and the truth.
    """
    A, B, C = (np.vstack(x) for x in (thin, black, truth))
    d = B - A
    dd = float(np.sum(d * d))
    t = 0.5 if dd == 0.0 else float(np.clip(np.sum(d * (C - A)) / dd, 0.0, 1.0))
    return t, float(np.sqrt(np.mean(np.sum(((1 - t) * A + t * B - C) ** 2, axis=1))))


def straight_blend(thin, black, t):
    """The designer's straight blend: ``(1 - t) * thin + t * black``, contour by contour."""
    return [(1.0 - t) * a + t * b for a, b in zip(thin, black)]


def resample_contour(contour, closed, n):
    """``n`` points spaced evenly by arc length from the contour's first point.

    Returns
    -------
    ndarray, shape (n, 2)
    """
    length = polyline_length(contour, closed)
    return points_at_arclength(contour, closed, np.linspace(0.0, length, n, endpoint=not closed))


def baseline_inbetween(thin, black, closed, t):
    """Blender-like in-between: contours paired by index, resampled to one count, blended.

    Each pair is resampled evenly by arc length from its first point to the larger of the two
    point counts, then blended linearly at t.

    Parameters
    ----------
    thin, black : list of ndarray, each shape (n_i, 2) / (m_i, 2)
    closed : array_like of bool, shape (S,)
    t : float

    Returns
    -------
    list of ndarray, each shape (max(n_i, m_i), 2)
    """
    out = []
    for a, b, cyc in zip(thin, black, closed):
        n = max(len(a), len(b))
        out.append((1.0 - t) * resample_contour(a, cyc, n) + t * resample_contour(b, cyc, n))
    return out


def peer_correspondence(thin, black, closed):
    """The tangent-alignment peer's correspondence: contours paired by index, each pair's
    tangent directions aligned along arc length by dynamic programming on the turning function,
    the keys left in place, the best cyclic start (the core's
    :func:`~ballmorph_core.morphs.tangent_dp.tangent_warps`).

    Returns
    -------
    list of (ndarray (n, 2), ndarray (n, 2))
        Per contour, matched points of the Thin and Black contours, on their own edges: every
        point of each with its match on the other (the keys' corners stay corners).
    """
    from ballmorph_core.morphs.tangent_dp import tangent_warps

    warps = tangent_warps(thin, black, closed)
    out = []
    for a, b, cyc, warp in zip(thin, black, closed, warps):
        length_a, length_b = polyline_length(a, cyc), polyline_length(b, cyc)
        u_p, u_q = warp.through(_fractions(a, cyc, length_a), _fractions(b, cyc, length_b))
        if cyc:
            u_p, u_q = u_p[:-1], u_q[:-1]  # the closing knot repeats the first
        out.append((points_at_arclength(a, cyc, u_p * length_a), points_at_arclength(b, cyc, u_q * length_b)))
    return out


def _fractions(contour, closed, length):
    """Arc-length fractions of a contour's points, shape (n,) (1 excluded for a closed one)."""
    steps = np.linalg.norm(np.diff(contour, axis=0), axis=1)
    return np.r_[0.0, np.cumsum(steps)][: len(contour)] / max(length, 1e-300)


def peer_inbetween(matched, t):
    """The peer's in-between at t: every matched pair of points blended straight."""
    return [(1.0 - t) * a + t * b for a, b in matched]


def frame_contours(frame):
    """A core StrokeSet's strokes as 2D contours (x and the canvas' z) and their cyclic flags."""
    pts = frame.positions[:, [0, 2]]
    return [pts[frame.points(i)] for i in range(len(frame))], np.asarray(frame.cyclic, dtype=bool)


NOTE_START = re.compile(r"; (?=lens \d+/\d+: |split at )")  # where the core's notes on one pair begin


def short_reason(reason, detail=20):
    """A pair's ``reason`` in brief: details in parentheses longer than ``detail`` characters
    dropped, and lenses with the same note grouped (``'lens 1, 3 of 4: ...'``).

    The notes are split where a lens or split note begins (:data:`NOTE_START`), not by
    parentheses: the core shortens long details with '...', which can leave them unbalanced.
    """
    notes, lenses = [], {}
    for part in NOTE_START.split(reason):
        head, paren, rest = part.partition(" (")
        if paren and len(rest) <= detail + 1:
            head += f" ({rest}"
        match = re.fullmatch(r"lens (\d+)/(\d+): (.*)", head)
        if match:
            key = (match[2], match[3])
            if key not in lenses:
                notes.append(key)
            lenses.setdefault(key, []).append(match[1])
        else:
            notes.append(head)
    return "; ".join(n if isinstance(n, str) else f"lens {', '.join(lenses[n])} of {n[0]}: {n[1]}" for n in notes)


def describe_pairs(pairs):
    """``result.pairs`` in brief: list of ``(stroke_a, stroke_b, method, notes)`` (None: no partner)."""
    return [(p.stroke_a, p.stroke_b, p.method, short_reason(p.reason)) for p in pairs]


def format_pair(pair):
    """One described pair as text: ``'0->0 circular-ball (split at 4 crossing/overlap pieces)'``."""
    a, b, method, notes = ("-" if x is None else x for x in pair)
    return f"{a}->{b} {method}" + (f" ({notes})" if notes else "")


def _alarm(signum, frame):
    """SIGALRM handler: stop a ``bm.inbetween`` call past its time limit."""
    raise TimeoutError("bm.inbetween took too long")


def ours_inbetween(masters, times, options, timeout):
    """Our in-betweens of one glyph at every time: one ``bm.inbetween`` call.

    Returns
    -------
    frames : list of (list of ndarray, ndarray of bool)
        Per time, the frame's contours (shape (n_i, 2)) and cyclic flags.
    result : InbetweenResult
    """
    keys = [bm.StrokeSet.from_strokes(c, cyclic=masters.closed.copy()) for c in (masters.thin, masters.black)]
    previous = signal.signal(signal.SIGALRM, _alarm)
    signal.setitimer(signal.ITIMER_REAL, timeout)
    try:
        result = bm.inbetween(keys[0], keys[1], times=list(times), **options)
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
    return [frame_contours(f) for f in result.frames], result


# --------------------------------------------------------------------------------------------
# Scoring
# --------------------------------------------------------------------------------------------


@dataclass
class Score:
    """One route's in-between against the truth: distances (thousandths of an em) and crossings."""

    mean: float
    hausdorff: float
    self_crossing: int
    pair_crossing: int

    def crosses_beyond(self, truth):
        """Whether this in-between crosses where the truth does not (more contours crossing
        themselves, or more crossing pairs of contours, than the truth has)."""
        return self.self_crossing > truth[0] or self.pair_crossing > truth[1]


@dataclass
class WeightResult:
    """One glyph at one weight: the fitted t, the truth's crossings and every route's score."""

    weight: int
    t: float
    residual: float
    truth_crossings: tuple
    scores: dict


@dataclass
class GlyphResult:
    """Everything measured on one glyph of one family (``error`` set when it was not scored)."""

    family: str
    char: str
    points: int = 0
    contours: int = 0
    weights: list = field(default_factory=list)
    pairs: list = field(default_factory=list)
    messages: list = field(default_factory=list)
    error: str = ""
    seconds: dict = field(default_factory=dict)
    figure: dict = field(default_factory=dict)

    def mean_of(self, route):
        """Mean distance of a route averaged over the weights."""
        return float(np.mean([w.scores[route].mean for w in self.weights]))


def score_route(contours, closed, truth_ref):
    """Score one in-between (contours and cyclic flags) against the prepared truth."""
    h, m = compare_drawings(Reference.of(contours, closed), truth_ref)
    return Score(m, h, *crossing_counts(contours, closed))


def score_glyph(task):
    """Benchmark one glyph of one family: read, fit t, run the three routes, score them.

    Parameters
    ----------
    task : tuple
        ``(family, path, char, options, timeout)``; options go to ``bm.inbetween``.

    Returns
    -------
    GlyphResult
        With ``error`` set (and nothing scored) when the glyph cannot be read or ours raised.
    """
    family, path, char, options, timeout = task
    out = GlyphResult(family, char)
    clock = time.perf_counter()
    try:
        masters = load_glyph(open_font(family, path), char)
    except GlyphError as exc:
        out.error = f"{type(exc).__name__}: {exc}"
        return out
    out.points, out.contours = sum(len(c) for c in masters.thin), len(masters.thin)
    weights = list(masters.truths)
    fits = {w: fit_t(masters.thin, masters.black, masters.truths[w]) for w in weights}
    out.seconds["read"] = time.perf_counter() - clock
    clock = time.perf_counter()
    try:
        frames, result = ours_inbetween(masters, [fits[w][0] for w in weights], options, timeout)
    except Exception as exc:  # whatever the core raises (a bug included) is reported, the run goes on
        out.error = f"bm.inbetween raised {type(exc).__name__}: {exc}"
        return out
    out.seconds["ours"] = time.perf_counter() - clock
    out.pairs, out.messages = describe_pairs(result.pairs), [f"{m.level}: {m.text}" for m in result.messages]
    clock = time.perf_counter()
    matched = peer_correspondence(masters.thin, masters.black, masters.closed)
    out.seconds["peer"] = time.perf_counter() - clock
    clock = time.perf_counter()
    figure_weight = min(weights, key=lambda w: abs(w - FIGURE_WEIGHT))
    for w, frame in zip(weights, frames):
        out.weights.append(score_weight(masters, w, fits[w], frame, matched, out.figure, figure_weight))
    out.seconds["score"] = time.perf_counter() - clock
    return out


def score_weight(masters, weight, fit, ours, matched, figure, figure_weight=FIGURE_WEIGHT):
    """Score the four routes at one weight; keep the drawings for the figure at ``figure_weight``
    (``matched``: the peer's correspondence, :func:`peer_correspondence`)."""
    t, residual = fit
    truth, closed = masters.truths[weight], masters.closed
    drawings = {
        "ours": ours,
        "peer": (peer_inbetween(matched, t), closed),
        "baseline": (baseline_inbetween(masters.thin, masters.black, closed, t), closed),
        "floor": (straight_blend(masters.thin, masters.black, t), closed),
    }
    truth_ref = Reference.of(truth, closed)
    scores = {route: score_route(*drawings[route], truth_ref) for route in ROADS}
    if weight == figure_weight:
        figure.update(drawings, truth=(truth, closed), thin=(masters.thin, closed), black=(masters.black, closed))
    return WeightResult(weight, t, residual, crossing_counts(truth, closed), scores)


def run_benchmark(fonts, glyphs, options, jobs, timeout):
    """Score every glyph of every family, on ``jobs`` processes.

    Parameters
    ----------
    fonts : list of (str, str)
        Family name and font path.
    glyphs : str
        The characters.

    Returns
    -------
    list of GlyphResult
        In family then glyph order.
    """
    tasks = [(family, path, char, options, timeout) for family, path in fonts for char in glyphs]
    results = []
    step = max(1, len(tasks) // 10)
    if jobs == 1:
        mapped = map(score_glyph, tasks)
    else:
        pool = ProcessPoolExecutor(max_workers=jobs)
        mapped = pool.map(score_glyph, tasks, chunksize=1)
    for k, res in enumerate(mapped, 1):
        results.append(res)
        if res.error:
            print(f"realdata: {res.family} {res.char!r}: {res.error}", file=sys.stderr)
        if k % step == 0 or k == len(tasks):
            print(f"realdata: {k}/{len(tasks)} glyphs", file=sys.stderr)
    if jobs != 1:
        pool.shutdown()
    return results


# --------------------------------------------------------------------------------------------
# Summary
# --------------------------------------------------------------------------------------------


@dataclass
class FamilySummary:
    """Medians and counts over one family's (glyph, weight) in-betweens.

    Attributes
    ----------
    median_mean, median_hausdorff : dict
        Road -> median over (glyph, weight) (thousandths of an em).
    ratio, ratio_hausdorff : dict
        'ours' / 'baseline' -> its median divided by the floor's median.
    wins : int
        Glyphs on which ours has the smaller mean distance (averaged over the weights).
    crossings : dict
        Road -> in-betweens crossing where the truth does not.
    """

    family: str
    glyphs: int
    errors: int
    inbetweens: int
    median_mean: dict
    median_hausdorff: dict
    ratio: dict
    ratio_hausdorff: dict
    wins: int
    crossings: dict


def _ratios(medians):
    """Each of ours' and the baseline's medians divided by the floor's."""
    floor = medians["floor"]
    return {route: (medians[route] / floor if floor > 0 else float("inf")) for route in ROADS[:-1]}


def summarise(family, results):
    """The :class:`FamilySummary` of one family's glyph results (errors counted, not scored)."""
    scored = [r for r in results if not r.error]
    rows = [w for r in scored for w in r.weights]

    def median(route, attr):
        return float(np.median([getattr(w.scores[route], attr) for w in rows])) if rows else float("nan")

    median_mean = {route: median(route, "mean") for route in ROADS}
    median_hausdorff = {route: median(route, "hausdorff") for route in ROADS}
    crossings = {route: sum(w.scores[route].crosses_beyond(w.truth_crossings) for w in rows) for route in ROADS}
    wins = sum(r.mean_of("ours") < r.mean_of("baseline") for r in scored)
    return FamilySummary(
        family,
        len(scored),
        len(results) - len(scored),
        len(rows),
        median_mean,
        median_hausdorff,
        _ratios(median_mean),
        _ratios(median_hausdorff),
        wins,
        crossings,
    )


def hausdorff_goal(floor):
    """Issue 38's bound on ours' median Hausdorff for a family whose floor's is ``floor``."""
    return max(GOAL_RATIO * floor, floor + GOAL_MARGIN)


def goals(summaries):
    """The goals of issues 11 and 38: list of (goal, measured, passed)."""
    worst = max(s.ratio["ours"] for s in summaries)
    beaten = [s.family for s in summaries if s.median_mean["ours"] >= s.median_mean["baseline"]]
    crossing = sum(s.crossings["ours"] for s in summaries)
    return [
        (
            "median mean distance at most 1.5x the floor's, in every family",
            "worst family " + f"{worst:.2f}x",
            worst <= 1.5,
        ),
        (
            "median mean distance below the baseline's, in every family",
            "not below in: " + (", ".join(beaten) if beaten else "none"),
            not beaten,
        ),
        ("no in-between crossing where the truth does not", f"{crossing} in-betweens", crossing == 0),
    ] + [_hausdorff_goal(s) for s in summaries]


def _hausdorff_goal(s):
    """Issue 38's goal for one family: (goal, measured, passed)."""
    h = s.median_hausdorff
    bound = hausdorff_goal(h["floor"])
    ok = h["ours"] <= bound and h["ours"] < h["baseline"] and h["ours"] <= h["peer"]
    return (
        f"{s.family}: median Hausdorff at most max({GOAL_RATIO:g}x floor, floor + {GOAL_MARGIN:g}),"
        " below the baseline's, no worse than the peer's",
        f"ours {_fmt(h['ours'])} (goal {_fmt(bound)}; peer {_fmt(h['peer'])}, baseline {_fmt(h['baseline'])},"
        f" floor {_fmt(h['floor'])})",
        ok,
    )


# --------------------------------------------------------------------------------------------
# Report
# --------------------------------------------------------------------------------------------


def _fmt(x):
    """A number with two decimals ('n/a' when not finite)."""
    return f"{x:.2f}" if np.isfinite(x) else "n/a"


def _road_cells(values):
    """'ours / baseline / floor' values of a route -> number dict."""
    return " / ".join(_fmt(values[route]) for route in ROADS)


def family_table(summaries):
    """Markdown table: one row per family."""
    lines = [
        "| family | glyphs | in-betweens | mean ‰ em (ours / peer / baseline / floor)"
        " | Hausdorff ‰ em (ours / peer / baseline / floor) | ours / floor | baseline / floor"
        " | Hausdorff ours / floor"
        " | glyphs ours beats baseline"
        " | crossing (ours / peer / baseline / floor) | not scored |",
        "|---|---:|---:|---|---|---:|---:|---:|---:|---|---:|",
    ]
    for s in summaries:
        lines.append(
            f"| {s.family} | {s.glyphs} | {s.inbetweens} | {_road_cells(s.median_mean)} | "
            f"{_road_cells(s.median_hausdorff)} | {_fmt(s.ratio['ours'])}x | {_fmt(s.ratio['baseline'])}x | "
            f"{_fmt(s.ratio_hausdorff['ours'])}x | {s.wins} / {s.glyphs} | "
            f"{' / '.join(str(s.crossings[r]) for r in ROADS)} | {s.errors} |"
        )
    return lines


def worst_table(results, count=10):
    """Markdown table of the ``count`` glyphs with the largest mean distance for ours."""
    scored = sorted((r for r in results if not r.error), key=lambda r: -r.mean_of("ours"))[:count]
    lines = [
        "| family | glyph | points | mean ‰ em (ours / peer / baseline / floor)"
        " | Hausdorff ours ‰ em (max over weights)"
        " | crossing weights | stroke pairs: morph used |",
        "|---|---|---:|---|---:|---|---|",
    ]
    for r in scored:
        means = {route: r.mean_of(route) for route in ROADS}
        crossing = [str(w.weight) for w in r.weights if w.scores["ours"].crosses_beyond(w.truth_crossings)]
        hausdorff = max(w.scores["ours"].hausdorff for w in r.weights)
        lines.append(
            f"| {r.family} | `{r.char}` | {r.points} | {_road_cells(means)} | {hausdorff:.1f} | "
            f"{', '.join(crossing) or '-'} | {'<br>'.join(map(format_pair, r.pairs))} |"
        )
    return lines


def crossing_lines(results, route="ours"):
    """Markdown list: the glyphs (and weights) whose in-betweens by ``route`` cross where the truth does not."""
    lines = []
    for r in results:
        weights = [str(w.weight) for w in r.weights if w.scores[route].crosses_beyond(w.truth_crossings)]
        if weights:
            w = next(w for w in r.weights if w.scores[route].crosses_beyond(w.truth_crossings))
            counts = f"{w.scores[route].self_crossing} self / {w.scores[route].pair_crossing} pairs"
            truth = f"{w.truth_crossings[0]} / {w.truth_crossings[1]}"
            lines.append(f"- {r.family} `{r.char}` at {', '.join(weights)} (at {w.weight}: {counts}; truth {truth})")
    return lines or ["None."]


def morph_table(results):
    """Markdown table: how many stroke pairs used each morph (``result.pairs``), per family."""
    families = list(dict.fromkeys(r.family for r in results))
    counts = {}
    for r in results:
        for _, _, method, _ in r.pairs:
            counts.setdefault(method, dict.fromkeys(families, 0))[r.family] += 1
    lines = ["| morph used | " + " | ".join(families) + " |", "|---|" + "---:|" * len(families)]
    for method, per in sorted(counts.items(), key=lambda kv: -sum(kv[1].values())):
        lines.append(f"| {method} | " + " | ".join(str(per[f]) for f in families) + " |")
    return lines


def timing_lines(results, wall, jobs, load):
    """Markdown lines: wall time (and the machine's load average when the run began), and per
    family the summed stage times."""
    cpu = platform.processor() or platform.machine()
    lines = [
        f"Wall time {wall:.0f} s on {jobs} process(es) ({os.cpu_count()} CPUs, {cpu}; load average {load:.1f}"
        " when the run began: the machine may be shared).",
        "",
    ]
    lines += [
        "| family | read + flatten (s) | bm.inbetween (s) | slowest glyph (s) | scoring (s) |",
        "|---|---:|---:|---:|---:|",
    ]
    for family in dict.fromkeys(r.family for r in results):
        rs = [r for r in results if r.family == family]
        total = {k: sum(r.seconds.get(k, 0.0) for r in rs) for k in ("read", "ours", "score")}
        slowest = max(rs, key=lambda r: r.seconds.get("ours", 0.0))
        lines.append(
            f"| {family} | {total['read']:.1f} | {total['ours']:.1f} | "
            f"{slowest.seconds.get('ours', 0.0):.2f} (`{slowest.char}`) | {total['score']:.1f} |"
        )
    return lines


def error_lines(results):
    """Markdown list of the glyphs that were reported instead of scored."""
    errors = [r for r in results if r.error]
    if not errors:
        return ["Every glyph was read and in-betweened."]
    return [f"- {r.family} `{r.char}`: {r.error}" for r in errors]


def fit_lines(results):
    """Markdown line: per family, the fitted t per weight (median over glyphs) and the fit's residual."""
    parts = []
    for family in dict.fromkeys(r.family for r in results):
        rows = [w for r in results if r.family == family for w in r.weights]
        cells = []
        for weight in sorted({w.weight for w in rows}):
            ws = [w for w in rows if w.weight == weight]
            t, residual = np.median([w.t for w in ws]), np.median([w.residual for w in ws])
            cells.append(f"{weight:g}: t = {t:.3f} ({residual:.2f})")
        parts.append(f"{family}: " + ", ".join(cells))
    return ["Fitted t, median over glyphs (and the median RMS point residual, ‰ em): " + "; ".join(parts) + "."]


METHOD_TEXT = f"""\
- **Drawings.** A glyph is a drawing; each of its contours is a closed stroke, in the font's
  contour order and from the font's start point (components decomposed). TrueType quadratic
  strings are split at their implied on-curve points. Each segment gets a fixed number of
  points (its end included, its start not), the same at every location, so the masters and
  instances flatten to point-compatible polylines. That number is the segment's control
  polygon length averaged over the two keys, divided by {POINT_SPACING:g} ‰ em and rounded (at
  least 1 per line, 2 per quadratic): the points are about evenly spaced, as a drawn stroke's
  are, a few hundred per glyph (see the table of the worst ones). A constant count per segment
  (tried first: 8 per curve, 4 per line) put 4 points on a 700 ‰ em stem and 8 on a 20 ‰ em
  curve, nothing like a drawing: the core's spline then spiked corners ('A': Hausdorff over
  200 ‰ em) and the baseline's resampling cut them. A point repeating its predecessor at every
  location is dropped. Coordinates are in thousandths of an em (font
  units x 1000 / unitsPerEm).
- **Keys and truth.** Inter (variable): the two ends of the weight axis (Thin 100 and Black
  900) are the keys; the truth is the instance at weight w in {", ".join(map(str, WEIGHTS))}
  (fontTools glyph set at that location; no other axis in these fonts). The static families
  ({", ".join(f for f, *_ in STATIC_FAMILIES)}; Debian packages
  {", ".join(p for _, p, *_ in STATIC_FAMILIES)}) ship one file per weight of one interpolable
  design: the lightest and heaviest (OS/2 weight class) are the keys, every other one a truth.
  Their contours are matched to the next lighter instance's: contour order (the closest
  contour whose segment kinds match) and start point (the closest cyclic rotation of its
  on-curve points whose segment kinds match); a glyph whose instances still differ (TrueType
  instances quadratic-converted each on its own) is listed as not scored. Inter's masters are
  Thin, Regular and Black, so the designer's path bends at Regular: per glyph and weight, t is
  the least-squares fit of the
  straight blend ``(1 - t) Thin + t Black`` to the instance, point by point (closed form of the
  1-D search, clipped to [0, 1]), and every route is evaluated at that t.
- **Roads.** *ours*: ``bm.inbetween(thin, black, times=[the five t])`` (one call per glyph,
  options as listed above). *baseline* (Blender-like): contours paired by index, each contour
  of both keys resampled evenly by arc length from its first point to the larger point count,
  blended linearly. (Blender's own Interpolate blends point by point when the counts agree:
  on these point-compatible keys that would be the floor, so the baseline stands for keys whose
  points do not correspond, as hand-drawn ones.) *peer*: contours paired by index, their
  tangent directions aligned along arc length (dynamic programming on the turning function,
  the keys left in place, the best cyclic start: the core's ``tangent_warps``), every point of
  both keys with its match, straight paths. *floor*: the designer's straight blend.
- **Distances.** Between drawings (the union of their contour polylines): samples every
  {SAMPLE_SPACING:g} ‰ em along each drawing, exact distances to the other's nearest segment
  (numpy; runs of {BLOCK} segments searched only where their bounding box can hold the nearest).
  Hausdorff: the larger of the two directed maxima (at most {SAMPLE_SPACING / 2:g} ‰ em short).
  Mean distance: the average of the two directed means. Per family, medians over every
  (glyph, weight); *ours / floor* is the ratio of the medians. A glyph counts as a win when
  ours' mean distance, averaged over the five weights, is below the baseline's.
- **Goals.** 1: in every family, ours' median mean distance at most 1.5 times the floor's.
  2: in every family, ours' median mean distance below the baseline's. 3: no in-between of
  ours crossing where the truth does not (below). Then per family (issue 38): ours' median
  Hausdorff at most max({GOAL_RATIO:g} x floor, floor + {GOAL_MARGIN:g}), below the baseline's and
  no worse than the peer's.
- **Crossings.** Segments that cross properly (each one's ends strictly on both sides of the
  other; neighbours along a contour excluded; candidates from a sweep over x). An in-between
  counts as crossing when more of its contours cross themselves, or more pairs of its contours
  cross each other, than in the truth (Inter's variable masters keep overlapping contours, so
  the truth itself often has crossing pairs).
- **Robustness.** A glyph whose contours differ between locations, that is not in the font,
  or on which ``bm.inbetween`` raises or runs past the time limit is listed below and left
  out of the medians."""


def report(summaries, results, args, wall, load):
    """The markdown report (docs/realdata.md)."""
    date = datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d %H:%M UTC")
    options = ", ".join(f"{k}={v!r}" for k, v in core_options(args).items()) or "default options"
    glyphs = "".join(dict.fromkeys(r.char for r in results))
    lines = [
        "# Real-data benchmark: glyph outlines against the designers' own instances (issues 11, 38)",
        "",
        f"`{command_line(args)}` on {date}, core at commit {git_commit()} (its last change);"
        f" `bm.inbetween` with {options}.",
        f"Glyphs ({len(glyphs)} per family): `{glyphs}`.",
        "",
        "## Goals",
        "",
        "| goal | measured | |",
        "|---|---|---|",
    ]
    lines += [f"| {g} | {m} | {'PASS' if ok else 'FAIL'} |" for g, m, ok in goals(summaries)]
    lines += ["", "## Per family", "", *family_table(summaries), ""]
    lines += [
        "Medians over every (glyph, weight) in-between, in thousandths of an em. *crossing*: in-betweens"
        " whose contours cross where the font's instance does not. " + fit_lines(results)[0],
        "",
        "## The 10 worst glyphs for ours",
        "",
        "Ranked by ours' mean distance averaged over the five weights; the morphs are those of"
        " `result.pairs` (stroke of the Thin key -> stroke of the Black key).",
        "",
        *worst_table(results),
        "",
        "## In-betweens of ours that cross where the truth does not",
        "",
        "Contours crossing themselves / pairs of contours crossing each other, against the truth's.",
        "",
        *crossing_lines(results),
        "",
        "## Morphs the stroke pairs used",
        "",
        *morph_table(results),
        "",
        f"## Keys, truth, ours and baseline at weight {FIGURE_WEIGHT}",
        "",
        "![glyphs](realdata.png)",
        "",
        "## Method",
        "",
        METHOD_TEXT,
        "",
        "## Not scored",
        "",
        *error_lines(results),
        "",
        "## Timings",
        "",
        *timing_lines(results, wall, args.jobs, load),
        "",
    ]
    return "\n".join(lines)


def core_options(args):
    """The options passed to ``bm.inbetween`` (only those given on the command line)."""
    return {k: getattr(args, k) for k in ("method", "carrier") if getattr(args, k) is not None}


def command_line(args):
    """The command as run (``make realdata`` runs ``tools/realdata.py --write docs/realdata.md``)."""
    return " ".join(["tools/realdata.py", *args.argv])


def git_commit():
    """The last commit that changed ``ballmorph_core/`` (short hash, '+ local changes' when the
    core differs from it), or 'unknown' outside a git checkout."""

    def git(*args):
        out = subprocess.run(["git", *args, "--", "ballmorph_core"], cwd=ROOT, capture_output=True, text=True)
        return out.stdout.strip() if out.returncode == 0 else None

    try:
        commit, status = git("log", "-1", "--format=%h"), git("status", "--porcelain")
    except OSError:
        return "unknown"
    return (commit or "unknown") + (" + local changes" if status else "")


# --------------------------------------------------------------------------------------------
# Figure
# --------------------------------------------------------------------------------------------


def figure_glyphs(results, count=6):
    """The glyphs drawn: :data:`FIGURE_GLYPHS` that were run, then ours' worst, up to ``count``."""
    scored = [r for r in results if not r.error and r.figure]
    chosen = [r for fam, ch in FIGURE_GLYPHS for r in scored if (r.family, r.char) == (fam, ch)]
    for r in sorted(scored, key=lambda r: -r.mean_of("ours")):
        if len(chosen) >= count:
            break
        if r.char not in {c.char for c in chosen}:  # one family per character: they look alike
            chosen.append(r)
    return chosen


STYLES = {
    "thin": dict(color="0.65", lw=0.8, ls="--", label="keys (Thin, Black)"),
    "black": dict(color="0.65", lw=0.8, ls="--", label=None),
    "truth": dict(color="black", lw=2.2, label="truth (instance)"),
    "baseline": dict(color="tab:orange", lw=1.0, label="baseline"),
    "ours": dict(color="tab:blue", lw=1.2, label="ours"),
}


def draw_figure(results, path):
    """Write the figure: a few glyphs with keys, truth, ours and baseline overlaid at FIGURE_WEIGHT."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    chosen = figure_glyphs(results)
    if not chosen:
        return False
    cols = min(3, len(chosen))
    rows = -(-len(chosen) // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 4.6 * rows + 0.4), squeeze=False)
    for ax in axes.flat:
        ax.axis("off")
    for ax, r in zip(axes.flat, chosen):
        for name, style in STYLES.items():
            contours, closed = r.figure[name]
            for k, (c, cyc) in enumerate(zip(contours, closed)):
                pts = np.vstack([c, c[:1]]) if cyc else c
                ax.plot(pts[:, 0], pts[:, 1], **{**style, "label": style["label"] if k == 0 else None})
        w = next(w for w in r.weights if w.weight == FIGURE_WEIGHT)
        means = ", ".join(f"{route} {w.scores[route].mean:.1f}" for route in ROADS)
        ax.set_title(
            f"{r.family} '{r.char}', weight {FIGURE_WEIGHT} (t = {w.t:.2f})\nmean distance ‰ em: {means}", fontsize=9
        )
        ax.set_aspect("equal")
    handles, labels = axes.flat[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=9, frameon=False)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return True


# --------------------------------------------------------------------------------------------
# Command line
# --------------------------------------------------------------------------------------------


def find_fonts(font_dir, families=None):
    """The families' font files: Inter's variable fonts in ``font_dir``, the static families'
    instances where their Debian packages put them; or stop saying how to install them.

    Parameters
    ----------
    font_dir : str
    families : collection of str, optional
        The families to run (default: every one).

    Returns
    -------
    list of (str, str or tuple of str)
        Family name and path (a variable font) or paths (static instances, sorted).
    """
    held_out = {f for f, *_ in HELD_OUT_FAMILIES}
    wanted = (lambda name: name not in held_out) if families is None else (lambda name: name in families)
    paths = [(family, os.path.join(font_dir, name)) for family, name in FAMILIES if wanted(family)]
    missing = [os.path.basename(p) for _, p in paths if not os.path.isfile(p)]
    if missing:
        raise SystemExit(
            f"realdata: the Inter variable fonts are not in {font_dir} (missing {', '.join(missing)}).\n"
            f"Install them with `sudo apt-get install {FONT_PACKAGE}` (Debian, Ubuntu; `make realdata` does it"
            " when run as root), or pass --font-dir (or set INTER_FONT_DIR) to a directory holding "
            + ", ".join(name for _, name in FAMILIES)
            + " (https://github.com/rsms/inter, the variable fonts)."
        )
    absent = []
    for family, package, directory, pattern in STATIC_FAMILIES + HELD_OUT_FAMILIES:
        if not wanted(family):
            continue
        found = tuple(sorted(glob.glob(os.path.join(directory, pattern))))
        if len(found) < 3:
            absent.append(package)
        paths.append((family, found))
    if absent:
        raise SystemExit(
            f"realdata: static font families missing: install them with `sudo apt-get install {' '.join(absent)}`"
            " (Debian, Ubuntu; `make realdata` does it when run as root), or leave them out with --families."
        )
    return paths


def family_list(text):
    """An argparse type: comma-separated family names, each one this tool knows."""
    known = [f for f, _ in FAMILIES] + [f for f, *_ in STATIC_FAMILIES + HELD_OUT_FAMILIES]
    names = [n.strip() for n in text.split(",") if n.strip()]
    unknown = [n for n in names if n not in known]
    if not names or unknown:
        raise argparse.ArgumentTypeError(f"unknown families {unknown or text!r}; choose from {', '.join(known)}")
    return tuple(names)


def vocabulary(values, what):
    """An argparse type: one of ``values``, named in any case with ``-`` or ``_`` (the core's spelling returned)."""

    def parse(text):
        key = text.strip().lower().replace("_", "-")
        for v in values:
            if v.lower().replace("_", "-") == key:
                return v
        raise argparse.ArgumentTypeError(f"unknown {what} {text!r}; choose from {', '.join(values)}")

    return parse


def glyph_list(text):
    """An argparse type: the characters to benchmark (no whitespace; repeats dropped)."""
    if not text or any(ch.isspace() for ch in text):
        raise argparse.ArgumentTypeError(f"expected characters without spaces, e.g. 'ag&', got {text!r}")
    return "".join(dict.fromkeys(text))


def positive(kind):
    """An argparse type: a positive number of type ``kind``."""

    def parse(text):
        try:
            value = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected a positive {kind.__name__}, got {text!r}") from None
        if not value > 0:
            raise argparse.ArgumentTypeError(f"expected a positive {kind.__name__}, got {text!r}")
        return value

    return parse


def _escaped(text):
    """``text`` for an argparse help string (which %-formats it)."""
    return text.replace("%", "%%")


def parse_args(argv):
    """The command line (see the module docstring)."""
    parser = argparse.ArgumentParser(
        description="Real-data benchmark: in-betweens of Inter's glyph outlines against the font's own instances.",
        epilog="examples: tools/realdata.py --write docs/realdata.md (make realdata); tools/realdata.py --quick;"
        " tools/realdata.py --glyphs 'ag&' --method linear-ball --carrier none",
    )
    chosen = parser.add_mutually_exclusive_group()
    chosen.add_argument("--quick", action="store_true", help=f"a dozen glyphs ({_escaped(QUICK_GLYPHS)})")
    chosen.add_argument("--glyphs", type=glyph_list, help=f"the characters to run (default {_escaped(GLYPHS)})")
    parser.add_argument(
        "--method", type=vocabulary(bm.METHODS, "method"), help="bm.inbetween's method (default its own)"
    )
    parser.add_argument(
        "--carrier", type=vocabulary(bm.CARRIERS, "carrier"), help="bm.inbetween's carrier (default its own)"
    )
    parser.add_argument(
        "--write", metavar="PATH", help="write the markdown report there (and the figure beside it, .png)"
    )
    parser.add_argument(
        "--font-dir", default=FONT_DIR, help=f"directory of the Inter variable fonts (default {FONT_DIR})"
    )
    parser.add_argument(
        "--families", type=family_list, help="comma-separated families to run (default: every one not held out)"
    )
    parser.add_argument(
        "--held-out",
        action="store_true",
        help="run the held-out families instead (" + ", ".join(f for f, *_ in HELD_OUT_FAMILIES) + ")",
    )
    parser.add_argument("--jobs", type=positive(int), default=os.cpu_count() or 1, help="processes (default: CPUs)")
    parser.add_argument(
        "--timeout", type=positive(float), default=DEFAULT_TIMEOUT, help="seconds per glyph for bm.inbetween"
    )
    args = parser.parse_args(argv)
    args.argv = list(argv)
    if args.held_out:
        args.families = tuple(f for f, *_ in HELD_OUT_FAMILIES)
    args.glyph_chars = QUICK_GLYPHS if args.quick else (args.glyphs or GLYPHS)
    return args


def main(argv=None):
    """Run the benchmark; print the report or write it (with its figure)."""
    args = parse_args(sys.argv[1:] if argv is None else argv)
    fonts = find_fonts(args.font_dir, args.families)
    load, start = os.getloadavg()[0], time.perf_counter()
    results = run_benchmark(fonts, args.glyph_chars, core_options(args), args.jobs, args.timeout)
    wall = time.perf_counter() - start
    summaries = [summarise(family, [r for r in results if r.family == family]) for family, _ in fonts]
    if not any(s.glyphs for s in summaries):
        print("realdata: no glyph could be scored", file=sys.stderr)
        return 1
    text = report(summaries, results, args, wall, load)
    if args.write:
        os.makedirs(os.path.dirname(os.path.abspath(args.write)), exist_ok=True)
        with open(args.write, "w", encoding="utf-8") as f:
            f.write(text)
        png = os.path.splitext(args.write)[0] + ".png"
        if draw_figure(results, png):
            print(f"realdata: wrote {args.write} and {png}", file=sys.stderr)
    else:
        print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
