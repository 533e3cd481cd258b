"""The stroke-pair pipeline: every pair's curves, routes, carriers, ends, crossings, ball maps and fallbacks."""
