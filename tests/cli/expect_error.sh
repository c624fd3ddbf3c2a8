#!/bin/sh
# Usage: expect_error.sh REGEX OUTPUT_FOLDER COMMAND...
# Passes when COMMAND exits with status 1 (an error, not a crash), writes exactly one line to stderr, that line
# starts with "s3d: error: " and matches the extended REGEX, and OUTPUT_FOLDER is missing or empty afterwards
# (OUTPUT_FOLDER "-": no such check, for commands that report a failure in files of their own).
regex=$1; output=$2; shift 2
[ "$output" = "-" ] || rm -rf "$output"
stderr_file=$(mktemp)
"$@" >/dev/null 2>"$stderr_file"
status=$?
lines=$(wc -l <"$stderr_file")
message=$(cat "$stderr_file")
rm -f "$stderr_file"
if [ "$status" -ne 1 ]; then echo "expected exit status 1, got $status: $message"; exit 1; fi
if [ "$lines" -ne 1 ]; then echo "expected one line on stderr, got $lines: $message"; exit 1; fi
case "$message" in "s3d: error: "*) ;; *) echo "not an s3d error line: $message"; exit 1 ;; esac
if ! printf '%s\n' "$message" | grep -Eq -- "$regex"; then echo "'$message' does not match '$regex'"; exit 1; fi
if [ "$output" != "-" ] && [ -d "$output" ] && [ -n "$(ls -A "$output")" ]; then echo "output folder is not empty: $(ls -A "$output")"; exit 1; fi
echo "ok: $message"
