// The package in a real page in headless Chromium (Debian's /usr/bin/chromium,
// driven by playwright-core): it loads without a bundler, draws a line and an
// area with d3, and its paths equal what Node computes. The screenshot goes to
// target/e2e/bzspline-js.png, or to BZSPLINE_SCREENSHOT (docs/bzspline-js.png
// for the README).
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { createServer } from "node:http";
import { existsSync, mkdirSync, readFileSync } from "node:fs";
import { dirname, extname, join, resolve } from "node:path";
import { fileURLToPath } from "node:url";
import { chromium } from "playwright-core";
import { line, area } from "d3-shape";
import { curveBzsplineX, Spline } from "../js/index.js";
import { data } from "./page/data.js";

const pkg = resolve(dirname(fileURLToPath(import.meta.url)), "..");
const root = resolve(pkg, "../..");
const screenshot = resolve(root, process.env.BZSPLINE_SCREENSHOT || "target/e2e/bzspline-js.png");
const CHROMIUM = process.env.CHROMIUM || "/usr/bin/chromium";
const types = { ".html": "text/html", ".js": "text/javascript", ".mjs": "text/javascript", ".wasm": "application/wasm" };

let server;
let browser;
let base;

before(async () => {
  server = createServer((req, res) => {
    const path = decodeURIComponent(new URL(req.url, "http://x").pathname);
    if (path === "/favicon.ico") {
      res.writeHead(204).end();
      return;
    }
    const file = join(pkg, path === "/" ? "test/page/index.html" : path);
    if (!file.startsWith(pkg) || !existsSync(file)) {
      res.writeHead(404).end();
      return;
    }
    res.writeHead(200, { "Content-Type": types[extname(file)] || "application/octet-stream" });
    res.end(readFileSync(file));
  });
  await new Promise((ok) => server.listen(0, "127.0.0.1", ok));
  base = `http://127.0.0.1:${server.address().port}`;
  browser = await chromium.launch({
    executablePath: CHROMIUM,
    args: ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
      "--disable-background-networking", "--disable-component-update", "--disable-sync"],
  });
});

after(async () => {
  await browser?.close();
  server?.close();
});

test("a page without a bundler draws the line and area Node draws", async () => {
  const page = await browser.newPage({ viewport: { width: 680, height: 380 } });
  const errors = [];
  page.on("pageerror", (e) => errors.push(e.message));
  page.on("console", (m) => m.type() === "error" && errors.push(m.text()));
  page.on("requestfailed", (r) => errors.push(`${r.url()}: failed`));
  await page.goto(`${base}/test/page/index.html`);
  await page.waitForFunction(() => window.result, null, { timeout: 15000 }).catch(() => assert.deepEqual(errors, []));
  const result = await page.evaluate(() => window.result);
  assert.deepEqual(errors, []);
  const x = (d) => 40 + d[0] * 56;
  const y = (d) => 280 - d[1] * 24;
  assert.equal(result.line, line().x(x).y(y).curve(curveBzsplineX)(data));
  assert.equal(result.area, area().x(x).y0(280).y1(y).curve(curveBzsplineX)(data));
  assert.equal(result.at, new Spline(data.map((d) => d[0]), data.map((d) => d[1])).at(4.5));
  mkdirSync(dirname(screenshot), { recursive: true });
  await page.screenshot({ path: screenshot });
  await page.close();
});

test("Chart.js with the plugin draws the spline's pieces and reads the curve at a pixel", async () => {
  const page = await browser.newPage({ viewport: { width: 1240, height: 300 } });
  const errors = [];
  page.on("pageerror", (e) => errors.push(e.message));
  page.on("console", (m) => m.type() === "error" && errors.push(m.text()));
  page.on("requestfailed", (r) => errors.push(`${r.url()}: failed`));
  await page.goto(`${base}/test/page/chartjs.html`);
  await page.waitForFunction(() => window.result, null, { timeout: 15000 }).catch(() => assert.deepEqual(errors, []));
  const result = await page.evaluate(() => window.result);
  assert.deepEqual(errors, []);
  // Every piece of the spline through the dataset's pixels was drawn by a
  // bezierCurveTo call of Chart.js's.
  assert.equal(result.pieces.length, 9);
  for (const [k, piece] of result.pieces.entries()) {
    assert.ok(
      result.calls.some((c) => c.every((v, j) => Math.abs(v - piece[j]) < 1e-9)),
      `piece ${k} was drawn`,
    );
  }
  for (const p of result.probes) {
    assert.ok(Math.abs(p.curve - p.spline) < 1e-9 * (1 + Math.abs(p.spline)), `value at ${p.px}`);
  }
  // On this data Chart.js's tension overshoots the data's range [10, 60];
  // the plugin's curve stays inside it.
  const [lo, hi] = result.reach.bzspline;
  assert.ok(lo >= 10 - 1e-9 && hi <= 60 + 1e-9, `bzspline reaches ${lo}..${hi}`);
  const [tlo, thi] = result.reach.tension;
  assert.ok(tlo < 10 || thi > 60, `tension 0.4 reaches ${tlo}..${thi}`);
  // Animated: several frames, each drawn as the method's pieces, the last
  // one the spline of the final pixels.
  const anim = await page.evaluate(() => window.animate());
  assert.ok(anim.count > 3, `${anim.count} frames`);
  assert.ok(anim.piecesPerFrame.every((n) => n === 9), `pieces per frame ${anim.piecesPerFrame}`);
  for (const [k, piece] of anim.pieces.entries()) {
    assert.ok(
      anim.last.some((c) => c.every((v, j) => Math.abs(v - piece[j]) < 1e-9)),
      `piece ${k} drawn in the last frame`,
    );
  }
  const shot = resolve(root, process.env.BZSPLINE_CHARTJS_SCREENSHOT || "target/e2e/chartjs.png");
  mkdirSync(dirname(shot), { recursive: true });
  await page.screenshot({ path: shot });
  await page.close();
});
