"""``blender -c ballmorph``: in-between saved .blend files from the command line, headless.

::

    blender -c ballmorph IN.blend [--output OUT.blend] [--object NAME]... [--layers active|all]
                                  [--method circular-ball|...] [--frame-count N] [--json] ...

opens IN.blend, in-betweens every key interval (every consecutive pair of keys with a frame
between them) on the chosen layers of the chosen Grease Pencil objects (all of them by default),
and saves to OUT.blend, or in place, keeping ``IN.blend1`` as Blender does. With ``--output`` it
never modifies IN.blend.

It runs the operator's own service (:func:`.operators.service.inbetween_object`) with the
operator's options (:data:`.operators.options.OPTIONS`, their lowercase values: ``--method
linear-ball``, ``--easing ease-in-out``), so the in-betweens, the reports and the guarantees are
the operator's: keys and drawn frames are never modified, an object is written all or nothing,
re-running replaces only the add-on's own in-betweens. Only the rule choosing the keys differs
(every pair, not the selection or the current frame), and ``--layers`` defaults to ``all``.

It prints a summary on stdout (JSON with ``--json``) and its progress, and Blender's own
messages, on stderr. Exit status: 0 when everything asked was in-betweened; 1 when anything was
skipped, failed or warned (said per object and layer), or nothing was written; 2 for bad
arguments or an unreadable file (nothing saved then).

The extension registers the command on ``register()`` (``bpy.utils.register_cli_command``) and
removes it on ``unregister()``.
"""

import argparse
import contextlib
import ctypes
import json
import os
import sys
import traceback

import bpy

from .addon_logic import pairing, reports
from .operators import options, service

__all__ = ["COMMAND", "main", "register", "unregister"]

COMMAND = "ballmorph"
OK, NOT_ALL_DONE, BAD_ARGUMENTS = 0, 1, 2
# Defaults that differ from the operator's: a batch in-betweens every layer.
_DEFAULTS = {"layers": "all"}
_LEVEL_WORDS = {reports.INFO: "Info", reports.WARNING: "Warning", reports.ERROR: "Error"}

_handle = None  # what register_cli_command returned


class BadArgumentsError(Exception):
    """Arguments or an input file the command cannot work with (exit status 2)."""


def register():
    global _handle
    _handle = bpy.utils.register_cli_command(COMMAND, main)


def unregister():
    global _handle
    if _handle is not None:
        bpy.utils.unregister_cli_command(_handle)
        _handle = None


def main(argv):
    """Run ``blender -c ballmorph`` with the arguments that follow the command's name.

    Parameters
    ----------
    argv : list of str
        E.g. ``['shot.blend', '--output', 'shot-inbetween.blend', '--frame-count', '3']``.

    Returns
    -------
    int
        0 when everything was in-betweened, 1 when anything was skipped, failed or warned (or
        nothing was written), 2 for bad arguments or an unreadable file.
    """
    try:
        args = parser().parse_args(list(argv))
    except SystemExit as exc:  # argparse printed the help, or the usage and what is wrong
        return OK if exc.code in (0, None) else BAD_ARGUMENTS
    try:
        return _Run(args).run()
    except BadArgumentsError as exc:
        _say(f"error: {exc}")
        return BAD_ARGUMENTS
    except Exception:  # a bug: nothing was saved; say where, for the bug report
        _say("internal error, nothing was saved; please report this:\n" + traceback.format_exc())
        return NOT_ALL_DONE


def parser():
    """The command's argument parser: its in-between options come from the operator's option table."""
    parser = argparse.ArgumentParser(
        prog=f"blender -c {COMMAND}",
        description="In-between every key interval of the Grease Pencil objects in a .blend file, as the "
        "Ball-morph In-between operator does, and save the result.",
        epilog="Exit status: 0 done; 1 something was skipped, failed or warned (see the summary), or nothing "
        "was written; 2 bad arguments or unreadable file.",
    )
    parser.add_argument("file", metavar="IN.blend", help="the file to in-between")
    parser.add_argument(
        "--output",
        metavar="OUT.blend",
        help="save the result here and leave IN.blend untouched (default: save IN.blend in place, keeping IN.blend1)",
    )
    parser.add_argument(
        "--object",
        metavar="NAME",
        action="append",
        dest="objects",
        default=[],
        help="a Grease Pencil object to in-between (repeat for more; default: all of them)",
    )
    parser.add_argument("--json", action="store_true", help="print the summary as JSON")
    group = parser.add_argument_group("in-between options (the operator's)")
    for option in options.OPTIONS:
        default = _DEFAULTS.get(option.name, option.default)
        group.add_argument(
            "--" + option.name.replace("_", "-"), dest=option.name, **_ARGUMENTS[option.kind](option, default)
        )
    return parser


def _at_least(low):
    def whole_number(text):
        try:
            number = int(text)
        except ValueError:
            number = None
        if number is None or number < low:
            raise argparse.ArgumentTypeError(f"expected a whole number of at least {low}, got {text!r}")
        return number

    return whole_number


def _between(low, high):
    def number_between(text):
        try:
            number = float(text)
        except ValueError:
            number = None
        if number is None or not low <= number <= high:
            raise argparse.ArgumentTypeError(f"expected a number from {low:g} to {high:g}, got {text!r}")
        return number

    return number_between


def _helped(option, default, **kwargs):
    shown = default if default != "" else "''"
    return {"default": default, "help": f"{option.description} (default: {shown})", **kwargs}


#: The argparse arguments of each kind of option: ``(option, default) -> add_argument keywords``.
_ARGUMENTS = {
    "ENUM": lambda option, default: _helped(option, default, choices=option.values),
    "INT": lambda option, default: _helped(option, default, type=_at_least(option.min), metavar="N"),
    "FLOAT": lambda option, default: _helped(option, default, type=_between(option.min, option.max), metavar="X"),
    "BOOLEAN": lambda option, default: {"action": "store_true", "help": option.description},
    "STRING": lambda option, default: _helped(option, default, metavar="TEXT"),
}


def _say(text):
    """Progress and problems: on stderr, as the command's own lines."""
    sys.stderr.write(f"{COMMAND}: {text}\n")
    sys.stderr.flush()


@contextlib.contextmanager
def _blender_output_to_stderr():
    """Send what Blender prints on stdout ("Read blend: ...", "Info: Saved ...") to stderr meanwhile.

    Blender writes some of it with C stdio on file descriptor 1 and some through Python's
    ``sys.stdout`` (operator reports, in bpy), so both are sent to stderr; this keeps stdout
    for the summary (the JSON of ``--json``).
    """
    sys.stdout.flush()
    try:
        saved = os.dup(1)
    except OSError:  # no stdout at all: nothing to keep clean
        saved = None
    try:
        if saved is not None:
            os.dup2(2, 1)
        with contextlib.redirect_stdout(sys.stderr):
            yield
    finally:
        if saved is not None:
            _flush_c_stdio()
            os.dup2(saved, 1)
            os.close(saved)


def _flush_c_stdio():
    try:
        ctypes.CDLL(None).fflush(None)
    except (OSError, AttributeError):  # no C library to ask (not POSIX): Blender flushes its own lines
        pass


class _StderrProgress(service.Progress):
    def __init__(self, object_name):
        self.object_name, self.total = object_name, 0

    def begin(self, total):
        self.total = total

    def step(self, done, interval):
        _say(f"{self.object_name}: {interval.name} ({done + 1}/{self.total})")


class _Run:
    """One run of the command: check, open, in-between, save, summarise."""

    def __init__(self, args):
        self.args = args
        self.source = os.path.abspath(args.file)
        self.target = os.path.abspath(args.output) if args.output else self.source
        self.values = {name: getattr(args, name) for name in options.OPTION_NAMES}
        self.results = []  # (object name, ObjectResult or None, name of the object it shares data with)
        self.notes = []  # (level, text) about the whole run
        self.saved = False

    def run(self):
        self._check()
        with _blender_output_to_stderr():
            self._open()
            chosen = self._chosen_objects()
            self._inbetween(chosen)
            self._save()
        code = NOT_ALL_DONE if self._incomplete() else OK
        sys.stdout.write(self._json(code) if self.args.json else self._text())
        sys.stdout.flush()
        return code

    # -- before anything is opened

    def _check(self):
        if not os.path.isfile(self.source):
            raise BadArgumentsError(f"cannot read {self.args.file}: no such file")
        if self.args.output:
            if os.path.realpath(self.target) == os.path.realpath(self.source):
                raise BadArgumentsError(
                    "--output names the input file: leave --output out to save in place (keeping a .blend1)"
                )
            if not os.path.isdir(os.path.dirname(self.target)):
                raise BadArgumentsError(f"cannot write {self.args.output}: no directory {os.path.dirname(self.target)}")
        problem = service.check_options(self.values)
        if problem:
            raise BadArgumentsError(problem)

    def _open(self):
        _say(f"reading {self.source}")
        try:
            bpy.ops.wm.open_mainfile(filepath=self.source)
        except RuntimeError as exc:  # Blender's own words: "Error: File format is not supported ..."
            reason = str(exc).strip().removeprefix("Error: ")
            raise BadArgumentsError(f"cannot read {self.args.file}: {reason}") from None

    def _chosen_objects(self):
        drawings = [obj for obj in bpy.data.objects if obj.type == "GREASEPENCIL"]
        if not self.args.objects:
            if not drawings:
                self.notes.append((reports.WARNING, f"{self.args.file} has no Grease Pencil object: nothing to do"))
            return drawings
        chosen = []
        for name in dict.fromkeys(self.args.objects):
            obj = bpy.data.objects.get(name)
            if obj is None:
                there = ", ".join(f"'{o.name}'" for o in drawings) or "none"
                raise BadArgumentsError(
                    f"--object '{name}': {self.args.file} has no object of that name (its Grease Pencil "
                    f"objects: {there})"
                )
            if obj.type != "GREASEPENCIL":
                kind = reports.object_kind(obj.type)
                raise BadArgumentsError(f"--object '{name}' is a {kind}, not a Grease Pencil object")
            chosen.append(obj)
        return chosen

    # -- the work

    def _inbetween(self, chosen):
        done = {}  # Grease Pencil data -> the object it was in-betweened with
        for obj in chosen:
            key = obj.data.as_pointer()
            if key in done:  # linked duplicates share their drawings: in-between them once
                self.results.append((obj.name, None, done[key]))
                continue
            done[key] = obj.name
            _say(f"{obj.name}: in-betweening")
            result = service.inbetween_object(obj, self.values, pairing.every_pair, _StderrProgress(obj.name))
            self.results.append((obj.name, result, None))

    def _frames(self):
        return sum(result.frames for _, result, _ in self.results if result is not None)

    def _save(self):
        in_place = not self.args.output
        if in_place and not self._frames():
            self.notes.append((reports.INFO, f"nothing was written: {self.args.file} was not saved"))
            return
        _say(f"saving {self.target}")
        try:
            if in_place:
                self._save_in_place()
            else:
                bpy.ops.wm.save_as_mainfile(filepath=self.target, copy=True)
        except RuntimeError as exc:
            reason = str(exc).strip().removeprefix("Error: ")
            self.notes.append((reports.ERROR, f"saving {self.target} failed, nothing was saved: {reason}"))
            return
        self.saved = True

    def _save_in_place(self):
        """Save over IN.blend, keeping at least one backup (IN.blend1) whatever the preferences say."""
        paths = bpy.context.preferences.filepaths
        kept = paths.save_version
        paths.save_version = max(kept, 1)
        try:
            bpy.ops.wm.save_mainfile(filepath=self.source)
        finally:
            paths.save_version = kept

    def _incomplete(self):
        if not self._frames() or any(reports.is_warning(level) for level, _ in self.notes):
            return True
        return any(result.error or result.warnings for _, result, _ in self.results if result is not None)

    # -- the summary

    def _backup(self):
        backup = self.source + "1"
        return backup if self.saved and not self.args.output and os.path.exists(backup) else None

    def _text(self):
        frames = self._frames()
        warnings = sum(result.warnings + bool(result.error) for _, result, _ in self.results if result is not None)
        warnings += sum(reports.is_warning(level) for level, _ in self.notes)
        saved = f"saved {self.target}" if self.saved else "nothing saved"
        if self._backup():
            saved += f" (the previous version is {self._backup()})"
        lines = [f"{self.args.file}: {frames} frame(s) written, {warnings} warning(s); {saved}"]
        for name, result, shared in self.results:
            if result is None:
                lines.append(f"{name}: uses the same Grease Pencil data as '{shared}': in-betweened with it")
                continue
            lines.append(f"{name}: {result.frames} frame(s) on {result.layers_written} layer(s)")
            if result.error:
                lines.append(f"  Error: {result.error}")
            lines.extend(f"  {_LEVEL_WORDS[level]}: {text}" for level, text in result.reports())
        lines.extend(f"{_LEVEL_WORDS[level]}: {text}" for level, text in self.notes)
        return "\n".join(lines) + "\n"

    def _json(self, code):
        def report(level, text):
            return {"level": level.lower(), "text": text}

        objects = []
        for name, result, shared in self.results:
            entry = {"name": name, "frames_written": 0, "same_data_as": shared, "error": "", "layers": []}
            if result is not None:
                entry["frames_written"], entry["error"] = result.frames, result.error
                entry["layers"] = [
                    {
                        "name": layer.name,
                        "frames_written": layer.frames,
                        "intervals": [
                            {
                                "keys": [interval.frame_a, interval.frame_b],
                                "frames": interval.targets.tolist(),
                                "method": method,
                                "replaced": interval.replace,
                                "left_untouched": interval.occupied,
                            }
                            for interval, method in layer.written
                        ],
                        "reports": [report(level, text) for level, text in layer.reports],
                    }
                    for layer in result.layers
                ]
            objects.append(entry)
        summary = {
            "input": self.source,
            "output": self.target,
            "saved": self.saved,
            "backup": self._backup(),
            "options": self.values,
            "frames_written": self._frames(),
            "objects": objects,
            "notes": [report(level, text) for level, text in self.notes],
            "exit_code": code,
        }
        return json.dumps(summary, indent=2) + "\n"
