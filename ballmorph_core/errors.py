"""Exceptions raised by the core.

Everything the core raises on purpose derives from :class:`BallMorphError`, so the Blender
operator can catch one type and turn it into a report (glTF-Blender-IO style: the core raises,
the add-on reports).
"""

__all__ = ["BallMorphError", "InvalidCurveError", "IncompatibleCurvesError"]


class BallMorphError(Exception):
    """Base class of every error the core raises on purpose."""


class InvalidCurveError(BallMorphError, ValueError):
    """Malformed input: wrong shape, non-finite values, too few distinct points, bad option.

    It is also a ``ValueError`` so generic callers can treat it as one. The message names the
    argument and what was wrong with it.
    """


class IncompatibleCurvesError(BallMorphError):
    """Well-formed curves that the requested morph cannot handle.

    Parameters
    ----------
    message : str
        What is wrong and, where it applies, where on the curves.
    report : object, optional
        A structured report (for example a :class:`~ballmorph_core.compat.CompatibilityReport`)
        that says where the curves are incompatible.
    """

    def __init__(self, message, report=None):
        super().__init__(message)
        self.report = report
