#!/bin/sh
# Usage: failed_run_leaves_folder.sh S3D DATA WORK CASE
# Runs `s3d convert` in a way that must fail and checks that the output folder holds exactly the same names
# and bytes as before, and that the failure was one "s3d: error:" line naming the cause.
#   late:      folder mode, frame a converts, frame b's depth is truncated (fails after a's files exist)
#   own_input: folder mode writing into its own input folder, where frame "1" would write left_1.png, which
#              is frame "left_1"'s color input
s3d=$1 data=$2 work=$3 case=$4
rm -rf "$work"
mkdir -p "$work/in" "$work/out"
if [ "$case" = late ]; then
  cp "$data/color.png" "$work/in/color_a.png"; cp "$data/depth.pfm" "$work/in/depth_a.pfm"
  cp "$data/color.png" "$work/in/color_b.png"; cp "$data/depth_truncated.pfm" "$work/in/depth_b.pfm"
  printf 'old' >"$work/out/left_a.png"; printf 'keep' >"$work/out/notes.txt"
  out="$work/out" regex="depth_b\.pfm"
  set -- convert --input-folder "$work/in" --color-pattern "color_*.png" --depth-pattern "depth_*.pfm" --output "$out"
else
  cp "$data/color.png" "$work/in/left_1.png"; cp "$data/depth.pfm" "$work/in/left_1.pfm"
  cp "$data/color.png" "$work/in/1.png"; cp "$data/depth.pfm" "$work/in/1.pfm"
  out="$work/in" regex="left_1\.png' would overwrite input"
  set -- convert --input-folder "$work/in" --color-pattern "*.png" --depth-pattern "*.pfm" --output "$out"
fi
snapshot() { (cd "$1" && find . -print | LC_ALL=C sort && find . -type f -exec md5sum {} + | LC_ALL=C sort); }
before=$(snapshot "$out")
message=$("$s3d" "$@" 2>&1 >/dev/null)
status=$?
after=$(snapshot "$out")
if [ "$status" -ne 1 ]; then echo "expected exit status 1, got $status: $message"; exit 1; fi
case "$message" in "s3d: error: "*) ;; *) echo "not an s3d error line: $message"; exit 1 ;; esac
if ! printf '%s\n' "$message" | grep -Eq -- "$regex"; then echo "'$message' does not match '$regex'"; exit 1; fi
if [ "$before" != "$after" ]; then printf 'folder changed:\n--- before\n%s\n--- after\n%s\n' "$before" "$after"; exit 1; fi
echo "ok: $message"
