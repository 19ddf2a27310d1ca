#!/usr/bin/env python3
"""Time per frame along each camera path, from an ab_runs.py report (ab.json): one SVG per
path and measured scope (shadow_sun, shadow_local), a line per run on that path (cache off
and on, or binaries), from the bench JSON's gpu_ms_per_frame. Plain SVG, no plotting
library (the device machine and CI have none).

Usage: plot_paths.py --in ab.json --out DIR [--scope shadow_sun] [--scope shadow_local]
"""
import argparse
import json
import os
import re

WIDTH, HEIGHT, MARGIN = 720, 300, 50
COLOURS = ["#d62728", "#1f77b4", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b"]


def path_of(label):
    """The camera path a run's label names: '..., orbit (60 frames)' -> 'orbit'."""
    found = re.search(r"(\w+) \(\d+ frames\)", label)
    return found.group(1) if found else "other"


def svg_frame(title, y_label, top, x_label=None, width=WIDTH, height=HEIGHT, margin=MARGIN, y_axis=True):
    """The opening of an SVG chart: white background, title, x axis (and y axis), the y
    label, and five gridlines labelled from 0 to `top`. Close the list with "</svg>"."""
    plot_h = height - 2 * margin
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" font-family="sans-serif" font-size="11">',
             f'<rect width="{width}" height="{height}" fill="white"/>',
             f'<text x="{width / 2}" y="18" text-anchor="middle" font-size="13">{title}</text>',
             f'<line x1="{margin}" y1="{height - margin}" x2="{width - margin}" y2="{height - margin}" stroke="black"/>']
    if y_axis:
        parts.append(f'<line x1="{margin}" y1="{margin}" x2="{margin}" y2="{height - margin}" stroke="black"/>')
    if x_label:
        parts.append(f'<text x="{width / 2}" y="{height - 12}" text-anchor="middle">{x_label}</text>')
    parts.append(f'<text x="14" y="{height / 2}" transform="rotate(-90 14 {height / 2})" text-anchor="middle">{y_label}</text>')
    for k in range(5):
        y = height - margin - plot_h * k / 4
        parts.append(f'<text x="{margin - 6}" y="{y + 4:.1f}" text-anchor="end">{top * k / 4:.2f}</text>')
        parts.append(f'<line x1="{margin}" y1="{y:.1f}" x2="{width - margin}" y2="{y:.1f}" stroke="#ddd"/>')
    return parts


def svg_plot(title, series, scope):
    """An SVG line plot of {label: [ms per frame]}."""
    longest = max(len(values) for values in series.values())
    top = max(max(values) for values in series.values()) or 1.0
    top *= 1.1
    plot_w, plot_h = WIDTH - 2 * MARGIN, HEIGHT - 2 * MARGIN

    def point(i, value):
        x = MARGIN + plot_w * i / max(longest - 1, 1)
        y = HEIGHT - MARGIN - plot_h * value / top
        return f"{x:.1f},{y:.1f}"

    parts = svg_frame(title, f"{scope} ms (GPU)", top, x_label="frame")
    for index, (label, values) in enumerate(series.items()):
        colour = COLOURS[index % len(COLOURS)]
        points = " ".join(point(i, v) for i, v in enumerate(values))
        parts.append(f'<polyline fill="none" stroke="{colour}" stroke-width="1.5" points="{points}"/>')
        parts.append(f'<text x="{MARGIN + 8}" y="{MARGIN + 14 * (index + 1)}" fill="{colour}">{label}</text>')
    parts.append("</svg>")
    return "\n".join(parts) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--in", dest="source", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--scope", action="append")
    args = parser.parse_args()
    scopes = args.scope or ["shadow_sun", "shadow_local"]
    with open(args.source) as file:
        results = json.load(file)
    os.makedirs(args.out, exist_ok=True)
    written = []
    for scope in scopes:
        by_path = {}
        for result in results:
            values = result["report"].get("gpu_ms_per_frame", {}).get(scope)
            if values:
                by_path.setdefault(path_of(result["label"]), {})[result["label"]] = values
        for path, series in by_path.items():
            name = os.path.join(args.out, f"{scope}-{path}.svg")
            with open(name, "w") as file:
                file.write(svg_plot(f"{scope} per frame, {path}", series, scope))
            written.append(name)
    for name in written:
        print(name)
    if not written:
        raise SystemExit("plot_paths: no run has gpu_ms_per_frame for " + ", ".join(scopes))


if __name__ == "__main__":
    main()
