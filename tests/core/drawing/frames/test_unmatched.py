"""Strokes without a partner (drawing/unmatched.py): switch, hold, fade, shrink, shrink into the
nearest paired stroke."""

import numpy as np
import pytest
from shapes import circle

import ballmorph_core as bm

TIMES = np.linspace(0.0, 1.0, 5)


def keys():
    """A face outline in both keys (moving right), a sweat drop only in the first key."""
    face = circle(1.0, 60)
    drop = circle(0.1, 20, centre=(1.3, 0.0))
    key_a = bm.StrokeSet.from_strokes([face, drop], cyclic=[True, True])
    key_b = bm.StrokeSet.from_strokes([face + [1.0, 0.0]], cyclic=[True])
    return key_a, key_b, drop


def the_drop(frame):
    """The drop's points in a frame (its second stroke), or None when it is not shown."""
    return frame.positions[frame.points(1)][:, [0, 2]] if len(frame) > 1 else None


def test_fade_keeps_the_stroke_and_fades_its_opacity():
    key_a, key_b, drop = keys()
    result = bm.inbetween(key_a, key_b, TIMES, unmatched="fade")
    shown = [the_drop(f) for f in result.frames]
    assert all(s is not None for s in shown[:-1]) and shown[-1] is None  # gone at the second key
    for t, frame in zip(TIMES[:-1], result.frames[:-1]):
        np.testing.assert_allclose(frame.opacity[frame.points(1)], 1.0 - t, atol=1e-12)
        np.testing.assert_allclose(the_drop(frame), drop, atol=1e-12)
    assert any("fades out" in m.text for m in result.messages)


def test_shrink_slides_the_stroke_into_its_middle():
    key_a, key_b, drop = keys()
    result = bm.inbetween(key_a, key_b, TIMES, unmatched="shrink")
    lengths = []
    for frame in result.frames[:-1]:
        xy = the_drop(frame)
        assert np.abs(np.linalg.norm(xy - (1.3, 0.0), axis=1) - 0.1).max() < 2e-3  # on the drop's chords
        lengths.append(np.linalg.norm(np.diff(xy, axis=0), axis=1).sum())
    assert np.all(np.diff(lengths) < 0)
    assert the_drop(result.frames[-1]) is None


def test_neighbour_shrinks_into_the_nearest_stroke_and_follows_it():
    key_a, key_b, drop = keys()
    result = bm.inbetween(key_a, key_b, TIMES, unmatched="neighbour")
    middle = the_drop(result.frames[2])
    # Half gone, and carried with the face (which moved by half its motion): shrunk to half its
    # size towards the face's point nearest it, (1, 0) moved to (1.5, 0).
    assert np.ptp(middle[:, 1]) == pytest.approx(0.5 * np.ptp(drop[:, 1]), rel=1e-6)
    assert middle[:, 0].min() == pytest.approx(1.5 + 0.5 * (1.2 - 1.0), abs=1e-3)
    end_times = bm.inbetween(key_a, key_b, [0.999], unmatched="neighbour")
    (point,) = {tuple(np.round(p, 2)) for p in the_drop(end_times.frames[0])}
    np.testing.assert_allclose(point, (2.0, 0.0), atol=0.01)  # into the face's point nearest the drop


@pytest.mark.parametrize("unmatched", ["middle", "hold", "fade", "shrink", "neighbour"])
def test_a_stroke_that_comes_is_drawn_as_in_its_key_at_the_end(unmatched):
    key_a, key_b, drop = keys()
    result = bm.inbetween(key_b, key_a, TIMES, unmatched=unmatched)  # the drop appears
    np.testing.assert_allclose(the_drop(result.frames[-1]), drop, atol=1e-12)
    if unmatched not in ("hold",):
        assert the_drop(result.frames[0]) is None
