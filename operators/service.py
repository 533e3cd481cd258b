"""In-between one Grease Pencil object: the one service the operator and the command line share.

:func:`inbetween_object` does everything the operator promises, for one object and its chosen
layers:

1. finds the key intervals of each layer with a *pairing rule* (:mod:`.pairing`: the operator's
   selected keys or current frame, or every key pair for ``blender -c ballmorph``), skipping
   locked and hidden layers, and the timing chart of each (:mod:`.charts`: the option's, else
   the one kept from an earlier run on the same keys);
2. computes every interval with the core (:mod:`.morph`), writing nothing yet; an interval whose
   morph fails unexpectedly is redone whole with the core's fallback morph, and one that still
   fails is left out, never the others; with Smooth key motion, consecutive intervals of a layer
   are then joined smoothly at the keys they share (:func:`ballmorph_core.chain_corrections`),
   except at keys typed Extreme, and should that fail they keep their own in-betweens;
3. writes all frames at once, all or nothing (:mod:`.writer`), and keeps each written
   interval's timing chart with it, and the strokes the run's warnings name (:mod:`.warned`);
4. returns what happened per layer (:class:`ObjectResult`): the reports the operator passes to
   ``self.report`` and the command line prints, and the intervals written.

It takes the options as values (:func:`.options.values_of`), never reads the context, and never
reports itself, so both callers say the same things.
"""

from dataclasses import dataclass, field

from ..addon_logic import charts, pairing, playhead, reports, warned
from ..addon_logic.report_data import Report
from ..ballmorph_core import (
    FALLBACK_METHOD,
    KEY_MOTIONS,
    BallMorphError,
    apply_favor,
    chain_corrections,
    parse_timing_chart,
)
from ..ballmorph_core.options import check_option
from . import keys, morph, options, writer
from .plans import PLANS

__all__ = ["LayerResult", "ObjectResult", "Progress", "check_options", "inbetween_object"]


@dataclass
class LayerResult:
    """What happened on one layer.

    Attributes
    ----------
    name : str
        The layer's name.
    reports : list of report_data.Report
        ``(level, text)`` pairs that also say what they are about (kind, layer, frames,
        strokes). In order: why the layer or some keys were skipped, then per interval what was
        written (or why not) and what the morph said.
    written : list of (pairing.Interval, str)
        The intervals written and the core method that made each.
    """

    name: str
    reports: list = field(default_factory=list)
    written: list = field(default_factory=list)

    @property
    def frames(self):
        """Number of frames written on this layer."""
        return sum(len(interval.targets) for interval, _ in self.written)


@dataclass
class ObjectResult:
    """What happened on one Grease Pencil object.

    Attributes
    ----------
    name : str
        The object's name.
    layers : list of LayerResult
        The layers the ``layers`` option chose, in stacking order.
    error : str
        Why nothing at all was written ('' otherwise): no layer to work on, or the write failed
        (then nothing was changed).
    """

    name: str
    layers: list = field(default_factory=list)
    error: str = ""

    @property
    def frames(self):
        """Number of frames written."""
        return 0 if self.error else sum(layer.frames for layer in self.layers)

    @property
    def layers_written(self):
        return sum(layer.frames > 0 for layer in self.layers)

    def reports(self):
        """Every layer's reports, layer by layer (the error is separate)."""
        return [report for layer in self.layers for report in layer.reports]

    @property
    def warnings(self):
        """Number of reports that ask for attention (warnings and errors)."""
        return sum(reports.is_warning(level) for level, _ in self.reports())


class Progress:
    """Where the service says how far it is: the operator shows it in the window, the command
    line on stderr. This one says nothing."""

    def begin(self, total):
        """``total`` intervals are about to be computed."""

    def step(self, done, interval):
        """``done`` intervals are computed; ``interval`` (a :class:`.pairing.Interval`) is next."""

    def end(self):
        """Computing is over (also after an error)."""

    def writing(self, done, total):
        """``done`` of ``total`` in-between frames are written (about a hundred calls in a run,
        and one at its end). Raising here (a KeyboardInterrupt: a stop) rolls the whole write
        back, and the exception reaches the caller."""


def check_options(values):
    """Why these option values cannot run at all ('' when they can): an unavailable morph, a
    favor out of range, an unknown key motion, a timing chart that is not one."""
    if not options.method_available(values["method"]):
        return reports.method_unavailable(options.label("method", values["method"]))
    try:
        apply_favor([], values["favor"])
        check_option("key_motion", values["key_motion"], KEY_MOTIONS)
    except ValueError as exc:
        return _labelled(str(exc))
    try:
        parse_timing_chart(values["timing_chart"])
    except ValueError as exc:
        return _labelled(reports.bad_chart(str(exc)))
    return ""


#: Options the core names in its errors (its arguments' names): said with their labels instead.
_NAMED_BY_THE_CORE = ("timing_chart", "favor")


def _labelled(text):
    """The core's words with the options named as the animator sees them (``Timing Chart``)."""
    for name in _NAMED_BY_THE_CORE:
        text = reports.labelled(text, name, options.option(name).label)
    return text


def inbetween_object(obj, values, rule, progress=None, only_frame=None):
    """In-between the key intervals of a Grease Pencil object's chosen layers.

    Parameters
    ----------
    obj : bpy.types.Object
        A Grease Pencil (v3) object.
    values : dict
        The options' values (:func:`.options.values_of`), checked by :func:`check_options`.
    rule : callable
        ``rule(layer_keys) -> (pairs, problems)``, e.g. :func:`.pairing.every_pair` or
        ``functools.partial(pairing.selected_or_current, current_frame=...)``.
    progress : Progress, optional
    only_frame : int, optional
        Write one in-between on this frame only (``current_frame_only``, :mod:`.playhead`): the
        frame count and timing charts do not apply then.

    Returns
    -------
    ObjectResult
        Nothing was written when its ``frames`` is 0: then its reports (or its error) say why.
        Keys are never modified; frames the animator drew are never overwritten or removed.
    """
    progress = progress or Progress()
    data = obj.data
    result = ObjectResult(obj.name)
    layers = keys.target_layers(data, values["layers"])
    if not layers:
        result.error = reports.no_layers(obj.name, values["layers"])
        return result
    # With every layer chosen, a layer that has nothing to pair is normal; on the one layer
    # the animator chose, it is worth a warning.
    problem_level = reports.INFO if values["layers"] == "all" else reports.WARNING
    work, corners = [], {}
    for layer in layers:
        layer_result = LayerResult(layer.name)
        result.layers.append(layer_result)
        blocker = keys.layer_blocker(layer)
        if blocker:
            layer_result.reports.append(Report(reports.WARNING, blocker, kind="layer-skipped", layer=layer.name))
            continue
        found = keys.layer_keys(data, layer)
        corners[layer.name] = found.corners
        pairs, problems = rule(found)
        layer_result.reports.extend(Report(problem_level, text, kind="keys", layer=layer.name) for text in problems)
        if only_frame is not None:
            every_frame = pairing.intervals(found, pairs, 0)
            work.extend((layer, layer_result, playhead.at_frame(interval, only_frame)) for interval in every_frame)
            continue
        try:
            layer_charts, notes = charts.charts_for(data, layer.name, pairs, values["timing_chart"])
        except ValueError as exc:  # the chart does not fit an interval: refuse the run, write nothing
            result.error = _labelled(str(exc))
            return result
        layer_result.reports.extend(
            Report(level, _labelled(text), kind="timing-chart", layer=layer.name) for level, text in notes
        )
        found_intervals = pairing.intervals(found, pairs, values["frame_count"], layer_charts)
        work.extend((layer, layer_result, interval) for interval in found_intervals)

    outcomes = _compute(work, values, progress, corners)
    morphed = [item for _, _, item, _ in outcomes if item is not None]
    if morphed:
        try:
            writer.write_all(data, morphed, progress=progress.writing)
        except Exception as exc:  # the writer restored the layers; say why nothing changed
            result.error = reports.write_failed(exc)
            return result
    _keep_outcomes(data, outcomes)
    if morphed:  # the strokes its warnings name, for Select Warned Strokes (warned.py: why kept there)
        warned.keep(data, result.reports())
    return result


def _keep_outcomes(data, outcomes):
    """Each interval's reports in its layer's result; a written one's chart kept on ``data``."""
    for layer_result, interval, item, problem in outcomes:
        about = {"layer": interval.layer, "frames": (interval.frame_a, interval.frame_b)}
        if item is None:
            layer_result.reports.append(Report(*problem, kind="failed", **about))
            continue
        charts.keep(data, interval)
        layer_result.written.append((interval, item.method))
        label = options.label("method", item.method)
        found = reports.interval_reports(interval, label, item.messages, item.strays)
        layer_result.reports.extend(report.about(**about) for report in found)


def _compute(work, values, progress, corners):
    """Morph every interval (nothing written): ``(layer result, interval, Morphed or None, problem)``;
    ``corners`` are each layer's keys typed Extreme (dict layer name -> frames)."""
    outcomes = []
    progress.begin(len(work))
    PLANS.begin()
    try:
        for done, (layer, layer_result, interval) in enumerate(work):
            progress.step(done, interval)
            outcomes.append((layer_result, interval, *_morph(layer, interval, values)))
        if values["key_motion"] != "per-interval":
            _join_smoothly(outcomes, values["key_motion"], corners)
    finally:
        PLANS.end()
        progress.end()
    return outcomes


def _morph(layer, interval, values):
    """``(Morphed, None)`` for an interval, or ``(None, (level, text))`` saying why not."""
    if len(interval.targets) == 0:
        return None, (reports.WARNING, reports.all_drawn(interval.name))
    try:
        item = morph.morph_interval(layer, interval, values, values["method"])
    except (BallMorphError, ValueError) as exc:  # the keys themselves cannot be in-betweened
        return None, (reports.WARNING, f"{interval.name}: {exc}")
    except Exception as exc:  # a bug: never lose the other intervals to it
        return _fall_back(layer, interval, values, exc)
    if item is None:
        return None, (reports.WARNING, reports.both_keys_empty(interval.name))
    return item, None


def _fall_back(layer, interval, values, exc):
    """Redo an interval whose morph failed unexpectedly with the core's fallback morph, whole.

    Its frames are then made by one morph, never half of them; if the fallback fails too (or
    was the morph that failed), nothing is written for the interval.
    """
    failed = reports.failure(exc)
    method = values["method"]
    if method != FALLBACK_METHOD:
        try:
            item = morph.morph_interval(layer, interval, values, FALLBACK_METHOD)
        except Exception as second:  # reported below: nothing written
            failed += f"; then {options.label('method', FALLBACK_METHOD)}: {reports.failure(second)}"
        else:
            if item is None:
                return None, (reports.WARNING, reports.both_keys_empty(interval.name))
            text = reports.fell_back(options.label("method", method), failed, options.label("method", FALLBACK_METHOD))
            item.messages.insert(0, (reports.WARNING, text))
            return item, None
    return None, (reports.WARNING, reports.morph_failed(interval.name, failed))


def _join_smoothly(outcomes, key_motion, corners):
    """Join each layer's consecutive computed intervals smoothly at the keys they share (not at
    its ``corners``): their Morphed items are replaced in ``outcomes`` by ones evaluated with the
    core's corrections. A chain whose joining fails keeps its items (and says why)."""
    by_layer = {}
    for k, (layer_result, _, item, _) in enumerate(outcomes):
        if item is not None:
            by_layer.setdefault(id(layer_result), []).append(k)
    for indices in by_layer.values():
        items = [outcomes[k][2] for k in indices]
        layer_corners = corners.get(items[0].layer.name, ())
        for run, smooth in pairing.chains([item.interval for item in items], layer_corners):
            chain = [items[i] for i in run]
            try:
                lengths = [item.interval.frame_b - item.interval.frame_a for item in chain]
                corrections = chain_corrections([item.plan for item in chain], lengths, smooth, key_motion)
                joined = [item if c is None else morph.corrected(item, c) for item, c in zip(chain, corrections)]
            except Exception as exc:  # a bug: the intervals keep their own in-betweens, nothing is lost
                chain[0].messages.append((reports.WARNING, reports.not_joined(reports.failure(exc))))
                continue
            inner = [item.interval.frame_b for item in chain[:-1]]
            for i, (k, item) in enumerate(zip((indices[r] for r in run), joined)):
                ends = [n for n in (i - 1, i) if 0 <= n < len(inner)]
                text = reports.joined_smoothly(
                    [inner[n] for n in ends if smooth[n]], [inner[n] for n in ends if not smooth[n]]
                )
                if text:
                    item.messages.append((reports.INFO, text))
                layer_result, interval, _, problem = outcomes[k]
                outcomes[k] = (layer_result, interval, item, problem)
