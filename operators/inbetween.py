"""``ballmorph.inbetween``: write ball-morph in-betweens between two Grease Pencil keys.

Thin: take the options (unset ones from the scene's settings, the sidebar panel, which fall
back to the add-on preferences), let the service (:mod:`.service`) in-between the active
object with the operator's pairing rule (selected keys, else the keys around the current frame),
and pass its reports on. With ``current_frame_only`` it writes one in-between on the current
frame, as Blender's Interpolate does (:mod:`.playhead`). Runs from the Dope Sheet, the 3D
viewport and scripts (no editor needed in poll, which only asks for an active Grease Pencil
object and says so when there is none). Every run stores its options back in the scene, so F9
changes are remembered.
"""

from functools import partial

import bpy
from bpy.app.translations import pgettext_rpt as rpt_

from ..addon_logic import pairing, playhead, reports, warned
from . import custom_curve, keys, options, service

__all__ = ["BALLMORPH_OT_inbetween"]


class _WindowProgress(service.Progress):
    """The service's progress on the window manager's progress indicator."""

    def __init__(self, window_manager):
        self.window_manager = window_manager
        self.writing_shown = False  # the indicator shows the frames' writing

    def begin(self, total):
        self.window_manager.progress_begin(0, max(total, 1))

    def step(self, done, interval):
        self.window_manager.progress_update(done)

    def end(self):
        self.window_manager.progress_end()

    def writing(self, done, total):
        # The frames' writing on the same indicator, from 0 again: a long interval moves it too.
        if done == 0 or not self.writing_shown:
            self.window_manager.progress_begin(0, max(total, 1))
            self.writing_shown = True
        self.window_manager.progress_update(done)
        if done >= total:
            self.window_manager.progress_end()
            self.writing_shown = False


class BALLMORPH_OT_inbetween(bpy.types.Operator):
    """Write in-between frames between two Grease Pencil keys, morphing each stroke along ball-morph paths"""

    bl_idname = "ballmorph.inbetween"
    bl_label = "Ball-morph In-between"
    bl_options = {"REGISTER", "UNDO"}

    __annotations__ = {
        **options.property_annotations(flags={"SKIP_SAVE"}),
        # The operator's own: a scene setting would turn every later run into a one-frame run.
        "current_frame_only": bpy.props.BoolProperty(
            name="Current Frame Only",
            description="One in-between on the current frame, at the fraction it sits between the keys around it "
            "(eased as set), as Blender's Interpolate does; other in-betweens stay",
            default=False,
            options={"SKIP_SAVE"},
        ),
    }

    @classmethod
    def poll(cls, context):
        # Only what every run needs; execute() explains the rest (one key only, locked layer, ...).
        if context.scene is None:
            return False
        if keys.grease_pencil_object(context) is None:
            cls.poll_message_set(rpt_(_no_object(context)))
            return False
        return True

    def draw(self, context):
        self.layout.prop(self, "current_frame_only")
        options.draw_options(self.layout, self, current_frame=self.current_frame_only, scene=context.scene)

    def execute(self, context):
        self._fill_options(context)
        obj = keys.grease_pencil_object(context)
        if obj is None:
            return self._cancel(_no_object(context))
        values = options.values_of(self)
        problem = service.check_options(values)
        if problem:
            return self._cancel(problem)
        values, curve_note = custom_curve.with_custom_curve(values, context.scene)
        frame = context.scene.frame_current
        progress = _WindowProgress(context.window_manager)
        if self.current_frame_only:
            result = service.inbetween_object(obj, values, playhead.around(frame), progress, only_frame=frame)
        else:
            rule = partial(pairing.selected_or_current, current_frame=frame)
            result = service.inbetween_object(obj, values, rule, progress)
        if result.error:
            return self._cancel(result.error)
        if not result.frames:
            return self._cancel(reports.nothing_to_do([text for _, text in result.reports()]))
        if curve_note:
            self.report({"INFO"}, rpt_(curve_note))
        for level, text in result.reports():
            self.report({level}, rpt_(text))
        # The status bar shows the last report: the summary, a warning when anything warned.
        named = bool(warned.warned_strokes(result.reports()))
        level, text = reports.summary(result.frames, result.layers_written, result.warnings, named)
        self.report({level}, rpt_(text))
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

    def _cancel(self, text):
        self.report({"ERROR"}, rpt_(text))
        return {"CANCELLED"}


def _no_object(context):
    """Why there is nothing to in-between: no active object, or one of another type."""
    active = getattr(context, "active_object", None)
    return reports.no_object(*((active.name, active.type) if active else ()))
