"""The demo's shots as plain numpy: the keys of every shot, stroke by stroke (x, z) on Blender's
front canvas.

Shared by the demo (tools/demo.py, inside Blender) and the core's golden test
(tests/scenarios/test_golden.py, plain CPython), so both see the same drawings.
"""

import numpy as np


def _loop(x, y):
    return np.c_[x, y]


def apple(n=160):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False) - np.pi / 2
    dimple = 0.08 * np.exp(-(((t - np.pi / 2) / 0.45) ** 2)) + 0.04 * np.exp(-(((t + np.pi / 2) / 0.5) ** 2))
    r = 1.0 - dimple + 0.04 * np.cos(2 * t)
    return _loop(1.08 * r * np.cos(t), r * np.sin(t))


def pear(n=160):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False) - np.pi / 2
    s = np.sin(t)
    width = 0.95 - 0.5 * np.clip(s, 0, None) ** 1.4
    return _loop(width * np.cos(t), 1.35 * s + 0.3)


def stem(base, top, n=20):
    u = np.linspace(0, 1, n)[:, None]
    bend = np.c_[0.08 * np.sin(np.pi * u[:, 0]), np.zeros(n)]
    return (1 - u) * np.asarray(base) + u * np.asarray(top) + bend


def bend_arch(n=90):
    """The golden test's bend, first key (tests/fixtures/golden_cases.py; the demo's until issue
    40 chose :func:`lean_left` and :func:`lean_right`, where the two morphs differ visibly)."""
    x = np.linspace(0, 2.4, n)
    return np.c_[x, 0.55 * np.sin(np.pi * x / 2.4)]


def bend_down(n=90):
    x = np.linspace(0, 2.4, n)
    return np.c_[x, -0.35 * np.sin(np.pi * x / 2.4) + 0.04 * np.sin(2 * np.pi * x / 2.4)]


def _lean(power, n=90):
    x = np.linspace(0, 2.4, n)
    return np.c_[x, 1.2 * np.sin(np.pi * (x / 2.4) ** power)]


def lean_left(n=90):
    """The demo's bend, first key: a hump leaning left (its ends stay put)."""
    return _lean(0.55, n)


def lean_right(n=90):
    """The demo's bend, second key: the hump leaning right; the two keys cross in the middle.

    The circular ball-morph swings the stroke over about that crossing, its top held flat at
    the crossing's height, where linear interpolation rounds it into a dome above it: their
    middle in-betweens lie 6% of the stroke's width apart, every in-between smooth (the keys of
    :func:`bend_arch` and :func:`bend_down` gave 0.7%, the same picture twice; a taller arch
    turned into a dip differs more, 14%, but its ball-morph in-betweens kink near the ends).
    """
    return _lean(1.85, n)


def ellipse(rx, rz, centre, n=96):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False) + np.pi / 2
    return np.c_[centre[0] + rx * np.cos(t), centre[1] + rz * np.sin(t)]


def floor(n=30):
    return np.c_[np.linspace(-1.2, 1.2, n), np.zeros(n)]


def pose(points, turn, centre):
    """Points turned by ``turn`` radians about the origin, then moved to ``centre``."""
    c, s = np.cos(turn), np.sin(turn)
    return points @ np.array([[c, s], [-s, c]]) + np.asarray(centre)


def head_outline(n=150):
    """A head seen from the front: round skull, narrower jaw, pointed chin (a loop, anticlockwise)."""
    t = np.linspace(0, 2 * np.pi, n, endpoint=False) + np.pi / 2
    low = np.clip(-np.sin(t), 0, None)  # 0 on the upper half, 1 at the chin
    x = 0.9 * np.cos(t) * (1 - 0.35 * low**1.5)
    return np.c_[x, 1.05 * np.sin(t) - 0.15 * low**3]


def bowed(start, end, sag, n=40):
    """A stroke from ``start`` to ``end`` bowed sideways by ``sag``."""
    u = np.linspace(0, 1, n)[:, None]
    start, end = np.asarray(start, float), np.asarray(end, float)
    d = end - start
    return start + u * d + sag * np.sin(np.pi * u) * np.array([-d[1], d[0]]) / np.linalg.norm(d)


def teardrop(centre, size, n=50):
    """A sweat drop: round at the bottom, pointed at the top (a loop)."""
    t = np.linspace(0, 2 * np.pi, n, endpoint=False) - np.pi / 2
    return np.c_[centre[0] + size * np.cos(t) * (1 - np.sin(t)) / 2, centre[1] + size * np.sin(t)]


def head_turn_keys():
    """(strokes, cyclic, materials) for the two keys of the head-turn shot, frames 1 and 11."""
    first_pose, second_pose = (0.0, (0.0, 0.0)), (0.35, (0.55, 0.15))
    first = [
        head_outline(),
        bowed((-0.6, 0.42), (-0.15, 0.52), 0.06),  # brow, drawn left to right
        ellipse(0.08, 0.1, (-0.35, 0.22), n=30),  # eye
        bowed((-0.45, -0.45), (0.15, -0.5), -0.12, 50),  # mouth, a small smile
    ]
    second = [
        # the outline, started at the chin and drawn clockwise this time
        np.roll(head_outline()[::-1], 70, axis=0),
        bowed((-0.1, 0.66), (-0.62, 0.5), -0.12),  # brow raised, drawn right to left
        ellipse(0.1, 0.14, (-0.33, 0.24), n=30),  # eye wide open
        bowed((-0.5, -0.42), (0.25, -0.38), -0.3, 50),  # mouth, a wide grin
    ]
    strokes_1 = [pose(s, *first_pose) for s in first]
    strokes_2 = [pose(s, *second_pose) for s in second] + [teardrop((1.6, 1.05), 0.16)]  # new: sweat
    return (
        (strokes_1, [True, False, True, False], [0, 0, 0, 0]),
        (strokes_2, [True, False, True, False, True], [0, 0, 0, 0, 1]),
    )
