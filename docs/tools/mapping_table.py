#!/usr/bin/env python3
"""Linear against nonlinear depth-to-parallax mapping for docs/RESULTS.md: every built-in scene's camera path x
display with the disparity budget on (1deg), from `s3d render --sequence --disparity-mapping linear|nonlinear`
report.json files. Per pair: the share beyond 1 degree (comfort), the used share of the budget (nearest to
farthest depth), the bulk share (5th to 95th percentile of the pixels' parallax over the budget: the depth
impression most of the image keeps), the error against the reference (linear: the two-pass reference; nonlinear:
the per-layer reference) and the per-layer reference's unresolved pixels.

usage: docs/tools/mapping_table.py S3D_BINARY OUT_FOLDER [--resolution 256x144] [--scenes a,b] [--displays a,b]
                                   [--linear-from BUDGET_OUT_FOLDER]
       docs/tools/mapping_table.py S3D_BINARY OUT_FOLDER --single 640x360 [--scenes a,b] [--displays a,b]
--linear-from takes the linear runs from budget_table.py's 1deg folders (the same command) instead of rendering them.
--single: single frames (`s3d render`, the scene's first frame) at that resolution instead of camera paths.
"""
import json, subprocess, sys
from pathlib import Path

SCENES = ["courtyard", "glass", "fence", "cover", "depth-range"]
DISPLAYS = ["tv55", "monitor27", "hmd"]


def run(binary, out, scene, display, mapping, resolution, linear_from=None):
    if mapping == "linear" and linear_from:
        return json.loads((Path(linear_from) / f"{scene}_{display}_1deg" / "report.json").read_text())["frames"]
    folder = Path(out) / f"{scene}_{display}_{mapping}"
    subprocess.run([binary, "render", "--sequence", "--scene", scene, "--display", display, "--disparity-budget", "1deg",
                    "--disparity-mapping", mapping, "--resolution", resolution, "--output", str(folder)], check=True,
                   stdout=subprocess.DEVNULL)
    return json.loads((folder / "report.json").read_text())["frames"]


def single(binary, out, scene, display, mapping, resolution):
    folder = Path(out) / f"single_{scene}_{display}_{mapping}"
    subprocess.run([binary, "render", "--scene", scene, "--display", display, "--disparity-budget", "1deg",
                    "--disparity-mapping", mapping, "--resolution", resolution, "--outputs", "report.json", "--output",
                    str(folder)], check=True, stdout=subprocess.DEVNULL)
    return json.loads((folder / "report.json").read_text())


def single_frames(binary, out, scenes, displays, resolution):
    print("| scene | display | PSNR dB, linear / nonlinear | SSIM, linear / nonlinear | bulk share, linear / nonlinear "
          "| reference layers | unresolved |")
    print("|---|---|---|---|---|---|---|")
    pixels = int(resolution.split("x")[0]) * int(resolution.split("x")[1]) * 2
    for scene in scenes:
        for display in displays:
            r = {m: single(binary, out, scene, display, m, resolution) for m in ("linear", "nonlinear")}
            eyes = lambda m, key: (r[m]["error"]["left"][key] + r[m]["error"]["right"][key]) / 2
            mapping = r["nonlinear"]["disparityMapping"]
            unresolved = (mapping["unresolvedPixels"]["left"] + mapping["unresolvedPixels"]["right"]) / pixels
            print(f"| {scene} | {display} | {eyes('linear', 'psnrDb'):.2f} / {eyes('nonlinear', 'psnrDb'):.2f} "
                  f"| {eyes('linear', 'ssim'):.3f} / {eyes('nonlinear', 'ssim'):.3f} "
                  f"| {100 * r['linear']['disparityBudget']['bulkShare']:.0f} % / "
                  f"{100 * r['nonlinear']['disparityBudget']['bulkShare']:.0f} % "
                  f"| {mapping['referenceLayers']} | {100 * unresolved:.2f} % |", flush=True)


def mean(values):
    return sum(values) / len(values)


def main():
    binary, out = sys.argv[1], sys.argv[2]
    option = lambda name, default: sys.argv[sys.argv.index(name) + 1] if name in sys.argv else default
    resolution = option("--resolution", "256x144")
    scenes = option("--scenes", ",".join(SCENES)).split(",")
    displays = option("--displays", ",".join(DISPLAYS)).split(",")
    linear_from = option("--linear-from", None)
    if "--single" in sys.argv:
        single_frames(binary, out, scenes, displays, option("--single", "640x360"))
        return
    print("| scene | display | beyond 1 deg max, linear / nonlinear | used share mean, linear / nonlinear "
          "| bulk share mean, linear / nonlinear | PSNR mean dB, linear / nonlinear | unresolved reference pixels |")
    print("|---|---|---|---|---|---|---|")
    for scene in scenes:
        for display in displays:
            rows = {m: run(binary, out, scene, display, m, resolution, linear_from) for m in ("nonlinear", "linear")}
            beyond = {m: max(f["comfort"]["shareBeyondOneDegree"] for f in rows[m]) for m in rows}
            used = {m: mean([f["disparityBudget"]["usedShare"] for f in rows[m]]) for m in rows}
            bulk = {m: mean([f["disparityBudget"]["bulkShare"] for f in rows[m]]) for m in rows}
            psnr = {m: mean([(f["psnrDb"]["left"] + f["psnrDb"]["right"]) / 2 for f in rows[m]]) for m in rows}
            pixels = int(resolution.split("x")[0]) * int(resolution.split("x")[1]) * 2
            unresolved = mean([(f["disparityMapping"]["unresolvedPixels"]["left"] +
                                f["disparityMapping"]["unresolvedPixels"]["right"]) / pixels for f in rows["nonlinear"]])
            print(f"| {scene} | {display} | {100 * beyond['linear']:.2f} % / {100 * beyond['nonlinear']:.2f} % "
                  f"| {100 * used['linear']:.0f} % / {100 * used['nonlinear']:.0f} % "
                  f"| {100 * bulk['linear']:.0f} % / {100 * bulk['nonlinear']:.0f} % "
                  f"| {psnr['linear']:.2f} / {psnr['nonlinear']:.2f} | {100 * unresolved:.2f} % |", flush=True)


if __name__ == "__main__":
    main()
