#!/usr/bin/env python3
"""Side-by-side bench runs of several penumbra binaries (or settings) on one GPU, in one
call of the device tool, so that every comparison is measured on the same machine in the
same session (docs/PERFORMANCE.md). Each run is `penumbra bench ... --json`; the report is
a markdown table of the per-frame GPU medians that the comparisons read (shadow_sun:
the sun's whole shadow work; lighting; visibility; frame) and the cached cascades' texel
counts, plus every run's JSON.

Usage: ab_runs.py --binary NAME=PATH [--binary ...] --plan cache|cache-each|local|movers|moments|filters|strategies|cached-strategies|goals|virtual|all --out DIR
(cache-each: the cache runs for every binary given, e.g. two layouts of the cascades)
"""
import argparse
import json
import os
import subprocess
import sys

FOREST = "builtin:forest?count=1000"  # 1 M triangles, the matrix's baseline scene
BASE = ["--width", "1920", "--height", "1080", "--cascades", "4", "--shadow-resolution", "2048"]
UHD = ["--width", "3840", "--height", "2160", "--cascades", "4", "--shadow-resolution", "2048"]


FRAMES = {"orbit": 60, "walk": 120, "flythrough": 120, "still": 60}


def cache_pairs(binary, label, scene, paths, extra=(), tag=""):
    """Cache off and on along each of `paths`, same scene and arguments (issue 15's numbers).
    Labels read "<label>, cache on, walk (120 frames)<tag>"."""
    runs = []
    for path in paths:
        for cache in ("off", "on"):
            arguments = BASE + list(extra) + ["--camera-path", path, "--frames", str(FRAMES[path]), "--warmup", "10"]
            if cache == "on":
                arguments.append("--shadow-cache")
            prefix = f"{label}, " if label else ""
            runs.append((f"{prefix}cache {cache}, {path} ({FRAMES[path]} frames){tag}", binary, scene, arguments))
    return runs


def cache_runs(binary, tag=""):
    """Cached cascades along each camera path."""
    return cache_pairs(binary, "", FOREST, ("orbit", "walk", "flythrough", "still"), tag=tag)


def local_runs(binary):
    """8 static spot and 8 static point lights over the forest."""
    return cache_pairs(binary, "local lights", f"{FOREST}&spots=8&points=8", ("still", "walk", "orbit"),
                       ["--local-shadow-budget", "16"])


def mover_runs(binary):
    """10 dynamic crowns moving every frame over the forest."""
    return cache_pairs(binary, "10 movers", f"{FOREST}&movers=10", ("still", "walk", "orbit"), ["--animate-dynamic"])


def moment_runs(binary):
    """The moment filters with cached cascades: moments updated only around changed depth."""
    runs = []
    for name in ("vsm", "evsm", "msm"):
        runs += cache_pairs(binary, name, FOREST, ("walk", "orbit"), ["--filter", name])
    return runs


def filter_runs(binaries):
    """The filters at 4K, forward and deferred, for every binary given (same-call A/B)."""
    runs = []
    configs = [("pcf R=2", ["--filter", "pcf", "--pcf-radius", "2"]),
               ("pcss high", ["--filter", "pcss", "--pcss-quality", "high"]),
               ("hard", ["--filter", "hard"])]
    for label, args in configs:
        for resolve in ("forward", "deferred"):
            for binary in binaries:
                runs.append((f"{label}, {resolve}, 4K [{binary}]", binary, FOREST,
                             UHD + args + ["--resolve", resolve, "--frames", "60", "--warmup", "10"]))
    lights = f"{FOREST}&spots=8&points=8"
    for binary in binaries:
        runs.append((f"pcss high, deferred, 8 spots + 8 points, 1080p [{binary}]", binary, lights,
                     BASE + ["--filter", "pcss", "--pcss-quality", "high", "--resolve", "deferred",
                             "--frames", "60", "--warmup", "10"]))
    return runs


FOREST_10M = "builtin:forest?count=10000"  # 10 M triangles, 30,001 instances


def strategy_runs(binary):
    """The three shadow strategies (CPU culling per cascade, multiview, GPU-driven layered),
    and per-cascade with the static caster cache, on the 1 M and 10 M forests, orbiting (the
    cascades move every frame), 1080p and 4K."""
    runs = []
    for scene_label, scene in (("1 M", FOREST), ("10 M", FOREST_10M)):
        for size_label, size in (("1080p", BASE), ("4K", UHD)):
            for strategy in ("per-cascade", "multiview", "layered", "per-cascade+cache"):
                options = ["--shadow-strategy", strategy.split("+")[0]] + (["--shadow-cache"] if "+cache" in strategy else [])
                runs.append((f"{scene_label}, {size_label}, {strategy}", binary, scene,
                             size + options + ["--camera-path", "orbit", "--frames", "60", "--warmup", "10"]))
    return runs


def cached_strategy_runs(binary):
    """The static caster cache with CPU culling (per-cascade) and GPU culling (layered), and
    the layered strategy uncached, on the 1 M and 10 M forests at 1080p, orbiting (strips
    exposed every frame) and walking."""
    runs = []
    for scene_label, scene in (("1 M", FOREST), ("10 M", FOREST_10M)):
        for path in ("orbit", "walk"):
            for strategy in ("per-cascade+cache", "layered+cache", "layered"):
                options = ["--shadow-strategy", strategy.split("+")[0]] + (["--shadow-cache"] if "+cache" in strategy else [])
                runs.append((f"{scene_label}, 1080p, {path}, {strategy}", binary, scene,
                             BASE + options + ["--camera-path", path, "--frames", "60", "--warmup", "10"]))
    return runs


def goal_runs(binary):
    """Issue 14's frame goals: PCF R=2 at 4K forward, deferred, and deferred with cached
    cascades (orbit); 8 spots + 8 points culled on the CPU and on the GPU."""
    runs = []
    pcf = ["--filter", "pcf", "--pcf-radius", "2", "--camera-path", "orbit", "--frames", "60", "--warmup", "10"]
    for label, extra in (("forward", ["--resolve", "forward"]), ("deferred", ["--resolve", "deferred"]),
                         ("deferred + cache", ["--resolve", "deferred", "--shadow-cache"])):
        runs.append((f"pcf R=2, 4K, {label}, orbit", binary, FOREST, UHD + pcf + extra))
    lights = f"{FOREST}&spots=8&points=8"
    local = ["--local-shadow-budget", "16", "--camera-path", "orbit", "--frames", "60", "--warmup", "10"]
    for strategy in ("per-cascade", "layered"):
        runs.append((f"8 spots + 8 points, 1080p, {strategy}, orbit", binary, lights,
                     BASE + local + ["--shadow-strategy", strategy]))
    return runs


def virtual_runs(binary):
    """Issue 28's goals: the virtual shadow map against the cascades (both cached) on the 1 M
    forest at 1080p, orbiting, walking, and with a sun that turns every frame (every page
    stale); the marking and allocation at 4K, camera still."""
    runs = []
    for label, extra in (("orbit", ["--camera-path", "orbit", "--frames", "60"]),
                         ("walk", ["--camera-path", "walk", "--frames", "120"]),
                         ("rotating sun", ["--camera-path", "still", "--light-path", "rotate", "--frames", "60"])):
        for technique in ("cascades", "virtual"):
            runs.append((f"1 M, 1080p, {technique}, cache, {label}", binary, FOREST,
                         BASE + extra + ["--warmup", "10", "--shadow-cache", "--shadow-technique", technique]))
    runs.append(("1 M, 4K, virtual, cache, still", binary, FOREST,
                 UHD + ["--camera-path", "still", "--frames", "60", "--warmup", "10", "--shadow-cache",
                        "--shadow-technique", "virtual"]))
    return runs


TERRAIN = "builtin:terrain"  # 20 km, 1.1 M triangles: casters from 8 m to 9 km


def terrain_runs(binary):
    """Issue 28's open world: the virtual shadow map against the cascades (both cached) on
    the terrain at 4K with the shadow distance stretched to 6 km, walking, orbiting and with
    a sun that turns every frame; the virtual map alone with the camera still."""
    runs = []
    far = ["--max-distance", "6000", "--warmup", "10", "--shadow-cache"]
    for label, extra in (("walk", ["--camera-path", "walk", "--frames", "120"]),
                         ("orbit", ["--camera-path", "orbit", "--frames", "60"]),
                         ("rotating sun", ["--camera-path", "still", "--light-path", "rotate", "--frames", "60"])):
        for technique in ("cascades", "virtual"):
            runs.append((f"terrain, 4K, {technique}, cache, 6 km, {label}", binary, TERRAIN,
                         UHD + far + extra + ["--shadow-technique", technique]))
    runs.append(("terrain, 4K, virtual, cache, 6 km, still", binary, TERRAIN,
                 UHD + far + ["--camera-path", "still", "--frames", "60", "--shadow-technique", "virtual"]))
    return runs


def median(report, name):
    entry = report["gpu_ms"].get(name)
    return entry["median"] if entry else None


def cpu_median(report, name):
    entry = report.get("cpu_ms", {}).get(name)
    return entry["median"] if entry else None


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--binary", action="append", required=True, help="NAME=PATH of a penumbra(-run) binary")
    parser.add_argument("--plan", choices=["cache", "cache-each", "local", "movers", "moments", "filters", "strategies", "cached-strategies", "goals",
                                           "virtual", "terrain", "all"],
                        default="all")
    parser.add_argument("--cache-binary", help="NAME of the binary for the cache runs (default: the first)")
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    binaries = dict(item.split("=", 1) for item in args.binary)
    names = list(binaries)
    runs = []
    if args.plan in ("cache", "all"):
        runs += cache_runs(args.cache_binary or names[0])
    if args.plan in ("moments", "all"):
        runs += moment_runs(args.cache_binary or names[0])
    if args.plan in ("movers", "all"):
        runs += mover_runs(args.cache_binary or names[0])
    if args.plan in ("local", "all"):
        runs += local_runs(args.cache_binary or names[0])
    if args.plan == "cache-each":
        for name in names:
            runs += cache_runs(name, f" [{name}]")
    if args.plan in ("filters", "all"):
        runs += filter_runs(names)
    if args.plan in ("strategies", "all"):
        runs += strategy_runs(args.cache_binary or names[0])
    if args.plan in ("cached-strategies", "all"):
        runs += cached_strategy_runs(args.cache_binary or names[0])
    if args.plan in ("goals", "all"):
        runs += goal_runs(args.cache_binary or names[0])
    if args.plan in ("virtual", "all"):
        runs += virtual_runs(args.cache_binary or names[0])
    if args.plan in ("terrain", "all"):
        runs += terrain_runs(args.cache_binary or names[0])
    os.makedirs(args.out, exist_ok=True)
    rows = ["| run | shadow_sun ms | shadow_local ms | lighting ms | visibility ms | frame ms | texels drawn / frame | texels copied / frame | local layers kept / frame | CPU culling ms | CPU recording ms | virtual mark + allocate ms | virtual cull + raster ms | pages drawn / frame | pages unserved / frame |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    results = []
    for index, (label, binary, scene, extra) in enumerate(runs):
        json_path = os.path.join(args.out, f"run{index:02d}.json")
        command = [binaries[binary], "bench", scene, "--json", json_path] + extra
        print(f"[{index + 1}/{len(runs)}] {label}: {' '.join(command[1:])}", flush=True)
        done = subprocess.run(command, capture_output=True, text=True)
        if done.returncode != 0:
            print(done.stderr, file=sys.stderr)
            rows.append(f"| {label} | failed ({done.returncode}) | | | | | | | | | | | | | |")
            continue
        with open(json_path) as file:
            report = json.load(file)
        cascades = report["cascades"]
        drawn = sum(c["texels_rendered"]["mean"] for c in cascades) if cascades and "texels_rendered" in cascades[0] else None
        copied = sum(c["texels_copied"]["mean"] for c in cascades) if cascades and "texels_copied" in cascades[0] else None
        virtual = report.get("virtual_map")
        pair = lambda a, b: None if median(report, a) is None else median(report, a) + (median(report, b) or 0.0)
        virtual_cells = [pair("shadow_virtual_mark", "shadow_virtual_allocate"),
                         pair("shadow_virtual_cull", "shadow_virtual_raster"),
                         round(virtual["pages_rendered"]["mean"], 1) if virtual else None,
                         round(virtual["pages_unserved"]["mean"], 1) if virtual else None]
        cells = [median(report, n) for n in ("shadow_sun", "shadow_local", "lighting", "visibility", "frame")]
        kept = sum(l["layers_kept"]["mean"] for l in report["local_shadows"]["lights"]
                   if "layers_kept" in l) if report.get("local_shadows", {}).get("lights") else None
        fmt = lambda v: "" if v is None else (f"{v:.3f}" if isinstance(v, float) else str(v))
        rows.append(f"| {label} | " + " | ".join(fmt(c) for c in cells) +
                    f" | {fmt(None if drawn is None else round(drawn))} | {fmt(None if copied is None else round(copied))}"
                    f" | {fmt(None if kept is None else round(kept, 1))} | {fmt(cpu_median(report, 'culling'))}"
                    f" | {fmt(cpu_median(report, 'recording'))} | " + " | ".join(fmt(c) for c in virtual_cells) + " |")
        results.append({"label": label, "binary": binary, "scene": scene, "args": extra, "report": report})
        write_report(args.out, rows, results)  # after every run: a run cut short keeps what it measured
    print(write_report(args.out, rows, results))


def write_report(out, rows, results):
    device = results[0]["report"]["device"]["name"] if results else "?"
    text = f"Device: {device}\n\n" + "\n".join(rows) + "\n"
    with open(os.path.join(out, "ab.md"), "w") as file:
        file.write(text)
    with open(os.path.join(out, "ab.json"), "w") as file:
        json.dump(results, file, indent=1)
    return text


if __name__ == "__main__":
    main()
