#!/usr/bin/env python3
"""Builds the ZIP that QGIS's "Install from ZIP" takes: the plugin folder
bzspline_processing/ with its README and the project's licence, without
caches.

    python3 qgis/build.py            # target/qgis/bzspline_processing.zip
    python3 qgis/build.py -o FILE.zip
"""

import argparse
import pathlib
import zipfile

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent
PLUGIN = "bzspline_processing"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", type=pathlib.Path,
                        default=ROOT / "target" / "qgis" / f"{PLUGIN}.zip")
    args = parser.parse_args()
    args.output.parent.mkdir(parents=True, exist_ok=True)
    files = sorted(p for p in (HERE / PLUGIN).rglob("*")
                   if p.is_file() and "__pycache__" not in p.parts and p.suffix != ".pyc")
    extra = [p for p in (ROOT / "LICENSE",) if p.is_file()]
    with zipfile.ZipFile(args.output, "w", zipfile.ZIP_DEFLATED) as z:
        for p in files:
            z.write(p, f"{PLUGIN}/{p.relative_to(HERE / PLUGIN).as_posix()}")
        for p in extra:
            z.write(p, f"{PLUGIN}/{p.name}")
    print(args.output)


if __name__ == "__main__":
    main()
