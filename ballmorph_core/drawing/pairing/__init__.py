"""Which strokes pair: matching by motion and shape, the assignment, lines redrawn in pieces."""
