"""The operator's options, declared once: enum tables, defaults, and the map to core names.

The same options appear three times in Blender: on the operator (what F9 edits), on the
scene (what the sidebar panel shows) and in the add-on preferences (the defaults). Each of
those builds its properties from :data:`OPTIONS` here, so labels, defaults and enum ids
never drift apart.
"""

from dataclasses import dataclass

import bpy

from ..ballmorph_core import METHODS as CORE_METHODS

__all__ = [
    "OPTIONS",
    "OPTION_NAMES",
    "Option",
    "CORE_METHOD",
    "method_label",
    "method_available",
    "property_annotations",
    "draw_options",
]

# Operator enum id -> (core method name, label, description). The ids are the operator's API.
_METHODS = (
    (
        "CIRCULAR_BALL",
        "circular-ball",
        "Circular Ball-morph",
        "Points travel on circular arcs tangent to both strokes: smooth, tight in-betweens",
    ),
    (
        "LINEAR_BALL",
        "linear-ball",
        "Linear Ball-morph",
        "Points travel straight between ball-map partners",
    ),
    (
        "PARABOLIC_BALL",
        "parabolic-ball",
        "Parabolic Ball-morph",
        "Points travel on parabolas through the maximal-disk centres",
    ),
    (
        "LINEAR_INTERPOLATION",
        "linear-interpolation",
        "Linear Interpolation",
        "Arc-length matched points move in straight lines (like Blender's Interpolate)",
    ),
    (
        "CLOSEST_PROJECTION",
        "closest-projection",
        "Closest Projection",
        "Each point moves to its closest point on the other stroke (comparison morph)",
    ),
    (
        "CURVATURE_INTERPOLATION",
        "curvature-interpolation",
        "Curvature Interpolation",
        "Edge lengths and turning angles are blended (Sederberg et al.; comparison morph)",
    ),
    (
        "LAPLACE_BLENDING",
        "laplace-blending",
        "Laplace Blending",
        "Laplacian coordinates are blended (comparison morph)",
    ),
    (
        "HEAT_PROPAGATION",
        "heat-propagation",
        "Heat Propagation",
        "In-betweens are iso-contours of heat flowing from one stroke to the other (comparison morph)",
    ),
)

#: Operator method id -> core method name.
CORE_METHOD = {ident: core for ident, core, _, _ in _METHODS}


def method_label(ident):
    """The animator-facing name of an operator method id."""
    return next(label for i, _, label, _ in _METHODS if i == ident)


def method_available(ident):
    """Whether the vendored core implements this method."""
    return CORE_METHOD.get(ident) in CORE_METHODS


_EASING_TYPES = (
    ("LINEAR", "Linear", "Straight-line interpolation between A and B (no easing)", "IPO_LINEAR"),
    ("SINE", "Sinusoidal", "Sinusoidal easing (weakest, almost linear but with a slight curvature)", "IPO_SINE"),
    ("QUAD", "Quadratic", "Quadratic easing", "IPO_QUAD"),
    ("CUBIC", "Cubic", "Cubic easing", "IPO_CUBIC"),
    ("QUART", "Quartic", "Quartic easing", "IPO_QUART"),
    ("QUINT", "Quintic", "Quintic easing", "IPO_QUINT"),
    ("EXPO", "Exponential", "Exponential easing (dramatic)", "IPO_EXPO"),
    ("CIRC", "Circular", "Circular easing (strongest and most dynamic)", "IPO_CIRC"),
    ("BACK", "Back", "Cubic easing with overshoot and settle", "IPO_BACK"),
    ("BOUNCE", "Bounce", "Exponentially decaying parabolic bounce, like when objects collide", "IPO_BOUNCE"),
    ("ELASTIC", "Elastic", "Exponentially decaying sine wave, like an elastic band", "IPO_ELASTIC"),
)
_EASING_MODES = (
    ("AUTO", "Automatic Easing", "Ease in for most types; ease out for Back, Bounce and Elastic", "IPO_EASE_IN_OUT"),
    ("EASE_IN", "Ease In", "Only on the end closest to the next key", "IPO_EASE_IN"),
    ("EASE_OUT", "Ease Out", "Only on the end closest to the first key", "IPO_EASE_OUT"),
    ("EASE_IN_OUT", "Ease In and Out", "Segment between both keys", "IPO_EASE_IN_OUT"),
)


@dataclass(frozen=True)
class Option:
    """One option: its kind ('ENUM', 'INT', 'BOOLEAN'), label, description and default.

    ``items`` are ``(id, label, description[, icon])`` for enums.
    """

    name: str
    kind: str
    label: str
    description: str
    default: object
    items: tuple = ()
    min: int = 0
    soft_max: int = 0

    def raw(self, value):
        """The value as Blender stores it (the item number for an enum)."""
        if self.kind == "ENUM":
            return [item[0] for item in self.items].index(value)
        return value


OPTIONS = (
    Option(
        "method",
        "ENUM",
        "Morph",
        "How points travel from the first key to the second",
        "CIRCULAR_BALL",
        items=tuple((i, label, desc) for i, _, label, desc in _METHODS),
    ),
    Option(
        "frame_count",
        "INT",
        "In-betweens",
        "Number of in-between frames, spread evenly between the keys (0: one on every frame)",
        0,
        min=0,
        soft_max=48,
    ),
    Option("easing_type", "ENUM", "Easing", "Interpolation easing (Blender's easing types)", "LINEAR", _EASING_TYPES),
    Option("easing", "ENUM", "Ease", "Which ends of the motion the easing affects", "EASE_IN", _EASING_MODES),
    Option(
        "layers",
        "ENUM",
        "Layers",
        "Which layers to in-between",
        "ACTIVE",
        (
            ("ACTIVE", "Active", "The active layer only"),
            ("ALL", "All", "Every visible, unlocked layer"),
        ),
    ),
    Option(
        "selected_only",
        "BOOLEAN",
        "Selected Strokes Only",
        "Morph only the selected strokes of each key into each other; the first key's other strokes are held unchanged",
        False,
    ),
    Option(
        "carrier",
        "ENUM",
        "Carrier Motion",
        "Overall motion carried along for strokes that moved, turned or grew between the keys",
        "SIMILARITY",
        (
            ("SIMILARITY", "Similarity", "Move, turn and scale along a steady spiral, then ball-morph the shape"),
            ("RIGID", "Rigid", "Move and turn only, then ball-morph the shape"),
            ("NONE", "None", "Pure ball-morph: no carrier motion"),
        ),
    ),
    Option(
        "matching",
        "ENUM",
        "Stroke Matching",
        "How the strokes of the two keys are paired",
        "AUTO",
        (
            ("AUTO", "Automatic", "By index when the stroke counts agree, otherwise by shape and position"),
            ("INDEX", "By Index", "The i-th stroke of one key with the i-th stroke of the other"),
        ),
    ),
    Option(
        "unmatched",
        "ENUM",
        "Unmatched Strokes",
        "What a stroke without a partner in the other key does",
        "MIDDLE",
        (
            ("MIDDLE", "Switch Halfway", "Shown until (or from) the middle of the in-betweens"),
            ("HOLD", "Hold", "Shown unchanged on every in-between"),
        ),
    ),
)

OPTION_NAMES = tuple(option.name for option in OPTIONS)


def _enum_items(option):
    """Blender enum items with explicit numbers (needed by get/set callbacks)."""
    return [(*item[:3], item[3] if len(item) > 3 else "NONE", number) for number, item in enumerate(option.items)]


def property_annotations(flags=None, getter=None, setter=None):
    """Blender properties for the options, to use as a class's ``__annotations__``.

    Parameters
    ----------
    flags : set of str, optional
        Blender property flags for every option (the operator passes ``{'SKIP_SAVE'}``).
    getter, setter : callable, optional
        Factories ``getter(option) -> get`` and ``setter(option) -> set`` (the scene settings use
        them to fall back to the preferences); without them the option's default is used.
    """
    annotations = {}
    for option in OPTIONS:
        kwargs = {"name": option.label, "description": option.description}
        if flags is not None:
            kwargs["options"] = set(flags)
        if getter is not None:
            kwargs["get"] = getter(option)
            kwargs["set"] = setter(option)
        else:
            kwargs["default"] = option.default
        if option.kind == "ENUM":
            annotations[option.name] = bpy.props.EnumProperty(items=_enum_items(option), **kwargs)
        elif option.kind == "INT":
            annotations[option.name] = bpy.props.IntProperty(min=option.min, soft_max=option.soft_max, **kwargs)
        else:
            annotations[option.name] = bpy.props.BoolProperty(**kwargs)
    return annotations


def draw_options(layout, data, compact=False):
    """Draw the options of ``data`` (operator, scene settings or preferences)."""
    layout.use_property_split = True
    layout.use_property_decorate = False
    col = layout.column()
    col.prop(data, "method")
    col.prop(data, "frame_count")
    col = layout.column()
    col.prop(data, "easing_type")
    sub = col.column()
    sub.active = data.easing_type != "LINEAR"
    sub.prop(data, "easing")
    col = layout.column()
    col.prop(data, "layers")
    col.prop(data, "selected_only")
    if compact:
        return
    col = layout.column()
    col.prop(data, "carrier")
    col.prop(data, "matching")
    col.prop(data, "unmatched")
