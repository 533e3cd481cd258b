"""Core demo: a circular ball-morph between two curves, drawn like the paper's figures 1 and 14.

Writes out/core_demo.png: the two keys, the ball-map trajectories and seven in-betweens for a
pair of loops (apple-like to pear-like) and a pair of strokes sharing their endpoints.
"""

import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import ballmorph_core as bm


def loops():
    t = np.linspace(0, 2 * np.pi, 240, endpoint=False)
    inner = np.c_[0.9 * np.cos(t), 0.7 * np.sin(t) + 0.08 * np.cos(2 * t)]
    r = 1.6 + 0.12 * np.cos(3 * t + 0.5)
    outer = np.c_[r * np.cos(t) + 0.1, 1.2 * r * np.sin(t) / 1.6 * 1.3]
    return inner, outer


def strokes():
    x = np.linspace(0, 1, 150)
    return np.c_[x, 0.35 * np.sin(np.pi * x)], np.c_[x, -0.2 * np.sin(np.pi * x) + 0.05 * np.sin(2 * np.pi * x)]


def draw(ax, P, Q, closed, title):
    morph = bm.make_morph(P, Q, "circular-ball", closed=closed)
    ts = np.linspace(0, 1, 41)
    paths = morph.frames(ts)
    for k in range(0, len(morph), max(1, len(morph) // 60)):
        ax.plot(paths[:, k, 0], paths[:, k, 1], color="0.15", lw=0.6)
    for t in np.linspace(0, 1, 9)[1:-1]:
        f = morph(t)
        f = np.vstack([f, f[:1]]) if closed else f
        ax.plot(f[:, 0], f[:, 1], color="tab:green", lw=1.0)
    for curve, colour in ((P, "tab:blue"), (Q, "tab:orange")):
        c = np.vstack([curve, curve[:1]]) if closed else curve
        ax.plot(c[:, 0], c[:, 1], color=colour, lw=2.2)
    ax.set_title(title)
    ax.set_aspect("equal")
    ax.axis("off")


def main():
    out = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "out")
    os.makedirs(out, exist_ok=True)
    fig, axes = plt.subplots(1, 2, figsize=(12, 5.5))
    draw(axes[0], *loops(), True, "nested loops: circular ball-morph (7 in-betweens)")
    draw(axes[1], *strokes(), False, "strokes sharing endpoints: circular ball-morph")
    path = os.path.join(out, "core_demo.png")
    fig.savefig(path, dpi=110, bbox_inches="tight")
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
