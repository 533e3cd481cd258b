"""``blender -c ballmorph``: in-between saved .blend files from the command line, headless.

::

    blender -c ballmorph IN.blend [--output OUT.blend] [--object NAME]... [--layers active|all]
                                  [--method circular-ball|...] [--frame-count N] [--json]
                                  [--json-file PATH] [--version] ...

opens IN.blend, in-betweens every key interval (every consecutive pair of keys with a frame
between them) on the chosen layers of the chosen Grease Pencil objects (all of them by default),
and saves to OUT.blend, or in place, keeping ``IN.blend1`` as Blender does. With ``--output`` it
never modifies IN.blend; an empty ``--output`` or one that names a directory is refused before
anything is read.

It runs the operator's own service (:func:`.operators.service.inbetween_object`) with the
operator's options (:data:`.operators.options.OPTIONS`, their lowercase values: ``--method
linear-ball``, ``--easing ease-in-out``), so the in-betweens, the reports and the guarantees are
the operator's: keys and drawn frames are never modified, an object is written all or nothing,
re-running replaces only the add-on's own in-betweens. Only the rule choosing the keys differs
(every pair, not the selection or the current frame), and ``--layers`` defaults to ``all``.

It prints a summary on stdout and its progress, and Blender's own messages, on stderr. With
``--json`` the summary is one JSON object, printed on every exit (an ``error`` object for bad
arguments, an unreadable file or an internal error); after it, stdout is closed to Blender's own
late messages (they go to stderr), so stdout parses as JSON. ``--json-file PATH`` writes the same
object to a file instead, for pipelines that keep stdout for something else.

Exit status (:data:`EXIT_CODES`): 0 everything asked was in-betweened and saved; 3 finished
with warnings (saved what could be in-betweened, or nothing to do: the summary says what and
where); 2 bad arguments or an unreadable input file (nothing read or saved); 1 an internal
error or a failed save (nothing saved; please report an internal error).

The extension registers the command on ``register()`` (``bpy.utils.register_cli_command``) and
removes it on ``unregister()``.
"""

import argparse
import contextlib
import ctypes
import json
import math
import os
import sys
import tomllib
import traceback

import bpy

from .addon_logic import pairing, report_data, reports
from .operators import custom_curve, options, service

__all__ = ["COMMAND", "main", "register", "unregister"]

COMMAND = "ballmorph"
OK, FAILED, BAD_ARGUMENTS, WARNINGS = 0, 1, 2, 3
#: What each exit status means (the help's epilog and the README say the same).
EXIT_CODES = {
    OK: "everything asked was in-betweened and saved",
    WARNINGS: "finished with warnings: what could be in-betweened was saved (or there was nothing to do); "
    "the summary says what and where",
    BAD_ARGUMENTS: "bad arguments or an unreadable input file: nothing was read or saved",
    FAILED: "an internal error (please report it) or the save failed: nothing was saved",
}
_MANIFEST = os.path.join(os.path.dirname(os.path.abspath(__file__)), "blender_manifest.toml")
# Defaults that differ from the operator's: a batch in-betweens every layer.
_DEFAULTS = {"layers": "all"}
_LEVEL_WORDS = {reports.INFO: "Info", reports.WARNING: "Warning", reports.ERROR: "Error"}

_handle = None  # what register_cli_command returned


class BadArgumentsError(Exception):
    """Arguments or an input file the command cannot work with (exit status 2)."""


class _Parser(argparse.ArgumentParser):
    """argparse, but a bad argument raises :class:`BadArgumentsError` (so ``--json`` can say it too)."""

    def error(self, message):
        raise BadArgumentsError(f"{message} (see blender -c {COMMAND} --help)")

    def __init__(self, **kwargs):
        # No abbreviations: --json and --json-file are found before parsing (see _Summary).
        super().__init__(allow_abbrev=False, **kwargs)


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
        The exit status (:data:`EXIT_CODES`): 0 done, 3 done with warnings, 2 bad arguments or
        an unreadable file, 1 an internal error or a failed save.
    """
    argv = [str(arg) for arg in argv]
    summary = _Summary(argv)
    try:
        args = parser().parse_args(argv)
    except SystemExit as exc:  # --help or --version: printed
        return OK if exc.code in (0, None) else BAD_ARGUMENTS
    except BadArgumentsError as exc:
        return summary.failed(BAD_ARGUMENTS, "bad-arguments", str(exc))
    summary.file = args.file
    run = None
    try:
        run = _Run(args)
        return summary.done(run.run(), run)
    except BadArgumentsError as exc:
        return summary.failed(BAD_ARGUMENTS, "bad-arguments", str(exc))
    except Exception:  # a bug: say where, for the bug report
        saved = f"after saving {run.target}" if run is not None and run.saved else "nothing was saved"
        message = f"internal error, {saved}; please report this"
        return summary.failed(FAILED, "internal", message, traceback.format_exc())


def version():
    """The add-on's version, as its manifest says (``'0.1.0'``)."""
    with open(_MANIFEST, "rb") as f:
        return tomllib.load(f)["version"]


def parser():
    """The command's argument parser: its in-between options come from the operator's option table."""
    exits = "; ".join(f"{code} {meaning}" for code, meaning in sorted(EXIT_CODES.items()))
    parser = _Parser(
        prog=f"blender -c {COMMAND}",
        description="In-between every key interval of the Grease Pencil objects in a .blend file, as the "
        "Ball-morph In-between operator does, and save the result.",
        epilog=f"Exit status: {exits}.",
        add_help=False,
    )
    parser.add_argument("file", metavar="IN.blend", help="The file to in-between")
    parser.add_argument(
        "--output",
        metavar="OUT.blend",
        help="Save the result here and leave IN.blend untouched (default: save IN.blend in place, keeping IN.blend1)",
    )
    parser.add_argument(
        "--object",
        metavar="NAME",
        action="append",
        dest="objects",
        default=[],
        help="A Grease Pencil object to in-between (repeat for more; default: all of them)",
    )
    parser.add_argument(
        "--json", action="store_true", help="Print the summary as one JSON object, on every exit (errors too)"
    )
    parser.add_argument(
        "--json-file", metavar="PATH", help="Write the JSON summary to this file (on every exit) instead of stdout"
    )
    parser.add_argument("-h", "--help", action="help", help="Show this help and exit")
    parser.add_argument(
        "--version", action="version", version=f"%(prog)s {version()}", help="Show the add-on's version and exit"
    )
    group = parser.add_argument_group("In-between options (the operator's)")
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
    """A finite number from ``low`` to ``high`` (None: that side unbounded)."""
    if low is not None and high is not None:
        wanted = f"a number from {low:g} to {high:g}"
    elif low is not None:
        wanted = f"a number of at least {low:g}"
    else:
        wanted = "a number" if high is None else f"a number of at most {high:g}"

    def number_between(text):
        try:
            number = float(text)
        except ValueError:
            number = None
        if (
            number is None
            or not math.isfinite(number)
            or (low is not None and number < low)
            or (high is not None and number > high)
        ):
            raise argparse.ArgumentTypeError(f"expected {wanted}, got {text!r}")
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
            try:
                _flush_c_stdio()
            finally:  # stdout comes back whatever happened
                os.dup2(saved, 1)
                os.close(saved)


def _flush_c_stdio():
    """Flush C stdio's buffers (Blender's printf lines) before file descriptor 1 changes: best effort."""
    try:
        # POSIX: the process's own C library. Windows raises TypeError (CDLL needs a name there);
        # Blender's lines then reach their destination when it flushes them itself.
        ctypes.CDLL(None).fflush(None)
    except (OSError, AttributeError, TypeError):
        pass


def _seal_stdout():
    """Send everything printed on stdout from now on to stderr (Blender's exit messages, such as
    "Not freed memory blocks"), so that stdout holds the JSON summary alone."""
    sys.stdout.flush()
    _flush_c_stdio()
    with contextlib.suppress(OSError):
        os.dup2(2, 1)


class _StderrProgress(service.Progress):
    def __init__(self, object_name):
        self.object_name, self.total = object_name, 0
        self.tenth = -1  # the last tenth of a long write said

    def begin(self, total):
        self.total = total

    def step(self, done, interval):
        _say(f"{self.object_name}: {interval.name} ({done + 1}/{self.total})")

    def writing(self, done, total):
        # About ten lines over a long write (the writer calls about a hundred times).
        if total >= 1000 and (done == total or done * 10 // total != self.tenth):
            self.tenth = done * 10 // total
            _say(f"{self.object_name}: writing frames {done}/{total}")


class _Run:
    """One run of the command: check, open, in-between, save, summarise."""

    def __init__(self, args):
        self.args = args
        self.source = os.path.abspath(args.file)
        self.in_place = args.output is None
        self.target = self.source if self.in_place else os.path.abspath(args.output)
        self.values = {name: getattr(args, name) for name in options.OPTION_NAMES}
        self.results = []  # (object name, ObjectResult or None, name of the object it shares data with)
        self.notes = []  # (level, text) about the whole run
        self.saved = False

    def run(self):
        """Everything but the summary (:class:`_Summary` prints it); returns the exit status."""
        self._check()
        with _blender_output_to_stderr():
            self._open()
            chosen = self._chosen_objects()
            self._inbetween(chosen)
            save_failed = not self._save()
        if save_failed:
            return FAILED
        return WARNINGS if self._incomplete() else OK

    # -- before anything is opened

    def _check(self):
        if not os.path.isfile(self.source):
            raise BadArgumentsError(f"cannot read {self.args.file}: no such file")
        if not self.in_place:
            _check_writable("--output", self.args.output, self.target)
            if os.path.realpath(self.target) == os.path.realpath(self.source):
                raise BadArgumentsError(
                    "--output names the input file: leave --output out to save in place (keeping a .blend1)"
                )
        if self.args.json_file is not None:
            _check_writable("--json-file", self.args.json_file, os.path.abspath(self.args.json_file))
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
        # The Custom type reads the curve of the file's scene (Interpolate Sequence's, in its tool
        # settings), as the operator reads its scene's.
        values, curve_note = custom_curve.with_custom_curve(self.values, bpy.context.scene)
        if curve_note and chosen:
            self.notes.append((reports.INFO, curve_note))
        done = {}  # Grease Pencil data -> the object it was in-betweened with
        for obj in chosen:
            key = obj.data.as_pointer()
            if key in done:  # linked duplicates share their drawings: in-between them once
                self.results.append((obj.name, None, done[key]))
                continue
            done[key] = obj.name
            _say(f"{obj.name}: in-betweening")
            result = service.inbetween_object(obj, values, pairing.every_pair, _StderrProgress(obj.name))
            self.results.append((obj.name, result, None))

    def _frames(self):
        return sum(result.frames for _, result, _ in self.results if result is not None)

    def _save(self):
        """Save (unless nothing was written in place); False when saving failed."""
        if self.in_place and not self._frames():
            self.notes.append((reports.INFO, f"nothing was written: {self.args.file} was not saved"))
            return True
        _say(f"saving {self.target}")
        try:
            if self.in_place:
                self._save_in_place()
            else:
                bpy.ops.wm.save_as_mainfile(filepath=self.target, copy=True)
        except RuntimeError as exc:
            reason = str(exc).strip().removeprefix("Error: ")
            self.notes.append((reports.ERROR, f"saving {self.target} failed, nothing was saved: {reason}"))
            return False
        self.saved = True
        return True

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
        return backup if self.saved and self.in_place and os.path.exists(backup) else None

    def text(self):
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

    def fields(self):
        """The summary as JSON-ready fields (without the exit status)."""
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
                        "reports": [report_data.fields(report, layer=layer.name) for report in layer.reports],
                    }
                    for layer in result.layers
                ]
            objects.append(entry)
        return {
            "input": self.source,
            "output": self.target,
            "saved": self.saved,
            "backup": self._backup(),
            "options": self.values,
            "frames_written": self._frames(),
            "objects": objects,
            "notes": [report_data.fields(note) for note in self.notes],
            "error": None,
        }


def _check_writable(flag, given, path):
    """Refuse an output path that cannot be a new file: empty, a directory, in no directory."""
    if not given:
        raise BadArgumentsError(
            f"{flag} is empty: give a file name"
            + (", or leave --output out to save IN.blend in place (keeping IN.blend1)" if flag == "--output" else "")
        )
    if os.path.isdir(path):
        raise BadArgumentsError(f"cannot write {given}: it is a directory; give a file name")
    folder = os.path.dirname(path)
    if not os.path.isdir(folder):
        raise BadArgumentsError(f"cannot write {given}: no directory {folder}")
    if not os.access(folder, os.W_OK):
        raise BadArgumentsError(f"cannot write {given}: the directory {folder} is not writable")


class _Summary:
    """The run's summary, on every exit: text on stdout, or one JSON object (``--json`` on stdout,
    ``--json-file`` in a file), the same fields whether the run finished or failed."""

    def __init__(self, argv):
        # Found by hand before parsing, so that bad arguments are said in JSON too.
        self.json = "--json" in argv
        self.json_file = _value_of("--json-file", argv)
        self.file = _input_in(argv)

    def failed(self, code, kind, message, details=""):
        """Say why the run stopped (stderr, and the JSON error object); returns ``code``."""
        _say(f"error: {message}" + (f"\n{details}" if details else ""))
        source = os.path.abspath(self.file) if self.file else None
        self._write_json(
            {
                "input": source,
                "output": None,
                "saved": False,
                "backup": None,
                "frames_written": 0,
                "objects": [],
                "notes": [],
                "error": {"kind": kind, "message": message},
            },
            code,
        )
        return code

    def done(self, code, run):
        """Print the finished run's summary; returns ``code``."""
        if not self.json:
            sys.stdout.write(run.text())
            sys.stdout.flush()
        self._write_json(run.fields(), code)
        return code

    def _write_json(self, fields, code):
        text = json.dumps({**fields, "exit_code": code}, indent=2) + "\n"
        if self.json_file:
            try:
                with open(self.json_file, "w", encoding="utf-8") as f:
                    f.write(text)
            except OSError as exc:
                _say(f"error: cannot write {self.json_file}: {exc}")
        if self.json:
            sys.stdout.write(text)
            _seal_stdout()


def _input_in(argv):
    """The input file among arguments that did not parse: the first word that is neither an
    option nor an option's value (``--output OUT.blend IN.blend`` -> ``IN.blend``), or None."""
    takes_value = {flag for action in parser()._actions if action.nargs != 0 for flag in action.option_strings}
    words = iter(argv)
    for word in words:
        if word in takes_value:
            next(words, None)
        elif not word.startswith("-"):
            return word
    return None


def _value_of(flag, argv):
    """The value given to ``flag`` in ``argv`` (``--flag VALUE`` or ``--flag=VALUE``), or None."""
    for i, arg in enumerate(argv):
        if arg == flag and i + 1 < len(argv):
            return argv[i + 1]
        if arg.startswith(flag + "="):
            return arg[len(flag) + 1 :]
    return None
