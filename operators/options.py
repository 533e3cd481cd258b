"""The operator's options, declared once: enum items with their core values, labels, defaults.

The same options appear four times: on the operator (what F9 edits), on the scene (what the
sidebar panel shows), in the add-on preferences (the defaults) and on the command line
(``blender -c ballmorph``). Each builds its options from :data:`OPTIONS` here, so labels,
defaults, Blender's enum ids and the values passed on never drift apart.

One vocabulary: every enum item pairs Blender's id (``'CIRCULAR_BALL'``, the operator's API)
with its lowercase value (``'circular-ball'``): the core's own name for it, or, for the
add-on's own options (``layers``), the word the command line takes. Everything past the
Blender properties works with values: :func:`values_of` reads them from any holder of the
properties, and only values reach the core.
"""

from dataclasses import dataclass

import bpy

from ..ballmorph_core import METHODS as CORE_METHODS

__all__ = [
    "OPTIONS",
    "OPTION_NAMES",
    "Item",
    "Option",
    "option",
    "values_of",
    "label",
    "method_available",
    "property_annotations",
    "draw_options",
]


@dataclass(frozen=True)
class Item:
    """One enum item: Blender's id, the lowercase value it stands for, what the animator reads.

    ``research``: a comparison morph from the paper, offered in the sidebar's Morph list but
    not in the menus' quick list.
    """

    id: str
    value: str
    label: str
    description: str
    icon: str = "NONE"
    research: bool = False


_METHODS = (
    Item(
        "CIRCULAR_BALL",
        "circular-ball",
        "Circular Ball-morph",
        "Points travel on circular arcs tangent to both strokes: smooth, tight in-betweens",
    ),
    Item("LINEAR_BALL", "linear-ball", "Linear Ball-morph", "Points travel straight between ball-map partners"),
    Item(
        "PARABOLIC_BALL",
        "parabolic-ball",
        "Parabolic Ball-morph",
        "Points travel on parabolas through the maximal-disk centres",
    ),
    Item(
        "LINEAR_INTERPOLATION",
        "linear-interpolation",
        "Linear Interpolation",
        "Arc-length matched points move in straight lines (like Blender's Interpolate)",
    ),
    Item(
        "CLOSEST_PROJECTION",
        "closest-projection",
        "Closest Projection",
        "Each point moves to its closest point on the other stroke (comparison morph)",
        research=True,
    ),
    Item(
        "CURVATURE_INTERPOLATION",
        "curvature-interpolation",
        "Curvature Interpolation",
        "Edge lengths and turning angles are blended (Sederberg et al.; comparison morph)",
        research=True,
    ),
    Item(
        "LAPLACE_BLENDING",
        "laplace-blending",
        "Laplace Blending",
        "Laplacian coordinates are blended (comparison morph)",
        research=True,
    ),
    Item(
        "HEAT_PROPAGATION",
        "heat-propagation",
        "Heat Propagation",
        "In-betweens are iso-contours of heat flowing from one stroke to the other (comparison morph)",
        research=True,
    ),
)

_EASING_TYPES = (
    Item("LINEAR", "linear", "Linear", "Straight-line interpolation between A and B (no easing)", "IPO_LINEAR"),
    Item(
        "SINE",
        "sine",
        "Sinusoidal",
        "Sinusoidal easing (weakest, almost linear but with a slight curvature)",
        "IPO_SINE",
    ),
    Item("QUAD", "quad", "Quadratic", "Quadratic easing", "IPO_QUAD"),
    Item("CUBIC", "cubic", "Cubic", "Cubic easing", "IPO_CUBIC"),
    Item("QUART", "quart", "Quartic", "Quartic easing", "IPO_QUART"),
    Item("QUINT", "quint", "Quintic", "Quintic easing", "IPO_QUINT"),
    Item("EXPO", "expo", "Exponential", "Exponential easing (dramatic)", "IPO_EXPO"),
    Item("CIRC", "circ", "Circular", "Circular easing (strongest and most dynamic)", "IPO_CIRC"),
    Item("BACK", "back", "Back", "Cubic easing with overshoot and settle", "IPO_BACK"),
    Item(
        "BOUNCE",
        "bounce",
        "Bounce",
        "Exponentially decaying parabolic bounce, like when objects collide",
        "IPO_BOUNCE",
    ),
    Item("ELASTIC", "elastic", "Elastic", "Exponentially decaying sine wave, like an elastic band", "IPO_ELASTIC"),
)
_EASING_MODES = (
    Item(
        "AUTO",
        "auto",
        "Automatic Easing",
        "Ease in for most types; ease out for Back, Bounce and Elastic",
        "IPO_EASE_IN_OUT",
    ),
    Item("EASE_IN", "ease-in", "Ease In", "Only on the end closest to the next key", "IPO_EASE_IN"),
    Item("EASE_OUT", "ease-out", "Ease Out", "Only on the end closest to the first key", "IPO_EASE_OUT"),
    Item("EASE_IN_OUT", "ease-in-out", "Ease In and Out", "Segment between both keys", "IPO_EASE_IN_OUT"),
)


@dataclass(frozen=True)
class Option:
    """One option: its kind ('ENUM', 'INT', 'FLOAT', 'BOOLEAN', 'STRING'), label, description and default.

    ``default`` is a value (for an enum: an item's lowercase value, not its Blender id);
    ``items`` are the enum's :class:`Item`s; ``min`` and ``max`` bound a number (``max`` None:
    unbounded), ``soft_max`` is where an integer's slider stops.
    """

    name: str
    kind: str
    label: str
    description: str
    default: object
    items: tuple = ()
    min: float = 0
    max: float = None
    soft_max: int = 0

    @property
    def values(self):
        """The lowercase values of an enum's items, in order."""
        return tuple(item.value for item in self.items)

    def item(self, key):
        """The item whose Blender id or value is ``key``."""
        for item in self.items:
            if key in (item.id, item.value):
                return item
        raise KeyError(f"option {self.name!r} has no item {key!r}")

    def value(self, stored):
        """The value of what a Blender property holds (an enum's id becomes its item's value)."""
        return self.item(stored).value if self.kind == "ENUM" else stored

    def blender(self, value):
        """What a Blender property holds for a value (an enum's value becomes its item's id)."""
        return self.item(value).id if self.kind == "ENUM" else value

    def raw(self, value):
        """A value as Blender stores it in an ID property (the item number for an enum)."""
        if self.kind == "ENUM":
            return self.items.index(self.item(value))
        return value


OPTIONS = (
    Option(
        "method",
        "ENUM",
        "Morph",
        "How points travel from the first key to the second",
        "circular-ball",
        items=_METHODS,
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
    Option(
        "timing_chart",
        "STRING",
        "Timing Chart",
        "Fractions of the morph in (0, 1), ascending, such as '0.1 0.3 0.6 0.9': one in-between per fraction, "
        "spread evenly between the keys, not eased (empty: In-betweens, Type and Easing; a chart is kept with its "
        "keys, and a later run with an empty chart uses it again)",
        "",
    ),
    # Labelled as Blender's Interpolate Sequence labels them: its "Type" and "Easing".
    Option(
        "easing_type",
        "ENUM",
        "Type",
        "How the in-betweens are spaced in time (Blender's interpolation types)",
        "linear",
        _EASING_TYPES,
    ),
    Option("easing", "ENUM", "Easing", "Which ends of the motion the type's easing affects", "ease-in", _EASING_MODES),
    Option(
        "favor",
        "FLOAT",
        "Favor",
        "Pull every in-between toward the first key (negative) or the second (positive), after easing; "
        "1 puts the middle in-between three quarters of the way",
        0.0,
        min=-1.0,
        max=1.0,
    ),
    Option(
        "key_motion",
        "ENUM",
        "Through Keys",
        "How in-betweens pass through the inner keys of three or more (selected, or every key from the "
        "command line); a key typed Extreme in the Dope Sheet always keeps its corner",
        "smooth",
        (
            Item(
                "SMOOTH",
                "smooth",
                "Smooth",
                "Arcs through the keys: every point's path and speed join smoothly at inner keys",
                "IPO_BEZIER",
            ),
            Item(
                "PER_INTERVAL",
                "per-interval",
                "Per Interval",
                "Each pair of keys in-betweened on its own: paths turn a corner at every key",
                "IPO_LINEAR",
            ),
        ),
    ),
    Option(
        "layers",
        "ENUM",
        "Layers",
        "Which layers to in-between",
        "active",
        (
            Item("ACTIVE", "active", "Active", "The active layer only"),
            Item("ALL", "all", "All", "Every visible, unlocked layer"),
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
        "similarity",
        (
            Item(
                "SIMILARITY",
                "similarity",
                "Similarity",
                "Move, turn and scale along a steady spiral, then ball-morph the shape",
            ),
            Item("RIGID", "rigid", "Rigid", "Move and turn only, then ball-morph the shape"),
            Item("NONE", "none", "None", "Pure ball-morph: no carrier motion"),
        ),
    ),
    Option(
        "matching",
        "ENUM",
        "Stroke Matching",
        "How the strokes of the two keys are paired",
        "auto",
        (
            Item("AUTO", "auto", "Automatic", "By index when the stroke counts agree, otherwise by shape and position"),
            Item("INDEX", "index", "By Index", "The i-th stroke of one key with the i-th stroke of the other"),
        ),
    ),
    Option(
        "unmatched",
        "ENUM",
        "Unmatched Strokes",
        "What a stroke without a partner in the other key does",
        "middle",
        (
            Item("MIDDLE", "middle", "Switch Halfway", "Shown until (or from) the middle of the in-betweens"),
            Item("HOLD", "hold", "Hold", "Shown unchanged on every in-between"),
            Item("FADE", "fade", "Fade", "Fades out (or in) over the in-betweens"),
            Item("SHRINK", "shrink", "Shrink to a Point", "Slides along itself into (or out of) its middle point"),
            Item(
                "NEIGHBOUR",
                "neighbour",
                "Shrink into Neighbour",
                "Shrinks into (or grows out of) the nearest point of its nearest stroke that has a partner",
            ),
        ),
    ),
)

OPTION_NAMES = tuple(option.name for option in OPTIONS)
_BY_NAME = {option.name: option for option in OPTIONS}


def option(name):
    """The :class:`Option` called ``name``."""
    return _BY_NAME[name]


def values_of(data):
    """Every option's value as held by ``data`` (operator, scene settings or preferences).

    Returns
    -------
    dict
        ``{option name: value}``: an enum's lowercase value (``'circular-ball'``), the number or
        flag of the others. This is what the in-betweening service takes.
    """
    return {option.name: option.value(getattr(data, option.name)) for option in OPTIONS}


def label(name, value):
    """The animator-facing label of an enum value (the value itself if the option has no such item)."""
    try:
        return option(name).item(value).label
    except KeyError:
        return value


def method_available(value):
    """Whether the vendored core implements this method (a value of the ``method`` option)."""
    return value in CORE_METHODS


def _enum_items(option):
    """Blender enum items with explicit numbers (needed by get/set callbacks)."""
    return [(item.id, item.label, item.description, item.icon, number) for number, item in enumerate(option.items)]


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
            kwargs["default"] = option.blender(option.default)
        annotations[option.name] = _PROPERTIES[option.kind](option, kwargs)
    return annotations


#: A Blender property for each kind of option: ``(option, common keyword arguments) -> property``.
_PROPERTIES = {
    "ENUM": lambda option, kwargs: bpy.props.EnumProperty(items=_enum_items(option), **kwargs),
    "INT": lambda option, kwargs: bpy.props.IntProperty(min=option.min, soft_max=option.soft_max, **kwargs),
    "FLOAT": lambda option, kwargs: bpy.props.FloatProperty(
        min=option.min, max=option.max, step=10, precision=2, subtype="FACTOR", **kwargs
    ),
    "BOOLEAN": lambda option, kwargs: bpy.props.BoolProperty(**kwargs),
    "STRING": lambda option, kwargs: bpy.props.StringProperty(**kwargs),
}


def draw_options(layout, data, compact=False, current_frame=False):
    """Draw the options of ``data`` (operator, scene settings or preferences).

    ``current_frame``: the run writes one in-between on the current frame, so the frame count
    and the timing chart do not apply (drawn inactive).
    """
    layout.use_property_split = True
    layout.use_property_decorate = False
    col = layout.column()
    col.prop(data, "method")
    charted = bool(data.timing_chart.strip()) and not current_frame  # a chart sets the frames and times itself
    sub = col.column()
    sub.active = not charted and not current_frame
    sub.prop(data, "frame_count")
    sub = col.column()
    sub.active = not current_frame
    sub.prop(data, "timing_chart")
    col = layout.column()
    sub = col.column()
    sub.active = not charted
    sub.prop(data, "easing_type")
    sub = sub.column()
    sub.active = data.easing_type != "LINEAR"
    sub.prop(data, "easing")
    col.prop(data, "favor", slider=True)
    col.prop(data, "key_motion")
    col = layout.column()
    col.prop(data, "layers")
    col.prop(data, "selected_only")
    if compact:
        return
    col = layout.column()
    col.prop(data, "carrier")
    col.prop(data, "matching")
    col.prop(data, "unmatched")
