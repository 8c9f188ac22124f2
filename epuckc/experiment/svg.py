"""summary.svg: each metric against the grid points, one panel per metric:
every run's value as a dot, the mean as a bar and its 95% confidence
interval as a whisker; series.svg: each series against time, one panel per
column, a line per grid point (the mean over its seeds) in a band (the 95%
interval). Plain SVG text, the same bytes for the same results; the
helpers (`nice_ticks`, `header`, `COLOURS`) serve tune's pictures too."""
from __future__ import annotations

import math
from html import escape

from . import metrics as M

PANEL_W, PANEL_H = 420, 260
MARGIN_L, MARGIN_R, MARGIN_T, MARGIN_B = 64, 16, 34, 58
COLUMNS = 2
COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf"]


def nice_ticks(lo: float, hi: float, count: int = 5) -> list:
    if hi <= lo:
        hi = lo + 1
    raw = (hi - lo) / count
    mag = 10 ** math.floor(math.log10(raw))
    step = next(s * mag for s in (1, 2, 2.5, 5, 10) if s * mag >= raw)
    first = math.floor(lo / step) * step
    ticks = []
    t = first
    while t <= hi + step * 1e-9:
        ticks.append(round(t, 10))
        t += step
    if ticks[-1] < hi:
        ticks.append(round(t, 10))
    return ticks


def _label(values: dict) -> str:
    return ", ".join(f"{k}={v}" for k, v in values.items()) or "all runs"


def label(values: dict) -> str:
    return _label(values)


def _n(v: float) -> str:
    return f"{v:.1f}".rstrip("0").rstrip(".")


def _panel(col: str, points: list, ox: float, oy: float) -> list:
    """`points`: (label, [values of the runs], describe()) per grid point."""
    out = [f'<g transform="translate({_n(ox)},{_n(oy)})">',
           f'<text x="{PANEL_W / 2:.0f}" y="18" text-anchor="middle" '
           f'font-weight="bold">{escape(col)}</text>']
    vals = [v for _, runs, _ in points for v in runs]
    vals += [s[k] for _, _, s in points for k in ("ci_low", "ci_high") if s[k] is not None]
    if not vals:
        out.append(f'<text x="{PANEL_W / 2:.0f}" y="{PANEL_H / 2:.0f}" text-anchor="middle">'
                   f'no value (every run failed)</text></g>')
        return out
    lo, hi = min(vals + [0.0]), max(vals)
    ticks = nice_ticks(lo, hi)
    lo, hi = ticks[0], ticks[-1]
    plot_w = PANEL_W - MARGIN_L - MARGIN_R
    plot_h = PANEL_H - MARGIN_T - MARGIN_B

    def y(v: float) -> float:
        return MARGIN_T + plot_h - (v - lo) / (hi - lo) * plot_h

    for t in ticks:
        out.append(f'<line x1="{MARGIN_L}" x2="{MARGIN_L + plot_w}" y1="{y(t):.1f}" '
                   f'y2="{y(t):.1f}" stroke="#ddd"/>')
        out.append(f'<text x="{MARGIN_L - 6}" y="{y(t) + 4:.1f}" text-anchor="end" '
                   f'font-size="11">{t:g}</text>')
    out.append(f'<line x1="{MARGIN_L}" x2="{MARGIN_L}" y1="{MARGIN_T}" '
               f'y2="{MARGIN_T + plot_h}" stroke="#333"/>')
    slot = plot_w / len(points)
    for i, (label, runs, s) in enumerate(points):
        cx = MARGIN_L + slot * (i + 0.5)
        colour = COLOURS[i % len(COLOURS)]
        for k, v in enumerate(runs):
            # spread the dots across the slot, the same way every time
            dx = (((k * 7919) % 17) / 16 - 0.5) * min(slot * 0.5, 40)
            out.append(f'<circle cx="{cx + dx:.1f}" cy="{y(v):.1f}" r="2.5" fill="{colour}" '
                       f'fill-opacity="0.45"><title>{escape(label)}: {M.fmt(v)}</title></circle>')
        if s["mean"] is not None:
            half = min(slot * 0.3, 30)
            out.append(f'<line x1="{cx - half:.1f}" x2="{cx + half:.1f}" y1="{y(s["mean"]):.1f}" '
                       f'y2="{y(s["mean"]):.1f}" stroke="{colour}" stroke-width="3">'
                       f'<title>mean {M.fmt(s["mean"])} (n = {s["n"]})</title></line>')
        if s["ci_low"] is not None:
            out.append(f'<line x1="{cx:.1f}" x2="{cx:.1f}" y1="{y(s["ci_low"]):.1f}" '
                       f'y2="{y(s["ci_high"]):.1f}" stroke="{colour}" stroke-width="1.5">'
                       f'<title>95% interval {M.fmt(s["ci_low"])} .. {M.fmt(s["ci_high"])}'
                       f'</title></line>')
        out.append(f'<text x="{cx:.1f}" y="{MARGIN_T + plot_h + 16}" text-anchor="middle" '
                   f'font-size="11">{escape(label)}</text>')
        out.append(f'<text x="{cx:.1f}" y="{MARGIN_T + plot_h + 30}" text-anchor="middle" '
                   f'font-size="10" fill="#666">n = {s["n"]}</text>')
    out.append("</g>")
    return out


def summary_svg(tasks: list, results: dict, summary: list, metrics: list, title: str) -> str:
    cols = M.columns(metrics)
    by_point = {}
    for task in sorted(tasks, key=lambda t: (t.point, t.seed)):
        r = results.get(task.key)
        if r is None:
            continue
        row = r.rows[-1] if r.rows else {}
        if not r.error and not row.get("error"):
            by_point.setdefault(task.point, []).append(row)
    rows_n = math.ceil(len(cols) / COLUMNS) if cols else 1
    width = PANEL_W * min(COLUMNS, max(len(cols), 1))
    height = 40 + PANEL_H * rows_n
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'viewBox="0 0 {width} {height}" font-family="sans-serif" font-size="12">',
           f'<rect width="{width}" height="{height}" fill="white"/>',
           f'<text x="{width / 2:.0f}" y="24" text-anchor="middle" font-size="15">'
           f'{escape(title)}</text>']
    for n, col in enumerate(cols):
        points = []
        for point, values, runs, failed, stats in summary:
            vals = [row[col] for row in by_point.get(point, [])
                    if isinstance(row.get(col), (int, float))]
            points.append((_label(values), vals, stats[col]))
        out += _panel(col, points, PANEL_W * (n % COLUMNS), 40 + PANEL_H * (n // COLUMNS))
    out.append(f'<text x="8" y="{height - 6}" font-size="10" fill="#666">dots: runs; bar: mean; '
               f'whisker: 95% confidence interval of the mean</text>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


def header(width: int, height: int, title: str) -> list:
    """An SVG's first lines: the element, a white ground, the title."""
    return [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
            f'viewBox="0 0 {width} {height}" font-family="sans-serif" font-size="12">',
            f'<rect width="{width}" height="{height}" fill="white"/>',
            f'<text x="{width / 2:.0f}" y="24" text-anchor="middle" font-size="15">'
            f'{escape(title)}</text>']


def axes(out: list, lo: float, hi: float, plot_w: float, plot_h: float, y, xticks, x):
    """Grid lines and tick labels of a panel: y from lo to hi, x at `xticks`."""
    for t in nice_ticks(lo, hi):
        if lo - 1e-9 <= t <= hi + 1e-9:
            out.append(f'<line x1="{MARGIN_L}" x2="{MARGIN_L + plot_w}" y1="{y(t):.1f}" '
                       f'y2="{y(t):.1f}" stroke="#ddd"/>')
            out.append(f'<text x="{MARGIN_L - 6}" y="{y(t) + 4:.1f}" text-anchor="end" '
                       f'font-size="11">{t:g}</text>')
    for t in xticks:
        out.append(f'<text x="{x(t):.1f}" y="{MARGIN_T + plot_h + 16}" text-anchor="middle" '
                   f'font-size="11">{t:g}</text>')
    out.append(f'<line x1="{MARGIN_L}" x2="{MARGIN_L}" y1="{MARGIN_T}" '
               f'y2="{MARGIN_T + plot_h}" stroke="#333"/>')
    out.append(f'<line x1="{MARGIN_L}" x2="{MARGIN_L + plot_w}" y1="{MARGIN_T + plot_h}" '
               f'y2="{MARGIN_T + plot_h}" stroke="#333"/>')


def _series_panel(col: str, lines: list, at: list, ox: float, oy: float) -> list:
    """`lines`: (label, [describe() at each time]) per grid point."""
    out = [f'<g transform="translate({_n(ox)},{_n(oy)})">',
           f'<text x="{PANEL_W / 2:.0f}" y="18" text-anchor="middle" '
           f'font-weight="bold">{escape(col)}</text>']
    vals = [s[k] for _, stats in lines for s in stats for k in ("mean", "ci_low", "ci_high")
            if s[k] is not None]
    if not vals or len(at) < 2:
        out.append(f'<text x="{PANEL_W / 2:.0f}" y="{PANEL_H / 2:.0f}" text-anchor="middle">'
                   f'no value</text></g>')
        return out
    ticks = nice_ticks(min(vals + [0.0]), max(vals))
    lo, hi = ticks[0], ticks[-1]
    plot_w = PANEL_W - MARGIN_L - MARGIN_R
    plot_h = PANEL_H - MARGIN_T - MARGIN_B
    t_end = at[-1] / 1000

    def x(t: float) -> float:
        return MARGIN_L + t / t_end * plot_w

    def y(v: float) -> float:
        return MARGIN_T + plot_h - (v - lo) / (hi - lo) * plot_h

    axes(out, lo, hi, plot_w, plot_h, y, nice_ticks(0, t_end), x)
    out.append(f'<text x="{MARGIN_L + plot_w / 2:.0f}" y="{MARGIN_T + plot_h + 32}" '
               f'text-anchor="middle" font-size="11" fill="#666">time (s)</text>')
    for i, (name, stats) in enumerate(lines):
        colour = COLOURS[i % len(COLOURS)]
        band = [(t / 1000, s) for t, s in zip(at, stats) if s["ci_low"] is not None]
        if len(band) > 1:
            edge = [f"{x(t):.1f},{y(s['ci_high']):.1f}" for t, s in band]
            edge += [f"{x(t):.1f},{y(s['ci_low']):.1f}" for t, s in reversed(band)]
            out.append(f'<polygon points="{" ".join(edge)}" fill="{colour}" '
                       f'fill-opacity="0.18" stroke="none"/>')
        mean = [f"{x(t / 1000):.1f},{y(s['mean']):.1f}" for t, s in zip(at, stats)
                if s["mean"] is not None]
        out.append(f'<polyline points="{" ".join(mean)}" fill="none" stroke="{colour}" '
                   f'stroke-width="2"><title>{escape(name)}</title></polyline>')
    out.append("</g>")
    return out


def series_svg(summary: list, at: list, title: str) -> str:
    """series.svg from series.summarise()'s rows."""
    cols, by_col, names = [], {}, []
    for point, values, col, stats in summary:
        if col not in by_col:
            cols.append(col)
        by_col.setdefault(col, []).append((_label(values), stats))
        if _label(values) not in names:
            names.append(_label(values))
    rows_n = math.ceil(len(cols) / COLUMNS) if cols else 1
    width = PANEL_W * min(COLUMNS, max(len(cols), 1))
    legend_h = 18 * len(names) + 10
    height = 40 + PANEL_H * rows_n + legend_h
    out = header(width, height, title)
    for n, col in enumerate(cols):
        out += _series_panel(col, by_col[col], at, PANEL_W * (n % COLUMNS),
                             40 + PANEL_H * (n // COLUMNS))
    top = 40 + PANEL_H * rows_n
    for i, name in enumerate(names):
        colour = COLOURS[i % len(COLOURS)]
        out.append(f'<rect x="16" y="{top + 18 * i}" width="14" height="10" fill="{colour}"/>')
        out.append(f'<text x="36" y="{top + 18 * i + 9}" font-size="11">{escape(name)}</text>')
    out.append(f'<text x="8" y="{height - 4}" font-size="10" fill="#666">line: mean over the '
               f'seeds; band: 95% confidence interval of the mean</text>')
    out.append("</svg>")
    return "\n".join(out) + "\n"
