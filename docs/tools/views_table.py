#!/usr/bin/env python3
"""View configurations table for docs/RESULTS.md: the TV pair and the headset-like pair of samples/views/ per scene,
and the headset pair again with its world scale set so its disparity range in pixels equals the TV pair's (the two
then move their pixels by the same amounts), from `s3d render --views` report.json files.

usage: docs/tools/views_table.py S3D_BINARY OUT_FOLDER [--scenes courtyard,fence]
"""
import json, subprocess, sys
from pathlib import Path

SAMPLES = Path(__file__).resolve().parents[2] / "samples" / "views"


def run(binary, out, scene, name, views_file):
    folder = Path(out) / f"{scene}_{name}"
    subprocess.run([binary, "render", "--views", str(views_file), "--scene", scene, "--output", str(folder)],
                   check=True, stdout=subprocess.DEVNULL)
    return json.loads((folder / "report.json").read_text())


def row(scene, name, views, report):
    psnr = [report["error"][e]["psnrDb"] for e in ("left", "right")]
    rng = report["disparityRangePx"]["left"], report["disparityRangeArcmin"]["left"]
    comfort = report["comfort"]
    c = report["center"]
    return (f"| {scene} | {name} | {views['worldScale']:.4g} | {rng[0]:.1f} px / {rng[1]:.0f}' | "
            f"{c['width']}x{c['height']} | {psnr[0]:.2f} / {psnr[1]:.2f} | "
            f"{100 * comfort['left']['shareBeyondOneDegree']:.1f} % / {100 * comfort['right']['shareBeyondOneDegree']:.1f} % | "
            f"{comfort['left']['meanConflictDiopters']:.2f} / {comfort['left']['maxConflictDiopters']:.2f} |")


def main():
    binary, out = sys.argv[1], Path(sys.argv[2])
    scenes = sys.argv[sys.argv.index("--scenes") + 1].split(",") if "--scenes" in sys.argv else ["courtyard", "fence"]
    out.mkdir(parents=True, exist_ok=True)
    print("| scene | views | world scale | disparity range (left eye) | center view | PSNR L / R (dB) | "
          "beyond the 1-degree rule L / R (hmd, 1.3 m) | conflict mean / max (D) |")
    print("|---|---|---|---|---|---|---|---|")
    for scene in scenes:
        tv_views = json.loads((SAMPLES / "tv-pair.json").read_text())
        headset_views = json.loads((SAMPLES / "headset-pair.json").read_text())
        tv = run(binary, out, scene, "tv", SAMPLES / "tv-pair.json")
        headset = run(binary, out, scene, "headset", SAMPLES / "headset-pair.json")
        matched_views = dict(headset_views)
        matched_views["worldScale"] = headset_views["worldScale"] * (tv["disparityRangePx"]["left"] /
                                                                     headset["disparityRangePx"]["left"])
        matched_file = out / f"{scene}_headset_matched.json"
        matched_file.write_text(json.dumps(matched_views))
        matched = run(binary, out, scene, "headset_matched", matched_file)
        print(row(scene, "tv-pair", tv_views, tv))
        print(row(scene, "headset-pair", headset_views, headset))
        print(row(scene, "headset-pair, TV's disparity range", matched_views, matched))


if __name__ == "__main__":
    main()
