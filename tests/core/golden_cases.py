"""The golden drawings: a fixed set of key pairs whose in-betweens are stored in ``golden/``.

A behaviour-preserving change (a refactor, a speed-up) must give the same frames; a change of
behaviour regenerates them with ``tools/golden.py --write`` in a commit that says why. The set
covers the demo's shots, every morph, every carrier, matching and unmatched option, crossing
splits, the composite ball-morph and the fallbacks (tangled crossings, a stroke crossing itself,
dots, mixed cyclic flags, side-by-side loops, non-planar keys).
"""

import os
import sys

import numpy as np
from shapes import circle

import ballmorph_core as bm

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
import shots  # the demo's drawings, plain numpy

#: The times every case is evaluated at.
TIMES = (0.0, 0.3, 0.5, 0.8, 1.0)

#: Where the stored frames live.
DIRECTORY = os.path.join(os.path.dirname(os.path.abspath(__file__)), "golden")


def _key(strokes, cyclic, **attributes):
    return bm.StrokeSet.from_strokes(strokes, cyclic=np.asarray(cyclic, bool), **attributes)


def _demo_shots():
    yield (
        "apple-pear",
        (
            _key([shots.apple(), shots.stem((0.0, 0.84), (0.12, 1.3))], [True, False]),
            _key([shots.pear(), shots.stem((0.0, 1.65), (0.16, 2.05))], [True, False]),
        ),
        {},
    )
    bend = (_key([shots.bend_arch()], [False]), _key([shots.bend_down()], [False]))
    yield "bend", bend, {}
    yield "bend-linear-interpolation", bend, {"method": "linear-interpolation"}
    balls = [
        shots.ellipse(0.5, 0.5, (0.0, 2.6)),
        shots.ellipse(0.36, 0.66, (0.0, 0.9)),
        shots.ellipse(0.72, 0.3, (0, 0.3)),
    ]
    squash = [_key([ball, shots.floor()], [True, False]) for ball in balls]
    yield "squash-fall", (squash[0], squash[1]), {"matching": "INDEX"}
    yield "squash-land", (squash[1], squash[2]), {"matching": "INDEX"}
    (a, cyc_a, mat_a), (b, cyc_b, mat_b) = shots.head_turn_keys()
    yield (
        "head-turn",
        (
            bm.StrokeSet.from_strokes(a, cyclic=np.asarray(cyc_a), material_index=mat_a),
            bm.StrokeSet.from_strokes(b, cyclic=np.asarray(cyc_b), material_index=mat_b),
        ),
        {},
    )


def _mixed_drawing():
    """Four strokes into five: a bump flips, a line reversed, a loop crossing its first position,
    a line moved, a new stroke; plus a self-crossing curl (a fallback) and a dot that grows."""
    x = np.linspace(0, 1, 60)
    t = np.linspace(0, 4 * np.pi, 90)
    curl = 0.2 * np.c_[t - 2 * np.sin(t), 1 - 2 * np.cos(t)]
    a = [
        np.c_[x, 0.3 * np.sin(np.pi * x)],
        np.c_[x, 2 + 0.1 * x],
        circle(0.3, 50, centre=(3.0, 1.0)),
        np.c_[x + 5, 0.5 * x],
        curl + (12, 0),
        np.array([[15.0, 0.0]]),
    ]
    b = [
        np.c_[x, -0.2 * np.sin(np.pi * x)],
        np.c_[x + 0.4, 2.3 - 0.1 * x][::-1],
        circle(0.35, 50, centre=(3.2, 1.1)),
        np.c_[x + 5.2, 0.4 + 0.3 * x],
        np.c_[x + 8, np.sin(3 * x)],
        curl * (1.0, 1.4) + (12.5, 0.2),
        np.array([[15.0, 0.0], [15.5, 0.3]]),
    ]
    sizes_a, sizes_b = [len(s) for s in a], [len(s) for s in b]
    key_a = _key(
        a,
        [False, False, True, False, False, False],
        radius=[np.linspace(0.01, 0.05, n) for n in sizes_a],
        vertex_color=[np.tile([0.2, 0.4, 0.6, 1.0], (n, 1)) for n in sizes_a],
    )
    key_b = _key(
        b,
        [False, False, True, False, False, False, False],
        radius=[np.full(n, 0.03) for n in sizes_b],
        opacity=[np.linspace(0.2, 1.0, n) for n in sizes_b],
    )
    return key_a, key_b


def _geometry_cases():
    ring = circle(1.0, 120)
    t = np.linspace(0, 2 * np.pi, 300, endpoint=False)
    notch = 1.0 - 0.6 * np.maximum(0, 1 - np.abs(np.angle(np.exp(1j * (t - 0.3)))) / 0.12)
    r = 1.6 + 0.25 * np.cos(t - np.pi / 2) + 0.1 * np.cos(2 * t)
    pear = np.c_[0.9 * r * np.cos(t), 1.2 * r * np.sin(t)]
    yield "composite-notch", (_key([notch[:, None] * np.c_[np.cos(t), np.sin(t)]], [True]), _key([pear], [True])), {}
    yield "crossing-loops", (_key([ring], [True]), _key([ring * (1.1, 0.8) + (0.4, 0.1)], [True])), {}
    yield (
        "crossing-loops-none",
        (_key([ring], [True]), _key([ring * (1.1, 0.8) + (0.4, 0.1)], [True])),
        {"carrier": "NONE"},
    )
    yield "touching-once", (_key([ring], [True]), _key([ring * 0.5 + (0.5, 0.0)], [True])), {"carrier": "NONE"}
    yield "side-by-side", (_key([ring], [True]), _key([ring + (3.0, 0.0)], [True])), {"carrier": "NONE"}
    wave = np.c_[np.linspace(0, 2, 80), 0.3 * np.sin(np.linspace(0, 6 * np.pi, 80))]
    yield "tangled-strokes", (_key([wave], [False]), _key([wave * (1, -1.5) + (0, 0.05)], [False])), {"carrier": "NONE"}
    yield "mixed-cyclic", (_key([ring], [True]), _key([ring[:100] * 1.2], [False])), {}
    x = np.linspace(0, 1, 40)
    lifted = _key([np.c_[x, 0.2 * np.sin(np.pi * x)]], [False])
    lifted.positions[:, 1] = 0.3 * x  # off the canvas: carried as a plane offset
    yield "non-planar", (lifted, _key([np.c_[x, -0.2 * np.sin(np.pi * x)]], [False])), {}
    grid = [np.c_[np.linspace(0, 1, 30), np.full(30, 0.1 * k)] for k in range(6)]
    yield "hatch-reordered", (_key(grid, [False] * 6), _key(grid[::-1], [False] * 6)), {}


def cases():
    """Every golden case: ``(name, key_a, key_b, options)`` for :func:`ballmorph_core.inbetween`."""
    out = [(name, a, b, opts) for name, (a, b), opts in _demo_shots()]
    out += [(name, a, b, opts) for name, (a, b), opts in _geometry_cases()]
    key_a, key_b = _mixed_drawing()
    for method in bm.METHODS:
        out.append((f"mixed-{method}", key_a, key_b, {"method": method}))
    for carrier in ("RIGID", "NONE"):
        for method in ("circular-ball", "linear-ball", "parabolic-ball"):
            out.append((f"mixed-{method}-{carrier.lower()}", key_a, key_b, {"method": method, "carrier": carrier}))
    out.append(("mixed-index-hold", key_a, key_b, {"matching": "INDEX", "unmatched": "HOLD"}))
    return out


#: StrokeSet arrays stored per frame.
FIELDS = ("positions", "offsets", "cyclic", "material_index", "radius", "opacity", "vertex_color", "origin")


def record(result):
    """The arrays of an InbetweenResult, as a flat dict for ``np.savez_compressed``."""
    out = {}
    for k, frame in enumerate(result.frames):
        for name in FIELDS:
            out[f"{k}/{name}"] = getattr(frame, name)
    out["messages"] = np.array([f"{m.level}: {m.text}" for m in result.messages], dtype=str)
    out["pairs"] = np.array([f"{p.stroke_a} {p.stroke_b} {p.method} | {p.reason}" for p in result.pairs], dtype=str)
    return out


def path(name):
    return os.path.join(DIRECTORY, f"{name}.npz")
