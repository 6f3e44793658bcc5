#!/usr/bin/env python3
"""Draws docs/coverage.svg (and .png with rsvg-convert, from Debian's
librsvg2-bin): a mosaic of nine cells as given, smoothed ring by ring
(`bzspline smooth --independent`) and smoothed as one coverage (the default).

Cells are filled with translucent colours over white: where two smoothed cells
overlap the colour darkens, where they part the white shows. The inset of each
panel enlarges the node at the middle of the mosaic.

Run from anywhere in a clone: python3 docs/make_coverage.py
"""

import json
import pathlib
import shutil
import subprocess

ROOT = pathlib.Path(__file__).resolve().parent.parent
FIXTURE = ROOT / "crates/bzspline-cli/tests/fixtures/mosaic.geojson"
COLOURS = ["#e41a1c", "#377eb8", "#4daf4a", "#984ea3", "#ff7f00",
           "#a65628", "#f781bf", "#1b9e77", "#d95f02"]


def smooth(extra):
    subprocess.run(["cargo", "build", "--quiet", "-p", "bzspline-cli"], cwd=ROOT, check=True)
    out = subprocess.run(
        [str(ROOT / "target/debug/bzspline"), "smooth", str(FIXTURE), "--tolerance", "0.002", *extra],
        check=True, capture_output=True, text=True).stdout
    return json.loads(out)["features"]


def rings(f):
    g = f["geometry"]
    if g["type"] == "Polygon":
        return g["coordinates"]
    return []


def panel(features, x0, y0, size, title, view, zoom=None):
    """An SVG group: the cells mapped from `view` = (xmin, ymin, span) into a
    square of `size` at (x0, y0)."""
    vx, vy, span = view
    sx = size / span

    def pt(p):
        return f"{x0 + (p[0] - vx) * sx:.2f},{y0 + size - (p[1] - vy) * sx:.2f}"

    clip = f"clip{int(x0)}{int(y0)}"
    parts = [f'<clipPath id="{clip}"><rect x="{x0}" y="{y0}" width="{size}" height="{size}"/></clipPath>',
             f'<rect x="{x0}" y="{y0}" width="{size}" height="{size}" fill="white" stroke="#999"/>',
             f'<g clip-path="url(#{clip})">']
    cells = [f for f in features if f["geometry"]["type"] == "Polygon"]
    for i, f in enumerate(cells):
        for r in rings(f):
            d = "M " + " L ".join(pt(p) for p in r) + " Z"
            parts.append(f'<path d="{d}" fill="{COLOURS[i % len(COLOURS)]}" fill-opacity="0.45" '
                         f'stroke="#222" stroke-width="{0.6 if zoom is None else 1.2}"/>')
    parts.append("</g>")
    if title:
        parts.append(f'<text x="{x0 + size / 2}" y="{y0 - 10}" text-anchor="middle" '
                     f'font-family="DejaVu Sans, sans-serif" font-size="15">{title}</text>')
    return "\n".join(parts)


def main():
    given = json.loads(FIXTURE.read_text())["features"]
    alone = smooth(["--independent"])
    coverage = smooth([])
    # The node shared by cells (1,1), (1,2), (2,1), (2,2).
    node = given[4]["geometry"]["coordinates"][0][0 + 8]  # the cell's top-right corner
    size, gap, inset = 300, 40, 130
    panels = [("as given", given), ("--independent: ring by ring", alone),
              ("default: one coverage", coverage)]
    width = 3 * size + 4 * gap
    height = size + inset + 3 * gap + 10
    svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'viewBox="0 0 {width} {height}">',
           f'<rect width="{width}" height="{height}" fill="white"/>']
    for k, (title, feats) in enumerate(panels):
        x0 = gap + k * (size + gap)
        svg.append(panel(feats, x0, gap, size, title, (-0.1, -0.6, 3.7)))
        zx = x0 + (size - inset) / 2
        svg.append(panel(feats, zx, gap + size + gap, inset, None,
                         (node[0] - 0.06, node[1] - 0.06, 0.12), zoom=True))
    svg.append("</svg>")
    out = ROOT / "docs/coverage.svg"
    out.write_text("\n".join(svg) + "\n")
    if shutil.which("rsvg-convert"):
        subprocess.run(["rsvg-convert", "-o", str(out.with_suffix(".png")), str(out)], check=True)
    print(f"wrote {out} (node at {node})")


if __name__ == "__main__":
    main()
