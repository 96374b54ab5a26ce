#!/usr/bin/env bash
# Compares two outputs of make.sh: `diff -r`, with manifest lines compared
# sorted and without their timing field ("seconds"). Prints `compared` last;
# any line before it is a difference.
# usage: .ci/same_bytes/compare.sh A B
A=$1; B=$2
diff -r -q -x 'shard-*.jsonl' "$A" "$B"
for m in $(cd "$A" && find . -name 'shard-*.jsonl'); do
  strip() { sed -E 's/"seconds":[0-9.e+-]+//' "$1" | sort; }
  diff <(strip "$A/$m") <(strip "$B/$m") >/dev/null || echo "manifest differs: $m"
done
echo compared
