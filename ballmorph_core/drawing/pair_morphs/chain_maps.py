"""Step 9 of the stroke-pair pipeline, *map chains*: the ball-maps of every chain of every pair,
in batches of whole pairs (:func:`map_chains`), and where their samples, and any other morph
of a chain, lie on the pairs' whole curves (:func:`ball_rows`, :func:`placed`: the end gaps of
:mod:`.ends` undone)."""

from dataclasses import dataclass

import numpy as np

from ... import tolerances as tol
from ...ballmap.correspondence import map_batch
from ...ballmap.onemap import OneWayMap
from ...geometry.ragged import Ragged
from ..frames.layout import BallRows, Segment

__all__ = ["BALLMAP_BATCH_POINTS", "ChainMaps", "map_chains", "ball_rows", "placed"]

#: The ball-maps of a drawing run in batches of about this many input points (whole pairs: each
#: pair's chains share one tolerance): one batch for a typical drawing, several for a huge one,
#: which bounds the ball-map's temporaries.
BALLMAP_BATCH_POINTS = 60_000


@dataclass
class ChainMaps:
    """The ball-maps of every chain that was mapped (step 9), as arrays.

    Attributes
    ----------
    samples : OneWayMap
        Their samples, ``chain`` the chain's index in the Chains.
    lengths : ndarray, shape (H, 2)
        Length of each chain's dense P and Q (0 where not mapped).
    reports : list of CompatibilityReport or None
    """

    samples: OneWayMap
    lengths: np.ndarray
    reports: list

    def held(self):
        """The chains whose ball-map holds (mapped and b-compatible), shape (H,) of bool."""
        return np.array([r is not None and not r.violations for r in self.reports], dtype=bool)

    def keeping(self, keep):
        """The maps of the chains ``keep`` (shape (H,) of bool) marks, numbered as
        :meth:`.crossings.Chains.keeping` numbers them (a ChainMaps)."""
        renumber = np.cumsum(keep) - 1
        samples = self.samples.take(keep[self.samples.chain])
        samples.chain = renumber[samples.chain]
        return ChainMaps(samples, self.lengths[keep], [r for r, k in zip(self.reports, keep) if k])


def map_chains(chains, spacing, eps):
    """Step 9: the ball-maps of every chain but the static overlaps, in batches of whole pairs."""
    mapped = np.flatnonzero(~chains.static)
    sizes = [len(chains.setups[k].P) + len(chains.setups[k].Q) for k in mapped]
    starts = np.cumsum([0] + sizes)[:-1] // BALLMAP_BATCH_POINTS
    pair = chains.pair[mapped]
    first_of_pair = np.r_[True, pair[1:] != pair[:-1]]
    batch_of = np.maximum.accumulate(np.where(first_of_pair, starts, 0)) if len(mapped) else starts
    parts, lengths, reports = [], np.zeros((len(chains), 2)), [None] * len(chains)
    for number in np.unique(batch_of):
        members = mapped[batch_of == number]
        samples, lengths[members], batch_reports = _mapped_batch(chains, members, spacing, eps)
        samples.chain = members[samples.chain]
        parts.append(samples)
        for i, report in zip(members, batch_reports):
            reports[i] = report
    return ChainMaps(OneWayMap.concatenate(parts) if parts else OneWayMap.empty(), lengths, reports)


def _mapped_batch(chains, members, spacing, eps):
    """What :func:`map_chains` keeps of the ball-maps of chains ``members``: their samples
    (OneWayMap), the lengths of their dense curves (shape (K, 2)) and their reports. The rest of
    the batch (its dense curves and their tables, tens of MiB for a big drawing) goes before the
    next batch is made."""
    owners = chains.pair[members]
    batch = map_batch([chains.setups[i] for i in members], spacing[owners], "symmetric", eps[owners])
    return batch.samples, np.c_[batch.sides_p.rg.length, batch.sides_q.rg.length], batch.reports


def ball_rows(chains, maps, index, good, ends):
    """The ball route's samples (BallRows): the chains whose ball-maps hold, and the overlaps
    (ranges on the pairs' whole curves, offsets undoing the end gaps' displacement)."""
    rows = maps.samples.take(good[maps.samples.chain])
    statics = np.flatnonzero(chains.static)
    overlap = Ragged.from_list([chains.setups[k].P for k in statics], False)
    chain = np.r_[rows.chain, statics[overlap.owner]].astype(np.int64)
    order = np.argsort(chain, kind="stable")
    # An overlap stays where it is: its fractions along the piece are its own.
    along = overlap.s / np.maximum(overlap.length, tol.TINY)[overlap.owner]
    lengths = np.maximum(maps.lengths[rows.chain], tol.TINY)
    u_p, u_q = np.r_[rows.s_src / lengths[:, 0], along], np.r_[rows.s_dst / lengths[:, 1], along]
    p, m, q = (np.concatenate([getattr(rows, f), overlap.pts]) for f in ("src", "m", "dst"))
    chain, kept = chain[order], np.flatnonzero(good | chains.static)
    first = np.searchsorted(chains.pair, chains.pair[kept])
    u_p, offset, on_whole = _on_whole(ends, chains.pair, chains.range_p, u_p[order], chain)
    owner = chains.pair[kept]
    return BallRows(
        pair=index[owner],
        order=kept - first,
        sizes=np.bincount(chain, minlength=len(chains))[kept],
        range_p=on_whole[kept],
        range_q=ends.on_q(owner[:, None], chains.range_q[kept]),
        static=chains.static[kept],
        u_p=u_p,
        u_q=u_q[order],
        p=np.take(p, order, axis=0),
        m=np.take(m, order, axis=0),
        q=np.take(q, order, axis=0),
        offset=offset,
    )


def _on_whole(ends, pair, range_p, u_p, chain):
    """Samples at fractions ``u_p`` of chains at ``range_p`` on the common parts, placed on the
    whole registered curves: their fractions of the chains' ranges there, the offsets undoing
    the displacement, and those ranges.

    Parameters
    ----------
    ends : Ends
    pair : ndarray of int, shape (G,)
        Each chain's pair.
    range_p : ndarray, shape (G, 2)
        Each chain's range on its pair's common part.
    u_p : ndarray, shape (K,)
    chain : ndarray of int, shape (K,)
        Each sample's chain.

    Returns
    -------
    u_p, offset, range_p : ndarrays, shapes (K,), (K, 2), (G, 2)
    """
    s = range_p[chain, 0] + u_p * (range_p[chain, 1] - range_p[chain, 0])
    ranges = ends.on_p(pair[:, None], range_p)
    at, offset = ends.place(pair[chain], s)
    start = ranges[chain, 0]
    span = ranges[chain, 1] - start
    u = np.divide(at - start, span, out=u_p.astype(np.float64), where=np.abs(span) > 0)
    return u, offset, ranges


def placed(ends, index, pairs, morphs, orders, ranges):
    """The Segments of morphs of chains whose pieces lie at ``ranges`` along the common parts:
    placed on the whole curves, their samples' displacement undone (their samples placed
    together).

    Parameters
    ----------
    ends : Ends
    index : ndarray of int, shape (C,)
        The batch's pairs in the drawing.
    pairs : array_like of int, shape (G,)
        The (local) pair of each morph.
    morphs : list of Morph
        G morphs of the common parts (left as they are: each Segment holds its samples'
        fractions on the whole curve of P).
    orders : array_like of int, shape (G,)
        Each morph's chain order within its pair.
    ranges : array_like, shape (G, 2, 2)
        Each morph's arc-length ranges on the common parts of P and of Q.

    Returns
    -------
    list of Segment
    """
    pairs = np.asarray(pairs, dtype=np.int64)
    ranges = np.asarray(ranges, dtype=np.float64).reshape(-1, 2, 2)
    counts = np.array([len(m.u_p) for m in morphs], dtype=np.int64)
    u_p = np.concatenate([m.u_p for m in morphs]) if morphs else np.zeros(0)
    u_p, offset, range_p = _on_whole(ends, pairs, ranges[:, 0], u_p, np.repeat(np.arange(len(pairs)), counts))
    range_q = ends.on_q(pairs[:, None], ranges[:, 1])
    stops = np.cumsum(counts)
    segments = []
    for g, morph in enumerate(morphs):
        lo, hi = stops[g] - counts[g], stops[g]
        piece = (tuple(range_p[g]) if hi > lo else tuple(ranges[g, 0]), tuple(range_q[g]))
        c = int(index[pairs[g]])
        segments.append(Segment(c, int(orders[g]), *piece, morph=morph, offset=offset[lo:hi], u_p=u_p[lo:hi]))
    return segments
