"""A tune's pictures, drawn as summary.svg is (experiment/svg.py's
helpers): convergence.svg, each candidate's objective against the runs
the search had taken when it ended (complete ones filled, pruned ones
hollow) under the best so far, with the best's and the programs' own
constants' mean on the test seeds; params.svg, one panel per searched
constant, the objective against its value, the best ringed."""
from __future__ import annotations

import math
from html import escape

from ..experiment import metrics as M
from ..experiment.svg import (COLOURS, MARGIN_B, MARGIN_L, MARGIN_R, MARGIN_T, PANEL_H,
                              PANEL_W, axes, header, nice_ticks)
from .race import test_summary

WIDE = 2 * PANEL_W
GREY = "#888"


def _frame(values: list, width: int):
    ticks = nice_ticks(min(values), max(values)) if values else [0, 1]
    lo, hi = ticks[0], ticks[-1]
    plot_w = width - MARGIN_L - MARGIN_R
    plot_h = PANEL_H - MARGIN_T - MARGIN_B

    def y(v: float) -> float:
        return MARGIN_T + plot_h - (v - lo) / (hi - lo) * plot_h
    return lo, hi, plot_w, plot_h, y


def _dot(x: float, y: float, colour: str, filled: bool, tip: str) -> str:
    fill = f'fill="{colour}"' if filled else f'fill="white" stroke="{colour}"'
    return (f'<circle cx="{x:.1f}" cy="{y:.1f}" r="3.5" {fill}>'
            f'<title>{escape(tip)}</title></circle>')


def _tip(c) -> str:
    values = ", ".join(f"{k}={v}" for k, v in c.values.items())
    return f"trial {c.number} ({c.state}, {len(c.per_seed)} seeds): {M.fmt(c.value)}; {values}"


def convergence_svg(search, result, title: str) -> str:
    shown = [c for c in result.candidates if c.value is not None]
    lines = {name: test_summary(runs)["mean"] for name, runs in result.test.items()}
    values = [c.value for c in shown] + [v for v in lines.values() if v is not None]
    height = 40 + PANEL_H + 24
    out = header(WIDE, height, title + ": convergence")
    out.append('<g transform="translate(0,40)">')
    if not values:
        out.append(f'<text x="{WIDE / 2:.0f}" y="{PANEL_H / 2:.0f}" text-anchor="middle">'
                   f'no candidate has a value</text></g></svg>\n')
        return "\n".join(out)
    lo, hi, plot_w, plot_h, y = _frame(values, WIDE)
    runs_end = max(result.runs, 1)

    def x(r: float) -> float:
        return MARGIN_L + r / runs_end * plot_w

    axes(out, lo, hi, plot_w, plot_h, y, nice_ticks(0, runs_end), x)
    out.append(f'<text x="{MARGIN_L + plot_w / 2:.0f}" y="{MARGIN_T + plot_h + 32}" '
               f'text-anchor="middle" font-size="11" fill="#666">runs</text>')
    best, steps = None, []
    for c in sorted(shown, key=lambda c: (c.runs_at_end, c.number)):
        if c.state == "complete" and (best is None or search.better(c.value, best)):
            best = c.value
        if best is not None:
            steps.append((c.runs_at_end, best))
    if steps:
        pts = [f"{x(steps[0][0]):.1f},{y(steps[0][1]):.1f}"]
        for (r0, b0), (r1, b1) in zip(steps, steps[1:]):
            pts += [f"{x(r1):.1f},{y(b0):.1f}", f"{x(r1):.1f},{y(b1):.1f}"]
        pts.append(f"{x(runs_end):.1f},{y(steps[-1][1]):.1f}")
        out.append(f'<polyline points="{" ".join(pts)}" fill="none" stroke="{COLOURS[1]}" '
                   f'stroke-width="2"><title>best so far</title></polyline>')
    for c in shown:
        out.append(_dot(x(c.runs_at_end), y(c.value), COLOURS[0] if c.state == "complete"
                        else GREY, c.state == "complete", _tip(c)))
    for i, (name, value) in enumerate(sorted(lines.items())):
        if value is None:
            continue
        colour = COLOURS[2 + i]
        label = "best, test seeds" if name == "best" else "programs' constants, test seeds"
        out.append(f'<line x1="{MARGIN_L}" x2="{MARGIN_L + plot_w}" y1="{y(value):.1f}" '
                   f'y2="{y(value):.1f}" stroke="{colour}" stroke-dasharray="6 4">'
                   f'<title>{label}: {M.fmt(value)}</title></line>')
        out.append(f'<text x="{MARGIN_L + plot_w - 4}" y="{y(value) - 4:.1f}" '
                   f'text-anchor="end" font-size="10" fill="{colour}">{label}</text>')
    out.append("</g>")
    out.append(f'<text x="8" y="{height - 6}" font-size="10" fill="#666">dots: candidates '
               f'(filled: every design seed; hollow: stopped early); line: the best so far; '
               f'objective "{escape(search.objective.text)}" ({search.direction})</text>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


def params_svg(search, result, title: str) -> str:
    shown = [c for c in result.candidates if c.value is not None]
    params = search.params
    columns = min(2, len(params))
    rows_n = math.ceil(len(params) / columns)
    width = PANEL_W * columns
    height = 40 + PANEL_H * rows_n + 20
    out = header(width, height, title + ": the objective against each constant")
    values = [c.value for c in shown]
    for n, p in enumerate(params):
        ox, oy = PANEL_W * (n % columns), 40 + PANEL_H * (n // columns)
        out.append(f'<g transform="translate({ox},{oy})">')
        out.append(f'<text x="{PANEL_W / 2:.0f}" y="18" text-anchor="middle" '
                   f'font-weight="bold">{escape(p.name)}{" (log)" if p.log else ""}'
                   f'{" (" + escape(p.unit) + ")" if p.unit else ""}</text>')
        if not values:
            out.append("</g>")
            continue
        lo, hi, plot_w, plot_h, y = _frame(values, PANEL_W)
        x, xticks = _x_axis(p, plot_w)
        axes(out, lo, hi, plot_w, plot_h, y, [], x)
        for t, label in xticks:
            out.append(f'<text x="{x(t):.1f}" y="{MARGIN_T + plot_h + 16}" '
                       f'text-anchor="middle" font-size="11">{escape(label)}</text>')
        for c in shown:
            v = _number(p, c.values[p.name])
            out.append(_dot(x(v), y(c.value), COLOURS[0] if c.state == "complete" else GREY,
                            c.state == "complete", _tip(c)))
        if result.best is not None:
            v = _number(p, result.best.values[p.name])
            out.append(f'<circle cx="{x(v):.1f}" cy="{y(result.best.value):.1f}" r="8" '
                       f'fill="none" stroke="{COLOURS[1]}" stroke-width="2">'
                       f'<title>the best: {escape(result.best.values[p.name])}</title></circle>')
        out.append("</g>")
    out.append(f'<text x="8" y="{height - 6}" font-size="10" fill="#666">dots: candidates '
               f'(filled: every design seed; hollow: stopped early); ring: the best</text>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


def _number(p, text: str) -> float:
    if p.kind == "choice":
        return float(p.choices.index(text))
    return float(text.split()[0])


def _x_axis(p, plot_w: float):
    """(x(value), [(tick, label)]) of a constant's panel."""
    if p.kind == "choice":
        n = len(p.choices)

        def x(v: float) -> float:
            return MARGIN_L + (v + 0.5) / n * plot_w
        return x, [(i, c) for i, c in enumerate(p.choices)]
    if p.log:
        lo, hi = math.log10(p.low), math.log10(p.high)

        def x(v: float) -> float:
            return MARGIN_L + (math.log10(v) - lo) / (hi - lo) * plot_w
        ticks = [10 ** k for k in range(math.ceil(lo), math.floor(hi) + 1)] or [p.low, p.high]
        return x, [(t, f"{t:g}") for t in ticks]

    def x(v: float) -> float:
        return MARGIN_L + (v - p.low) / (p.high - p.low) * plot_w
    return x, [(t, f"{t:g}") for t in nice_ticks(p.low, p.high) if p.low <= t <= p.high]
