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
from ..ballmorph_core.drawing.frames.timing import AMPLITUDE, BACK, PERIOD

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
    not in the menus' quick list. ``number``: the number Blender stores for the item (scenes and
    preferences keep it), when it is not the item's place in the list: an item added in the
    middle of a list keeps the numbers of those after it, so saved settings keep their meaning.
    """

    id: str
    value: str
    label: str
    description: str
    icon: str = "NONE"
    research: bool = False
    number: int = None


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
    # Second, as in Interpolate Sequence's list, but numbered after the types that came before it.
    Item(
        "CUSTOM",
        "custom",
        "Custom",
        "Custom interpolation defined using a curve map: the curve Interpolate Sequence's Custom type uses "
        "(the scene's tool settings)",
        "IPO_BEZIER",
        number=11,
    ),
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
    ``items`` are the enum's :class:`Item`s; ``min`` and ``max`` bound a number (None:
    unbounded), ``soft_max`` is where an integer's slider stops; a float shows ``precision``
    digits, moves by ``step`` hundredths and has Blender's ``subtype``. ``types``: the values of
    the Type option (``easing_type``) that use this option (empty: every run uses it).
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
    precision: int = 2
    step: int = 10
    subtype: str = "FACTOR"
    types: tuple = ()

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
            return self.number(self.item(value))
        return value

    def number(self, item):
        """The number Blender stores for an enum item: its own, else its place among the items
        without one."""
        if item.number is not None:
            return item.number
        return [other for other in self.items if other.number is None].index(item)


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
    # Interpolate Sequence's own settings of its Back and Elastic types: names, labels, defaults
    # and ranges as Blender 4.5 and 5.0 define them (the core's timing.BACK, AMPLITUDE, PERIOD).
    Option(
        "back",
        "FLOAT",
        "Back",
        "Amount of overshoot for 'back' easing",
        BACK,
        min=0.0,
        precision=3,
        step=1,
        subtype="NONE",
        types=("back",),
    ),
    Option(
        "amplitude",
        "FLOAT",
        "Amplitude",
        "Amount to boost elastic bounces for 'elastic' easing",
        AMPLITUDE,
        min=0.0,
        precision=3,
        step=1,
        subtype="NONE",
        types=("elastic",),
    ),
    Option(
        "period",
        "FLOAT",
        "Period",
        "Time between bounces for elastic easing",
        PERIOD,
        min=None,
        precision=3,
        step=1,
        subtype="NONE",
        types=("elastic",),
    ),
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
    return [(item.id, item.label, item.description, item.icon, option.number(item)) for item in option.items]


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
        **_bounds(option), step=option.step, precision=option.precision, subtype=option.subtype, **kwargs
    ),
    "BOOLEAN": lambda option, kwargs: bpy.props.BoolProperty(**kwargs),
    "STRING": lambda option, kwargs: bpy.props.StringProperty(**kwargs),
}


def _bounds(option):
    """A float's ``min`` and ``max`` for Blender (unbounded sides left out: Blender's own limits)."""
    return {name: bound for name, bound in (("min", option.min), ("max", option.max)) if bound is not None}


def used_by_type(option, easing_type):
    """Whether a run with Type ``easing_type`` (a Blender id or value) uses ``option`` (its settings
    Back, Amplitude and Period belong to one type each, as in Interpolate Sequence's panel)."""
    if not option.types:
        return True
    return _BY_NAME["easing_type"].value(easing_type) in option.types


def draw_options(layout, data, compact=False, current_frame=False, scene=None):
    """Draw the options of ``data`` (operator, scene settings or preferences).

    ``current_frame``: the run writes one in-between on the current frame, so the frame count
    and the timing chart do not apply (drawn inactive). A type's own settings are drawn only
    with that type, as Interpolate Sequence draws them: Back with Back, Amplitude and Period
    with Elastic, and, with ``scene``, the scene's Custom curve with Custom.
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
    if data.easing_type == "CUSTOM" and scene is not None:
        _draw_custom_curve(sub, scene)
    settings = sub.column()
    settings.active = data.easing_type not in ("LINEAR", "CUSTOM")
    settings.prop(data, "easing")
    for name in ("back", "amplitude", "period"):
        if used_by_type(_BY_NAME[name], data.easing_type):
            settings.prop(data, name)
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


def _draw_custom_curve(layout, scene):
    """The scene's Custom curve (Interpolate Sequence's), or why there is none yet."""
    holder = scene.tool_settings.gpencil_interpolate
    if holder.interpolation_curve is not None:
        layout.template_curve_mapping(
            holder, "interpolation_curve", brush=True, use_negative_slope=True
        )  # as Blender draws it
        return
    col = layout.column(align=True)
    col.label(text="No Custom curve in this scene yet: runs are Linear", icon="INFO")
    col.label(text="Interpolate Sequence (Type Custom) makes and shows it")
