#!/bin/sh
# Adds the seeds of the `read_xml` and `lossless` targets to their corpora (committed,
# minimized: run `cargo +nightly fuzz cmin read_xml` and
# `cargo +nightly fuzz cmin -s none lossless` after this before committing):
# every *.xml file of the repository outside target/, fuzz/ and schema/ (the
# conformance cases under tests/conformance/cases and any other model files), copied
# into fuzz/corpus/read_xml/ under a name made from its path, and into
# fuzz/corpus/lossless/ as it is, with a byte-order mark and \r\n line endings
# (`bom-crlf-`), and with lone \r line endings (`cr-`). schema/schema.xml is left
# out: it is not MJCF, and at 216 KB it would raise libFuzzer's default -max_len.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
repo=$(dirname "$here")
out="$here/corpus/read_xml"
lossless="$here/corpus/lossless"
mkdir -p "$out" "$lossless"
cd "$repo"
find . \( -path ./target -o -path ./fuzz -o -path ./schema -o -path ./.git \) -prune -o -type f -name '*.xml' -print | sort | while read -r f; do
    name=$(printf '%s' "${f#./}" | tr '/' '_')
    cat "$f" >"$out/$name"
    cat "$f" >"$lossless/$name"
    { printf '\357\273\277'; sed 's/$/\r/' "$f"; } >"$lossless/bom-crlf-$name"
    tr '\n' '\r' <"$f" >"$lossless/cr-$name"
done
echo "$(ls "$out" | wc -l) files in $out, $(ls "$lossless" | wc -l) in $lossless"
