"""The in-between frames: timing, where every sample sits (layout), attributes, unmatched strokes, the path preview."""
