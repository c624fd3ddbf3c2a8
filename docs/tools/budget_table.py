#!/usr/bin/env python3
"""Disparity budget table for docs/RESULTS.md: every built-in scene's camera path x display, with the budget
off (before) and at 1deg (after), from `s3d render --sequence` report.json files.

usage: docs/tools/budget_table.py S3D_BINARY OUT_FOLDER [--resolution 256x144] [--scenes a,b]
"""
import json, math, subprocess, sys
from pathlib import Path

SCENES = ["courtyard", "glass", "fence", "cover", "depth-range"]
DISPLAYS = ["tv55", "monitor27", "hmd"]


def run(binary, out, scene, display, rule, resolution):
    folder = Path(out) / f"{scene}_{display}_{rule}"
    subprocess.run([binary, "render", "--sequence", "--scene", scene, "--display", display, "--disparity-budget", rule,
                    "--resolution", resolution, "--output", str(folder)], check=True, stdout=subprocess.DEVNULL)
    return json.loads((folder / "report.json").read_text())["frames"]


def steps(frames, key):
    values = [math.log(f[key]) for f in frames]
    return [abs(b - a) for a, b in zip(values, values[1:])]


def main():
    binary, out = sys.argv[1], sys.argv[2]
    resolution = sys.argv[sys.argv.index("--resolution") + 1] if "--resolution" in sys.argv else "256x144"
    scenes = sys.argv[sys.argv.index("--scenes") + 1].split(",") if "--scenes" in sys.argv else SCENES
    print(f"| scene | display | frames | beyond 1 deg, off: max / mean | beyond 1 deg, 1deg: max | used share, 1deg: "
          f"min / mean | frames used >= 80 % | max step ln m / ln ZPP per frame | forced frames |")
    print("|---|---|---|---|---|---|---|---|---|")
    for scene in scenes:
        for display in DISPLAYS:
            off = run(binary, out, scene, display, "off", resolution)
            on = run(binary, out, scene, display, "1deg", resolution)
            before = [f["comfort"]["shareBeyondOneDegree"] for f in off]
            after = [f["comfort"]["shareBeyondOneDegree"] for f in on]
            used = [f["disparityBudget"]["usedShare"] for f in on]
            forced = sum(1 for f in on if f["disparityBudget"]["forced"])
            print(f"| {scene} | {display} | {len(on)} | {100 * max(before):.1f} % / {100 * sum(before) / len(before):.1f} % "
                  f"| {100 * max(after):.2f} % | {100 * min(used):.0f} % / {100 * sum(used) / len(used):.0f} % "
                  f"| {sum(1 for u in used if u >= 0.8)} of {len(used)} "
                  f"| {max(steps(on, 'maxSeparation')):.3f} / {max(steps(on, 'zeroParallaxDistance')):.3f} | {forced} |",
                  flush=True)


if __name__ == "__main__":
    main()
