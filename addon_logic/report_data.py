"""A report that says what it is about: the ``(level, text)`` pair, plus its kind, layer, frames
and strokes, for the command line's JSON (and for selecting the strokes a warning names).

No bpy here (plain CPython imports it: ``tests/addon``). :class:`Report` *is* a ``(level, text)``
tuple (it unpacks and compares as one, so every caller that reads pairs keeps working); its
other fields ride along as attributes.
"""

__all__ = ["KINDS", "Report", "StrokeRef", "fields"]

#: What a report can be about (its ``kind``).
KINDS = (
    "note",  # anything else
    "layer-skipped",  # a locked or hidden layer
    "keys",  # keys that could not be paired
    "written",  # what was written on an interval
    "timing-chart",  # a chart kept, or ignored
    "drawn-frames",  # frames between the keys that were left untouched
    "morph",  # what the morph said (per stroke or per pair)
    "stray",  # a stroke pair whose in-betweens stray from its keys
    "failed",  # an interval that could not be in-betweened
)


class StrokeRef(tuple):
    """A stroke as the animator finds it: ``(key frame, stroke number from 1)``.

    Examples
    --------
    >>> StrokeRef(9, 2)
    (9, 2)
    >>> StrokeRef.of_index(9, 1).fields()
    {'key': 9, 'stroke': 2}
    """

    def __new__(cls, key, number):
        return super().__new__(cls, (int(key), int(number)))

    @classmethod
    def of_index(cls, key, index):
        """The stroke with index ``index`` (from 0, as in the drawing) in the key on frame ``key``."""
        return cls(key, index + 1)

    def fields(self):
        return {"key": self[0], "stroke": self[1]}


class Report(tuple):
    """A ``(level, text)`` report and what it is about.

    Attributes
    ----------
    kind : str
        One of :data:`KINDS`.
    layer : str or None
        The layer it is about.
    frames : tuple of int
        The frames it is about (an interval's keys, a frame to draw a breakdown on, ...).
    strokes : tuple of StrokeRef
        The strokes it is about.

    Examples
    --------
    >>> report = Report("WARNING", "Ink 1→9: ...", kind="stray", layer="Ink", frames=(1, 9))
    >>> level, text = report
    >>> report == ("WARNING", "Ink 1→9: ..."), report.kind, report.frames
    (True, 'stray', (1, 9))
    """

    def __new__(cls, level, text, kind="note", layer=None, frames=(), strokes=()):
        report = super().__new__(cls, (level, text))
        report.kind, report.layer = kind, layer
        report.frames = tuple(int(n) for n in frames)
        report.strokes = tuple(strokes)
        return report

    @property
    def level(self):
        return self[0]

    @property
    def text(self):
        return self[1]

    def about(self, kind=None, layer=None, frames=None):
        """This report with the fields it does not know yet filled in (a plain pair knows none)."""
        return Report(
            self[0],
            self[1],
            kind=self.kind if self.kind != "note" or kind is None else kind,
            layer=self.layer if self.layer is not None else layer,
            frames=self.frames or (frames or ()),
            strokes=self.strokes,
        )


def fields(report, **about):
    """A report (a :class:`Report` or a plain ``(level, text)`` pair) as JSON-ready fields.

    ``about``: ``kind``, ``layer``, ``frames`` for a plain pair (a Report's own win).

    Examples
    --------
    >>> fields(("INFO", "layer 'Notes' has 1 keyframe(s)"), kind="keys", layer="Notes")
    {'level': 'info', 'text': "layer 'Notes' has 1 keyframe(s)", 'kind': 'keys', 'layer': 'Notes', 'frames': [], \
'strokes': []}
    """
    report = report if isinstance(report, Report) else Report(*report)
    report = report.about(**about)
    return {
        "level": report.level.lower(),
        "text": report.text,
        "kind": report.kind,
        "layer": report.layer,
        "frames": list(report.frames),
        "strokes": [stroke.fields() for stroke in report.strokes],
    }
