#!/bin/sh
# Adds the seeds of the `read_xml` target to its corpus (committed, minimized: run
# `cargo +nightly fuzz cmin read_xml` after this before committing):
# every *.xml file of the repository outside target/, fuzz/ and schema/ (the
# conformance cases under tests/conformance/cases and any other model files), copied
# into fuzz/corpus/read_xml/ under a name made from its path. schema/schema.xml is
# left out: it is not MJCF, and at 216 KB it would raise libFuzzer's default -max_len.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
repo=$(dirname "$here")
out="$here/corpus/read_xml"
mkdir -p "$out"
cd "$repo"
find . \( -path ./target -o -path ./fuzz -o -path ./schema -o -path ./.git \) -prune -o -type f -name '*.xml' -print | sort | while read -r f; do
    name=$(printf '%s' "${f#./}" | tr '/' '_')
    cat "$f" >"$out/$name"
done
echo "$(ls "$out" | wc -l) files in $out"
