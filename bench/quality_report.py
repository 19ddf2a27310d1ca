#!/usr/bin/env python3
"""Runs the `penumbra compare` matrix and writes the quality report (docs/QUALITY.md).

Every filter mode the binary accepts x fit mode (stable, tight) x 1 / 4 cascades, on the
built-in scenes and the real glTF scenes of ../shared/assets (bench/scenes/quality-*.toml;
skipped when the assets are absent), then one-axis sweeps of the defaults (slope bias,
normal offset, split lambda, blend width) around Penumbra's defaults. Filter modes are
read from `penumbra compare --help` and each is probed with a tiny run: modes the binary
rejects (exit 2) are skipped. Python 3 standard library only.

    python3 bench/quality_report.py --binary build/penumbra            # 480x270 (lavapipe: ~20 min)
    python3 bench/quality_report.py --binary build/penumbra --quick    # smoke test, 96x54
    python3 bench/quality_report.py --binary build/penumbra --assets-only   # the real-asset table alone

The real-asset table runs hard, pcf and pcss at the default settings on glTF models of
Debian's assimp-testmodels package (/usr/share/assimp/models/glTF2) and on ../shared/assets,
checks them against the quality goals of issue 16 and says which assets are absent. It has
markers of its own in docs/QUALITY.md, so --assets-only regenerates it alone.

Outputs: --work DIR/<run>/ (compare.json and images of every run), DIR/quality.json (all
runs), and, unless --no-docs, the report: docs/QUALITY.md with its generated parts
(between the BEGIN/END GENERATED markers; the prose around them is kept) replaced, written
to --out (default DIR/QUALITY.md, with its images in DIR/images/quality/). The tracked page
changes only when asked for: `--out docs/QUALITY.md`.

Every real asset must be present (they are checked before anything runs: exit 2 naming the
missing ones), so that a clone without them does not replace measured rows with "absent"
ones; --allow-missing runs without them and lists them as absent.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ASSETS = os.path.join(ROOT, "..", "shared", "assets")
SCENES = [
    ("default", "builtin:default", False),
    ("box-on-plane", "builtin:box-on-plane", False),
    ("oak-terrain", os.path.join(ROOT, "bench", "scenes", "quality-oak-terrain.toml"), True),
    ("alpha-modes", os.path.join(ROOT, "bench", "scenes", "quality-alpha-modes.toml"), True),
]
ASSIMP_MODELS = "/usr/share/assimp/models/glTF2"
# (name, scene, the asset file it needs, where that comes from): the real-asset table.
ASSET_SCENES = [
    ("engine", "quality-engine.toml", os.path.join(ASSIMP_MODELS, "2CylinderEngine-glTF-Binary", "2CylinderEngine.glb"),
     "assimp-testmodels"),
    ("clearcoat", "quality-clearcoat.toml", os.path.join(ASSIMP_MODELS, "ClearCoat-glTF", "ClearCoatTest.gltf"),
     "assimp-testmodels"),
    ("textured-box", "quality-textured-box.toml",
     os.path.join(ASSIMP_MODELS, "BoxTextured-glTF-Binary", "BoxTextured.glb"), "assimp-testmodels"),
    ("oak-terrain", "quality-oak-terrain.toml", os.path.join(ASSETS, "oaktree", "oaktree.gltf"), "../shared/assets"),
    ("alpha-modes", "quality-alpha-modes.toml",
     os.path.join(ASSETS, "AlphaBlendModeTest", "glTF", "AlphaBlendModeTest.gltf"), "../shared/assets"),
]
ASSET_FILTERS = ["hard", "pcf", "pcss"]
# Issue 16's goals at the default settings: false shadow <= 0.1 % and false lit <= 0.5 %
# outside the 2-px edge band; the PCSS penumbra within 0.3 px of the reference's width.
GOAL_FALSE_SHADOW, GOAL_FALSE_LIT, GOAL_PCSS_WIDTH = 0.1, 0.5, 0.3
FITS = ["stable", "tight"]
CASCADES = [1, 4]
# One axis at a time around the defaults (src/core/shadow_settings.hpp).
SWEEPS = [
    ("slope_bias", "--slope-bias", ["0", "0.5", "1", "2", "4"]),
    ("normal_offset", "--normal-offset", ["0", "0.5", "1", "2", "4"]),
    ("split_lambda", "--split-lambda", ["0.5", "0.75", "0.9"]),
    ("blend_width", "--blend-width", ["0", "0.1", "0.2"]),
]
SWEEP_SCENES = ["default", "oak-terrain"]
BEGIN, END = "<!-- BEGIN GENERATED -->", "<!-- END GENERATED -->"
ASSETS_BEGIN, ASSETS_END = "<!-- BEGIN GENERATED ASSETS -->", "<!-- END GENERATED ASSETS -->"


def run(binary, args, out_dir):
    os.makedirs(out_dir, exist_ok=True)
    command = [binary, "compare"] + args + ["--out-dir", out_dir]
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        return {"status": "skipped" if done.returncode == 2 else "failed", "reason": done.stderr.strip()}
    with open(os.path.join(out_dir, "compare.json")) as file:
        return {"status": "ok", "report": json.load(file)}


def filter_modes(binary, work):
    """Names after --filter in the help text, kept when a tiny run accepts them."""
    help_text = subprocess.run([binary, "compare", "--help"], capture_output=True, text=True).stdout
    match = re.search(r"--filter\s+\S+\s+[^:]*?:\s*([^\n]+)", help_text)
    candidates = ["hard"]
    if match:
        candidates = [re.sub(r"\s*\(.*?\)", "", name).strip() for name in match.group(1).split("|")]
    modes = []
    for mode in candidates:
        probe = ["--filter", mode, "--width", "16", "--height", "16", "--rays", "1", "--stability-frames", "1"]
        result = run(binary, probe, os.path.join(work, "probe-" + mode))
        if result["status"] == "ok":
            modes.append(mode)
        else:
            print(f"quality: skipping filter {mode}: {result['reason']}", file=sys.stderr)
    return modes


def size_args(quick):
    if quick:
        return ["--width", "96", "--height", "54", "--rays", "4", "--stability-frames", "2"]
    return ["--width", "480", "--height", "270", "--rays", "32", "--stability-frames", "6"]


def scenes(skip_assets):
    available = os.path.isdir(ASSETS) and not skip_assets
    return [(name, spec) for name, spec, needs_assets in SCENES if available or not needs_assets]


def run_matrix(binary, work, quick, modes, scene_list):
    runs = []
    for scene_name, spec in scene_list:
        for mode in modes:
            for fit in FITS:
                for cascades in CASCADES:
                    run_id = f"{scene_name}-{mode}-{fit}-{cascades}c"
                    args = [spec, "--filter", mode, "--fit", fit, "--cascades", str(cascades)] + size_args(quick)
                    print(f"quality: {run_id}", file=sys.stderr, flush=True)
                    result = run(binary, args, os.path.join(work, run_id))
                    runs.append({"id": run_id, "scene": scene_name, "filter": mode, "fit": fit,
                                 "cascades": cascades, **result})
    return runs


def run_sweeps(binary, work, quick, scene_list):
    runs = []
    for scene_name, spec in scene_list:
        if scene_name not in SWEEP_SCENES:
            continue
        for axis, flag, values in SWEEPS:
            for value in values:
                run_id = f"sweep-{scene_name}-{axis}-{value}"
                print(f"quality: {run_id}", file=sys.stderr, flush=True)
                result = run(binary, [spec, flag, value] + size_args(quick), os.path.join(work, run_id))
                runs.append({"id": run_id, "scene": scene_name, "axis": axis, "value": value, **result})
    return runs


def metrics_cells(report):
    hard, soft, stability = report["hard"], report["soft"], report["stability"] or {}
    return [f"{hard['false_shadow']['percent']:.3f}", f"{hard['false_shadow_outside_edges']['percent']:.3f}",
            f"{hard['false_lit']['percent']:.2f}", f"{hard['false_lit_outside_edges']['percent']:.2f}",
            f"{soft['mean_abs_error']:.4f}", f"{soft['p95_abs_error']:.3f}", f"{soft['edge_mean_abs_error']:.3f}",
            f"{soft['penumbra_width_render_px']:.2f} / {soft['penumbra_width_reference_px']:.2f}",
            f"{stability.get('mean_change', 0.0):.5f}", f"{stability.get('flicker_percent', 0.0):.3f}"]


METRIC_HEADER = ("false shadow % | (outside edges) | false lit % | (outside edges) | mean abs err | p95 | "
                 "edge err | penumbra px (render / ref) | shimmer mean | flicker %")


def matrix_tables(runs):
    lines = []
    for scene_name in dict.fromkeys(run["scene"] for run in runs):
        scene_runs = [run for run in runs if run["scene"] == scene_name]
        first = next((run for run in scene_runs if run["status"] == "ok"), None)
        evaluated = first["report"]["pixels"]["evaluated"] if first else 0
        lines += [f"### {scene_name}", "", f"{evaluated} evaluated pixels.", "",
                  f"| filter | fit | cascades | {METRIC_HEADER} |", "|---" * 13 + "|"]
        for run in scene_runs:
            cells = metrics_cells(run["report"]) if run["status"] == "ok" else [run["status"]] + [""] * 9
            lines.append(f"| {run['filter']} | {run['fit']} | {run['cascades']} | " + " | ".join(cells) + " |")
        lines.append("")
    return lines


def sweep_tables(runs):
    lines = []
    for scene_name in dict.fromkeys(run["scene"] for run in runs):
        for axis, _, _ in SWEEPS:
            axis_runs = [run for run in runs if run["scene"] == scene_name and run["axis"] == axis]
            if not axis_runs:
                continue
            lines += [f"#### {scene_name}: {axis}", "", f"| {axis} | {METRIC_HEADER} |", "|---" * 11 + "|"]
            for run in axis_runs:
                cells = metrics_cells(run["report"]) if run["status"] == "ok" else [run["status"]] + [""] * 9
                lines.append(f"| {run['value']} | " + " | ".join(cells) + " |")
            lines.append("")
    return lines


def copy_images(work, runs, images_dir):
    """The side-by-side of every scene's default configuration (hard, stable, 4 cascades)."""
    os.makedirs(images_dir, exist_ok=True)
    lines = []
    for run in runs:
        if run["status"] != "ok" or (run["filter"], run["fit"], run["cascades"]) != ("hard", "stable", 4):
            continue
        name = f"{run['scene']}-side-by-side.png"
        shutil.copyfile(os.path.join(work, run["id"], "side_by_side.png"), os.path.join(images_dir, name))
        lines += [f"**{run['scene']}** (hard, stable, 4 cascades): render | soft reference | errors", "",
                  f"![{run['scene']}](images/quality/{name})", ""]
    return lines


def run_assets(binary, work, quick):
    """hard, pcf and pcss at the defaults on every real asset; an absent asset is one entry."""
    runs = []
    for scene_name, scene_file, asset, source in ASSET_SCENES:
        if not os.path.exists(asset):
            print(f"quality: asset {scene_name} absent ({asset}, from {source})", file=sys.stderr)
            runs.append({"id": f"asset-{scene_name}", "scene": scene_name, "status": "absent", "asset": asset,
                         "source": source})
            continue
        for mode in ASSET_FILTERS:
            run_id = f"asset-{scene_name}-{mode}"
            print(f"quality: {run_id}", file=sys.stderr, flush=True)
            spec = os.path.join(ROOT, "bench", "scenes", scene_file)
            result = run(binary, [spec, "--filter", mode] + size_args(quick), os.path.join(work, run_id))
            runs.append({"id": run_id, "scene": scene_name, "filter": mode, "source": source, **result})
    return runs


def asset_cells(report):
    hard, soft, noise = report["hard"], report["soft"], report.get("sampling_noise") or {}
    return [f"{hard['false_shadow']['percent']:.3f}", f"{hard['false_shadow_outside_edges']['percent']:.3f}",
            f"{hard['false_lit']['percent']:.2f}", f"{hard['false_lit_outside_edges']['percent']:.3f}",
            f"{soft['mean_abs_error']:.4f}", f"{soft['edge_mean_abs_error']:.3f}",
            f"{soft['penumbra_width_render_px']:.2f} / {soft['penumbra_width_reference_px']:.2f}",
            f"{soft['penumbra_width_error_px']:+.2f}", f"{noise.get('mean_change', 0.0):.5f}"]


def asset_goals(report, mode):
    """The goals this run misses, as text ("" when it meets them)."""
    hard, soft = report["hard"], report["soft"]
    missed = []
    if hard["false_shadow_outside_edges"]["percent"] > GOAL_FALSE_SHADOW:
        missed.append(f"false shadow {hard['false_shadow_outside_edges']['percent']:.3f} % > {GOAL_FALSE_SHADOW}")
    if hard["false_lit_outside_edges"]["percent"] > GOAL_FALSE_LIT:
        missed.append(f"false lit {hard['false_lit_outside_edges']['percent']:.3f} % > {GOAL_FALSE_LIT}")
    if mode == "pcss" and abs(soft["penumbra_width_error_px"]) > GOAL_PCSS_WIDTH:
        missed.append(f"width {soft['penumbra_width_error_px']:+.2f} px, more than {GOAL_PCSS_WIDTH} off")
    return "; ".join(missed)


ASSET_HEADER = ("| asset | filter | false shadow % | (outside edges) | false lit % | (outside edges) | soft mean abs err | "
                "edge err | penumbra px (render / ref) | width error px | frame change | goals |")


def asset_table(runs):
    lines = [ASSET_HEADER, "|---" * 12 + "|"]
    for run in runs:
        if run["status"] == "absent":
            lines.append(f"| {run['scene']} | absent: {run['asset']} (install {run['source']}) |" + " |" * 10)
        elif run["status"] != "ok":
            lines.append(f"| {run['scene']} | {run['filter']}: {run['status']} |" + " |" * 10)
        else:
            missed = asset_goals(run["report"], run["filter"])
            cells = asset_cells(run["report"]) + [("missed: " + missed) if missed else "met"]
            lines.append(f"| {run['scene']} | {run['filter']} | " + " | ".join(cells) + " |")
    return lines


def asset_section(runs, quick, binary):
    size = " ".join(size_args(quick))
    commit = subprocess.run(["git", "-C", ROOT, "describe", "--always", "--dirty"], capture_output=True,
                            text=True).stdout.strip() or "unknown"
    device = next((run["report"]["device"] for run in runs if run["status"] == "ok"), "no device")
    date = subprocess.run(["date", "-u", "+%Y-%m-%d"], capture_output=True, text=True).stdout.strip()
    return [f"Generated by `python3 bench/quality_report.py --binary {binary} --assets-only` "
            f"(or a full run) at commit `{commit}` on {date}, {device}, `{size}`, every other setting at its "
            "default (stable fit, 4 cascades, 2048 texels, 0.53 degree sun as the scenes set it).", "",
            "Goals (issue 16), at the default settings: false shadow <= 0.1 % and false lit <= 0.5 % outside "
            "the 2-px edge band; for pcss, the penumbra width within 0.3 px of the reference's. \"frame change\" "
            "is compare's sampling noise: the mean per-pixel change of frame 0 rendered again with its sampling "
            "pattern rotated, the grain a temporal filter averages away (0 for hard and pcf, which do not "
            "rotate).", ""] + \
        asset_table(runs) + [""]


def start_report(out):
    """The report starts as a copy of the tracked page (its prose), unless it is that page."""
    page = os.path.join(ROOT, "docs", "QUALITY.md")
    if os.path.abspath(out) != os.path.abspath(page):
        os.makedirs(os.path.dirname(out), exist_ok=True)
        shutil.copyfile(page, out)


def write_section(docs_path, generated, begin, end):
    text = open(docs_path).read() if os.path.exists(docs_path) else f"# Shadow quality\n\n{begin}\n{end}\n"
    if begin not in text:
        text += f"\n{begin}\n{end}\n"
    start, stop = text.index(begin) + len(begin), text.index(end)
    with open(docs_path, "w") as file:
        file.write(text[:start] + "\n" + "\n".join(generated) + "\n" + text[stop:])


def write_docs(docs_path, generated):
    write_section(docs_path, generated, BEGIN, END)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--binary", default=os.path.join(ROOT, "build", "penumbra"))
    parser.add_argument("--work", default=os.path.join(ROOT, "build", "quality"))
    parser.add_argument("--quick", action="store_true", help="tiny sizes (smoke test)")
    parser.add_argument("--no-assets", action="store_true", help="built-in scenes only")
    parser.add_argument("--no-docs", action="store_true", help="write no report, only the runs' JSON")
    parser.add_argument("--out", help="the report (default: WORK/QUALITY.md; docs/QUALITY.md updates the page)")
    parser.add_argument("--allow-missing", action="store_true",
                        help="run without the real assets that are absent, listing them as absent")
    parser.add_argument("--assets-only", action="store_true", help="only the real-asset table")
    options = parser.parse_args()
    out = os.path.abspath(options.out or os.path.join(options.work, "QUALITY.md"))
    missing = [f"{name} ({asset}, from {source})" for name, _, asset, source in ASSET_SCENES
               if not os.path.exists(asset)]
    if missing and not (options.allow_missing or options.no_assets):
        print("quality_report: real assets missing: " + "; ".join(missing) +
              " (install them, or give --allow-missing to list them as absent)", file=sys.stderr)
        return 2

    os.makedirs(options.work, exist_ok=True)
    if not options.no_docs:
        start_report(out)
    asset_runs = run_assets(options.binary, options.work, options.quick)
    with open(os.path.join(options.work, "quality-assets.json"), "w") as file:
        json.dump(asset_runs, file, indent=1)
    if not options.no_docs:
        write_section(out, asset_section(asset_runs, options.quick, options.binary), ASSETS_BEGIN, ASSETS_END)
    asset_failed = [run["id"] for run in asset_runs if run["status"] == "failed"]
    if options.assets_only:
        if asset_failed:
            print("quality: failed runs: " + ", ".join(asset_failed), file=sys.stderr)
        return 1 if asset_failed else 0
    modes = filter_modes(options.binary, options.work)
    scene_list = scenes(options.no_assets)
    matrix_runs = run_matrix(options.binary, options.work, options.quick, modes, scene_list)
    sweep = run_sweeps(options.binary, options.work, options.quick, scene_list)
    with open(os.path.join(options.work, "quality.json"), "w") as file:
        json.dump({"filters": modes, "matrix": matrix_runs, "sweeps": sweep}, file, indent=1)
    if options.no_docs:
        return 0
    size = " ".join(size_args(options.quick))
    device = next((run["report"]["device"] for run in matrix_runs if run["status"] == "ok"), "no device")
    generated = [f"Generated by `python3 bench/quality_report.py` on {device}, `{size}`.", "",
                 "## Matrix", ""] + matrix_tables(matrix_runs)
    generated += ["## Sweeps of the defaults (hard filter, stable fit, 4 cascades)", ""] + sweep_tables(sweep)
    generated += ["## Images", ""] + copy_images(options.work, matrix_runs,
                                                 os.path.join(os.path.dirname(out), "images", "quality"))
    write_docs(out, generated)
    failed = asset_failed + [run["id"] for run in matrix_runs + sweep if run["status"] == "failed"]
    if failed:
        print("quality: failed runs: " + ", ".join(failed), file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
