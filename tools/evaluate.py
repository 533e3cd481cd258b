#!/usr/bin/env python3
"""Re-run the paper's comparative study (Whited & Rossignac, section 8, figures 24-26).

For every curve pair (default: the three test cases of ``tools/paper_cases.py``) and every
method in ``bm.METHODS`` (read at run time, so newly added morphs are picked up), compute the
six quality measures with ``bm.measure`` and write ``docs/evaluation/results.md``: per case a
method x measure table with the best of each column in bold, a check of each claim the paper
makes about that case, and per method a figure like the paper's (trajectories and in-between
frames; the stacked-frames surface). A method that raises (not applicable to the pair, not b-
compatible, too slow) shows as ``n/a (reason)`` instead of stopping the run.

Usage::

    tools/evaluate.py                                # the paper's three cases
    tools/evaluate.py --pair mine.npz --no-figures   # your own pair: arrays P, Q, closed
    tools/evaluate.py --methods circular-ball,linear-ball --steps 20

A pair file is an ``.npz`` with arrays ``P`` and ``Q`` (``(N, 2)``), ``closed`` (bool) and
optionally ``height``, ``spacing``, ``name``, ``title``.
"""

import argparse
import os
import signal
import sys
import time
from dataclasses import dataclass, field

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from PIL import Image

TOOLS = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(TOOLS)
sys.path.insert(0, ROOT)
sys.path.insert(0, TOOLS)

from paper_cases import Case, paper_cases  # noqa: E402

import ballmorph_core as bm  # noqa: E402
from ballmorph_core.geometry.polyline import curve_length, scale_of  # noqa: E402
from ballmorph_core.study.measures import MEASURES, strip_mesh  # noqa: E402

DEFAULT_OUT = os.path.join(ROOT, "docs", "evaluation")
DEFAULT_STEPS = 40
DEFAULT_TIMEOUT = 120.0

COLUMNS = {
    "travel_distance": "travel",
    "distortion": "distortion",
    "stretch": "stretch",
    "acceleration": "acceleration",
    "mean_curvature_sq_avg": "avg H²",
    "mean_curvature_sq_max": "max H²",
}

BALL_MORPHS = ("circular-ball", "linear-ball", "parabolic-ball")


@dataclass
class Claim:
    """A statement of the paper's section 8 about one case, checked against a run.

    ``kind`` is ``'best'`` (the smallest value of ``measure`` is one of ``methods``),
    ``'worst'`` (the largest is), ``'above'`` (``methods[0]`` scores higher than every other of
    ``methods``) or ``'close'`` (``methods[0]`` is within 10 % of ``methods[1]`` on travel and
    stretch). ``among`` restricts the comparison to the methods the paper showed.
    """

    text: str
    kind: str
    measure: str
    methods: tuple
    among: tuple = ()


PAPER_CLAIMS = {
    "circle-ellipse": [
        Claim("the linear ball-morph has the shortest travel", "best", "travel_distance", ("linear-ball",)),
        Claim("the circular ball-morph has the least distortion", "best", "distortion", ("circular-ball",)),
        Claim(
            "curvature-interpolation / laplace-blending give the least average squared mean curvature",
            "best",
            "mean_curvature_sq_avg",
            ("curvature-interpolation", "laplace-blending"),
        ),
        Claim(
            "curvature-interpolation / laplace-blending give the least maximum squared mean curvature",
            "best",
            "mean_curvature_sq_max",
            ("curvature-interpolation", "laplace-blending"),
        ),
        Claim(
            "heat-propagation suffers more acceleration than the circular ball-morph (close curves vs grid)",
            "above",
            "acceleration",
            ("heat-propagation", "circular-ball"),
        ),
        Claim(
            "heat-propagation looks like the circular ball-morph (travel and stretch within 10 %)",
            "close",
            "travel_distance",
            ("heat-propagation", "circular-ball"),
        ),
        Claim(
            "the parabolic ball-morph has a higher maximum squared mean curvature than the circular",
            "above",
            "mean_curvature_sq_max",
            ("parabolic-ball", "circular-ball"),
        ),
    ],
    "s-strokes": [
        Claim("the linear ball-morph has the shortest travel", "best", "travel_distance", ("linear-ball",)),
        Claim("the circular ball-morph has the least distortion", "best", "distortion", ("circular-ball",)),
        Claim(
            "uniform arc-length linear interpolation distorts more than every ball-morph",
            "above",
            "distortion",
            ("linear-interpolation",) + BALL_MORPHS,
        ),
        Claim(
            "uniform arc-length linear interpolation travels farther than every ball-morph",
            "above",
            "travel_distance",
            ("linear-interpolation",) + BALL_MORPHS,
        ),
        Claim(
            "heat-propagation gives the least average squared mean curvature",
            "best",
            "mean_curvature_sq_avg",
            ("heat-propagation",),
        ),
        Claim(
            "heat-propagation gives the least maximum squared mean curvature",
            "best",
            "mean_curvature_sq_max",
            ("heat-propagation",),
        ),
        Claim(
            "heat-propagation is close to the ball-morphs (travel and stretch within 10 % of the circular)",
            "close",
            "travel_distance",
            ("heat-propagation", "circular-ball"),
        ),
    ],
    "apple-pear": [
        Claim(
            "the linear ball-morph has the shortest travel (of the four shown)",
            "best",
            "travel_distance",
            ("linear-ball",),
            ("linear-ball", "circular-ball", "heat-propagation", "laplace-blending"),
        ),
        Claim(
            "the circular ball-morph has the least distortion (of the four shown)",
            "best",
            "distortion",
            ("circular-ball",),
            ("linear-ball", "circular-ball", "heat-propagation", "laplace-blending"),
        ),
        Claim(
            "laplace-blending has the least stretch (of the four shown)",
            "best",
            "stretch",
            ("laplace-blending",),
            ("linear-ball", "circular-ball", "heat-propagation", "laplace-blending"),
        ),
        Claim(
            "a ball-morph has the least acceleration (of the four shown)",
            "best",
            "acceleration",
            ("linear-ball", "circular-ball"),
            ("linear-ball", "circular-ball", "heat-propagation", "laplace-blending"),
        ),
        Claim(
            "a ball-morph has the largest average squared mean curvature (of the four shown)",
            "worst",
            "mean_curvature_sq_avg",
            ("linear-ball", "circular-ball"),
            ("linear-ball", "circular-ball", "heat-propagation", "laplace-blending"),
        ),
        Claim(
            "heat-propagation is close to the ball-morphs (travel and stretch within 10 % of the circular)",
            "close",
            "travel_distance",
            ("heat-propagation", "circular-ball"),
        ),
    ],
}


@dataclass
class CaseResult:
    case: Case
    scores: dict = field(default_factory=dict)  # method -> dict of measures
    failures: dict = field(default_factory=dict)  # method -> short reason
    seconds: dict = field(default_factory=dict)  # method -> run time of the measures
    figures: dict = field(default_factory=dict)  # method -> png file name


# ------------------------------------------------------------------------------- running


class _TimeoutError(Exception):
    pass


def _alarm(signum, frame):
    raise _TimeoutError()


def short_reason(exc, limit=70):
    """One line saying why a method did not run, for the table (str)."""
    if isinstance(exc, _TimeoutError):
        return "timed out"
    text = str(exc).strip().splitlines()[0] if str(exc).strip() else ""
    text = text.split(": ")[0] if isinstance(exc, bm.BallMorphError) else f"{type(exc).__name__}: {text}"
    text = text.replace("|", "/")
    return text if len(text) <= limit else text[: limit - 1] + "…"


def _with_timeout(seconds, fn, *args, **kwargs):
    if not seconds or not hasattr(signal, "SIGALRM"):
        return fn(*args, **kwargs)
    old = signal.signal(signal.SIGALRM, _alarm)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        return fn(*args, **kwargs)
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)


def run_case(case, methods, steps, timeout):
    """Measure every method on one case (CaseResult)."""
    result = CaseResult(case)
    for method in methods:
        start = time.perf_counter()
        try:
            result.scores[method] = _with_timeout(
                timeout,
                bm.measure,
                case.P,
                case.Q,
                method,
                closed=case.closed,
                spacing=case.spacing,
                steps=steps,
                height=case.height,
            )
        except Exception as exc:  # any failure of one method is reported, not fatal
            result.failures[method] = short_reason(exc)
        result.seconds[method] = time.perf_counter() - start
    return result


# ------------------------------------------------------------------------------- figures


def _closed_line(curve, closed):
    return np.vstack([curve, curve[:1]]) if closed else curve


def draw_case_figure(case, method, path, steps=40):
    """Trajectories with seven in-betweens (paper Figs. 24-26) and the stacked surface."""
    morph = bm.make_morph(case.P, case.Q, method, closed=case.closed, spacing=case.spacing)
    frames = morph.frames(np.linspace(0.0, 1.0, steps + 1))
    fig = plt.figure(figsize=(12, 5.2), dpi=80)
    ax = fig.add_subplot(1, 2, 1)
    stride = max(1, frames.shape[1] // 70)
    ax.plot(frames[:, ::stride, 0], frames[:, ::stride, 1], color="0.2", lw=0.5)
    for t in np.linspace(0, 1, 9)[1:-1]:
        f = _closed_line(morph(t), case.closed)
        ax.plot(f[:, 0], f[:, 1], color="tab:green", lw=0.9)
    for curve, colour in ((case.P, "tab:blue"), (case.Q, "tab:orange")):
        c = _closed_line(curve, case.closed)
        ax.plot(c[:, 0], c[:, 1], color=colour, lw=2.0)
    ax.set_aspect("equal")
    ax.axis("off")
    ax.set_title(f"{method}: trajectories, 7 in-betweens", fontsize=10)

    ax3 = fig.add_subplot(1, 2, 2, projection="3d")
    coarse = frames[:: max(1, steps // 20), :: max(1, frames.shape[1] // 90)]
    vertices, tri, _ = strip_mesh(coarse, case.closed, case.height)
    ax3.plot_trisurf(vertices[:, 0], vertices[:, 1], vertices[:, 2], triangles=tri, cmap="viridis", linewidth=0)
    span = np.ptp(vertices, axis=0)
    ax3.set_box_aspect(tuple(np.maximum(span, 0.05 * span.max())))
    ax3.set_title(f"stacked frames, z = t x {case.height:g}", fontsize=10)
    ax3.set_axis_off()
    ax3.view_init(elev=24, azim=-60)
    fig.tight_layout()
    _save(fig, path)


def _save(fig, path):
    """Save as a 256-colour PNG (a third of the size; these figures are committed)."""
    fig.canvas.draw()
    image = Image.fromarray(np.asarray(fig.canvas.buffer_rgba())[..., :3])
    image.quantize(256, method=Image.Quantize.MEDIANCUT).save(path, optimize=True)
    plt.close(fig)


def draw_cases_overview(cases, path):
    fig, axes = plt.subplots(1, len(cases), figsize=(5 * len(cases), 4.2), dpi=80, squeeze=False)
    for ax, case in zip(axes[0], cases):
        for curve, colour, label in ((case.P, "tab:blue", "P"), (case.Q, "tab:orange", "Q")):
            c = _closed_line(curve, case.closed)
            ax.plot(c[:, 0], c[:, 1], color=colour, lw=2.0, label=label)
        ax.set_aspect("equal")
        ax.axis("off")
        ax.set_title(case.title, fontsize=10)
        ax.legend(loc="lower right", fontsize=8, frameon=False)
    fig.tight_layout()
    _save(fig, path)


# ------------------------------------------------------------------------------- report


def _fmt(value):
    return f"{value:.4g}"


def markdown_table(result, methods):
    """Method x measure table; the best (smallest) of each column in bold (str)."""
    best = {}
    for name in MEASURES:
        if result.scores:
            best[name] = _fmt(min(s[name] for s in result.scores.values()))
    header = "| method | " + " | ".join(COLUMNS[n] for n in MEASURES) + " | time (s) |"
    lines = [header, "|" + "---|" * (len(MEASURES) + 2)]
    for method in methods:
        if method in result.scores:
            cells = []
            for name in MEASURES:
                text = _fmt(result.scores[method][name])
                cells.append(f"**{text}**" if text == best.get(name) else text)
        else:
            cells = [f"n/a ({result.failures.get(method, 'not run')})"] + [""] * (len(MEASURES) - 1)
        lines.append(f"| {method} | " + " | ".join(cells) + f" | {result.seconds.get(method, 0.0):.2f} |")
    return "\n".join(lines)


#: Relative difference below which an 'above' claim is reported as a tie.
TIE_MARGIN = 0.01


def check_claim(claim, scores):
    """(verdict, detail): verdict is 'yes', 'yes (tie at 4 digits)', 'tie (within 1%)', 'no' or
    'not testable'."""
    needed = set(claim.methods) | ({claim.methods[1]} if claim.kind == "close" else set())
    missing = sorted(m for m in needed if m not in scores)
    pool = {m: s for m, s in scores.items() if not claim.among or m in claim.among}
    if claim.kind in ("best", "worst"):
        if not set(claim.methods) & set(pool):
            return "not testable", f"{', '.join(claim.methods)} did not run"
        values = {m: s[claim.measure] for m, s in pool.items()}
        pick = (min if claim.kind == "best" else max)(values, key=values.get)
        claimed = [m for m in claim.methods if m in values and m != pick]
        absent = [m for m in claim.among if m not in scores]
        detail = f"{claim.kind}: {pick} {_fmt(values[pick])}" + "".join(f"; {m} {_fmt(values[m])}" for m in claimed)
        detail += f" ({', '.join(absent)} did not run)" if absent else ""
        if pick in claim.methods:
            return "yes", detail
        tied = any(_fmt(values[m]) == _fmt(values[pick]) for m in claimed)
        return ("yes (tie at 4 digits)" if tied else "no"), detail
    if missing:
        return "not testable", f"{', '.join(missing)} did not run"
    if claim.kind == "above":
        first = scores[claim.methods[0]][claim.measure]
        others = {m: scores[m][claim.measure] for m in claim.methods[1:]}
        detail = f"{claim.methods[0]} {_fmt(first)} vs " + ", ".join(f"{m} {_fmt(v)}" for m, v in others.items())
        # Margins under TIE_MARGIN are no finding: max H² alone moved 3 % when a path formula was
        # rewritten with the same mathematics (its maximum sits on the strip mesh's thinnest triangles).
        margin = min((first - v) / max(abs(v), 1e-300) for v in others.values())
        if abs(margin) <= TIE_MARGIN:
            return f"tie (within {TIE_MARGIN:.0%})", detail
        return ("yes" if margin > 0 else "no"), detail
    a, b = scores[claim.methods[0]], scores[claim.methods[1]]
    ratios = {n: a[n] / b[n] if b[n] else np.inf for n in ("travel_distance", "stretch")}
    detail = ", ".join(f"{COLUMNS[n]} ratio {r:.3f}" for n, r in ratios.items())
    return ("yes" if all(abs(r - 1) <= 0.1 for r in ratios.values()) else "no"), detail


def write_report(results, methods, steps, out_dir, figures):
    lines = [
        "# Re-running the paper's comparative study",
        "",
        "Generated by `tools/evaluate.py` (`make evaluate`); do not edit by hand. Whited & Rossignac,",
        '"Ball-morph: Definition, Implementation and Comparative Evaluation", section 8 and figures 24-26,',
        "on test cases made to look like the paper's (`tools/paper_cases.py`).",
        "",
        "Each number is the paper's symmetric measure: the mean of a weighted average over samples",
        "spaced uniformly on P and mapped forward, and one over samples spaced uniformly on Q mapped",
        "backward (`bm.measure`; the exact definitions and every choice the paper leaves open are in",
        "the docstrings of `ballmorph_core/measures.py`). **Smaller is better in every column; the best",
        "of each column is in bold.** travel: mean arc length of the trajectories; distortion: time",
        "average of |cos| between travel and curve tangent (0: along the normal); stretch: total change",
        "of edge lengths over the mean curve length; acceleration: change of the velocity's barycentric",
        "coordinates in the local frames (lack of steadiness); avg/max H²: squared mean curvature of",
        "the frames stacked along z (cotangent Laplacian).",
        "",
        f"Methods are those of `bm.METHODS` at run time: {', '.join(f'`{m}`' for m in methods)}.",
        f"Time steps T = {steps}. Per case: sample spacing u and surface height H below (the same for",
        "every method of a case). `n/a (reason)`: the method did not run on that pair.",
        "",
    ]
    lines += [
        "Reading the tables: the heat-propagation-morph moves points along the gradient of a harmonic",
        "field whose level sets are the frames, so its distortion is near 0 by construction (up to its",
        "grid; the paper's coarser grid presumably added error there). Stretch ties between morphs that",
        "share a correspondence: when every edge length changes monotonically, its total change is fixed",
        "by the first and last frames. Acceleration and max H² are discrete quantities (they depend on",
        "u and T); acceleration is ill-conditioned where a morph slides points almost along the curve.",
        "Max H² is the least stable column: its maximum sits on the thinnest triangles of the strip",
        "mesh, and it moved by 3 % (circle and ellipse, circular ball-morph: 0.958 to 0.991) when a",
        "path formula was rewritten with the same mathematics. A claim that one method is above",
        f"another is therefore reported as a tie when they differ by less than {TIE_MARGIN:.0%}.",
        "",
    ]
    if figures:
        lines += ["![The test cases](cases.png)", ""]
    for result in results:
        case = result.case
        config = bm.classify(case.P, case.Q, closed=case.closed)
        lines += [
            f"## {case.title}",
            "",
            f"`{case.name}`: {config}, {len(case.P)} and {len(case.Q)} input points, lengths "
            f"{curve_length(case.P, case.closed):.3g} and {curve_length(case.Q, case.closed):.3g}; "
            f"u = {case.spacing if case.spacing else 'default'}, H = {case.height:g}.",
            "",
            markdown_table(result, methods),
            "",
        ]
        claims = PAPER_CLAIMS.get(case.name, [])
        if claims:
            lines += ["What the paper reports for this case, and this run:", ""]
            lines += ["| paper (section 8) | reproduced | this run |", "|---|---|---|"]
            for claim in claims:
                verdict, detail = check_claim(claim, result.scores)
                lines.append(f"| {claim.text} | {verdict} | {detail} |")
            lines.append("")
        for method in methods:
            if method in result.figures:
                lines += [f"![{case.name}: {method}]({result.figures[method]})", ""]
    with open(os.path.join(out_dir, "results.md"), "w", encoding="utf-8") as fh:
        fh.write("\n".join(lines).rstrip() + "\n")


# ------------------------------------------------------------------------------- main


def load_pair(path):
    """A Case from an ``.npz`` file with P, Q, closed (and optional height, spacing, name)."""
    data = np.load(path)
    P, Q = data["P"], data["Q"]
    closed = bool(data["closed"]) if "closed" in data else False
    name = str(data["name"]) if "name" in data else os.path.splitext(os.path.basename(path))[0]
    title = str(data["title"]) if "title" in data else name
    height = float(data["height"]) if "height" in data else scale_of(P, Q)
    spacing = float(data["spacing"]) if "spacing" in data else None  # None: bm.measure's default
    return Case(name, title, P, Q, closed, height, spacing)


def evaluate(cases, methods=None, steps=DEFAULT_STEPS, out_dir=DEFAULT_OUT, figures=True, timeout=DEFAULT_TIMEOUT):
    """Run the study and write ``out_dir/results.md`` (and PNGs). Returns the CaseResults."""
    methods = tuple(bm.METHODS if methods is None else methods)
    os.makedirs(out_dir, exist_ok=True)
    results = []
    for case in cases:
        result = run_case(case, methods, steps, timeout)
        if figures:
            for method in result.scores:
                name = f"{case.name}_{method}.png"
                try:
                    _with_timeout(timeout, draw_case_figure, case, method, os.path.join(out_dir, name))
                    result.figures[method] = name
                except Exception as exc:  # a figure that fails must not lose the table
                    print(f"  figure {name} not drawn: {short_reason(exc)}", file=sys.stderr)
        results.append(result)
        print(f"\n## {case.title}\n")
        print(markdown_table(result, methods))
        for claim in PAPER_CLAIMS.get(case.name, []):
            verdict, detail = check_claim(claim, result.scores)
            print(f"  [{verdict}] {claim.text}: {detail}")
    if figures:
        draw_cases_overview(cases, os.path.join(out_dir, "cases.png"))
    write_report(results, methods, steps, out_dir, figures)
    return results


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=DEFAULT_OUT, help="output directory (default docs/evaluation)")
    parser.add_argument("--steps", type=int, default=DEFAULT_STEPS, help="time steps T (default 40)")
    parser.add_argument("--methods", help="comma-separated subset of bm.METHODS (default: all)")
    parser.add_argument("--cases", help="comma-separated subset of the paper cases (default: all)")
    parser.add_argument("--pair", action="append", default=[], help=".npz file with P, Q, closed (repeatable)")
    parser.add_argument("--no-figures", action="store_true", help="only the table")
    parser.add_argument("--timeout", type=float, default=DEFAULT_TIMEOUT, help="seconds per method and case")
    args = parser.parse_args(argv)

    cases = [load_pair(p) for p in args.pair]
    if not args.pair or args.cases:
        wanted = set(args.cases.split(",")) if args.cases else None
        cases = [c for c in paper_cases() if wanted is None or c.name in wanted] + cases
    methods = args.methods.split(",") if args.methods else None
    start = time.perf_counter()
    evaluate(cases, methods, args.steps, args.out, not args.no_figures, args.timeout)
    print(f"\nwrote {os.path.join(args.out, 'results.md')} in {time.perf_counter() - start:.1f} s")


if __name__ == "__main__":
    main()
