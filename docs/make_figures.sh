#!/usr/bin/env bash
# Redraws every figure in docs/ with the bzspline command (run from anywhere in a
# clone). PNG text needs a system font: on Debian/Ubuntu, apt-get install fonts-dejavu-core.
# compare.* also needs Python 3 (make_compare.py makes docs/.venv with numpy and scipy).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --quiet -p bzspline-cli
bz=target/debug/bzspline
for ext in svg png; do
    "$bz" plot --example 1 --title "Example 1 of the paper (α = 1/2)" -o "docs/fig1.$ext"
    "$bz" plot --example 2 --knots --equal-aspect \
        --title "Example 2 of the paper: points of y = √(x − x²) (α = 1/2)" -o "docs/fig2.$ext"
    "$bz" plot --example 1 --alpha-sweep 1/3,1/2,2/3 \
        --title "Example 1 with α = 1/3, 1/2 and 2/3" -o "docs/alpha.$ext"
    "$bz" plot docs/visitors.csv --no-polygon \
        --title "Daily visitors, January 2024 (α = 1/2)" -o "docs/dated.$ext"
done
# dense.png: 5,104 daily closes of the S&P 500 from vega-datasets (fetched with npm).
vd=$(mktemp -d)
(cd "$vd" && npm pack --silent vega-datasets@2.11.0 >/dev/null && tar xzf vega-datasets-2.11.0.tgz)
"$bz" plot "$vd/package/data/sp500-2000.csv" --x date --y close \
    --title "S&P 500, daily close: 5,104 points drawn as a chart" -o docs/dense.png
# band.png: the yearly global temperature anomaly, smoothed, with its 95 % band.
"$bz" plot "$vd/package/data/global-temp.csv" --smooth auto --band 0.95 \
    --title "Global temperature anomaly (°C), yearly: smoothed, with its 95 % band" -o docs/band.png
rm -rf "$vd"
python3 docs/make_compare.py
python3 docs/make_coverage.py   # coverage.png needs rsvg-convert (apt-get install librsvg2-bin)
python3 docs/make_through.py    # through.* and step.*: curves through the points (docs/.venv)
# smoothing.png: a noisy bump fitted by bzspline and scipy; needs the Python package
# installed (pip install ./crates/bzspline-py scipy matplotlib).
python3 -c "import sys; sys.path.insert(0, 'bench'); import smoothing; smoothing.figure('docs/smoothing.png', 0)"
# qgis.png is drawn by QGIS's renderer: with python3-qgis, and bzspline and shapely 2 in
# QGIS's Python, run QT_QPA_PLATFORM=offscreen python3 docs/make_qgis.py.
