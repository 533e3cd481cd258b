"""``ballmorph.inbetween``: write ball-morph in-betweens between two Grease Pencil keys.

Thin: find the key intervals (:mod:`.keys`), compute every interval with the core
(:mod:`.morph`), then write all frames at once (:mod:`.writer`) and report. Runs from the Dope
Sheet, the 3D viewport and scripts (no editor needed in poll). Options not given by the caller
come from the scene's settings (the sidebar panel), which fall back to the add-on preferences;
every run stores its options back there, so F9 changes are remembered.
"""

import bpy

from ..ballmorph_core import FALLBACK_METHOD, BallMorphError
from . import keys, morph, options, writer
from .plans import PLANS

__all__ = ["BALLMORPH_OT_inbetween"]

# Messages listed per interval before "and N more" (the Info editor keeps them all).
_MESSAGES_PER_REPORT = 6


def _frames_text(numbers):
    numbers = [int(n) for n in numbers]
    if len(numbers) > 2 and numbers[-1] - numbers[0] == len(numbers) - 1:
        return f"{numbers[0]}\u2013{numbers[-1]}"
    return ", ".join(str(n) for n in numbers)


def _core_label(core_method):
    return options.method_label(next(ident for ident, core in options.CORE_METHOD.items() if core == core_method))


class BALLMORPH_OT_inbetween(bpy.types.Operator):
    """Write in-between frames between two Grease Pencil keys, morphing each stroke along ball-morph paths"""

    bl_idname = "ballmorph.inbetween"
    bl_label = "Ball-morph In-between"
    bl_options = {"REGISTER", "UNDO"}

    __annotations__ = options.property_annotations(flags={"SKIP_SAVE"})

    @classmethod
    def poll(cls, context):
        # Deliberately permissive: execute() explains what is missing (no Grease Pencil object,
        # one key only, ...) instead of a greyed-out entry.
        return context.scene is not None

    def draw(self, context):
        options.draw_options(self.layout, self)

    def execute(self, context):
        self._fill_options(context)
        obj = keys.grease_pencil_object(context)
        if obj is None:
            return self._cancel(self._no_object_text(context))
        if not options.method_available(self.method):
            return self._cancel(
                f"The {options.method_label(self.method)} morph is not available in this version: choose another"
            )
        grease_pencil_data = obj.data
        layers = keys.target_layers(grease_pencil_data, self.layers)
        if not layers:
            return self._cancel(f"'{obj.name}' has no active layer: add or select a layer")

        problems, intervals = [], []
        for layer in layers:
            blocker = keys.layer_blocker(layer)
            if blocker:
                problems.append(("WARNING", blocker))
                continue
            found, problem = keys.find_intervals(
                grease_pencil_data, layer, context.scene.frame_current, self.frame_count
            )
            if problem:
                problems.append(("INFO" if self.layers == "ALL" else "WARNING", problem))
            intervals.extend(found)

        morphed = self._compute(context, intervals, problems)
        if not morphed:
            return self._cancel("Nothing to in-between: " + "; ".join(text for _, text in problems))
        try:
            written = writer.write_all(grease_pencil_data, morphed)
        except Exception as exc:  # the writer restored the layers; tell the animator why
            return self._cancel(f"Writing the in-betweens failed, nothing was changed: {exc}")

        reports = list(problems)
        for item in morphed:
            reports.extend(self._interval_reports(item))
        for level, text in reports:
            self.report({level}, text)
        warnings = sum(level == "WARNING" for level, _ in reports)
        summary = (
            f"Ball-morph In-between: {written} frame(s) on {len({id(m.interval.layer) for m in morphed})} layer(s)"
        )
        # The status bar shows the last report: make warnings visible there.
        if warnings:
            self.report({"WARNING"}, f"{summary}, {warnings} warning(s): see the Info editor")
        else:
            self.report({"INFO"}, summary)
        self._store_options(context)
        return {"FINISHED"}

    def _fill_options(self, context):
        """Take every option the caller did not set from the scene settings."""
        settings = getattr(context.scene, "ballmorph_inbetween", None)
        for name in options.OPTION_NAMES:
            if settings is not None and not self.properties.is_property_set(name):
                setattr(self, name, getattr(settings, name))

    def _store_options(self, context):
        settings = getattr(context.scene, "ballmorph_inbetween", None)
        if settings is not None:
            for name in options.OPTION_NAMES:
                setattr(settings, name, getattr(self, name))

    def _option_values(self):
        return {name: getattr(self, name) for name in options.OPTION_NAMES}

    def _compute(self, context, intervals, problems):
        """Morph every interval (nothing written yet); collect what cannot be done."""
        values = self._option_values()
        core_method = options.CORE_METHOD[self.method]
        window_manager = context.window_manager
        window_manager.progress_begin(0, max(len(intervals), 1))
        morphed = []
        PLANS.begin()
        try:
            for i, interval in enumerate(intervals):
                window_manager.progress_update(i)
                if len(interval.targets) == 0:
                    problems.append(
                        (
                            "WARNING",
                            f"{interval.name}: every frame between the keys is drawn by hand: nothing was "
                            "written (delete drawn frames there to make room for in-betweens)",
                        )
                    )
                    continue
                try:
                    item = morph.morph_interval(interval, values, core_method)
                except (BallMorphError, ValueError) as exc:  # the keys themselves cannot be in-betweened
                    problems.append(("WARNING", f"{interval.name}: {exc}"))
                    continue
                except Exception as exc:  # a bug: never lose the other intervals to it
                    item = self._fall_back(interval, values, exc, problems)
                    if item is not None:
                        morphed.append(item)
                    continue
                if item is None:
                    problems.append(("WARNING", f"{interval.name}: both keys are empty: draw strokes in them first"))
                    continue
                morphed.append(item)
        finally:
            PLANS.end()
            window_manager.progress_end()
        return morphed

    def _fall_back(self, interval, values, exc, problems):
        """In-between an interval whose morph failed unexpectedly with the core's fallback morph.

        The whole interval is redone with :data:`FALLBACK_METHOD` (so its frames are written with
        one morph, never half of them); if that fails too, nothing is written for it and the
        returned item is None.
        """
        failure = f"{type(exc).__name__}: {exc}"
        if options.CORE_METHOD[self.method] != FALLBACK_METHOD:
            try:
                item = morph.morph_interval(interval, values, FALLBACK_METHOD)
            except Exception as second:  # reported below: nothing written
                failure += f"; then {_core_label(FALLBACK_METHOD)}: {type(second).__name__}: {second}"
            else:
                item.messages.insert(
                    0,
                    (
                        "WARNING",
                        f"the {options.method_label(self.method)} morph failed ({failure}): every in-between "
                        f"here was made with {_core_label(FALLBACK_METHOD)} instead; please report this drawing",
                    ),
                )
                return item
        problems.append(
            (
                "WARNING",
                f"{interval.name}: the morph failed ({failure}): nothing was written between these keys; "
                "try another morph, or simplify the strokes, and please report this drawing",
            )
        )
        return None

    def _interval_reports(self, item):
        """(level, text) reports for one computed interval: what was written, skipped, fell back."""
        interval = item.interval
        replaced = f", replacing {len(interval.replace)} earlier" if interval.replace else ""
        reports = [
            (
                "INFO",
                f"{interval.name}: {len(interval.targets)} in-between(s) on frame(s) "
                f"{_frames_text(interval.targets)} ({_core_label(item.method)}{replaced})",
            )
        ]
        if interval.skipped:
            reports.append(
                ("WARNING", f"{interval.name}: frame(s) {_frames_text(interval.skipped)} already drawn: left untouched")
            )
        elif interval.occupied:
            reports.append(
                ("INFO", f"{interval.name}: frame(s) {_frames_text(interval.occupied)} between the keys left untouched")
            )
        for level in ("WARNING", "INFO"):
            # the core's ERROR messages concern single strokes: the run went on, so they warn
            texts = [text for lvl, text in item.messages if (lvl == "INFO") == (level == "INFO")]
            if texts:
                more = len(texts) - _MESSAGES_PER_REPORT
                shown = "; ".join(texts[:_MESSAGES_PER_REPORT]) + (f"; and {more} more" if more > 0 else "")
                reports.append((level, f"{interval.name}: {shown}"))
        return reports

    @staticmethod
    def _no_object_text(context):
        active = getattr(context, "active_object", None)
        if active is None:
            return "No Grease Pencil object is active: select one and run Ball-morph In-between again"
        kind = active.type.replace("_", " ").lower()
        return (
            f"The active object '{active.name}' is a {kind}, not a Grease Pencil object: "
            "make a Grease Pencil object active and run Ball-morph In-between again"
        )

    def _cancel(self, text):
        self.report({"ERROR"}, text)
        return {"CANCELLED"}
