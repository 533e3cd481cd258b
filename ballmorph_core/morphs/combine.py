"""Morphs built from other morphs: moved along a carrier, or joined piece by piece."""

import numpy as np

from .base import Morph

__all__ = ["CarriedMorph", "PiecewiseMorph"]


class CarriedMorph(Morph):
    """``frame(t) = C_t(inner(t))``: a morph moved along a carrier motion.

    Parameters
    ----------
    inner : Morph
        The morph between the registered P and Q.
    carrier : Carrier
        See :mod:`~ballmorph_core.registration`; ``C_0`` undoes the registration, ``C_1`` is
        the identity.
    """

    def __init__(self, inner, carrier):
        super().__init__(inner.closed)
        self.inner = inner
        self.carrier = carrier
        self.method = inner.method
        self.u_p, self.u_q = inner.u_p, inner.u_q

    def _frame(self, t):
        return self.carrier.apply(t, self.inner(t))

    def __len__(self):
        return len(self.inner)


class PiecewiseMorph(Morph):
    """Pieces of P morphing into pieces of Q, joined end to end (crossing or overlap splits).

    Consecutive pieces share an endpoint (a crossing point, or the end of an overlap), which
    appears once in the joined frame.

    Parameters
    ----------
    pieces : list of Morph
        Stroke morphs in order along P; piece ``k`` ends where piece ``k + 1`` starts.
    ranges_p, ranges_q : ndarray, shape (n_pieces, 2)
        Where each piece starts and ends on P and on Q, as arc-length fractions along the
        curves as given (for loops a range may wrap past 1).
    closed : bool
        For loops the last piece ends where the first starts.
    """

    def __init__(self, pieces, ranges_p, ranges_q, closed):
        super().__init__(closed)
        self.pieces = list(pieces)
        self.method = "+".join(sorted({p.method for p in self.pieces}))
        keep = []
        for k, piece in enumerate(self.pieces):
            n = len(piece)
            sl = np.arange(n)
            if k > 0:
                sl = sl[1:]
            if closed and k == len(self.pieces) - 1:
                sl = sl[:-1]
            keep.append(sl)
        self._keep = keep
        self.u_p = self._global(ranges_p, "u_p")
        self.u_q = self._global(ranges_q, "u_q")

    def _global(self, ranges, attr):
        parts = []
        for piece, sl, (u0, u1) in zip(self.pieces, self._keep, np.asarray(ranges, dtype=np.float64)):
            local = getattr(piece, attr)[sl]
            parts.append(u0 + local * (u1 - u0))
        u = np.concatenate(parts)
        return np.mod(u, 1.0) if self.closed else np.clip(u, 0.0, 1.0)

    def _frame(self, t):
        return np.concatenate([piece(t)[sl] for piece, sl in zip(self.pieces, self._keep)])

    def __len__(self):
        return sum(len(sl) for sl in self._keep)
