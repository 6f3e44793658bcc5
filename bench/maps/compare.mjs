// bzspline/geo's smooth beside mapshaper's -smooth on us-atlas and
// world-atlas, in one Node process: time, and how many polygons valid before
// each made invalid (judged by crates/bzspline-io/examples/validity.rs).
//   (cd crates/bzspline-js && npm ci && npm run build)
//   cargo build --release -p bzspline-io --example validity
//   cd bench/maps && npm ci && BZSPLINE_ATLAS=$(bash ../atlas.sh) node compare.mjs
import { execFileSync } from "node:child_process";
import { readFileSync, writeFileSync, mkdtempSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, resolve } from "node:path";
import mapshaper from "mapshaper";
import { smooth } from "../../crates/bzspline-js/js/geo.js";

const atlas = process.env.BZSPLINE_ATLAS;
if (!atlas) throw new Error("set BZSPLINE_ATLAS (bash bench/atlas.sh)");
const root = resolve(import.meta.dirname, "../..");
const judge = join(root, "target/release/examples/validity");
const dir = mkdtempSync(join(tmpdir(), "maps-"));

const cases = [
  ["US states", "states.geojson", "20km"],
  ["US counties", "counties.geojson", "5km"],
  ["world countries", "countries.geojson", "20km"],
];

function validity(before, after) {
  return JSON.parse(execFileSync(judge, [before, after]).toString());
}

console.log("| coverage | polygons valid before | mapshaper -smooth: made invalid | time | bzspline smooth: made invalid | time |");
console.log("|---|---:|---:|---:|---:|---:|");
for (const [name, file, distance] of cases) {
  const input = join(atlas, file);
  const text = readFileSync(input, "utf8");
  let t0 = performance.now();
  const out = await mapshaper.applyCommands(`-i in.geojson -smooth ${distance} -o out.geojson format=geojson`, { "in.geojson": text });
  const msTime = performance.now() - t0;
  const msFile = join(dir, `ms-${file}`);
  writeFileSync(msFile, out["out.geojson"]);
  t0 = performance.now();
  const ours = smooth(text);
  const bzTime = performance.now() - t0;
  const bzFile = join(dir, `bz-${file}`);
  writeFileSync(bzFile, ours);
  const m = validity(input, msFile);
  const b = validity(input, bzFile);
  console.log(`| ${name} | ${m.valid_before} | ${m.made_invalid} | ${(msTime / 1000).toFixed(2)} s | ${b.made_invalid} | ${(bzTime / 1000).toFixed(2)} s |`);
}
