#!/usr/bin/env python3
"""Runs the `penumbra bench` matrix in one go and writes a markdown report plus JSON.

One axis varies at a time around a baseline (not the full cross product), so that the
whole matrix stays within a few minutes on a discrete GPU. Variants that the binary
rejects as bad input (exit 2, e.g. a filter it does not implement yet) are recorded as
skipped with the binary's one-line reason. Python 3 standard library only.

    python3 bench/run_matrix.py --binary build/penumbra --out bench/results
    python3 bench/run_matrix.py --quick ...   # tiny sizes and few frames (smoke test)

Outputs in --out: runs/<id>.json (one `penumbra bench --json` report per run),
matrix.json (every run: axis, variant, arguments, status, report) and report.md.
"""
import argparse
import datetime
import json
import os
import shlex
import subprocess
import sys
import time

BASELINE_SCENE = "builtin:forest?count=1000"  # 1 M triangles
BASELINE = ["--width", "1920", "--height", "1080", "--cascades", "4", "--shadow-resolution", "2048"]

# (axis, variant, scene or None for the baseline scene, extra arguments replacing baseline ones)
FILTERS = [
    ("hard", ["--filter", "hard"]),
    ("pcf r=1", ["--filter", "pcf", "--pcf-radius", "1"]),
    ("pcf r=2", ["--filter", "pcf", "--pcf-radius", "2"]),
    ("pcf r=3", ["--filter", "pcf", "--pcf-radius", "3"]),
    ("poisson", ["--filter", "poisson"]),
    ("pcss low", ["--filter", "pcss", "--pcss-quality", "low"]),
    ("pcss medium", ["--filter", "pcss", "--pcss-quality", "medium"]),
    ("pcss high", ["--filter", "pcss", "--pcss-quality", "high"]),
    ("vsm", ["--filter", "vsm"]),
    ("evsm", ["--filter", "evsm"]),
    ("msm", ["--filter", "msm"]),
]


def matrix(scenes_dir):
    runs = [("baseline", "forest 1M, 1080p, 4x2048", None, [])]
    runs += [("strategy", s, None, ["--shadow-strategy", s]) for s in ("per-cascade", "multiview", "layered")]
    # The sun's technique, cached (the virtual map is made to be): orbiting and with a
    # turning sun (every page stale every frame).
    runs += [("technique", f"{t}, cached, {path}", None,
              ["--shadow-technique", t, "--shadow-cache"] + path_args)
             for t in ("cascades", "virtual")
             for path, path_args in (("orbit", ["--camera-path", "orbit"]),
                                     ("rotating sun", ["--camera-path", "still", "--light-path", "rotate"]))]
    runs += [("culling", "on", None, []), ("culling", "off", None, ["--no-cull"])]
    runs += [("filter", name, None, args) for name, args in FILTERS]
    runs += [("cascades", str(c), None, ["--cascades", str(c)]) for c in (1, 2, 4, 8)]
    runs += [("shadow resolution", str(r), None, ["--shadow-resolution", str(r)]) for r in (1024, 2048, 4096)]
    runs += [("output", f"{w}x{h}", None, ["--width", str(w), "--height", str(h)])
             for w, h in ((1920, 1080), (3840, 2160))]
    runs += [("scene triangles", f"{count * 1000 / 1e6:g}M", f"builtin:forest?count={count}", [])
             for count in (100, 1000, 10000)]
    oak = os.path.join(scenes_dir, "oak-forest.toml")
    if os.path.exists(oak):
        runs.append(("scene", "oak-forest (glTF)", oak, []))
    runs += [("ceiling triangles", f"{count * 1000 / 1e6:g}M", f"builtin:forest?count={count}",
              ["--ceiling", "triangles"]) for count in (100, 1000, 10000)]
    runs += [("ceiling taps", f"{taps} taps 1080p", None, ["--ceiling", "taps", "--taps", str(taps)])
             for taps in (1, 16, 64)]
    runs += [("ceiling compute taps", f"{taps} taps {label}", None,
              ["--ceiling", "compute-taps", "--taps", str(taps)] + size)
             for taps in (1, 16, 64) for label, size in (("1080p", []), ("4K", UHD))]
    runs += [("ceiling layer start", f"{count} x {resolution}²", None,
              ["--ceiling", "layer-start", "--cascades", str(count), "--shadow-resolution", str(resolution)])
             for count, resolution in ((4, 2048), (4, 4096))]
    runs += resolve_runs()
    runs += [("camera path", "flythrough", None, ["--camera-path", "flythrough"]),
             ("light path", "rotate", None, ["--light-path", "rotate"])]
    runs += local_light_runs()
    runs += cache_runs()
    return runs


def cache_runs():
    """Cached shadows (--shadow-cache), off and on in the same run, along each camera path, with
    ten moving dynamic instances, and with 8 static spots and 8 static points."""
    runs = []
    for path in ("orbit", "walk", "flythrough", "still"):
        runs += [("shadow cache", f"{path}, {cache}", None,
                  ["--camera-path", path] + (["--shadow-cache"] if cache == "on" else [])) for cache in ("off", "on")]
    movers = f"{BASELINE_SCENE}&movers=10"
    runs += [("shadow cache, 10 movers", f"orbit, {cache}", movers,
              ["--camera-path", "orbit", "--animate-dynamic"] +
              (["--shadow-cache"] if cache == "on" else [])) for cache in ("off", "on")]
    lights = f"{BASELINE_SCENE}&spots=8&points=8"
    runs += [("shadow cache, 8 spots + 8 points", f"still, {cache}", lights,
              ["--camera-path", "still", "--local-shadow-budget", "16"] +
              (["--shadow-cache"] if cache == "on" else [])) for cache in ("off", "on")]
    return runs


UHD = ["--width", "3840", "--height", "2160"]
RESOLVE_FILTERS = ("hard", "pcf r=2", "poisson", "pcss high", "vsm", "msm")


def resolve_runs():
    """Forward shading against the deferred compute resolve (--resolve), at 1080p and 4K, for
    the filters whose cost the resolve changes, and with spot and point lights."""
    runs = []
    for label, size in (("1080p", []), ("4K", UHD)):
        runs += [(f"resolve {label}", f"{resolve}, {name}", None, ["--resolve", resolve] + size + args)
                 for name, args in FILTERS if name in RESOLVE_FILTERS for resolve in ("forward", "deferred")]
    forest = f"{BASELINE_SCENE}&spots=8&points=8"
    runs += [("resolve local lights", f"{resolve}, 8 spots + 8 points, {name}", forest,
              ["--resolve", resolve, "--local-shadow-budget", "16"] + args)
             for name, args in FILTERS if name in ("hard", "pcf r=2", "pcss high") for resolve in ("forward", "deferred")]
    return runs


def local_light_runs():
    """Spot and point lights over the baseline forest (docs/local-lights.md): count, kind,
    filter, sizing. The sun keeps its baseline settings except where the filter changes both."""
    def forest(spots=0, points=0, spot_angle=None):
        angle = f"&spot_angle={spot_angle}" if spot_angle else ""
        return f"{BASELINE_SCENE}&spots={spots}&points={points}{angle}"
    runs = [("local lights", "none", forest(), [])]
    runs += [("local lights", f"{n} spot{'s' if n > 1 else ''}", forest(spots=n), []) for n in (1, 8)]
    runs += [("local lights", "32 spots (budget 32)", forest(spots=32), ["--local-shadow-budget", "32"]),
             ("local lights", "64 spots, 32 shadowed", forest(spots=64), ["--local-shadow-budget", "32"]),
             ("local lights", "1 point", forest(points=1), []),
             ("local lights", "8 points (48 faces)", forest(points=8), []),
             ("local lights", "1 wide spot (100 deg, cube)", forest(spots=1, spot_angle=100), []),
             ("local lights", "8 wide spots (100 deg, 48 faces)", forest(spots=8, spot_angle=100), [])]
    runs += [("local filter", f"8 spots, {name}", forest(spots=8), args)
             for name, args in FILTERS if name in ("hard", "pcf r=1", "poisson", "pcss medium", "vsm", "msm")]
    runs += [("local sizing", "8 spots, coverage (default)", forest(spots=8), []),
             ("local sizing", "8 spots, fixed 1024", forest(spots=8), ["--local-shadow-sizing", "fixed"]),
             ("local sizing", "8 spots, fixed 2048", forest(spots=8),
              ["--local-shadow-sizing", "fixed", "--local-shadow-resolution", "2048"])]
    return runs


def merge_arguments(base, extra):
    """Baseline arguments with any flag in `extra` replaced by extra's value."""
    merged, i = [], 0
    extra_flags = {extra[j] for j in range(len(extra)) if extra[j].startswith("--")}
    while i < len(base):
        if base[i] in extra_flags:
            i += 2
            continue
        merged.append(base[i])
        i += 1
    return merged + extra


def run_id(index, axis, variant):
    text = f"{index:02d}-{axis}-{variant}".lower()
    return "".join(c if c.isalnum() or c in "-." else "_" for c in text)


def quick_arguments(arguments):
    """--quick: small sizes so the matrix runs on a CPU device in a minute or two."""
    shrink = {"--width": "160", "--height": "90", "--shadow-resolution": "512"}
    out, i = [], 0
    while i < len(arguments):
        flag = arguments[i]
        if flag in shrink and i + 1 < len(arguments):
            out += [flag, shrink[flag]]
            i += 2
        else:
            out.append(flag)
            i += 1
    return out


def run_one(binary, scene, arguments, json_path, common, timeout):
    command = [binary, "bench", scene] + arguments + common + ["--json", json_path]
    started = time.monotonic()
    try:
        done = subprocess.run(command, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return command, "failed", f"timed out after {timeout} s", None, time.monotonic() - started
    seconds = time.monotonic() - started
    reason = (done.stderr.strip().splitlines() or [""])[-1]
    if done.returncode == 2:
        return command, "skipped", reason, None, seconds
    if done.returncode != 0:
        return command, "failed", f"exit {done.returncode}: {reason}", None, seconds
    with open(json_path) as file:
        return command, "ok", "", json.load(file), seconds


def shadow_ms(report):
    """The sun's shadow passes (the spot/point lights' pass is its own column): the bench's
    per-frame total `shadow_sun` where it reports one (a scope absent from some frames, as a
    cached cascade's, would skew a sum of medians), else the sum of the scopes' medians."""
    if "shadow_sun" in report["gpu_ms"]:
        return report["gpu_ms"]["shadow_sun"]["median"]
    return sum(v["median"] for k, v in report["gpu_ms"].items()
               if k.startswith("shadow_") and k != "shadow_local")


def local_summary(report):
    """Shadowed local lights, their layers and the mean map size: '8 / 8 L / 512'."""
    lights = report.get("local_shadows", {}).get("lights", [])
    if not lights:
        return ""
    layers = sum(light["layers"] for light in lights)
    resolution = sum(light["resolution"]["mean"] for light in lights) / len(lights)
    return f"{len(lights)} / {layers} L / {resolution:.0f}"


def fmt(value, digits=3):
    return "" if value is None else f"{value:.{digits}f}"


def report_row(entry):
    r = entry["report"]
    if r is None:
        return f"| {entry['variant']} | {entry['status']}: {entry['reason']} | | | | | | | | | | |"
    gpu, cpu = r["gpu_ms"], r["cpu_ms"]
    frame = gpu.get("frame", {})
    lighting = gpu.get("lighting", {}).get("median")
    moments = sum(v["median"] for k, v in gpu.items() if "moments" in k) or None
    triangles = sum(c["triangles"]["mean"] for c in r["cascades"])
    ceiling = r.get("ceiling")
    extra = f"{ceiling['per_second']:.4g} {ceiling['unit']}/s" if ceiling else f"{triangles / 1e6:.2f}M"
    local = gpu.get("shadow_local", {}).get("median")
    prepass = gpu.get("prepass", {}).get("median")
    resolve = gpu.get("visibility", {}).get("median")
    return (f"| {entry['variant']} | {fmt(frame.get('median'))} | {fmt(frame.get('p95'))} | {fmt(shadow_ms(r))} | "
            f"{fmt(moments)} | {fmt(local)} | {local_summary(r)} | {fmt(prepass)} | {fmt(resolve)} | "
            f"{fmt(lighting)} | "
            f"{fmt(cpu.get('recording', {}).get('median'))} | {extra} |")


def write_report(path, entries, header):
    lines = [f"# Penumbra benchmark matrix", "", *header, "",
             "Times are medians over the measured frames in milliseconds (frame: also p95). "
             "Shadow = sum of the sun's shadow-pass scopes; local = the spot/point lights' pass "
             "(depth, and moments with a moment filter), with shadowed lights / layers / mean map size; "
             "prepass and resolve: the depth and normal pre-pass and the compute resolve of `--resolve deferred`; "
             "last column: the sun's shadow triangles submitted per frame (sum over cascades), or the "
             "ceiling rate.", ""]
    axis = None
    for entry in entries:
        if entry["axis"] != axis:
            axis = entry["axis"]
            lines += ["", f"## {axis}", "",
                      "| variant | frame | frame p95 | shadow | moments | local | local lights | prepass | resolve | "
                      "lighting | CPU recording | triangles / rate |",
                      "|---|---|---|---|---|---|---|---|---|---|---|---|"]
        lines.append(report_row(entry))
    with open(path, "w") as file:
        file.write("\n".join(lines) + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    here = os.path.dirname(os.path.abspath(__file__))
    parser.add_argument("--binary", default=os.path.join(here, "..", "build", "penumbra"))
    parser.add_argument("--out", default=os.path.join(here, "results"))
    parser.add_argument("--scenes-dir", default=os.path.join(here, "scenes"))
    parser.add_argument("--frames", type=int, default=60)
    parser.add_argument("--warmup", type=int, default=10)
    parser.add_argument("--device", default="", help="passed to --device")
    parser.add_argument("--quick", action="store_true", help="tiny sizes, 3 frames: a smoke test for CPU devices")
    parser.add_argument("--only", default="", help="run only the axes whose name contains this text")
    parser.add_argument("--timeout", type=int, default=120, help="seconds per run")
    args = parser.parse_args()

    frames, warmup = (3, 1) if args.quick else (args.frames, args.warmup)
    common = ["--frames", str(frames), "--warmup", str(warmup)]
    if args.device:
        common += ["--device", args.device]
    os.makedirs(os.path.join(args.out, "runs"), exist_ok=True)
    entries, started = [], time.monotonic()
    runs = [run for run in matrix(args.scenes_dir) if args.only in run[0]]
    for index, (axis, variant, scene, extra) in enumerate(runs):
        arguments = merge_arguments(BASELINE, extra)
        if args.quick:
            arguments = quick_arguments(arguments)
            scene = (scene or BASELINE_SCENE).replace("count=10000", "count=300")
        json_path = os.path.join(args.out, "runs", run_id(index, axis, variant) + ".json")
        command, status, reason, report, seconds = run_one(args.binary, scene or BASELINE_SCENE, arguments,
                                                           json_path, common, args.timeout)
        print(f"[{index + 1}/{len(runs)}] {axis} / {variant}: {status} {reason} ({seconds:.1f} s)", flush=True)
        entries.append({"axis": axis, "variant": variant, "command": shlex.join(command), "status": status,
                        "reason": reason, "seconds": seconds, "report": report})

    device = next((e["report"]["device"] for e in entries if e["report"]), {})
    header = [f"- date: {datetime.datetime.now().isoformat(timespec='seconds')}",
              f"- device: {device.get('name', '?')} ({device.get('driver', '?')})",
              f"- baseline: `{BASELINE_SCENE}` {' '.join(BASELINE)}, per-cascade, culling on, camera orbit; "
              f"{frames} frames after {warmup} warm-up",
              f"- runs: {sum(e['status'] == 'ok' for e in entries)} ok, "
              f"{sum(e['status'] == 'skipped' for e in entries)} skipped, "
              f"{sum(e['status'] == 'failed' for e in entries)} failed; {time.monotonic() - started:.0f} s in all"]
    with open(os.path.join(args.out, "matrix.json"), "w") as file:
        json.dump({"header": header, "runs": entries}, file, indent=1)
    write_report(os.path.join(args.out, "report.md"), entries, header)
    print(f"wrote {os.path.join(args.out, 'report.md')} and matrix.json")
    return 1 if any(e["status"] == "failed" for e in entries) else 0


if __name__ == "__main__":
    sys.exit(main())
