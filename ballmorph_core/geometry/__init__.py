"""Planar geometry, nothing from the paper: polylines and batches of them (ragged arrays),
splines, spatial search, intersections, closest points, circles, the drawing plane, similarities."""
