#!/usr/bin/env python3
"""Contact shadows against the ray-traced reference: `penumbra compare` with them off and on.

For each scene (the built-in box-on-plane and default scenes, and the real assets of
docs/QUALITY.md when they are installed), at the default settings and the default filter,
compares the sun's shadow with contact shadows off and on and writes one markdown table
(to --out, default build/contact/contact.md) and the raw reports (contact.json beside it):
false lit and false shadow in the 4-px band around contact lines (compare's "contact"
numbers: pixels shadowed by an occluder within 0.25 m) and outside the shadow edges. Then
box-on-plane, seen from its shadow side, and the engine model again under one coarse
cascade (512 x 512), whose texels and normal offset detach shadows from their casters: the
case contact shadows are for. Issue 29's goals: false lit near contacts at least halved on
box-on-plane and the engine model (the coarse rows: at the defaults the cascades keep their
contacts), false shadow outside edges at most 0.1 % wherever the map alone was.

    python3 bench/contact_report.py --binary build/penumbra
    python3 bench/contact_report.py --binary build/penumbra --quick   # tiny sizes (smoke test)

An asset that is absent is listed as such (nothing is measured for it); the script never
writes into docs/. Standard library only.
"""
import argparse
import json
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ASSETS = os.path.join(ROOT, "..", "shared", "assets")
ASSIMP_MODELS = "/usr/share/assimp/models/glTF2"
SCENES_DIR = os.path.join(ROOT, "bench", "scenes")
ENGINE = os.path.join(ASSIMP_MODELS, "2CylinderEngine-glTF-Binary", "2CylinderEngine.glb")
SHADOW_SIDE = ["--eye", "-3,1.2,-3", "--target", "-1,0,-1"]
COARSE = ["--cascades", "1", "--shadow-resolution", "512"]
# (name, scene, extra arguments, the file it needs or None, whether the false-lit goal applies)
SCENES = [
    ("box-on-plane", "builtin:box-on-plane", [], None, False),
    ("default", "builtin:default", [], None, False),
    ("engine", os.path.join(SCENES_DIR, "quality-engine.toml"), [], ENGINE, False),
    ("clearcoat", os.path.join(SCENES_DIR, "quality-clearcoat.toml"), [],
     os.path.join(ASSIMP_MODELS, "ClearCoat-glTF", "ClearCoatTest.gltf"), False),
    ("textured-box", os.path.join(SCENES_DIR, "quality-textured-box.toml"), [],
     os.path.join(ASSIMP_MODELS, "BoxTextured-glTF-Binary", "BoxTextured.glb"), False),
    ("oak-terrain", os.path.join(SCENES_DIR, "quality-oak-terrain.toml"), [],
     os.path.join(ASSETS, "oaktree", "oaktree.gltf"), False),
    ("alpha-modes", os.path.join(SCENES_DIR, "quality-alpha-modes.toml"), [],
     os.path.join(ASSETS, "AlphaBlendModeTest", "glTF", "AlphaBlendModeTest.gltf"), False),
    ("box-on-plane, shadow side, 1 x 512", "builtin:box-on-plane", SHADOW_SIDE + COARSE, None, True),
    ("engine, 1 x 512", os.path.join(SCENES_DIR, "quality-engine.toml"), COARSE, ENGINE, True),
]
GOAL_FALSE_SHADOW = 0.1  # % outside edges, with contact shadows on
GOAL_FALSE_LIT_RATIO = 0.5  # near contacts, on / off


def size_args(quick):
    if quick:
        return ["--width", "96", "--height", "54", "--rays", "4", "--stability-frames", "1"]
    return ["--width", "480", "--height", "270", "--rays", "32", "--stability-frames", "1"]


def compare(binary, scene, extra, out_dir):
    os.makedirs(out_dir, exist_ok=True)
    command = [binary, "compare", scene] + extra + ["--out-dir", out_dir]
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit(f"contact_report: {' '.join(command)} failed ({done.returncode}): {done.stderr.strip()}")
    with open(os.path.join(out_dir, "compare.json")) as file:
        return json.load(file)


def row(name, off, on, goal_lit):
    near_off, near_on = off["contact"], on["contact"]
    lit_off, lit_on = near_off["false_lit"]["percent"], near_on["false_lit"]["percent"]
    shadow_off = off["hard"]["false_shadow_outside_edges"]["percent"]
    shadow_on = on["hard"]["false_shadow_outside_edges"]["percent"]
    missed = []
    if shadow_on > GOAL_FALSE_SHADOW:
        already = f" (off: {shadow_off:.3f})" if shadow_off > GOAL_FALSE_SHADOW else ""
        missed.append(f"false shadow {shadow_on:.3f} % > {GOAL_FALSE_SHADOW}{already}")
    if goal_lit and lit_off > 0 and lit_on > GOAL_FALSE_LIT_RATIO * lit_off:
        missed.append(f"false lit near contacts {lit_on:.2f} % > half of {lit_off:.2f}")
    cells = [name, f"{near_off['contact_pixels']}", f"{lit_off:.2f} -> {lit_on:.2f}",
             f"{near_off['false_shadow']['percent']:.2f} -> {near_on['false_shadow']['percent']:.2f}",
             f"{off['hard']['false_lit_outside_edges']['percent']:.3f} -> "
             f"{on['hard']['false_lit_outside_edges']['percent']:.3f}",
             f"{shadow_off:.3f} -> {shadow_on:.3f}",
             ("missed: " + "; ".join(missed)) if missed else "met"]
    return "| " + " | ".join(cells) + " |"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--binary", default=os.path.join(ROOT, "build", "penumbra"))
    parser.add_argument("--out", default=os.path.join(ROOT, "build", "contact", "contact.md"))
    parser.add_argument("--quick", action="store_true", help="tiny sizes (smoke test)")
    options = parser.parse_args()
    work = os.path.dirname(os.path.abspath(options.out))
    lines = ["| scene | contact pixels | false lit % near contacts (off -> on) | false shadow % near contacts | "
             "false lit % outside edges | false shadow % outside edges | goals |", "|---" * 7 + "|"]
    reports = {}
    for name, scene, extra, needs, goal_lit in SCENES:
        if needs and not os.path.exists(needs):
            print(f"contact_report: {name} absent ({needs})", file=sys.stderr)
            lines.append(f"| {name} | absent: {needs} |" + " |" * 5)
            continue
        print(f"contact_report: {name}", file=sys.stderr, flush=True)
        folder = os.path.join(work, re.sub(r"[^a-z0-9]+", "-", name))
        args = extra + size_args(options.quick)
        off = compare(options.binary, scene, args, folder + "-off")
        on = compare(options.binary, scene, args + ["--contact-shadows"], folder + "-on")
        reports[name] = {"off": off, "on": on}
        lines.append(row(name, off, on, goal_lit))
    os.makedirs(work, exist_ok=True)
    with open(os.path.join(work, "contact.json"), "w") as file:
        json.dump(reports, file, indent=1)
    with open(options.out, "w") as file:
        file.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
