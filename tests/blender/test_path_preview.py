"""The path preview (issue 13.4): the sidebar toggle's draw handler and the geometry it draws."""

import importlib
import pathlib
import sys
import types

import bpy
import gp_data
import numpy as np
import pytest
from conftest import MODULE, disable_addon, enable_addon

import ballmorph_core as bm


@pytest.fixture
def preview(addon):
    """The add-on's draw-handler module and its geometry cache."""
    return (
        importlib.import_module(f"{MODULE}.ui.path_preview"),
        importlib.import_module(f"{MODULE}.operators.preview").PREVIEW,
    )


def _ours(functions):
    return [f for f in functions if getattr(f, "__module__", "").startswith(MODULE)]


def _our_app_handlers():
    """This add-on's functions in any of bpy.app.handlers' lists."""
    handlers = bpy.app.handlers
    return {name: _ours(getattr(handlers, name)) for name in dir(handlers) if isinstance(getattr(handlers, name), list)}


def _draw_handler_removed(handle):
    """Whether Blender no longer has the draw handler ``handle`` (removing it again fails)."""
    try:
        bpy.types.SpaceView3D.draw_handler_remove(handle, "WINDOW")
    except ValueError:
        return True
    return False


def _preview_updates():
    """The path preview's own functions in depsgraph_update_post (the hints' dots have theirs)."""
    return [f for f in _our_app_handlers()["depsgraph_update_post"] if f.__module__.endswith(".path_preview")]


def test_the_toggle_installs_and_removes_the_draw_handler(preview):
    handler, _ = preview
    settings = bpy.context.scene.ballmorph_inbetween
    assert not settings.path_preview and not handler.installed()
    assert _preview_updates() == []
    settings.path_preview = True
    assert handler.installed()
    handle = handler._handle
    assert _preview_updates() == [handler._edited]
    settings.path_preview = False
    assert not handler.installed() and _draw_handler_removed(handle)
    assert _preview_updates() == []


def test_disabling_the_addon_leaves_no_handler(preview):
    handler, _ = preview
    bpy.context.scene.ballmorph_inbetween.path_preview = True
    handle = handler._handle
    assert handle is not None
    disable_addon()
    assert _draw_handler_removed(handle)
    assert not any(_our_app_handlers().values()), _our_app_handlers()
    assert not handler.installed()
    enable_addon()  # the scene still has the toggle on: enabling installs the handler again
    assert importlib.import_module(f"{MODULE}.ui.path_preview").installed()


def test_a_file_saved_with_the_toggle_on_shows_the_preview_when_loaded(preview, tmp_path):
    handler, _ = preview
    settings = bpy.context.scene.ballmorph_inbetween
    settings.path_preview = True
    bpy.ops.wm.save_as_mainfile(filepath=str(tmp_path / "on.blend"))
    settings.path_preview = False
    bpy.ops.wm.save_as_mainfile(filepath=str(tmp_path / "off.blend"))
    assert not handler.installed()
    bpy.ops.wm.open_mainfile(filepath=str(tmp_path / "on.blend"))
    assert bpy.context.scene.ballmorph_inbetween.path_preview and handler.installed()
    bpy.ops.wm.open_mainfile(filepath=str(tmp_path / "off.blend"))
    assert not handler.installed()


def _expected(obj, frame_a, frame_b, **options):
    """The core's preview of a layer's two keys, computed here independently, in world space."""
    layer = obj.data.layers.active
    local = np.array(layer.matrix_local, dtype=np.float64)
    keys = []
    for number in (frame_a, frame_b):
        key = gp_data.read_strokes(gp_data.frame_at(layer, number).drawing)
        key.positions = key.positions.astype(np.float64) @ local[:3, :3].T + local[:3, 3]
        keys.append(key)
    plan = bm.plan_inbetween(*keys, **options)
    return bm.path_preview(plan).transformed(np.array(obj.matrix_world, dtype=np.float64))


def test_the_geometry_is_the_cores_preview_of_the_keys_around_the_frame_in_world_space(shot, preview):
    _, cache = preview
    layer = shot.data.layers["Ink"]
    layer.translation, layer.rotation, layer.scale = (0.3, 0.0, -0.2), (0.0, 0.4, 0.0), (1.2, 1.0, 1.2)
    shot.location, shot.rotation_euler, shot.scale = (2.0, -1.0, 0.5), (0.2, 0.1, 0.6), (1.5, 1.5, 1.5)
    bpy.context.view_layer.update()
    got = cache.world(bpy.context)
    want = _expected(shot, 1, 9)
    assert len(got) == len(want) == 2 * bm.PREVIEW_POINTS  # a loop and an arc, 8 trajectories each
    np.testing.assert_allclose(got.points, want.points, rtol=0, atol=1e-9)
    np.testing.assert_array_equal(got.pair, want.pair)
    np.testing.assert_array_equal(got.strokes, [[0, 0], [1, 1]])


def test_the_geometry_follows_the_sidebar_options_and_the_current_frame(shot, preview):
    _, cache = preview
    settings = bpy.context.scene.ballmorph_inbetween
    settings.method, settings.carrier = "LINEAR_BALL", "NONE"
    got = cache.world(bpy.context)
    np.testing.assert_allclose(got.points, _expected(shot, 1, 9, method="linear-ball", carrier="none").points)
    bpy.context.scene.frame_current = 9  # no key after the last one: nothing to preview
    assert cache.world(bpy.context) is None
    bpy.context.scene.frame_current = 1
    assert cache.world(bpy.context) is not None


def test_the_preview_follows_the_playhead_not_the_dope_sheet_selection(shot, preview):
    _, cache = preview
    layer = shot.data.layers["Ink"]
    gp_data.add_key(layer, 13, [gp_data.loop(0.7), gp_data.arc(0.1)], cyclic=[True, False])
    for number in (1, 9):
        gp_data.frame_at(layer, number).select = True  # the operator would in-between 1 -> 9
    bpy.context.scene.frame_current = 10
    bpy.context.scene.ballmorph_inbetween.key_motion = "PER_INTERVAL"  # (Smooth: test_arcs.py)
    np.testing.assert_allclose(cache.world(bpy.context).points, _expected(shot, 9, 13).points, atol=1e-9)


def test_a_morph_is_computed_only_when_the_frame_interval_keys_or_options_change(shot, preview):
    _, cache = preview
    computed = cache.computed
    first = cache.world(bpy.context)
    assert cache.computed == computed + 1
    for frame in (5, 8, 1):  # the same keys around every frame from 1 to 8
        bpy.context.scene.frame_current = frame
        np.testing.assert_array_equal(cache.world(bpy.context).points, first.points)
    assert cache.computed == computed + 1
    bpy.context.scene.ballmorph_inbetween.frame_count = 3  # the in-betweens' times: not the paths
    assert cache.world(bpy.context) is not None and cache.computed == computed + 1
    bpy.context.scene.ballmorph_inbetween.method = "PARABOLIC_BALL"
    cache.world(bpy.context)
    assert cache.computed == computed + 2
    # An edit of a key (a depsgraph update) gives other trajectories.
    bpy.context.scene.ballmorph_inbetween.path_preview = True  # the handler counts the edits
    drawing = gp_data.frame_at(shot.data.layers["Ink"], 9).drawing
    position = drawing.attributes["position"]
    points = np.empty(len(position.data) * 3, np.float32)
    position.data.foreach_get("vector", points)
    position.data.foreach_set("vector", points + 0.25)
    drawing.tag_positions_changed()
    bpy.context.view_layer.update()
    moved = cache.world(bpy.context)
    assert cache.computed == computed + 3
    ends = moved.points[:, -1]
    np.testing.assert_allclose(ends, _expected(shot, 1, 9, method="parabolic-ball").points[:, -1], atol=1e-9)
    assert np.abs(ends - first.points[:, -1]).max() > 0.1


def test_the_operators_kept_plan_is_reused(shot, preview):
    _, cache = preview
    assert bpy.ops.ballmorph.inbetween() == {"FINISHED"}
    planned = cache.planned
    assert cache.world(bpy.context) is not None
    assert cache.planned == planned  # the operator's plan of the same keys and options
    # The in-betweens it wrote are not keys: the preview still spans frames 1 to 9.
    np.testing.assert_allclose(cache.world(bpy.context).points, _expected(shot, 1, 9).points, atol=1e-9)


def test_no_grease_pencil_object_or_keys_means_no_preview(addon, preview):
    _, cache = preview
    bpy.context.scene.ballmorph_inbetween.path_preview = True  # the handler counts the edits

    def world():
        bpy.context.view_layer.update()
        return cache.world(bpy.context)

    assert world() is None  # nothing active
    obj = gp_data.new_object()
    assert world() is None  # no keys
    gp_data.add_key(obj.data.layers["Ink"], 1, [gp_data.arc(0.3)])
    assert world() is None  # one key
    obj.data.layers["Ink"].frames.new(5)  # an empty key: the stroke disappears
    empty = world()
    assert empty is not None and len(empty) == 0


def test_in_background_the_handler_draws_nothing_and_raises_nothing(shot, preview, monkeypatch):
    handler, cache = preview
    assert bpy.app.background
    bpy.context.scene.ballmorph_inbetween.path_preview = True
    fake = _FakeGPU()  # what a draw would ask of the GPU
    fake.install(monkeypatch)
    computed = cache.computed
    assert handler.draw() is None
    assert fake.log == [] and fake.batches == [] and cache.computed == computed  # not even the geometry


class _FakeGPU:
    """Stands in for the ``gpu`` module and ``gpu_extras.batch`` (background mode has no GPU):
    records what the draw handler asks of them."""

    def __init__(self):
        self.log = []
        self.shader = types.SimpleNamespace(uniform_float=lambda name, value: self.log.append((name, value)))
        self.shader_module = types.SimpleNamespace(from_builtin=self._from_builtin)
        self.state = types.SimpleNamespace(
            blend_set=lambda mode: self.log.append(("blend", mode)), viewport_get=lambda: (0, 0, 640, 480)
        )
        self.batches = []

    def _from_builtin(self, name):
        self.log.append(("shader", name))
        return self.shader

    def batch_for_shader(self, shader, kind, content, indices=None):
        batch = types.SimpleNamespace(kind=kind, content=content, indices=indices)
        batch.draw = lambda used: self.log.append(("draw", batch, used))
        self.batches.append(batch)
        return batch

    def install(self, monkeypatch):
        monkeypatch.setitem(sys.modules, "gpu", types.SimpleNamespace(shader=self.shader_module, state=self.state))
        monkeypatch.setitem(
            sys.modules, "gpu_extras.batch", types.SimpleNamespace(batch_for_shader=self.batch_for_shader)
        )


def test_the_trajectories_become_one_batch_of_lines_coloured_by_pair(shot, preview, monkeypatch):
    handler, cache = preview
    fake = _FakeGPU()
    fake.install(monkeypatch)
    world = cache.world(bpy.context)
    handler._draw_lines(world)
    handler._draw_lines(world)  # a redraw: the same batch
    assert len(fake.batches) == 1
    batch = fake.batches[0]
    vertices, indices, owner = world.segments()
    assert batch.kind == "LINES"
    np.testing.assert_array_equal(batch.content["pos"], vertices.astype(np.float32))
    np.testing.assert_array_equal(
        batch.content["color"], bm.pair_colors(world.pair, handler.ALPHA)[owner].astype(np.float32)
    )
    np.testing.assert_array_equal(batch.indices, indices)
    draws = [entry for entry in fake.log if entry[0] == "draw"]
    assert len(draws) == 2 and all(used is fake.shader for _, _, used in draws)
    assert ("shader", handler.SHADER) in fake.log
    assert ("viewportSize", (640, 480)) in fake.log and ("lineWidth", handler.LINE_WIDTH) in fake.log
    assert fake.log[-1] == ("blend", "NONE")  # the GPU state is left as it was found
    handler._draw_lines(bm.PathPreview(world.points[:2], world.pair[:2], world.times, world.strokes))
    assert len(fake.batches) == 2  # other trajectories: a new batch


def test_the_shader_is_one_this_blenders_own_scripts_draw_with(preview):
    # Built-in shader names changed across versions (the 3D_ prefixes went in 4.0) and
    # background mode cannot create shaders: check the name against the scripts Blender ships.
    handler, _ = preview
    scripts = pathlib.Path(bpy.utils.system_resource("SCRIPTS"))
    call = f"from_builtin('{handler.SHADER}')"
    assert any(call in path.read_text(errors="ignore") for path in scripts.rglob("*.py")), handler.SHADER
