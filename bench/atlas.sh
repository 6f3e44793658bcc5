#!/usr/bin/env bash
# Fetches the public coverages the smoothing checks use (us-atlas, world-atlas)
# from the npm registry at pinned versions, converts them to GeoJSON with
# topojson-client's topo2geo, and prints the folder that holds both:
#
#   export BZSPLINE_ATLAS=$(bash bench/atlas.sh)
#   cargo test -p bzspline-cli --test atlas
set -euo pipefail
here="$(cd "$(dirname "$0")/atlas" && pwd)"
cd "$here"
npm ci --no-audit --no-fund --loglevel=error >&2
data="$here/data"
mkdir -p "$data"
cp -r node_modules/us-atlas node_modules/world-atlas "$data/"
topo2geo=node_modules/.bin/topo2geo
"$topo2geo" states="$data/states.geojson" < node_modules/us-atlas/states-10m.json
"$topo2geo" counties="$data/counties.geojson" < node_modules/us-atlas/counties-10m.json
"$topo2geo" countries="$data/countries.geojson" < node_modules/world-atlas/countries-50m.json
echo "$data"
