#!/bin/sh
# Usage: file_size_limit.sh S3D WORK
# Runs `s3d render` under a file-size limit (ulimit -f 2: a few hundred bytes to a kilobyte, below any image)
# into a folder holding an earlier output. The run must end in one "s3d: error:" line saying which file is too
# large (not die by SIGXFSZ), keep the earlier output byte for byte, and leave no staging or temporary file.
s3d=$1 work=$2
rm -rf "$work"
mkdir -p "$work/out"
printf 'earlier' >"$work/out/left.png"
message=$( (ulimit -f 2 && exec "$s3d" render --resolution 64x36 --outputs left.png,report.json \
              --output "$work/out") 2>&1 >/dev/null)
status=$?
if [ "$status" -ne 1 ]; then echo "expected exit status 1, got $status: $message"; exit 1; fi
case "$message" in "s3d: error: "*) ;; *) echo "not one s3d error line: $message"; exit 1 ;; esac
if ! printf '%s\n' "$message" | grep -Eq "cannot write .*(left\.png|report\.json)': File too large$"; then
  echo "'$message' does not name the file and 'File too large'"; exit 1
fi
if [ "$(ls -A "$work/out")" != "left.png" ]; then echo "left behind: $(ls -A "$work/out")"; exit 1; fi
if [ "$(cat "$work/out/left.png")" != "earlier" ]; then echo "the earlier left.png changed"; exit 1; fi
echo "ok: $message"
