#!/usr/bin/env python3
"""Bar charts of the shadow strategies from an ab_runs.py report of `--plan strategies`
(ab.json): per scene and size ("1 M, 1080p"), one bar per strategy for the sun's shadow
on the GPU (shadow_sun median) and one for the CPU's culling + recording (medians). Plain
SVG, no plotting library (the device machine and CI have none).

Usage: plot_strategies.py --in ab.json --out DIR   (writes strategies-gpu.svg, strategies-cpu.svg)
"""
import argparse
import json
import os

from plot_paths import svg_frame

WIDTH, HEIGHT, MARGIN = 760, 320, 56
COLOURS = {"per-cascade": "#1f77b4", "multiview": "#ff7f0e", "layered": "#2ca02c", "per-cascade+cache": "#9467bd"}


def groups_of(results, measure):
    """{"1 M, 1080p": {"layered": value, ...}} from labels "<scene>, <size>, <strategy>"."""
    groups = {}
    for result in results:
        parts = [part.strip() for part in result["label"].split(",")]
        if len(parts) != 3:
            continue
        value = measure(result["report"])
        if value is not None:
            groups.setdefault(f"{parts[0]}, {parts[1]}", {})[parts[2]] = value
    return groups


def gpu_ms(report):
    entry = report["gpu_ms"].get("shadow_sun")
    return entry["median"] if entry else None


def cpu_ms(report):
    cpu = report.get("cpu_ms", {})
    if "culling" not in cpu or "recording" not in cpu:
        return None
    return cpu["culling"]["median"] + cpu["recording"]["median"]


def svg_bars(title, axis, groups):
    strategies = [s for s in COLOURS if any(s in g for g in groups.values())]
    top = max(max(g.values()) for g in groups.values()) * 1.15 or 1.0
    plot_w, plot_h = WIDTH - 2 * MARGIN, HEIGHT - 2 * MARGIN
    group_w = plot_w / max(len(groups), 1)
    bar_w = group_w * 0.8 / max(len(strategies), 1)
    parts = svg_frame(title, axis, top, width=WIDTH, height=HEIGHT, margin=MARGIN, y_axis=False)
    for g, (name, values) in enumerate(groups.items()):
        x0 = MARGIN + g * group_w + group_w * 0.1
        parts.append(f'<text x="{MARGIN + (g + 0.5) * group_w:.1f}" y="{HEIGHT - MARGIN + 16}" text-anchor="middle">{name}</text>')
        for s, strategy in enumerate(strategies):
            if strategy not in values:
                continue
            height = plot_h * values[strategy] / top
            x = x0 + s * bar_w
            y = HEIGHT - MARGIN - height
            parts.append(f'<rect x="{x:.1f}" y="{y:.1f}" width="{bar_w * 0.9:.1f}" height="{height:.1f}" fill="{COLOURS[strategy]}"/>')
            parts.append(f'<text x="{x + bar_w * 0.45:.1f}" y="{y - 3:.1f}" text-anchor="middle" font-size="9">{values[strategy]:.2f}</text>')
    for s, strategy in enumerate(strategies):
        parts.append(f'<text x="{MARGIN + 8}" y="{MARGIN - 18 + 13 * s}" fill="{COLOURS[strategy]}">{strategy}</text>')
    parts.append("</svg>")
    return "\n".join(parts) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--in", dest="source", required=True)
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    with open(args.source) as file:
        results = json.load(file)
    os.makedirs(args.out, exist_ok=True)
    charts = [("strategies-gpu.svg", "the sun's shadow on the GPU (median per frame)", "shadow_sun ms (GPU)", gpu_ms),
              ("strategies-cpu.svg", "CPU culling + recording (median per frame)", "ms (CPU)", cpu_ms)]
    for name, title, axis, measure in charts:
        groups = groups_of(results, measure)
        if not groups:
            continue
        path = os.path.join(args.out, name)
        with open(path, "w") as file:
            file.write(svg_bars(title, axis, groups))
        print(path)


if __name__ == "__main__":
    main()
