#!/usr/bin/env bash
# Renders the refactoring check of issue 20 with binary BIN into OUT: the
# street (320x180, 4 spp, seed 3), a foggy town03 frame, the street by night
# with --hdr, the demo preset and a small four-layout dataset. Compare two
# OUTs with compare.sh: a refactor must leave them byte-identical.
# usage: .ci/same_bytes/make.sh BIN OUT   (BIN, OUT absolute paths; BIN must
# read this checkout's scenes/, so run an older binary from its own checkout)
set -euo pipefail
P=$1; O=$2
here="$(cd "$(dirname "$0")" && pwd)"
cd "$here/../.."
rm -rf "$O"; mkdir -p "$O"
"$P" render scenes/street.toml -o "$O/street" --width 320 --height 180 --spp 4 --seed 3 >/dev/null 2>&1
"$P" render --town town03 --seed 0 --frame 40 --config normal --weather foggy --width 320 --height 180 --spp 4 -o "$O/fog" --baselines 10,54 >/dev/null 2>&1
"$P" render scenes/street.toml -o "$O/streethdr" --width 160 --height 90 --spp 2 --seed 5 --hdr --weather night >/dev/null 2>&1
"$P" dataset --preset demo -o "$O/demo" >/dev/null 2>&1
"$P" dataset "$here/layouts.toml" -o "$O/layouts" >/dev/null 2>&1
