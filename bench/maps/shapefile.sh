#!/usr/bin/env bash
# `bzspline smooth` beside `mapshaper -smooth` on the same Shapefiles, each a
# command reading and writing files as a GIS user runs it: wall time and peak
# memory (GNU time), the polygons each made invalid and the borders each split
# (crates/bzspline-io/examples/validity.rs: geo's OGC rules; pairs of features
# sharing an edge before and none after). The Shapefiles are mapshaper's
# conversion of bench/atlas.sh's GeoJSON, and both outputs are converted back to
# GeoJSON by mapshaper for the judge, so neither tool's writer favours it.
#
#   cargo build --release -p bzspline-cli && cargo build --release -p bzspline-io --example validity
#   (cd bench/maps && npm ci)
#   BZSPLINE_ATLAS=$(bash bench/atlas.sh) bash bench/maps/shapefile.sh
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
atlas="${BZSPLINE_ATLAS:?set BZSPLINE_ATLAS (bash bench/atlas.sh)}"
ms="$root/bench/maps/node_modules/.bin/mapshaper"
bz="$root/target/release/bzspline"
judge="$root/target/release/examples/validity"
for tool in "$ms" "$bz" "$judge" /usr/bin/time; do
    [ -x "$tool" ] || { echo "missing $tool (see the header)" >&2; exit 2; }
done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# time and peak resident memory (MB) of a command, as "seconds MB".
measure() {
    /usr/bin/time -f "%e %M" -o "$tmp/time" "$@" >/dev/null 2>"$tmp/err" || { cat "$tmp/err" >&2; exit 1; }
    awk '{printf "%.2f %.0f", $1, $2 / 1024}' "$tmp/time"
}

echo "| Shapefile | polygons | tool | time | peak memory | made invalid | borders split |"
echo "|---|---:|---|---:|---:|---:|---:|"
while read -r name file distance; do
    "$ms" -i "$atlas/$file" -o "$tmp/$name.shp" >/dev/null 2>&1
    "$ms" -i "$tmp/$name.shp" -o "$tmp/$name.geojson" format=geojson >/dev/null 2>&1
    mkdir -p "$tmp/ms" "$tmp/bz"
    read -r ms_s ms_mb <<<"$(measure "$ms" -i "$tmp/$name.shp" -smooth "$distance" -o "$tmp/ms/$name.shp")"
    read -r bz_s bz_mb <<<"$(measure "$bz" smooth "$tmp/$name.shp" --tolerance "$distance" -o "$tmp/bz/$name.shp")"
    for t in ms bz; do
        "$ms" -i "$tmp/$t/$name.shp" -o "$tmp/$t/$name.geojson" format=geojson >/dev/null 2>&1
        "$judge" "$tmp/$name.geojson" "$tmp/$t/$name.geojson" > "$tmp/$t.json"
    done
    field() { sed -n "s/.*\"$2\": \([0-9]*\).*/\1/p" "$tmp/$1.json"; }
    n=$(field bz valid_before)
    echo "| $name ($distance) | $n | mapshaper \`-smooth $distance\` | $ms_s s | $ms_mb MB | $(field ms made_invalid) | $(field ms borders_split) of $(field ms borders) |"
    echo "| | | bzspline \`smooth --tolerance $distance\` | $bz_s s | $bz_mb MB | $(field bz made_invalid) | $(field bz borders_split) of $(field bz borders) |"
done <<'CASES'
states states.geojson 20km
counties counties.geojson 5km
countries countries.geojson 20km
CASES
