"""Which keys pair up, and which frames between them get in-betweens: plain data in and out.

No bpy here (plain CPython imports it: ``tests/addon``). The Blender side (:mod:`.keys`)
describes each layer's frames as a :class:`LayerKeys`; a *rule* chooses the key pairs; and
:func:`intervals` says, for each pair, which frames to write, which earlier in-betweens to
replace and which drawn frames to leave alone.

Keys on a layer are its frames other than the in-betweens this add-on made (and nobody changed
since). Two rules choose the pairs:

- :func:`selected_or_current` (the operator, as Blender's own Interpolate): two or more
  selected keys -> every consecutive pair of them; otherwise the last key at or before the
  current frame and the first key after it;
- :func:`every_pair` (the command line): every consecutive pair of keys with a frame between.

A rule is any ``rule(layer) -> (pairs, problems)``: ``pairs`` a list of ``(frame_a, frame_b)``,
``problems`` report texts for what it could not pair (see :mod:`.reports`).

An interval with a timing chart (:class:`Chart`) gets one in-between per fraction of the chart,
on frames spread evenly between its keys, at that fraction of the morph; the others get the
frame count's frames, eased.
"""

from dataclasses import dataclass, field

import numpy as np

from ..ballmorph_core import frame_times
from . import reports

__all__ = [
    "LayerKeys",
    "Chart",
    "Interval",
    "interval_name",
    "selected_or_current",
    "every_pair",
    "intervals",
    "chains",
]


@dataclass(frozen=True)
class LayerKeys:
    """A layer's frames as the pairing sees them.

    Attributes
    ----------
    name : str
        The layer's name.
    keys : tuple of int
        Frame numbers of its keys (frames this add-on did not make), ascending.
    selected : tuple of int
        The keys selected in the Dope Sheet, ascending.
    made : tuple of int
        Frames this add-on made (unchanged since), ascending.
    corners : tuple of int
        The keys typed Extreme in the Dope Sheet, ascending: with Smooth key motion the paths
        still turn a corner there (a contact, a sharp change of direction).
    """

    name: str
    keys: tuple = ()
    selected: tuple = ()
    made: tuple = ()
    corners: tuple = ()


@dataclass(frozen=True)
class Chart:
    """The timing chart of one interval.

    Attributes
    ----------
    fractions : tuple of float
        Morph fractions in (0, 1), ascending (:func:`ballmorph_core.parse_timing_chart`), no
        more of them than frames between the interval's keys.
    kept : bool
        The chart was kept from an earlier run on the same keys (this run's option was empty).
    """

    fractions: tuple
    kept: bool = False

    @property
    def text(self):
        """The chart as the option spells it (and as it is kept): ``'0.1 0.5 0.9'``.

        Examples
        --------
        >>> Chart((0.1, 0.5, 0.9)).text
        '0.1 0.5 0.9'
        """
        return " ".join(repr(fraction) for fraction in self.fractions)


def interval_name(layer, frame_a, frame_b):
    """``'Ink 1→9'``: how reports name the interval between two keys of a layer.

    Examples
    --------
    >>> interval_name("Ink", 1, 9)
    'Ink 1→9'
    """
    return f"{layer} {frame_a}\u2192{frame_b}"


@dataclass
class Interval:
    """Two keys on one layer and the frames between them.

    Attributes
    ----------
    layer : str
        The layer's name.
    frame_a, frame_b : int
        The two keys (``frame_a < frame_b``).
    targets : ndarray of int, shape (T,)
        Frames to write an in-between on.
    fractions : ndarray, shape (T,)
        ``(target - frame_a) / (frame_b - frame_a)``.
    replace : list of int
        Frames between the keys that this add-on made earlier: removed before writing.
    occupied : list of int
        Keys between the two (frames the animator drew): never touched.
    skipped : list of int
        Requested in-between frames not written because they are occupied.
    chart : Chart or None
        The timing chart that times this interval (None: the frame count and easing do).
    chart_times : ndarray, shape (T,), or None
        With a chart: each target's morph fraction from the chart (not to be eased).
    """

    layer: str
    frame_a: int
    frame_b: int
    targets: np.ndarray
    fractions: np.ndarray
    replace: list = field(default_factory=list)
    occupied: list = field(default_factory=list)
    skipped: list = field(default_factory=list)
    chart: Chart = None
    chart_times: np.ndarray = None

    @property
    def name(self):
        """``'Ink 1→9'``: how reports name the interval."""
        return interval_name(self.layer, self.frame_a, self.frame_b)


def _with_room(layer, pairs):
    """The pairs with a frame between their keys, and a problem for each of the others."""
    kept, problems = [], []
    for a, b in pairs:
        if b - a < 2:
            problems.append(reports.no_frame_between(layer.name, a, b))
        else:
            kept.append((a, b))
    return kept, problems


def selected_or_current(layer, current_frame):
    """The operator's rule: the selected keys, else the keys around the current frame.

    Parameters
    ----------
    layer : LayerKeys
    current_frame : int

    Returns
    -------
    pairs : list of (int, int)
    problems : list of str
        Why keys could not be paired (too few keys, none on one side of the current frame, a
        pair with no frame between).

    Examples
    --------
    >>> selected_or_current(LayerKeys("Ink", keys=(1, 5, 9)), 6)
    ([(5, 9)], [])
    >>> selected_or_current(LayerKeys("Ink", keys=(1, 5, 9), selected=(1, 5, 9)), 30)
    ([(1, 5), (5, 9)], [])
    """
    keys, chosen = list(layer.keys), set(layer.selected)
    selected = [n for n in keys if n in chosen]
    if len(selected) >= 2:
        return _with_room(layer, list(zip(selected[:-1], selected[1:])))
    if len(keys) < 2:
        return [], [reports.too_few_keys(layer.name, len(keys))]
    before = [n for n in keys if n <= current_frame]
    after = [n for n in keys if n > current_frame]
    if not before or not after:
        return [], [reports.no_key_around(layer.name, "before" if not before else "after", current_frame)]
    return _with_room(layer, [(before[-1], after[0])])


def every_pair(layer):
    """The command line's rule: every consecutive pair of keys with a frame between them.

    Pairs of keys on consecutive frames (a layer animated on ones) are not problems here:
    there is nothing to in-between, and nobody asked for them. Only a layer where nothing pairs
    up is reported.

    Parameters
    ----------
    layer : LayerKeys

    Returns
    -------
    pairs : list of (int, int)
    problems : list of str

    Examples
    --------
    >>> every_pair(LayerKeys("Ink", keys=(1, 2, 5, 9)))
    ([(2, 5), (5, 9)], [])
    """
    keys = list(layer.keys)
    if len(keys) < 2:
        return [], [reports.too_few_keys(layer.name, len(keys))]
    pairs = [(a, b) for a, b in zip(keys[:-1], keys[1:]) if b - a >= 2]
    if not pairs:
        return [], [reports.no_room_between_keys(layer.name)]
    return pairs, []


def intervals(layer, pairs, frame_count, charts=None):
    """The frames to write between each pair of keys.

    Parameters
    ----------
    layer : LayerKeys
    pairs : sequence of (int, int)
        Key pairs from a rule (``frame_a < frame_b``, frames between them).
    frame_count : int
        In-betweens per interval: 0 fills every frame between the keys; N spreads N evenly
        (at most one per frame).
    charts : dict, optional
        ``{(frame_a, frame_b): Chart}``: the pairs timed by a chart get one in-between per
        fraction instead (frames spread evenly as for that frame count), whatever ``frame_count``.

    Returns
    -------
    list of Interval
        One per pair. A frame chosen for an in-between that holds a key is skipped (listed in
        ``skipped``); the add-on's earlier in-betweens between the keys are to be replaced.

    Raises
    ------
    ValueError
        When a chart has more fractions than frames between its keys (the caller checks
        charts with :func:`ballmorph_core.parse_timing_chart` first).

    Examples
    --------
    >>> [i.targets.tolist() for i in intervals(LayerKeys("Ink", keys=(1, 9)), [(1, 9)], 3)]
    [[3, 5, 7]]
    >>> [charted] = intervals(LayerKeys("Ink", keys=(1, 9)), [(1, 9)], 0, {(1, 9): Chart((0.1, 0.5, 0.9))})
    >>> charted.targets.tolist(), charted.chart_times.tolist()
    ([3, 5, 7], [0.1, 0.5, 0.9])
    """
    charts = charts or {}
    out = []
    for a, b in pairs:
        chart = charts.get((a, b))
        frames, fractions = frame_times(a, b, frame_count if chart is None else len(chart.fractions))
        times = None
        if chart is not None:
            if len(frames) != len(chart.fractions):
                raise ValueError(f"{interval_name(layer.name, a, b)}: {len(chart.fractions)} fractions do not fit")
            times = np.asarray(chart.fractions, dtype=np.float64)
        between = [n for n in layer.keys if a < n < b]
        keep = ~np.isin(frames, between)
        out.append(
            Interval(
                layer=layer.name,
                frame_a=a,
                frame_b=b,
                targets=frames[keep],
                fractions=fractions[keep],
                replace=sorted(n for n in layer.made if a < n < b),
                occupied=between,
                skipped=[int(n) for n in frames[~keep]],
                chart=chart,
                chart_times=None if times is None else times[keep],
            )
        )
    return out


def chains(found, corners=()):
    """Runs of consecutive intervals that share their keys, to be joined smoothly there.

    Parameters
    ----------
    found : sequence of Interval
        One layer's intervals, in frame order.
    corners : collection of int
        Keys that keep their corner (typed Extreme).

    Returns
    -------
    list of (list of int, list of bool)
        Each run of two or more intervals sharing keys: the indices into ``found``, and for each
        inner key whether it is passed smoothly (False: a corner).

    Examples
    --------
    >>> ivs = [Interval("Ink", a, b, np.arange(a + 1, b), np.zeros(0)) for a, b in ((1, 7), (7, 13), (20, 30))]
    >>> chains(ivs)
    [([0, 1], [True])]
    >>> chains(ivs, corners=(7,))
    [([0, 1], [False])]
    """
    out, run = [], []
    for k, interval in enumerate(found):
        if run and found[run[-1]].frame_b != interval.frame_a:
            out.append(run)
            run = []
        run.append(k)
    out.append(run)
    return [(run, [found[k].frame_b not in corners for k in run[:-1]]) for run in out if len(run) >= 2]
