#!/usr/bin/env bash
# Runs one harness: fuzz/run.sh NAME [SECONDS] [BUILD] [libFuzzer flags...]
# (NAME: obj ply stl off vds points).
# The corpus grows in BUILD/fuzz-corpus/NAME, seeded from fuzz/corpus/NAME;
# crashes land in BUILD/fuzz-findings/NAME. Limits as in docs/fuzzing.md.
set -euo pipefail
name=$1
seconds=${2:-600}
build=${3:-build-fuzz}
here=$(cd "$(dirname "$0")" && pwd)
work="$build/fuzz-corpus/$name"
findings="$build/fuzz-findings/$name"
mkdir -p "$work" "$findings"
case $name in points) words=ply ;; *) words=$name ;; esac # points come as text or PLY
dict=()
if [ -f "$here/dict/$words.dict" ]; then dict=(-dict="$here/dict/$words.dict"); fi
exec "$build/fuzz/vds_fuzz_$name" "${dict[@]}" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
  -print_final_stats=1 -artifact_prefix="$findings/" "${@:4}" "$work" "$here/corpus/$name"
