"""Where a pair of curves is not b-compatible (paper sections 3.3-3.4): reports, not yes or no.

A :class:`CompatibilityReport` lists every maximal disk that a curve enters or that touches a
curve twice (:class:`Violation`), grouped into runs of consecutive samples for the animator.
"""

from dataclasses import dataclass, field

import numpy as np

__all__ = ["Violation", "CompatibilityReport", "MORPHABLE"]

# Configurations a ball-map is computed for directly ("coincident": P == Q, a static morph).
MORPHABLE = ("disjoint-loops", "quasi-disjoint-strokes", "coincident")


@dataclass
class Violation:
    """One maximal disk that a curve enters (a place where the pair is not b-compatible).

    Attributes
    ----------
    driver : str
        ``'P'`` if the disk is that of a dense sample of P mapped to Q, ``'Q'`` for the reverse,
        ``'P+Q'`` where the two one-way maps disagree (a disk touching a curve twice).
    sample : int
        Index of that dense sample on its curve.
    p, q : ndarray, shape (2,)
        The disk's contact points on P and Q.
    s_p, s_q : float
        Their arc-length positions on the oriented P and Q.
    witness_curve : str
        ``'P'`` (the disk touches P twice) or ``'Q'`` (it touches Q twice).
    witness : ndarray, shape (2,)
        A point of that curve inside the disk (or touched a second time).
    depth : float
        How far inside the disk the witness lies (or how far the two maps disagree).
    """

    driver: str
    sample: int
    p: np.ndarray
    q: np.ndarray
    s_p: float
    s_q: float
    witness_curve: str
    witness: np.ndarray
    depth: float


@dataclass
class CompatibilityReport:
    """Where a pair of curves is not b-compatible.

    Attributes
    ----------
    configuration : str
        See :func:`classify`.
    violations : list of Violation
        Empty when every maximal disk is empty (within ``check.DISK_PENETRATION``).
    samples : int
        Number of correspondence samples checked.
    """

    configuration: str
    violations: list = field(default_factory=list)
    samples: int = 0

    @property
    def compatible(self):
        """True when no violation was found."""
        return self.configuration in MORPHABLE and not self.violations

    def runs(self):
        """Violations grouped into runs of consecutive samples.

        Returns
        -------
        list of tuple
            ``(first, last)`` Violation of each run.
        """
        runs = []
        for v in sorted(self.violations, key=lambda v: (v.driver, v.sample)):
            if runs and v.driver == runs[-1][1].driver and v.sample - runs[-1][1].sample <= 1:
                runs[-1] = (runs[-1][0], v)
            else:
                runs.append((v, v))
        return runs

    def describe(self, limit=3):
        """A sentence naming where the curves are incompatible (str)."""
        if self.configuration not in MORPHABLE:
            return f"configuration {self.configuration!r} is not b-compatible"
        if not self.violations:
            return "b-compatible"
        parts = []
        for first, last in self.runs()[:limit]:
            deepest = max(
                (v for v in self.violations if v.driver == first.driver and first.sample <= v.sample <= last.sample),
                key=lambda v: v.depth,
            )
            parts.append(
                f"P s={first.s_p:.4g}..{last.s_p:.4g} / Q s={first.s_q:.4g}..{last.s_q:.4g} "
                f"near P({deepest.p[0]:.4g}, {deepest.p[1]:.4g}): the maximal disk also touches "
                f"{deepest.witness_curve} at ({deepest.witness[0]:.4g}, {deepest.witness[1]:.4g})"
            )
        more = len(self.runs()) - limit
        tail = f"; and {more} more places" if more > 0 else ""
        n = len(self.violations)
        return (
            f"not b-compatible: {n} of {self.samples} maximal disks are entered by the curves "
            "or touched twice (the medial axis of the gap bifurcates): " + "; ".join(parts) + tail
        )
