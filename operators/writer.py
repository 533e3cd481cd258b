"""Write computed in-betweens as 'BREAKDOWN' frames, all or nothing.

Frames this add-on made earlier between the keys are removed first (their strokes are kept in
memory); then every in-between frame is created and filled. If anything fails, the frames this
run created are removed, the earlier ones restored and the record of generated frames put back,
so the layers are as they were, and the error is raised again for the caller to report.
"""

from dataclasses import dataclass

from . import generated, grease_pencil

__all__ = ["write_all"]


@dataclass
class _Removed:
    layer: object
    frame_number: int
    strokes: object  # StrokeSet in layer space


def _remove_earlier(morphed, removed):
    layer = morphed.layer
    frames = {frame.frame_number: frame for frame in layer.frames}
    for number in morphed.interval.replace:
        strokes = grease_pencil.read_strokes(frames[number].drawing)
        layer.frames.remove(number)
        removed.append(_Removed(layer, number, strokes))


def _new_breakdown(layer, number):
    frame = layer.frames.new(number)
    frame.keyframe_type = "BREAKDOWN"
    frame.select = False
    return frame


def _fill(grease_pencil_data, layer, frame, strokes, staging):
    written = grease_pencil.write_strokes(frame.drawing, strokes, staging=staging)
    generated.mark(grease_pencil_data, layer, frame, written)


def write_all(grease_pencil_data, morphed_list):
    """Write every interval's in-betweens.

    Parameters
    ----------
    grease_pencil_data : bpy.types.GreasePencil
    morphed_list : list of morph.Morphed
        Each frame is let go (``None`` in its ``frames``) once written.

    Returns
    -------
    int
        Frames written.
    """
    created, removed = [], []
    record = generated.save(grease_pencil_data)
    staging = grease_pencil.Staging()  # one set of conversion buffers for every frame
    try:
        for morphed in morphed_list:
            _remove_earlier(morphed, removed)
        for morphed in morphed_list:
            layer = morphed.layer
            for i, number in enumerate(morphed.interval.targets.tolist()):
                frame = _new_breakdown(layer, number)
                created.append((layer, number))
                _fill(grease_pencil_data, layer, frame, morphed.frames[i], staging)
                # Written: let it go, so Blender's copy of a big run's frames does not pile up on ours.
                morphed.frames[i] = None
    except Exception:
        _roll_back(grease_pencil_data, created, removed, record)
        raise
    return len(created)


def _roll_back(grease_pencil_data, created, removed, record):
    for layer, number in reversed(created):
        if any(frame.frame_number == number for frame in layer.frames):
            layer.frames.remove(number)
    for item in removed:
        grease_pencil.write_strokes(_new_breakdown(item.layer, item.frame_number).drawing, item.strokes)
    generated.restore(grease_pencil_data, record)
