"""Benchmark of the operator against Blender's own Interpolate Sequence (issues 6 and 14).

Runs inside bpy (Blender as a Python module, headless)::

    $(tools/bootstrap.sh 5.0.1) tools/benchmark.py [--quick] [--sizes 100x200x9,...]
                                                   [--kinds loops,open,jagged,deforming]
                                                   [--cases deforming:400x500x23,loops:100x200x9,...]
                                                   [--methods CIRCULAR_BALL,...] [--write docs/benchmark.md]

For every drawing of the grid strokes {10, 100, 400} x points per stroke {50, 200, 500} x
in-betweens {3, 9, 23}, once with loops and once with open strokes (and jagged redraws, strokes
retraced with a tremor whose lenses take the fallback step, on a short grid of their own; and
loops changing shape where they lie, each of key B key A's stretched 1.25x about its centre,
at the goal sizes), it
builds two identical Grease Pencil objects whose layer has key A on frame 1 and key B on frame
in-betweens + 2 (key B is key A with every stroke moved, turned, scaled and smoothly deformed: a
fixed-seed random wobble, so the strokes really morph), puts each in Edit Mode in the factory
screen's 3D viewport
(what Blender's operator needs) and times, in this one process:

- ``bpy.ops.grease_pencil.interpolate_sequence`` (C++, pairs strokes by index and lerps),
- ``bpy.ops.ballmorph.inbetween`` with each ball-morph method (carrier and every other option
  at its default, every frame between the keys filled),

each as the median of several runs (``time.perf_counter`` around the operator call; more runs
for fast cases), the frames made by a run being removed before the next one, so every run starts
from the same drawing (as a redo from F9 does: Blender undoes the previous run first). Our runs
are cold: the plans the operator keeps for a redo (operators/plans.py) are dropped before each.
The *redo* column times what F9 then costs: the same keys, another easing each run, so the kept
plan is re-evaluated at new times and written. It splits
one circular-ball run into stages by wrapping the add-on's functions (keys, read, core:
matching / ball-map / frames evaluation / assembly, write-back), and measures the peak memory of one cold
run of every operator on the largest drawing (and the goal sizes), each in a fresh bpy process
(the growth of the process's peak resident set, see :func:`_reset_peak`).

The ball-map scaling (tools/bench_ballmap.py), the matching scaling on reordered look-alike
strokes (tools/bench_matching.py) and the scribble (one stroke of random points whose long edges
all cross, issue 14's superlinear case) run in plain CPython subprocesses and their tables are
embedded. ``--write`` writes the markdown report (docs/benchmark.md for ``make bench``).
"""

import argparse
import ctypes
import datetime
import functools
import gc
import importlib
import itertools
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field

import bpy
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# tools/ (the plain-CPython benchmarks) and tests/fixtures (the drawings they share with the tests).
sys.path[:0] = [os.path.dirname(os.path.abspath(__file__)), os.path.join(ROOT, "tests", "fixtures")]

import bench_ballmap  # noqa: E402  (after the path set-up; it imports no bpy)
import bench_matching  # noqa: E402  (the same)
from bench_drawings import KINDS, make_keys  # noqa: E402  (the same)

addon_utils = importlib.import_module("addon_utils")

ADDON_ID = "ballmorph_inbetween"
REPO_MODULE = "ballmorph_bench"
MODULE = f"bl_ext.{REPO_MODULE}.{ADDON_ID}"

KIND_TITLES = {
    "loops": "Loops (closed strokes)",
    "open": "Open strokes",
    "jagged": "Jagged redraws (open strokes retraced with a tremor: the fallback path)",
    "deforming": "Loops changing shape where they lie (each of key B key A's stretched 1.25x about its centre)",
}
STROKES = (10, 100, 400)
POINTS = (50, 200, 500)
INBETWEENS = (3, 9, 23)
METHODS = ("CIRCULAR_BALL", "LINEAR_BALL", "PARABOLIC_BALL")
QUICK_SIZES = ((10, 50, 3), (100, 200, 9))
# Jagged redraws cross their first drawing again and again: every pair is cut into dozens of
# lenses and many of them take the composite ball-morph or aligned interpolation (the fallback
# step), so they get a short grid of their own.
JAGGED_SIZES = ((10, 60, 9), (60, 60, 9), (200, 60, 9))
# Loops changing shape where they lie (issue 38): the goal sizes only.
DEFORMING_SIZES = ((100, 200, 9), (400, 500, 23))

# The goals of issue 14 (issue 6 asked for 1.5 and 1.0: out of reach for numpy, see its note).
GOAL_RATIOS = {(100, 200, 9): 8.0, (400, 500, 23): 5.0}  # cold run, ours (circular) / built-in, at most
REDO_GOAL = 1.0  # the redo (F9 with another easing) / built-in at the goal sizes, at most
# The scribble: random points in the unit square, against itself plus 1 % noise (one stroke each).
SCRIBBLE_POINTS = (1000, 2000, 3000)
SCRIBBLE_GOAL = (2000, 2.0)  # this many points in at most this many seconds
GOAL_METHOD = "CIRCULAR_BALL"
GOAL_MEMORY = 2.0  # peak memory ours / built-in on the largest drawing, at most
# Issue 41: peak memory of one cold circular run against the built-in's on a drawing of many
# strokes (kind, strokes x points x in-betweens), at most GOAL_MEMORY; not timed, only probed.
SCALE_MEMORY = ("open", (5000, 50, 3))
# Where re-running over the operator's own earlier in-betweens is timed too.
REPLACE_SIZES = ((100, 200, 9),)

# Repeats: a first run under WARM_UP seconds is a discarded warm-up (slower ones count); then
# runs until at least MIN_RUNS are done and BUDGET seconds spent, at most MAX_RUNS; runs slower
# than SLOW seconds stop at SLOW_RUNS, to keep the whole grid near ten minutes on two cores.
WARM_UP, BUDGET, MIN_RUNS, MAX_RUNS = 1.0, 1.0, 3, 9
SLOW, SLOW_RUNS = 2.5, 2
# The instrumented (stage) runs: this many, fewer for slow drawings.
STAGE_RUNS, STAGE_SLOW = 3, 1.0

BUILTIN_OPTIONS = {
    "step": 1,
    "layers": "ACTIVE",
    "exclude_breakdowns": False,
    "use_selection": False,
    "flip": "AUTO",
    "smooth_steps": 1,
    "smooth_factor": 0.0,
    "type": "LINEAR",
    "easing": "EASE_IN",
}
OURS_OPTIONS = {
    "frame_count": 0,  # every frame between the keys, as the built-in does with step 1
    "easing_type": "LINEAR",
    "easing": "EASE_IN",
    "layers": "ACTIVE",
    "selected_only": False,
    "carrier": "SIMILARITY",
    "matching": "AUTO",
    "unmatched": "MIDDLE",
}

# Stages of one operator run: stage -> (module under the add-on, attribute path) to wrap. Names
# that are missing (the core is being reworked) are skipped and the stage shows "n/a".
STAGES = {
    "keys": [("operators.keys", "layer_keys"), ("addon_logic.pairing", "intervals")],
    "read": [("operators.grease_pencil", "read_strokes")],
    "core": [("operators.plans", "PlanCache.plan"), ("ballmorph_core.drawing.plan", "InbetweenPlan.evaluate")],
    "match": [("ballmorph_core.drawing.plan", "match_strokes")],
    "ball-map": [
        ("ballmorph_core.drawing.pair_morphs.pipeline", "map_batch"),
        ("ballmorph_core.morphs.ball", "ball_map"),
        ("ballmorph_core.morphs.ball", "ball_maps"),
        ("ballmorph_core.morphs.composite", "dense_map_batch"),
    ],
    "frames": [
        ("ballmorph_core.drawing.frames.layout", "Layout.__init__"),
        ("ballmorph_core.drawing.frames.layout", "Layout.evaluate"),
    ],
    "assemble": [("ballmorph_core.drawing.plan", "assemble_frames")],
    "write": [("operators.writer", "write_all")],
}
CORE_PARTS = ("match", "ball-map", "frames", "assemble")

_console = sys.stdout


def say(text=""):
    print(text, file=_console, flush=True)


# -- Blender data ------------------------------------------------------------------------------


def enable_addon():
    """Enable the add-on from this checkout through a temporary development repository."""
    repo_dir = tempfile.mkdtemp(prefix="ballmorph-bench-repo-")
    link = os.path.join(repo_dir, ADDON_ID)
    os.symlink(ROOT, link)
    bpy.context.preferences.extensions.repos.new(
        name="Ball-morph bench", module=REPO_MODULE, custom_directory=repo_dir, source="USER"
    )
    addon_utils.enable(MODULE, default_set=True, handle_error=_raise)
    return link


def disable_addon(link):
    """Disable the add-on (bpy may hang at exit with operators registered) and drop the repo link."""
    addon_utils.disable(MODULE, default_set=True)
    os.unlink(link)
    os.rmdir(os.path.dirname(link))


def _raise(exc):
    raise exc


def addon_module(name):
    return importlib.import_module(f"{MODULE}.{name}")


def view3d_override():
    """Context of the factory screen's 3D viewport (Interpolate Sequence polls for it)."""
    window = bpy.context.window_manager.windows[0]
    area = next(a for a in window.screen.areas if a.type == "VIEW_3D")
    region = next(r for r in area.regions if r.type == "WINDOW")
    return bpy.context.temp_override(window=window, area=area, region=region)


def build_object(name, kind, key_a, key_b, last_frame):
    """A Grease Pencil object with layer 'Ink' holding both keys (written with the add-on's I/O)."""
    io = addon_module("operators.grease_pencil")
    core = addon_module("ballmorph_core")
    data = io.data_collection().new(name)
    material = bpy.data.materials.get("Bench ink")
    if material is None:
        material = bpy.data.materials.new("Bench ink")
        bpy.data.materials.create_gpencil_data(material)
    data.materials.append(material)
    obj = bpy.data.objects.new(name, data)
    bpy.context.scene.collection.objects.link(obj)
    data.layers.new("Ink")
    closed = kind in ("loops", "deforming")
    for number, strokes in ((1, key_a), (last_frame, key_b)):
        n = [len(s) for s in strokes]
        # Pressure-like radius on open strokes (thin ends), constant on loops.
        radius = [np.full(k, 0.01) if closed else 0.01 * (0.3 + 0.7 * np.sin(np.linspace(0, np.pi, k))) for k in n]
        keys = core.StrokeSet.from_strokes(
            strokes, cyclic=[closed] * len(strokes), radius=radius, opacity=[np.ones(k) for k in n]
        )
        io.write_strokes(data.layers["Ink"].frames.new(number).drawing, keys)
    return obj


def activate(obj):
    """Make ``obj`` the only selected, active object, in Edit Mode (inside the 3D viewport override)."""
    if bpy.context.object is not None and bpy.context.object.mode != "OBJECT":
        bpy.ops.object.mode_set(mode="OBJECT")
    for other in bpy.context.scene.objects:
        other.select_set(other == obj)
    bpy.context.view_layer.objects.active = obj
    bpy.ops.object.mode_set(mode="EDIT")


def remove_object(obj):
    if bpy.context.object is not None and bpy.context.object.mode != "OBJECT":
        bpy.ops.object.mode_set(mode="OBJECT")
    data = obj.data
    bpy.data.objects.remove(obj)
    addon_module("operators.grease_pencil").data_collection().remove(data)


def clear_between(obj, last_frame):
    """Remove every frame between the keys, and the add-on's record of the frames it made."""
    layer = obj.data.layers["Ink"]
    for number in [f.frame_number for f in layer.frames if 1 < f.frame_number < last_frame]:
        layer.frames.remove(number)
    record = addon_module("operators.generated").PROPERTY
    if record in obj.data:
        del obj.data[record]


def points_per_frame(obj, last_frame):
    """Points of the middle in-between (after a run), or 0 when there is none."""
    middle = 1 + (last_frame - 1) // 2
    frame = next((f for f in obj.data.layers["Ink"].frames if f.frame_number == middle), None)
    if frame is None or "position" not in frame.drawing.attributes:
        return 0
    return len(frame.drawing.attributes["position"].data)


# -- measuring ---------------------------------------------------------------------------------

try:
    _libc = ctypes.CDLL("libc.so.6")
except OSError:  # not glibc: no trimming
    _libc = None


def _status_kib(field_name):
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith(field_name + ":"):
                return int(line.split()[1])
    raise RuntimeError(f"/proc/self/status has no {field_name}")


def _reset_peak():
    """Hand freed heap back to the OS, reset the peak RSS to the current RSS; return it (KiB).

    Writing 5 to /proc/self/clear_refs resets VmHWM (Linux >= 4.0), so VmHWM after the run is
    the exact peak resident set during it, C++ allocations included, with no sampling interval
    in which a short peak could be missed.
    """
    if _libc is not None:
        _libc.malloc_trim(0)
    with open("/proc/self/clear_refs", "w") as refs:
        refs.write("5")
    return _status_kib("VmRSS")


def _peak_memory(base):
    """Peak RSS growth since :func:`_reset_peak`, MiB."""
    return (_status_kib("VmHWM") - base) / 1024.0


@dataclass
class Timing:
    """Run times (s) of one operator on one drawing, and the points of one in-between it made."""

    seconds: list = field(default_factory=list)
    points: int = 0

    @property
    def median(self):
        return statistics.median(self.seconds)


# What the runs are timed by (--clock): the wall clock, or this process's CPU time (every thread
# of it), which a machine busy with other work inflates far less.
CLOCKS = {"wall": time.perf_counter, "cpu": time.process_time}
CLOCK_TEXT = {
    "wall": "wall (`time.perf_counter`)",
    "cpu": "CPU time of the process, every thread of it (`time.process_time`, `--clock cpu`): the"
    " machine was busy with other work, which stretches wall times far more",
}
_clock = "wall"


def measure(run, clean, check, prime=False):
    """Time ``run()`` several times, calling ``clean()`` before each (see the repeat constants).

    ``check(result)`` validates each run's result. With ``prime`` the first run is always
    discarded (it sets up the state the timed runs start from).
    """
    timing = Timing()
    first = True
    while True:
        clean()
        gc.collect()
        start = CLOCKS[_clock]()
        result = run()
        seconds = CLOCKS[_clock]() - start
        check(result)
        if first and (prime or seconds < WARM_UP):
            first = False
            continue
        first = False
        timing.seconds.append(seconds)
        n = len(timing.seconds)
        if n >= MAX_RUNS or (n >= MIN_RUNS and sum(timing.seconds) >= BUDGET) or (seconds > SLOW and n >= SLOW_RUNS):
            return timing


class StageClock:
    """Wrap the add-on's functions named in :data:`STAGES` and add up their time per stage.

    Only the outermost call of a stage counts (a stage nested in itself is not counted twice);
    stages nest in each other on purpose (the core contains the ball-map).
    """

    def __init__(self):
        self.total = dict.fromkeys(STAGES, 0.0)
        self.depth = dict.fromkeys(STAGES, 0)
        self.found = dict.fromkeys(STAGES, False)
        self.results = []
        self._undo = []

    def __enter__(self):
        for stage, targets in STAGES.items():
            for module_name, path in targets:
                try:
                    owner = addon_module(module_name)
                except ImportError:
                    continue
                *parents, name = path.split(".")
                for parent in parents:
                    owner = getattr(owner, parent, None)
                original = getattr(owner, name, None) if owner is not None else None
                if original is None:
                    continue
                # A method a class inherits is wrapped on that class and removed again afterwards.
                inherited = isinstance(owner, type) and name not in vars(owner)
                setattr(owner, name, self._wrap(stage, original))
                self._undo.append((owner, name, None if inherited else original))
                self.found[stage] = True
        return self

    def __exit__(self, *exc):
        for owner, name, original in reversed(self._undo):
            if original is None:
                delattr(owner, name)
            else:
                setattr(owner, name, original)
        self._undo.clear()

    def _wrap(self, stage, function):
        @functools.wraps(function)
        def timed(*args, **kwargs):
            if self.depth[stage]:
                return function(*args, **kwargs)
            self.depth[stage] += 1
            start = CLOCKS[_clock]()
            try:
                result = function(*args, **kwargs)
            finally:
                self.total[stage] += CLOCKS[_clock]() - start
                self.depth[stage] -= 1
            if stage == "core" and type(result).__name__ == "InbetweenResult":
                self.results.append(result)
            return result

        return timed

    def reset(self):
        self.total = dict.fromkeys(STAGES, 0.0)
        self.results = []


def _derived(row):
    """Add the parts no wrapper measures: 'core rest' and 'other' (the operator's own overhead),
    and 'per pair' (ball-map seconds per stroke pair)."""
    core = row["core"]
    inner = [row[p] for p in CORE_PARTS if row[p] is not None]
    row["core rest"] = core - sum(inner) if core is not None else None
    row["other"] = row["operator"] - sum(row[p] for p in ("keys", "read", "core", "write") if row[p] is not None)
    row["per pair"] = row["ball-map"] / row["pairs"] if row["ball-map"] is not None and row["pairs"] else None
    return row


def _fell_back(result, method):
    """How many of an InbetweenResult's pairs used a fallback morph other than ``method``
    (the fallbacks named by the add-on's own core, found through the result's module)."""
    core = importlib.import_module(type(result).__module__.split(".drawing")[0])
    fallbacks = [f for f in core.FALLBACK_MORPHS if f != method]
    return sum(any(f in str(getattr(p, "method", "")) for f in fallbacks) for p in getattr(result, "pairs", []))


def stage_times(run, clean, runs, method):
    """Median per-stage seconds over ``runs`` instrumented operator runs (see :class:`StageClock`).

    Also 'operator' (the whole call), 'pairs' (stroke pairs) and 'fallbacks' (pairs one of whose
    pieces used a fallback morph, the core's ``FALLBACK_MORPHS``, other than the requested
    ``method``, a core method name), and :func:`_derived`'s parts.
    """
    per_run = []
    with StageClock() as clock:
        for _ in range(runs):
            clean()
            gc.collect()
            clock.reset()
            start = CLOCKS[_clock]()
            run()
            total = CLOCKS[_clock]() - start
            row = {stage: clock.total[stage] if clock.found[stage] else None for stage in STAGES}
            row["operator"] = total
            pairs = [p for result in clock.results for p in getattr(result, "pairs", [])]
            row["pairs"] = len(pairs)
            row["fallbacks"] = sum(_fell_back(result, method) for result in clock.results)
            per_run.append(_derived(row))
    clean()
    out = {}
    for key in per_run[0]:
        values = [r[key] for r in per_run]
        out[key] = None if values[0] is None else statistics.median(values)
    return out


BUILTIN = "BUILTIN"


def call(op):
    """Run one operator on the active object: Blender's (``BUILTIN``) or ours with method ``op``."""
    if op == BUILTIN:
        return bpy.ops.grease_pencil.interpolate_sequence("EXEC_DEFAULT", **BUILTIN_OPTIONS)
    return bpy.ops.ballmorph.inbetween("EXEC_DEFAULT", method=op, **OURS_OPTIONS)


@dataclass
class Case:
    """One drawing (kind and size) and everything measured on it."""

    kind: str
    strokes: int
    points: int
    inbetweens: int
    builtin: Timing = None
    ours: dict = field(default_factory=dict)
    redo: Timing = None
    replace: Timing = None
    stages: dict = None
    memory: dict = None

    @property
    def size(self):
        return (self.strokes, self.points, self.inbetweens)

    @property
    def label(self):
        return f"{self.strokes}x{self.points}x{self.inbetweens}"

    @property
    def last(self):
        """Key B's frame."""
        return self.inbetweens + 2


def _checker(obj, case):
    def check(result):
        if result != {"FINISHED"}:
            raise RuntimeError(f"{obj.name}: the operator returned {result}")
        made = sum(1 < f.frame_number < case.last for f in obj.data.layers["Ink"].frames)
        if made != case.inbetweens:
            raise RuntimeError(f"{obj.name}: {made} in-betweens instead of {case.inbetweens}")

    return check


def forget_plans():
    """Drop the plans our operator keeps for a redo, so the next run is cold."""
    addon_module("operators.plans").PLANS.clear()


def _cold(obj, case):
    """Before each run: the drawing as built, and no plan kept from an earlier run."""

    def clean():
        clear_between(obj, case.last)
        forget_plans()

    return clean


def _timed(case, obj, op):
    """:func:`measure` of one operator on its object, from cold (left clean afterwards)."""
    timing = measure(lambda: call(op), _cold(obj, case), _checker(obj, case))
    timing.points = points_per_frame(obj, case.last)  # the last run's frames are still there
    clear_between(obj, case.last)
    return timing


# A redo from F9 with another easing: the easings alternate so every run has new times.
REDO_EASINGS = (("SINE", "EASE_IN_OUT"), ("QUAD", "EASE_OUT"))


def _redo_timed(case, obj):
    """:func:`measure` of our operator re-run on the same keys with another easing each time
    (what dragging an F9 option costs): the plan of the primed first run is reused."""
    easings = itertools.cycle(REDO_EASINGS)

    def run():
        easing_type, easing = next(easings)
        options = {**OURS_OPTIONS, "easing_type": easing_type, "easing": easing}
        return bpy.ops.ballmorph.inbetween("EXEC_DEFAULT", method=GOAL_METHOD, **options)

    forget_plans()
    timing = measure(run, lambda: clear_between(obj, case.last), _checker(obj, case), prime=True)
    clear_between(obj, case.last)
    forget_plans()
    return timing


def run_case(case, methods, replace):
    """Build the two objects of one drawing and time everything on them."""
    key_a, key_b = make_keys(case.kind, case.strokes, case.points)
    builtin_obj = build_object(f"builtin {case.kind} {case.label}", case.kind, key_a, key_b, case.last)
    ours_obj = build_object(f"ours {case.kind} {case.label}", case.kind, key_a, key_b, case.last)
    bpy.context.scene.frame_current = 1  # both operators take the keys around the current frame
    try:
        with view3d_override():
            activate(builtin_obj)
            case.builtin = _timed(case, builtin_obj, BUILTIN)
            activate(ours_obj)
            for method in methods:
                case.ours[method] = _timed(case, ours_obj, method)
            if GOAL_METHOD in methods:
                case.redo = _redo_timed(case, ours_obj)
                clean = _cold(ours_obj, case)
                slow = case.ours[GOAL_METHOD].median > STAGE_SLOW
                core_name = addon_module("operators.options").option("method").value(GOAL_METHOD)
                runs = 1 if slow else STAGE_RUNS
                case.stages = stage_times(lambda: call(GOAL_METHOD), clean, runs, core_name)
                if replace:
                    # Re-running over the frames it made: the operator replaces them itself.
                    check = _checker(ours_obj, case)
                    case.replace = measure(lambda: call(GOAL_METHOD), forget_plans, check, prime=True)
                clean()
    finally:
        remove_object(builtin_obj)
        remove_object(ours_obj)


def probe(kind, size, op):
    """Peak memory of one cold run of ``op``, in this process (started fresh for it).

    Returns
    -------
    dict
        ``peak_mib`` (growth of the peak resident set during the run), ``seconds``, ``points``.
    """
    case = Case(kind, *size)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    link = enable_addon()  # for both operators, so the two processes start alike
    try:
        key_a, key_b = make_keys(kind, case.strokes, case.points)
        obj = build_object(f"probe {kind} {case.label}", kind, key_a, key_b, case.last)
        bpy.context.scene.frame_current = 1
        with view3d_override():
            activate(obj)
            gc.collect()
            base = _reset_peak()
            start = time.perf_counter()
            result = call(op)
            seconds = time.perf_counter() - start
            peak = _peak_memory(base)
            _checker(obj, case)(result)
            points = points_per_frame(obj, case.last)
            remove_object(obj)
    finally:
        disable_addon(link)
    return {"peak_mib": peak, "seconds": seconds, "points": points}


def memory_of(case, ops):
    """Run :func:`probe` for every operator in a fresh bpy process each; {op: peak MiB}."""
    out = {}
    for op in ops:
        proc = subprocess.run(
            [sys.executable, os.path.abspath(__file__), "--probe", case.kind, case.label, op],
            capture_output=True,
            text=True,
            timeout=1200,
        )
        lines = [line for line in proc.stdout.splitlines() if line.startswith("{")]
        if proc.returncode or not lines:
            raise RuntimeError(f"memory probe {case.kind} {case.label} {op} failed:\n{proc.stderr[-3000:]}")
        out[op] = json.loads(lines[-1])["peak_mib"]
    return out


# -- report ------------------------------------------------------------------------------------


def _ms(seconds):
    if seconds is None:
        return "n/a"
    ms = seconds * 1e3
    return f"{ms:.1f}" if ms < 100 else f"{ms:.0f}"


def _read(path):
    try:
        with open(path) as f:
            return f.read()
    except OSError:
        return ""


def _git(*args):
    try:
        return subprocess.run(["git", "-C", ROOT, *args], capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def machine():
    """What the numbers were measured on."""
    cpu = next(
        (
            line.split(":", 1)[1].strip()
            for line in _read("/proc/cpuinfo").splitlines()
            if line.startswith("model name")
        ),
        platform.processor() or "unknown",
    )
    mem = next((line.split()[1] for line in _read("/proc/meminfo").splitlines() if line.startswith("MemTotal")), "0")
    dirty = _git("status", "--porcelain", "--", "ballmorph_core", "operators")
    return {
        "nproc": os.cpu_count(),
        "cpu": cpu,
        "ram": f"{int(mem) / 1024**2:.1f} GiB",
        "bpy": bpy.app.version_string,
        "python": platform.python_version(),
        "numpy": np.__version__,
        "date": datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d %H:%M UTC"),
        "commit": _git("rev-parse", "--short", "HEAD") + (" + uncommitted changes to the core" if dirty else ""),
        "load": _read("/proc/loadavg").split()[:3],
    }


_SCRIBBLE = """
import sys, time
import numpy as np
sys.path.insert(0, sys.argv[1])
from ballmorph_core import StrokeSet, inbetween
rng = np.random.default_rng(1)
a = rng.random((int(sys.argv[2]), 2))
A = StrokeSet.from_strokes([a])
B = StrokeSet.from_strokes([a + 0.01 * rng.standard_normal(a.shape)])
started = time.perf_counter()
inbetween(A, B, [0.0, 0.5, 1.0])
print(time.perf_counter() - started)
"""


def scribble_times():
    """Seconds of one cold ``inbetween`` of the scribble per point count (fresh CPython each)."""
    times = {}
    for points in SCRIBBLE_POINTS:
        run = [sys.executable, "-c", _SCRIBBLE, ROOT, str(points)]
        times[points] = float(subprocess.run(run, capture_output=True, text=True, check=True).stdout)
        say(f"scribble {points} points: {times[points]:.2f} s")
    return times


def plain_rows(tool, *options):
    """The rows of ``tool`` (bench_ballmap.py or bench_matching.py), run with ``--json`` (and
    ``options``) in a plain CPython subprocess (no bpy imported)."""
    script = os.path.join(ROOT, "tools", tool)
    run = [sys.executable, script, "--json", *options]
    out = subprocess.run(run, capture_output=True, text=True, check=True).stdout
    return json.loads(out)


def _scale_memory_goal(memory):
    """The goal row of the peak memory at SCALE_MEMORY (``memory``: {op: MiB}, empty when not probed)."""
    if not memory:
        return []
    kind, size = SCALE_MEMORY
    ours, theirs = memory[GOAL_METHOD], memory[BUILTIN]
    ratio = ours / max(theirs, 1e-9)
    label = "x".join(map(str, size))
    goal = f"peak memory circular / built-in at {label} ({kind}, issue 41) <= {GOAL_MEMORY}"
    return [(goal, f"{ratio:.2f} ({ours:.1f} MiB / {theirs:.1f} MiB)", ratio <= GOAL_MEMORY)]


def goals(cases, ballmap_rows, methods, scribble, matching_rows=(), moving_rows=(), scale_memory=None):
    """(goal text, measured text, verdict) rows."""
    rows = [*_time_goals(cases), *_growth_goals(ballmap_rows, matching_rows, scribble), *_memory_goals(cases)]
    rows += _scale_memory_goal(scale_memory)
    worst = bench_matching.moving_goal(moving_rows) if moving_rows else None
    if worst is not None:
        sizes = f"{moving_rows[0]['n']:,} -> {moving_rows[-1]['n']:,}"
        goal = f"match_strokes of the moving drawing {sizes} strokes, per doubling <= {bench_matching.MOVING_GOAL}"
        rows.append((goal, f"{worst:.2f} (largest ratio)", worst <= bench_matching.MOVING_GOAL))
    return rows


def _time_goals(cases):
    """The cold and redo ratios against the built-in at the goal sizes."""
    rows = []
    by_key = {(c.kind, c.size): c for c in cases}
    for size, limit in GOAL_RATIOS.items():
        for kind in KINDS:
            case = by_key.get((kind, size))
            if case is None or GOAL_METHOD not in case.ours:
                continue
            ratio = case.ours[GOAL_METHOD].median / case.builtin.median
            rows.append(
                (
                    f"circular / built-in at {size[0]}x{size[1]}x{size[2]} ({kind}) <= {limit}",
                    f"{ratio:.2f} ({_ms(case.ours[GOAL_METHOD].median)} ms / {_ms(case.builtin.median)} ms)",
                    ratio <= limit,
                )
            )
            if case.redo is not None:
                ratio = case.redo.median / case.builtin.median
                rows.append(
                    (
                        f"the same, redo (F9 with another easing: the kept plan re-evaluated) ({kind}) <= {REDO_GOAL}",
                        f"{ratio:.2f} ({_ms(case.redo.median)} ms / {_ms(case.builtin.median)} ms)",
                        ratio <= REDO_GOAL,
                    )
                )
    return rows


def _growth_goals(ballmap_rows, matching_rows, scribble):
    """The plain-CPython goals: the ball-map's and the matching's growth, the scribble's time."""
    rows = []
    for which in bench_ballmap.SPACINGS:
        growth = bench_ballmap.goal(ballmap_rows, which) if ballmap_rows else None
        if growth is not None:
            rows.append(
                (
                    f"ball_map time(4000) / time(2000) vertices ({which} spacing) <= {bench_ballmap.GROWTH_GOAL}",
                    f"{growth:.2f}",
                    growth <= bench_ballmap.GROWTH_GOAL,
                )
            )
    growth = bench_matching.goal(matching_rows) if matching_rows else None
    if growth is not None:
        rows.append(
            (
                f"match_strokes time(1000) / time(500) reordered hatch lines <= {bench_matching.GROWTH_GOAL}",
                f"{growth:.2f}",
                growth <= bench_matching.GROWTH_GOAL,
            )
        )
    points, limit = SCRIBBLE_GOAL
    if points in scribble:
        rows.append(
            (
                f"the {points}-point scribble (core, cold) < {limit:g} s",
                f"{scribble[points]:.2f} s",
                scribble[points] < limit,
            )
        )
    return rows


def _memory_goals(cases):
    """Peak memory against the built-in on the largest drawing."""
    rows = []
    by_key = {(c.kind, c.size): c for c in cases}
    largest = max((c.size for c in cases), default=None, key=lambda s: s[0] * s[1] * s[2])
    for kind in KINDS:
        case = by_key.get((kind, largest))
        if case is None or not case.memory or GOAL_METHOD not in case.memory:
            continue
        ours, theirs = case.memory[GOAL_METHOD], case.memory[BUILTIN]
        ratio = ours / max(theirs, 1e-9)
        rows.append(
            (
                f"peak memory circular / built-in at {case.label} ({kind}) <= {GOAL_MEMORY}",
                f"{ratio:.2f} ({ours:.1f} MiB / {theirs:.1f} MiB)",
                ratio <= GOAL_MEMORY,
            )
        )
    return rows


def _kind_section(kind, rows, methods, short):
    """The report's tables for one kind of drawing (lines of markdown)."""
    lines = []
    title = KIND_TITLES[kind]
    lines += [
        "",
        f"## {title}",
        "",
        "Median operator time in ms (runs in brackets); ratio = ours / built-in; points = points"
        " of one in-between frame. Our runs are cold (no plan kept from an earlier run);"
        " *redo* is a circular run on the same keys with another easing, as F9 does (the"
        " kept plan re-evaluated at the new times, then written).",
        "",
        "| strokes x points x in-betweens | built-in | "
        + " | ".join(short.get(m, m) for m in methods)
        + " | redo | "
        + " | ".join(f"{short.get(m, m)} / built-in" for m in methods)
        + " | redo / built-in | points built-in / ours |",
        "|---|" + "---:|" * (1 + 2 * len(methods) + 3),
    ]
    for c in rows:
        redo = c.redo.median if c.redo is not None else None
        cells = [f"{_ms(c.builtin.median)} ({len(c.builtin.seconds)})"]
        cells += [f"{_ms(c.ours[m].median)} ({len(c.ours[m].seconds)})" for m in methods]
        cells.append(f"{_ms(redo)} ({len(c.redo.seconds)})" if redo is not None else "n/a")
        cells += [f"{c.ours[m].median / c.builtin.median:.1f}" for m in methods]
        cells.append(f"{redo / c.builtin.median:.1f}" if redo is not None else "n/a")
        ours_points = c.ours[methods[0]].points
        cells.append(f"{c.builtin.points} / {ours_points}")
        lines.append(f"| {c.label} | " + " | ".join(cells) + " |")
    staged = [c for c in rows if c.stages]
    if staged:
        lines += [
            "",
            f"### {title}: where a circular ball-morph run spends its time (ms)",
            "",
            f"Instrumented operator runs (median of {STAGE_RUNS}; one for runs over {STAGE_SLOW:g} s)."
            " *keys*: finding the keys and target frames; *read*: reading both keys into"
            " StrokeSets; *core*: planning (`plan_inbetween`) and evaluating the plan, and inside it *match*"
            " (stroke pairing), *ball-map* (`ball_maps`, all stroke pairs; *per pair* = ball-map"
            " / pairs), *frames* (frames evaluation: building the trajectories, evaluating them"
            " and the carrier at every in-between time), *assemble* (attributes and StrokeSets"
            " per frame) and *core rest* (plane fit, registration, crossings and lenses,"
            " fallbacks); *write*: the Blender write-back of every frame; *other*: the"
            " operator's own overhead. *fallbacks*: stroke pairs a piece of which took a fallback"
            " morph (composite ball-morph, aligned or linear interpolation, straight point motion).",
            "",
            "| size | operator | keys | read | core | match | ball-map | per pair | frames | assemble"
            " | core rest | write | other | pairs | fallbacks |",
            "|---|" + "---:|" * 14,
        ]
        columns = ("operator", "keys", "read", "core", "match", "ball-map", "per pair", "frames", "assemble")
        columns += ("core rest", "write", "other")
        for c in staged:
            cells = [_ms(c.stages[k]) for k in columns]
            cells += [str(int(c.stages["pairs"])), str(int(c.stages["fallbacks"]))]
            lines.append(f"| {c.label} | " + " | ".join(cells) + " |")
    replaced = [c for c in rows if c.replace is not None]
    if replaced:
        lines += [
            "",
            f"### {title}: re-running over the in-betweens it made (circular, ms)",
            "",
            "| size | from a clean drawing | replacing its earlier in-betweens |",
            "|---|---:|---:|",
        ]
        for c in replaced:
            lines.append(
                f"| {c.label} | {_ms(c.ours[GOAL_METHOD].median)} | {_ms(c.replace.median)} "
                f"({len(c.replace.seconds)}) |"
            )
    return lines


def report(
    cases, methods, ballmap_rows, scribble, info, wall, argv, matching_rows=(), moving_rows=(), scale_memory=None
):
    short = {"CIRCULAR_BALL": "circular", "LINEAR_BALL": "linear", "PARABOLIC_BALL": "parabolic"}
    lines = [
        "# Benchmark: Ball-morph In-between against Blender's Interpolate Sequence",
        "",
        "Generated by `make bench` (`tools/benchmark.py"
        + (" " + " ".join(argv) if argv else "")
        + "`); do not edit by hand.",
        "",
        "## Machine",
        "",
        f"- CPU: {info['cpu']}, `nproc` = {info['nproc']} (shared with other work: load average "
        f"{' '.join(info['load'])} at the start, {' '.join(info.get('load_end', []))} at the end)",
        f"- RAM: {info['ram']}",
        f"- Blender (bpy) {info['bpy']}, Python {info['python']}, numpy {info['numpy']}",
        f"- Date: {info['date']}; code: commit {info['commit']}",
        f"- Whole run: {wall / 60:.1f} min",
        "- Threads: one. The add-on starts no worker threads, so its default is that single thread.",
        f"- Clock: {CLOCK_TEXT[_clock]}",
        "",
        "## Goals (issue 14)",
        "",
        "| goal | measured | verdict |",
        "|---|---|---|",
    ]
    for goal, measured, ok in goals(cases, ballmap_rows, methods, scribble, matching_rows, moving_rows, scale_memory):
        lines.append(f"| {goal} | {measured} | {'pass' if ok else '**FAIL**'} |")
    for kind in KINDS:
        rows = [c for c in cases if c.kind == kind]
        if rows:
            lines += _kind_section(kind, rows, methods, short)
    lines += _memory_lines(cases, methods, short)
    lines += _scale_memory_lines(scale_memory)
    if scribble:
        lines += [
            "",
            "## The scribble (plain CPython, one cold `inbetween` each in a fresh process)",
            "",
            "One stroke of N random points in the unit square (its long edges cross each other about "
            "N^2 / 9 times) against the same points plus 1 % noise, in-betweened at t = 0, 0.5, 1.",
            "",
            "| points | seconds |",
            "|---:|---:|",
            *(f"| {n} | {t:.2f} |" for n, t in sorted(scribble.items())),
        ]
    if ballmap_rows:
        lines += [
            "",
            "## Ball-map scaling (plain CPython, `tools/bench_ballmap.py`)",
            "",
            bench_ballmap.description(),
            "",
            bench_ballmap.markdown(ballmap_rows),
        ]
    if matching_rows:
        lines += [
            "",
            "## Matching look-alike strokes (plain CPython, `tools/bench_matching.py`)",
            "",
            bench_matching.description(),
            "",
            bench_matching.markdown(matching_rows),
        ]
    lines += _moving_lines(moving_rows)
    lines += ["", method_notes(cases)]
    return "\n".join(lines) + "\n"


def _memory_lines(cases, methods, short):
    """The report's peak memory table (none when nothing was probed)."""
    probed = [c for c in cases if c.memory]
    if not probed:
        return []
    ops = [BUILTIN, *methods]
    lines = [
        "",
        "## Peak memory (MiB; one cold run, each in a fresh bpy process)",
        "",
        "| drawing | "
        + " | ".join("built-in" if op == BUILTIN else short.get(op, op) for op in ops)
        + " | circular / built-in |",
        "|---|" + "---:|" * (len(ops) + 1),
    ]
    for c in probed:
        cells = [f"{c.memory[op]:.1f}" for op in ops]
        ratio = c.memory[GOAL_METHOD] / max(c.memory[BUILTIN], 1e-9) if GOAL_METHOD in c.memory else None
        cells.append(f"{ratio:.1f}" if ratio is not None else "n/a")
        lines.append(f"| {c.kind} {c.label} | " + " | ".join(cells) + " |")
    return lines


def _scale_memory_lines(memory):
    """The report's line on the peak memory at SCALE_MEMORY (none when not probed)."""
    if not memory:
        return []
    kind, size = SCALE_MEMORY
    ratio = memory[GOAL_METHOD] / max(memory[BUILTIN], 1e-9)
    return [
        "",
        f"Many strokes (issue 41), probed only (built-in and circular): {kind} {'x'.join(map(str, size))}:"
        f" built-in {memory[BUILTIN]:.1f} MiB, circular {memory[GOAL_METHOD]:.1f} MiB ({ratio:.1f} times).",
    ]


def _moving_lines(rows):
    """The report's section on matching the moving drawing (none when not run)."""
    if not rows:
        return []
    return [
        "",
        "## Matching a moving drawing, 400 to 6,400 strokes (plain CPython, `tools/bench_matching.py --moving`)",
        "",
        bench_matching.moving_description(),
        "",
        bench_matching.markdown_moving(rows),
    ]


def method_notes(cases):
    """The 'How it is measured' section (with this run's repeat settings and spread)."""

    def spread(timings):
        values = [max(t.seconds) / min(t.seconds) - 1 for t in timings if len(t.seconds) > 1]
        return f"{100 * statistics.median(values):.0f} %" if values else "n/a"

    builtin = spread([c.builtin for c in cases])
    circular = spread([c.ours[GOAL_METHOD] for c in cases if GOAL_METHOD in c.ours])
    replaced = ", ".join("x".join(map(str, s)) for s in REPLACE_SIZES)
    return f"""## How it is measured

- **Drawings.** Strokes on a unit grid of the XZ (front) canvas, one layer, key A on frame 1
  and key B on frame in-betweens + 2; both operators fill every frame between (step 1 /
  `frame_count=0`). Key B is key A with the whole drawing moved a little, and every stroke moved,
  turned (up to 8 degrees), scaled (up to 8 %) and smoothly deformed (3 random harmonics along
  its normal, up to 6 % of its size), fixed seed: the strokes really morph (a rigid copy would be
  registered exactly and be trivially cheap). Loops and open strokes are separate drawings; key
  B has the same stroke and point counts, so both operators pair strokes by index. Jagged
  redraws (their own sizes, {", ".join("x".join(map(str, s)) for s in JAGGED_SIZES)}) are wavy
  strokes drawn twice over the same line with a tremor (0.01 of noise at every point, key B moved
  by (0.01, 0.005)): the drawings cross again and again, so each pair is cut into lenses and many
  lenses take the fallback step (composite ball-morph, else aligned interpolation).
- **Loops changing shape where they lie** (issue 38, at the goal sizes): key A is the loops'
  drawing's, each loop of key B key A's stretched 1.25x along an axis of its own about its
  centre, overlapping and crossing it.
- **Same process, identical copies.** Each drawing is built twice (the same arrays written
  twice), one object per operator, each in Edit Mode in the factory screen's 3D viewport:
  `grease_pencil.interpolate_sequence` only runs there (poll: 3D viewport, Grease Pencil paint
  settings). Options: built-in step 1, active layer, flip AUTO, no smoothing, linear; ours each
  ball-morph method with every other option at its default (similarity carrier, automatic
  matching, linear easing), called with `EXEC_DEFAULT`. Blender's reports are printed to the
  console in background mode; they go wherever stdout goes.
- **Runs.** `time.perf_counter()` (with `--clock cpu`: `time.process_time()`) around the
  operator call. Before every run the frames between the keys are removed (and the add-on's
  record of them), so every run starts from the same drawing, as a redo from F9 does (Blender
  undoes the previous run before running it again; in background mode undo is off for both
  operators, so its cost is in neither number). Our
  operator's kept plans (operators/plans.py) are dropped before each run, so these runs are
  cold; the *redo* column keeps them and changes the easing every run (Sine In-Out, Quad Out):
  the times change, the keys do not, as when an option is dragged in the F9 panel. Re-running
  without removing them (the operator then finds and replaces its own earlier in-betweens,
  fingerprinting each) is timed separately at {replaced}. A first run under {WARM_UP:g} s is a
  discarded warm-up; then at least {MIN_RUNS} runs and {BUDGET:g} s, at most {MAX_RUNS}; runs over
  {SLOW:g} s stop after {SLOW_RUNS}. The median is reported.
- **Stages.** Separate runs of the circular ball-morph with the add-on's functions wrapped
  (outermost call of each stage, `perf_counter`): `keys.layer_keys` + `pairing.intervals`,
  `grease_pencil.read_strokes`, `PlanCache.plan` and `InbetweenPlan.evaluate` (the core) and
  inside them `match_strokes`, `ball_maps`/`dense_map_batch`, the trajectories (`BallPaths`
  construction, every paths class's `at`, `Morph.frames`/`__call__`, the batch's `carrier_at`),
  `_assemble`; `writer.write_all`.
  The wrappers add a few microseconds per call; stages that the core no longer has show n/a.
- **Peak memory.** One cold run per operator and drawing, each in a fresh bpy process (this
  script with `--probe`): factory settings, the add-on enabled (for both operators, so both
  processes start alike), the drawing built, then freed heap handed back (`malloc_trim(0)`),
  the kernel's peak-RSS counter reset (`5` written to `/proc/self/clear_refs`), the operator run
  once; VmHWM minus the RSS before is its peak growth. That is exact for everything resident, C++
  allocations included, with no sampling interval in which a short peak could be missed. Why
  fresh processes: in one long process the allocators keep freed memory and the next run reuses
  it unseen (Blender's operator read 9 MiB cold and 0.8 MiB on the next runs at 100x200x9),
  which would flatter whichever operator frees memory the allocator keeps. Limits: the new
  frames stay in Blender after the run and count for both operators (ours writes about as many
  points, see the tables); page-granular (4 KiB); one run, so a few hundred KiB of noise.
- **Noise.** The machine is shared with other jobs (two cores; see the load average above).
  Run-to-run spread (slowest / fastest run - 1), median over the drawings: built-in {builtin},
  circular {circular}. Differences smaller than that between neighbouring sizes are noise.
"""


# -- main --------------------------------------------------------------------------------------


def parse_sizes(text):
    if text.lower() == "none":
        return []
    sizes = []
    for item in text.split(","):
        parts = item.lower().split("x")
        if len(parts) != 3:
            raise argparse.ArgumentTypeError(f"size {item!r}: expected STROKESxPOINTSxINBETWEENS, e.g. 100x200x9")
        sizes.append(tuple(int(p) for p in parts))
    return sizes


def parse_cases(text):
    """``KIND:SIZE,...`` -> {kind: [size, ...]} (kinds in the order first named)."""
    cases = {}
    for item in text.split(","):
        kind, _, size = item.partition(":")
        if kind not in KINDS or not size:
            raise argparse.ArgumentTypeError(
                f"case {item!r}: expected KIND:STROKESxPOINTSxINBETWEENS, KIND one of {KINDS}"
            )
        cases.setdefault(kind, []).extend(parse_sizes(size))
    return cases


def _default_memory_sizes(sizes):
    """The largest drawing of the run (the memory goal) and the goal sizes that are in the run."""
    largest = max(sizes, key=lambda s: s[0] * s[1] * s[2])
    return sorted({largest, *(s for s in GOAL_RATIOS if s in sizes)}, key=lambda s: s[0] * s[1] * s[2])


def _quiet_stdout():
    """Send fd 1 (where Blender prints every operator report) to /dev/null; return our own stdout."""
    console = os.fdopen(os.dup(sys.stdout.fileno()), "w")
    sys.stdout.flush()
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.stdout.fileno())
    os.close(devnull)
    return console


def _parser():
    parser = argparse.ArgumentParser(
        description="Benchmark the operator against Interpolate Sequence (issues 6 and 14)."
    )
    parser.add_argument(
        "--quick", action="store_true", help=f"only {', '.join('x'.join(map(str, s)) for s in QUICK_SIZES)}"
    )
    parser.add_argument("--sizes", type=parse_sizes, help="comma-separated STROKESxPOINTSxINBETWEENS")
    parser.add_argument(
        "--cases",
        type=parse_cases,
        help="comma-separated KIND:STROKESxPOINTSxINBETWEENS, e.g. deforming:400x500x23 (for --kinds and --sizes)",
    )
    parser.add_argument("--kinds", default=",".join(KINDS), help=f"any of {', '.join(KINDS)} (comma-separated)")
    parser.add_argument("--methods", default=",".join(METHODS), help="operator method ids, comma-separated")
    parser.add_argument(
        "--memory-sizes",
        type=parse_sizes,
        help="drawings to probe memory on (default: the largest and the goal sizes; 'none')",
    )
    parser.add_argument(
        "--no-ballmap", action="store_true", help="skip the ball-map and matching scaling and the scribble tables"
    )
    parser.add_argument("--clock", choices=sorted(CLOCKS), default="wall", help="what times the runs (default: wall)")
    parser.add_argument("--write", metavar="PATH", help="write the markdown report there (else print it)")
    parser.add_argument("--probe", nargs=3, metavar=("KIND", "SIZE", "OP"), help=argparse.SUPPRESS)
    return parser


def _chosen_sizes(args, kind):
    """The sizes run for drawings of ``kind``."""
    if args.sizes:
        sizes = args.sizes
    elif kind == "jagged":
        sizes = list(JAGGED_SIZES[:2] if args.quick else JAGGED_SIZES)
    elif kind == "deforming":
        sizes = list(DEFORMING_SIZES[:1] if args.quick else DEFORMING_SIZES)
    elif args.quick:
        sizes = list(QUICK_SIZES)
    else:
        sizes = [(s, p, t) for s in STROKES for p in POINTS for t in INBETWEENS]
    return sorted(sizes, key=lambda s: (s[0] * s[1] * s[2], s))


def _run_cases(sizes, methods, started):
    """Every case timed in this process (the add-on enabled meanwhile); ``sizes``: kind -> its sizes."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    link = enable_addon()
    cases = []
    try:
        for kind, kind_sizes in sizes.items():
            for strokes, points, inbetweens in kind_sizes:
                case = Case(kind, strokes, points, inbetweens)
                run_case(case, methods, replace=case.size in REPLACE_SIZES)
                cases.append(case)
                ours = "  ".join(f"{m.split('_')[0].lower()} {_ms(t.median)}" for m, t in case.ours.items())
                say(
                    f"{kind:6s} {case.label:>10s}: built-in {_ms(case.builtin.median)} ms  {ours} ms  "
                    f"({time.perf_counter() - started:.0f} s so far)"
                )
    finally:
        disable_addon(link)
    return cases


def main(argv=None):
    global _console, _clock
    argv = sys.argv[1:] if argv is None else argv
    parser = _parser()
    args = parser.parse_args(argv)
    _clock = args.clock
    _console = _quiet_stdout()
    if args.probe:  # a child of memory_of()
        kind, size, op = args.probe
        say(json.dumps(probe(kind, parse_sizes(size)[0], op)))
        return 0
    kinds = [k for k in args.kinds.split(",") if k]
    methods = [m for m in args.methods.split(",") if m]
    for kind in kinds:
        if kind not in KINDS:
            parser.error(f"--kinds: {kind!r} is not one of {', '.join(KINDS)}")
    sizes = args.cases or {kind: _chosen_sizes(args, kind) for kind in kinds}
    every = [size for kind_sizes in sizes.values() for size in kind_sizes]
    memory_sizes = args.memory_sizes if args.memory_sizes is not None else _default_memory_sizes(every)
    info = machine()
    say(f"benchmark: bpy {info['bpy']}, {info['cpu']}, nproc {info['nproc']}, commit {info['commit']}")
    started = time.perf_counter()
    cases = _run_cases(sizes, methods, started)
    for case in cases:
        if case.size in memory_sizes:
            case.memory = memory_of(case, [BUILTIN, *methods])
            say(f"memory {case.kind} {case.label}: " + "  ".join(f"{op} {v:.1f} MiB" for op, v in case.memory.items()))
    ballmap_rows = [] if args.no_ballmap else plain_rows("bench_ballmap.py")
    matching_rows = [] if args.no_ballmap else plain_rows("bench_matching.py")
    moving_rows = [] if args.no_ballmap else plain_rows("bench_matching.py", "--moving")
    scale_memory = None
    if not args.no_ballmap:
        scale_memory = memory_of(Case(SCALE_MEMORY[0], *SCALE_MEMORY[1]), [BUILTIN, GOAL_METHOD])
        say("memory at " + "  ".join(f"{op} {v:.1f} MiB" for op, v in scale_memory.items()))
    scribble = {} if args.no_ballmap else scribble_times()
    info["load_end"] = _read("/proc/loadavg").split()[:3]
    wall = time.perf_counter() - started
    text = report(cases, methods, ballmap_rows, scribble, info, wall, argv, matching_rows, moving_rows, scale_memory)
    if args.write:
        with open(args.write, "w") as f:
            f.write(text)
        say(f"wrote {args.write}")
    else:
        say(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
