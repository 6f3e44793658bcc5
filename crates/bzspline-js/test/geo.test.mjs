// bzspline/geo: the command's smoothing, bit for bit. Each document goes
// through `smooth` here and through the `bzspline smooth` binary (BZSPLINE_BIN,
// default the workspace's target/debug/bzspline) with the same options; the
// outputs are equal as JSON values (every number the same double). With
// BZSPLINE_ATLAS (bench/atlas.sh), the public us-atlas and world-atlas
// coverages too.
import { test } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { existsSync, readFileSync, mkdtempSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath } from "node:url";
import { smooth } from "../js/geo.js";

const here = dirname(fileURLToPath(import.meta.url));
const root = resolve(here, "../../..");
const bin = process.env.BZSPLINE_BIN || join(root, "target/debug/bzspline");
const fixtures = join(root, "crates/bzspline-cli/tests/fixtures");
const atlas = process.env.BZSPLINE_ATLAS;

/** `bzspline smooth FILE ARGS` as a JSON value. */
function command(file, args) {
  const out = execFileSync(bin, ["smooth", file, ...args], { maxBuffer: 1 << 30 });
  return JSON.parse(out.toString());
}

/** smooth(doc, options) beside the command with `args`, on `file`. */
function same(file, options, args) {
  const doc = JSON.parse(readFileSync(file, "utf8"));
  const ours = smooth(doc, options);
  assert.deepEqual(ours, command(file, args), `${file} ${args.join(" ")}`);
  return ours;
}

test("the binary is there to compare with", () => {
  assert.ok(existsSync(bin), `${bin} is missing: cargo build -p bzspline-cli`);
});

test("GeoJSON coverages: the command's output, bit for bit, with each option", () => {
  for (const name of ["mosaic.geojson", "shapes.geojson", "countries.geojson"]) {
    const file = join(fixtures, name);
    same(file, {}, []);
    same(file, { tolerance: 0.01 }, ["--tolerance", "0.01"]);
    same(file, { through: true, alpha: 1 / 3 }, ["--through", "--alpha", "1/3"]);
    same(file, { keepAngle: 60, param: "uniform" }, ["--keep-angle", "60", "--param", "uniform"]);
    same(file, { independent: true }, ["--independent"]);
    same(file, { snap: 1e-9 }, ["--snap", "1e-9"]);
    same(file, { tolerance: "20km", snap: "1m" }, ["--tolerance", "20km", "--snap", "1m"]);
    same(file, { output: "topojson", name: name.replace(".geojson", "") }, ["--output-format", "topojson"]);
  }
});

test("keepAngle with z keeps the corners, as the command does", () => {
  // Right-angled corners with z rising along the line: the turning angle is
  // planar, z is carried along (the command writes a note on standard error).
  const file = join(fixtures, "z_corners.geojson");
  const ours = same(file, { keepAngle: 30 }, ["--keep-angle", "30"]);
  const has = (line, p) => line.some((q) => q.length === p.length && q.every((v, i) => v === p[i]));
  for (const corner of JSON.parse(readFileSync(file, "utf8")).coordinates) {
    assert.ok(has(ours.coordinates, corner), `corner ${corner} is not kept`);
  }
  assert.ok(!has(smooth(JSON.parse(readFileSync(file, "utf8")), {}).coordinates, [1, 1, 3]));
});

test("TopoJSON in gives TopoJSON out, as the command writes it", () => {
  const dir = mkdtempSync(join(tmpdir(), "bzspline-"));
  const topo = join(dir, "mosaic.topojson");
  writeFileSync(topo, JSON.stringify(command(join(fixtures, "mosaic.geojson"), ["--output-format", "topojson"])));
  const out = same(topo, {}, ["--output-format", "topojson"]);
  assert.deepEqual(Object.keys(out.objects), ["mosaic"]);
  assert.equal(out.type, "Topology");
  same(topo, { output: "geojson" }, []);
});

test("a string in gives a string out; bad documents and options throw, naming the fault", () => {
  const text = readFileSync(join(fixtures, "shapes.geojson"), "utf8");
  assert.equal(typeof smooth(text), "string");
  assert.throws(() => smooth("{"), (e) => e instanceof TypeError && /invalid JSON/.test(e.message));
  assert.throws(() => smooth(42), TypeError);
  assert.throws(() => smooth(JSON.parse(text), { tolerance: -1 }), (e) => e instanceof RangeError && /tolerance/.test(e.message));
  assert.throws(() => smooth(JSON.parse(text), { tolerance: "5 furlongs" }), (e) => e instanceof RangeError && /50m, 0\.5km/.test(e.message));
  assert.throws(() => smooth(JSON.parse(text), { tolerance: true }), (e) => e instanceof TypeError && /tolerance/.test(e.message));
  assert.throws(() => smooth(JSON.parse(text), { independent: true, snap: 1 }), RangeError);
  assert.throws(() => smooth(JSON.parse(text), { output: "svg" }), RangeError);
  const bad = { type: "Feature", properties: {}, geometry: { type: "LineString", coordinates: [[0, 0], [1]] } };
  assert.throws(() => smooth(bad), (e) => e instanceof RangeError && /coordinates\[1\]/.test(e.message));
});

test("the public coverages (BZSPLINE_ATLAS): the command's output, bit for bit", { skip: !atlas && "BZSPLINE_ATLAS is not set" }, () => {
  for (const file of ["us-atlas/states-10m.json", "world-atlas/countries-110m.json", "world-atlas/countries-50m.json"]) {
    same(join(atlas, file), {}, ["--output-format", "topojson"]);
  }
  same(join(atlas, "states.geojson"), {}, []);
});
