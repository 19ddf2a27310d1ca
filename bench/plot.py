#!/usr/bin/env python3
"""Plots bench/run_matrix.py results as PNG (and SVG) line charts, Python 3 stdlib only.

    python3 bench/plot.py --in bench/results [--out bench/results]

Writes time_vs_triangles, time_vs_shadow_resolution, time_vs_output_resolution and
time_vs_cascades (.png and .svg): median GPU milliseconds per pass against the axis the
matrix varied. The PNGs are drawn by a tiny rasterizer (lines, boxes, a 3x5 pixel font)
and compressed with zlib; the SVGs carry the same data with real text.
"""
import argparse
import json
import math
import os
import struct
import zlib

WIDTH, HEIGHT = 820, 500
LEFT, RIGHT, TOP, BOTTOM = 80, 190, 50, 60
COLORS = [(31, 119, 180), (214, 39, 40), (44, 160, 44), (255, 127, 14), (148, 103, 189), (140, 86, 75)]

# 3x5 glyphs, rows top to bottom; drawn at 2x.
FONT = {
    "0": "111101101101111", "1": "010110010010111", "2": "111001111100111", "3": "111001111001111",
    "4": "101101111001001", "5": "111100111001111", "6": "111100111101111", "7": "111001001001001",
    "8": "111101111101111", "9": "111101111001111", "A": "010101111101101", "B": "110101110101110",
    "C": "011100100100011", "D": "110101101101110", "E": "111100110100111", "F": "111100110100100",
    "G": "011100101101011", "H": "101101111101101", "I": "111010010010111", "J": "001001001101010",
    "K": "101101110101101", "L": "100100100100111", "M": "101111111101101", "N": "110101101101101",
    "O": "010101101101010", "P": "110101110100100", "Q": "010101101110011", "R": "110101110101101",
    "S": "011100010001110", "T": "111010010010010", "U": "101101101101111", "V": "101101101101010",
    "W": "101101111111101", "X": "101101010101101", "Y": "101101010010010", "Z": "111001010100111",
    ".": "000000000000010", "-": "000000111000000", "(": "001010010010001", ")": "100010010010100",
    "/": "001001010100100", ":": "000010000010000", " ": "000000000000000", "=": "000111000111000",
    ",": "000000000010100", "%": "101001010100101", "_": "000000000000111",
}


class Canvas:
    def __init__(self, width, height):
        self.width, self.height = width, height
        self.pixels = bytearray([255] * (width * height * 3))

    def dot(self, x, y, color):
        if 0 <= x < self.width and 0 <= y < self.height:
            i = (y * self.width + x) * 3
            self.pixels[i:i + 3] = bytes(color)

    def line(self, x0, y0, x1, y1, color, thickness=1):
        x0, y0, x1, y1 = int(round(x0)), int(round(y0)), int(round(x1)), int(round(y1))
        steps = max(abs(x1 - x0), abs(y1 - y0), 1)
        for s in range(steps + 1):
            x = x0 + (x1 - x0) * s // steps
            y = y0 + (y1 - y0) * s // steps
            for dx in range(thickness):
                for dy in range(thickness):
                    self.dot(x + dx - thickness // 2, y + dy - thickness // 2, color)

    def box(self, x, y, size, color):
        for dy in range(-size, size + 1):
            for dx in range(-size, size + 1):
                self.dot(int(x) + dx, int(y) + dy, color)

    def text(self, x, y, text, color=(0, 0, 0), scale=2):
        for n, char in enumerate(text.upper()):
            glyph = FONT.get(char, FONT[" "])
            for row in range(5):
                for col in range(3):
                    if glyph[row * 3 + col] == "1":
                        for sy in range(scale):
                            for sx in range(scale):
                                self.dot(int(x) + n * 4 * scale + col * scale + sx, int(y) + row * scale + sy, color)

    def png(self):
        raw = b"".join(b"\x00" + bytes(self.pixels[y * self.width * 3:(y + 1) * self.width * 3])
                       for y in range(self.height))

        def chunk(kind, data):
            return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

        header = struct.pack(">IIBBBBB", self.width, self.height, 8, 2, 0, 0, 0)
        return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(
            b"IEND", b"")


def text_width(text, scale=2):
    return len(text) * 4 * scale


def nice_max(value):
    if value <= 0:
        return 1.0
    magnitude = 10 ** math.floor(math.log10(value))
    for step in (1, 2, 2.5, 5, 10):
        if value <= step * magnitude:
            return step * magnitude
    return 10 * magnitude


def label(value):
    return f"{value:.3g}" if value < 1000 else f"{value / 1e6:.3g}M" if value >= 1e6 else f"{value / 1e3:.3g}K"


class Plot:
    """Series of (x, y) points on linear y and linear or log x axes."""

    def __init__(self, title, x_label, log_x=False):
        self.title, self.x_label, self.log_x = title, x_label, log_x
        self.series = []  # (name, [(x, y)])

    def add(self, name, points):
        points = sorted(p for p in points if p[1] is not None)
        if points:
            self.series.append((name, points))

    def _frame(self):
        xs = [x for _, pts in self.series for x, _ in pts]
        ys = [y for _, pts in self.series for _, y in pts]
        tx = (lambda v: math.log10(v)) if self.log_x else (lambda v: v)
        x_lo, x_hi = tx(min(xs)), tx(max(xs))
        if x_hi == x_lo:
            x_lo, x_hi = x_lo - 1, x_hi + 1
        y_hi = nice_max(max(ys) * 1.05)
        plot_w, plot_h = WIDTH - LEFT - RIGHT, HEIGHT - TOP - BOTTOM

        def to_px(x, y):
            return LEFT + (tx(x) - x_lo) / (x_hi - x_lo) * plot_w, TOP + plot_h - y / y_hi * plot_h

        return sorted(set(xs)), y_hi, to_px

    def png(self, path):
        canvas = Canvas(WIDTH, HEIGHT)
        xs, y_hi, to_px = self._frame()
        canvas.text(LEFT, 15, self.title, scale=3)
        axis = (80, 80, 80)
        canvas.line(LEFT, HEIGHT - BOTTOM, WIDTH - RIGHT, HEIGHT - BOTTOM, axis)
        canvas.line(LEFT, TOP, LEFT, HEIGHT - BOTTOM, axis)
        for i in range(6):
            value = y_hi * i / 5
            _, y = to_px(xs[0], value)
            canvas.line(LEFT - 4, y, WIDTH - RIGHT, y, (225, 225, 225) if i else axis)
            canvas.text(LEFT - 8 - text_width(label(value)), y - 5, label(value))
        for x_value in xs:
            x, _ = to_px(x_value, 0)
            canvas.line(x, HEIGHT - BOTTOM, x, HEIGHT - BOTTOM + 4, axis)
            canvas.text(x - text_width(label(x_value)) / 2, HEIGHT - BOTTOM + 10, label(x_value))
        canvas.text(LEFT + (WIDTH - LEFT - RIGHT - text_width(self.x_label)) / 2, HEIGHT - 22, self.x_label)
        canvas.text(8, TOP - 16, "GPU MS (MEDIAN)")
        for n, (name, points) in enumerate(self.series):
            color = COLORS[n % len(COLORS)]
            pixels = [to_px(x, y) for x, y in points]
            for a, b in zip(pixels, pixels[1:]):
                canvas.line(a[0], a[1], b[0], b[1], color, thickness=2)
            for x, y in pixels:
                canvas.box(x, y, 3, color)
            canvas.box(WIDTH - RIGHT + 20, TOP + 10 + n * 22, 5, color)
            canvas.text(WIDTH - RIGHT + 32, TOP + 5 + n * 22, name)
        with open(path, "wb") as file:
            file.write(canvas.png())

    def svg(self, path):
        xs, y_hi, to_px = self._frame()
        out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{HEIGHT}" font-family="sans-serif" '
               f'font-size="12"><rect width="100%" height="100%" fill="white"/>',
               f'<text x="{LEFT}" y="30" font-size="18">{self.title}</text>']
        for i in range(6):
            value = y_hi * i / 5
            _, y = to_px(xs[0], value)
            out.append(f'<line x1="{LEFT}" y1="{y:.1f}" x2="{WIDTH - RIGHT}" y2="{y:.1f}" stroke="#ddd"/>'
                       f'<text x="{LEFT - 6}" y="{y + 4:.1f}" text-anchor="end">{label(value)}</text>')
        for x_value in xs:
            x, _ = to_px(x_value, 0)
            out.append(f'<text x="{x:.1f}" y="{HEIGHT - BOTTOM + 18}" text-anchor="middle">{label(x_value)}</text>')
        out.append(f'<text x="{(LEFT + WIDTH - RIGHT) / 2}" y="{HEIGHT - 15}" text-anchor="middle">{self.x_label}'
                   f'</text><text x="10" y="{TOP - 12}">GPU ms (median)</text>')
        for n, (name, points) in enumerate(self.series):
            color = "#%02x%02x%02x" % COLORS[n % len(COLORS)]
            coords = " ".join(f"{x:.1f},{y:.1f}" for x, y in (to_px(*p) for p in points))
            out.append(f'<polyline points="{coords}" fill="none" stroke="{color}" stroke-width="2"/>')
            out.append(f'<rect x="{WIDTH - RIGHT + 15}" y="{TOP + 5 + n * 22}" width="10" height="10" fill="{color}"/>'
                       f'<text x="{WIDTH - RIGHT + 32}" y="{TOP + 14 + n * 22}">{name}</text>')
        with open(path, "w") as file:
            file.write("\n".join(out) + "\n</svg>\n")


def gpu_median(report, prefix):
    """The median of scope `prefix`, or the sum of its `prefix_*` scopes. "shadow" is the sun's
    shadow: the `shadow_sun` total where the report has it (summing it with the scopes it
    totals would count them twice), else the sun's scopes (not `shadow_local`)."""
    gpu = report["gpu_ms"]
    if prefix == "shadow" and "shadow_sun" in gpu:
        return gpu["shadow_sun"]["median"]
    values = [v["median"] for k, v in gpu.items()
              if (k == prefix or k.startswith(prefix + "_")) and k not in ("shadow_local", "shadow_sun")]
    return sum(values) if values else None


def axis_plot(runs, axis, title, x_label, x_of, log_x=False, series=("frame", "shadow", "lighting")):
    reports = [r["report"] for r in runs if r["axis"] == axis and r["report"]]
    if not reports:
        return None
    plot = Plot(title, x_label, log_x)
    for name in series:
        plot.add(name, [(x_of(r), gpu_median(r, name)) for r in reports])
    return plot if plot.series else None


def resolve_plot(runs):
    """Frame time against output size, forward against deferred, for hard, pcf r=2 and pcss
    high (the "resolve 1080p" and "resolve 4K" axes)."""
    reports = [(r["variant"], r["report"]) for r in runs if r["axis"].startswith("resolve ") and
               r["axis"] != "resolve local lights" and r["report"]]
    if not reports:
        return None
    plot = Plot("Frame time: forward vs deferred resolve", "MEGAPIXELS", False)
    for resolve in ("forward", "deferred"):
        for filter_name in ("hard", "pcf r=2", "pcss high"):
            points = [(r["settings"]["width"] * r["settings"]["height"] / 1e6, gpu_median(r, "frame"))
                      for variant, r in reports if variant == f"{resolve}, {filter_name}"]
            if points:
                plot.add(f"{resolve} {filter_name}", sorted(points))
    return plot if plot.series else None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    here = os.path.dirname(os.path.abspath(__file__))
    parser.add_argument("--in", dest="source", default=os.path.join(here, "results"))
    parser.add_argument("--out", default="")
    args = parser.parse_args()
    out = args.out or args.source
    with open(os.path.join(args.source, "matrix.json")) as file:
        runs = json.load(file)["runs"]
    plots = {
        "time_vs_triangles": axis_plot(runs, "scene triangles", "Time vs scene triangles", "TRIANGLES",
                                       lambda r: r["scene"]["triangles"], log_x=True),
        "time_vs_shadow_resolution": axis_plot(runs, "shadow resolution", "Time vs shadow resolution",
                                               "SHADOW MAP TEXELS PER SIDE",
                                               lambda r: r["settings"]["shadow_resolution"]),
        "time_vs_output_resolution": axis_plot(runs, "output", "Time vs output resolution", "MEGAPIXELS",
                                               lambda r: r["settings"]["width"] * r["settings"]["height"] / 1e6),
        "time_vs_cascades": axis_plot(runs, "cascades", "Time vs cascade count", "CASCADES",
                                      lambda r: r["settings"]["cascades"]),
        "frame_forward_vs_deferred": resolve_plot(runs),
    }
    os.makedirs(out, exist_ok=True)
    for name, plot in plots.items():
        if plot is None:
            print(f"plot: no data for {name}")
            continue
        plot.png(os.path.join(out, name + ".png"))
        plot.svg(os.path.join(out, name + ".svg"))
        print(f"plot: wrote {os.path.join(out, name)}.png/.svg")


if __name__ == "__main__":
    main()
