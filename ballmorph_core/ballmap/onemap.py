"""One-way ball-maps: every dense sample of a source curve mapped onto its target, as arrays.

The lacing, the disk check, the repair and the symmetric thinning all pass these between them;
:class:`OneWayMap` names their fields and says how to take rows, read a map backwards and join
two maps.
"""

from dataclasses import dataclass, fields, replace

import numpy as np

__all__ = ["OneWayMap"]

#: Fields that trade places when a map is read backwards.
_MIRROR = (("src", "dst"), ("s_src", "s_dst"), ("n_src", "n_dst"))


@dataclass
class OneWayMap:
    """Samples of the source curves of a batch of chains, each with its maximal disk.

    Attributes
    ----------
    src, dst : ndarray, shape (K, 2)
        Sample on the source curve and its contact on the target curve.
    m : ndarray, shape (K, 2)
        Disk centres.
    r : ndarray, shape (K,)
        Disk radii (0 where no disk was found).
    ok : ndarray of bool, shape (K,)
        A disk was found.
    s_src, s_dst : ndarray, shape (K,)
        Arc lengths of the sample and of its contact (unwrapped on loops).
    n_src, n_dst : ndarray, shape (K, 2)
        Unit normals into the gap at both contacts.
    chain : ndarray of int, shape (K,)
        The chain (stroke pair or lens) of each sample, non-decreasing.
    bad : ndarray of bool, shape (K,), optional
        Set by the disk check: the disk is entered by a curve, or missing.
    """

    src: np.ndarray
    dst: np.ndarray
    m: np.ndarray
    r: np.ndarray
    ok: np.ndarray
    s_src: np.ndarray
    s_dst: np.ndarray
    n_src: np.ndarray
    n_dst: np.ndarray
    chain: np.ndarray
    bad: np.ndarray = None

    def __len__(self):
        return len(self.r)

    def take(self, rows):
        """The map restricted to ``rows`` (indices or a boolean mask), a new OneWayMap."""
        return OneWayMap(**{f.name: _rows(getattr(self, f.name), rows) for f in fields(self)})

    def put(self, rows, other, names=("dst", "m", "r", "ok", "s_dst", "n_dst")):
        """Overwrite the given fields at ``rows`` with the rows of ``other`` (in place)."""
        for name in names:
            getattr(self, name)[rows] = getattr(other, name)

    def flipped(self):
        """The same disks read from the target to the source (the check's marks are dropped)."""
        mirrored = {a: getattr(self, b) for pair in _MIRROR for a, b in (pair, pair[::-1])}
        return replace(self, bad=None, **mirrored)

    @classmethod
    def empty(cls):
        """A map of no sample."""
        points, values = np.zeros((0, 2)), np.zeros(0)
        return cls(
            points, points, points, values, np.zeros(0, bool), values, values, points, points, np.zeros(0, np.int64)
        )

    @classmethod
    def concatenate(cls, maps):
        """Rows of several maps, one after the other (the check's marks are dropped)."""
        names = [f.name for f in fields(cls) if f.name != "bad"]
        return cls(**{name: np.concatenate([getattr(m, name) for m in maps]) for name in names})


def _rows(values, rows):
    """``values[rows]`` by np.compress / np.take (several times faster on (K, 2) rows)."""
    if values is None:
        return None
    if isinstance(rows, np.ndarray) and rows.dtype == bool and rows.shape == values.shape[:1]:
        return np.compress(rows, values, axis=0)
    if isinstance(rows, np.ndarray) and rows.dtype.kind in "iu":
        return np.take(values, rows, axis=0)
    return values[rows]  # a slice, a list
