// End-to-end test of the `bzspline serve` editor in headless Chromium.
// Run with `node --test editor.test.mjs` (see run.sh). BZSPLINE_BIN names the
// binary (default: the workspace's target/debug/bzspline). The screenshot goes to
// target/e2e/editor.png, or to BZSPLINE_SCREENSHOT (docs/editor.png to refresh the
// README's picture).
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawn, spawnSync } from 'node:child_process';
import { mkdirSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const here = dirname(fileURLToPath(import.meta.url));
const root = resolve(here, '../../../..');
const bin = process.env.BZSPLINE_BIN || resolve(root, 'target/debug/bzspline');
const screenshot = resolve(root, process.env.BZSPLINE_SCREENSHOT || 'target/e2e/editor.png');
const CHROMIUM = process.env.CHROMIUM || '/usr/bin/chromium';

let server;
let base;
let browser;
let page;

function startServer() {
  return new Promise((ok, fail) => {
    server = spawn(bin, ['serve', '--port', '0'], { stdio: ['ignore', 'pipe', 'pipe'] });
    server.on('error', fail);
    server.stderr.on('data', (d) => {
      for (const line of d.toString().split('\n')) {
        if (line.startsWith('fit: 1000 points')) serverLog.push(line);
      }
    });
    let out = '';
    server.stdout.on('data', (d) => {
      out += d.toString();
      const m = out.match(/http:\/\/[^\s]+\//);
      if (m) ok(m[0]);
    });
    setTimeout(() => fail(new Error(`no address printed by ${bin}: ${out}`)), 15000);
  });
}
const serverLog = [];

async function apiFit(body) {
  const res = await fetch(new URL('/api/fit', base), {
    method: 'POST',
    headers: { 'Content-Type': 'application/json' },
    body: JSON.stringify(body),
  });
  assert.equal(res.status, 200, `the API refused ${JSON.stringify(body)}`);
  return res.json();
}

// `bzspline fit` on `points` (JSON on standard input), or null when this build
// has no `fit` command.
function cliFit(points, alphas) {
  if (spawnSync(bin, ['fit', '--help']).status !== 0) return null;
  const r = spawnSync(bin, ['fit', '--input-format', 'json', '--alphas', alphas.join(',')], { input: JSON.stringify(points) });
  assert.equal(r.status, 0, `bzspline fit failed: ${r.stderr}`);
  return JSON.parse(r.stdout.toString());
}

// Waits until the page has no fit pending and at least `after` fits done.
async function settled(after = 0) {
  await page.waitForFunction((n) => window.bzEditor.idle() && window.bzEditor.fits > n, after);
}
const fits = () => page.evaluate(() => window.bzEditor.fits);
const shownFit = async () => JSON.parse(await page.locator('#fit-json').textContent());
const curvePath = () => page.locator('#curve').getAttribute('d');

async function centre(selector) {
  const box = await page.locator(selector).boundingBox();
  assert.ok(box, `${selector} is not on the page`);
  return [box.x + box.width / 2, box.y + box.height / 2];
}

async function drag(from, to, steps = 12) {
  await page.mouse.move(...from);
  await page.mouse.down();
  await page.mouse.move(...to, { steps });
}

before(async () => {
  base = await startServer();
  browser = await chromium.launch({
    executablePath: CHROMIUM,
    args: [
      '--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync',
    ],
  });
  page = await browser.newPage({ viewport: { width: 1280, height: 760 }, deviceScaleFactor: 1 });
  page.on('pageerror', (e) => { throw e; });
  await page.goto(base);
  await settled();
});

after(async () => {
  await browser?.close();
  server?.kill();
});

test('starts from the paper\'s Example 1', async () => {
  const fit = await shownFit();
  assert.deepEqual(fit.knots, [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11]);
  assert.equal(fit.knot_values[0], 1);
  assert.equal(fit.knot_values[10], 1.5);
  assert.match(await curvePath(), /^M ?1 1 C/);
  assert.equal(await page.locator('.pt').count(), 11);
  assert.equal(await page.locator('.tp').count(), 10);
});

test('dragging a control point redraws the curve with the server\'s knot values', async () => {
  const before = await curvePath();
  const n = await fits();
  const [x, y] = await centre('.pt[data-index="5"]');
  await drag([x, y], [x, y + 120]);
  await page.mouse.up();
  await settled(n);
  const after = await curvePath();
  assert.notEqual(after, before, 'the drawn path did not change');
  const points = await page.evaluate(() => window.bzEditor.state.points);
  assert.ok(points[5][1] < 7, `point 5 did not move down: ${points[5]}`);
  const shown = await shownFit();
  const alphas = await page.evaluate(() => window.bzEditor.state.alphas);
  const direct = await apiFit({ points, alphas });
  assert.deepEqual(shown.knot_values, direct.knot_values);
  // And the command line's `fit` on the same points, when this build has it.
  const cli = cliFit(points, alphas);
  if (cli) assert.deepEqual(shown.knot_values, cli.knot_values);
  assert.equal(shown.svg_path, direct.svg_path);
  assert.equal(after, direct.svg_path);
  // The side panel lists the same knot values.
  const listed = await page.locator('#knot-list li').allTextContents();
  assert.equal(listed.length, 11);
  assert.ok(Math.abs(Number(listed[5]) - direct.knot_values[5]) < 1e-4, `${listed[5]} vs ${direct.knot_values[5]}`);
});

test('a function refuses a move that would break increasing x', async () => {
  const [x, y] = await centre('.pt[data-index="3"]');
  const [x2] = await centre('.pt[data-index="2"]');
  await drag([x, y], [x2 - 30, y]);
  await page.mouse.up();
  await settled();
  assert.match(await page.locator('#status').textContent(), /x must keep increasing/);
  const pts = await page.evaluate(() => window.bzEditor.state.points);
  assert.ok(pts[3][0] > pts[2][0], `x order broken: ${pts[2]} ${pts[3]}`);
});

test('dragging a tangent point stops at alpha = 1/3', async () => {
  const n = await fits();
  const from = await centre('.tp[data-leg="7"]');
  const to = await centre('.pt[data-index="8"]');
  // Past the far end of leg 7: the tangent point stops at 2/3 of the leg.
  await drag(from, [to[0] + 40, to[1] - 40]);
  assert.equal(await page.locator('#alpha-readout').textContent(), 'leg 7: 0.3333');
  assert.match(await page.locator('#alpha-label text').textContent(), /= 0\.3333$/);
  await page.mouse.up();
  await settled(n);
  const fit = await shownFit();
  assert.ok(Math.abs(fit.alphas[7] - 1 / 3) < 1e-12, `alpha ${fit.alphas[7]}`);
  assert.equal(await page.locator('.tp[data-leg="7"]').getAttribute('data-alpha'), '0.3333');
  // And back the other way to 2/3.
  const m = await fits();
  const p7 = await centre('.pt[data-index="7"]');
  await drag(await centre('.tp[data-leg="7"]'), [p7[0] - 40, p7[1] + 40]);
  assert.equal(await page.locator('#alpha-readout').textContent(), 'leg 7: 0.6667');
  await page.mouse.up();
  await settled(m);
  assert.ok(Math.abs((await shownFit()).alphas[7] - 2 / 3) < 1e-12);
});

test('double-click adds a point on the nearest leg; right-click removes it; undo and redo', async () => {
  const n0 = await page.locator('.pt').count();
  const a = await centre('.pt[data-index="0"]');
  const b = await centre('.pt[data-index="1"]');
  let n = await fits();
  await page.mouse.dblclick(a[0] + 0.3 * (b[0] - a[0]), a[1] + 0.3 * (b[1] - a[1]));
  await settled(n);
  assert.equal(await page.locator('.pt').count(), n0 + 1);
  assert.equal((await shownFit()).knots.length, n0 + 1);
  n = await fits();
  await page.click('.pt[data-index="1"]', { button: 'right' });
  await settled(n);
  assert.equal(await page.locator('.pt').count(), n0);
  n = await fits();
  await page.click('#undo');
  await settled(n);
  assert.equal(await page.locator('.pt').count(), n0 + 1);
  n = await fits();
  await page.keyboard.press('Control+Shift+Z');
  await settled(n);
  assert.equal(await page.locator('.pt').count(), n0);
});

test('curve mode: chordal parameters, and back to a function only while x increases', async () => {
  let n = await fits();
  await page.selectOption('#mode', 'curve');
  await page.selectOption('#param', 'chordal');
  await settled(n);
  let fit = await shownFit();
  assert.equal(fit.dimension, 2);
  const points = await page.evaluate(() => window.bzEditor.state.points);
  const direct = await apiFit({ points, mode: 'curve', param: 'chordal', alphas: await page.evaluate(() => window.bzEditor.state.alphas) });
  assert.deepEqual(fit.knot_values, direct.knot_values);
  // Move a point left of its neighbour: allowed for a curve...
  n = await fits();
  const [x, y] = await centre('.pt[data-index="4"]');
  const [x3] = await centre('.pt[data-index="3"]');
  await drag([x, y], [x3 - 40, y]);
  await page.mouse.up();
  await settled(n);
  fit = await shownFit();
  assert.equal(fit.dimension, 2);
  // ...but then y(x) is refused with a reason.
  await page.selectOption('#mode', 'function');
  assert.equal(await page.locator('#mode').inputValue(), 'curve');
  assert.match(await page.locator('#status').textContent(), /needs increasing x/);
  n = await fits();
  await page.click('#undo');
  await page.selectOption('#mode', 'function');
  await settled(n);
  assert.equal(await page.locator('#mode').inputValue(), 'function');
  assert.equal((await shownFit()).dimension, 1);
});

test('points load from CSV and GeoJSON text, and export as CSV', async () => {
  let n = await fits();
  await page.evaluate(() => window.bzEditor.importText('x,y\n0,0\n1,2\n2,1\n3,3\n', 'test.csv'));
  await settled(n);
  assert.equal((await shownFit()).knots.length, 4);
  assert.match(await page.locator('#status').textContent(), /Loaded 4 points from test.csv as a function/);
  n = await fits();
  const geo = { type: 'Feature', geometry: { type: 'LineString', coordinates: [[0, 0], [2, 1], [1, 3], [-1, 2]] } };
  await page.evaluate((t) => window.bzEditor.importText(t, 'line.geojson'), JSON.stringify(geo));
  await settled(n);
  assert.equal(await page.locator('#mode').inputValue(), 'curve');
  assert.equal((await shownFit()).dimension, 2);
  n = await fits();
  const ring = { type: 'Polygon', coordinates: [[[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]]] };
  await page.evaluate((t) => window.bzEditor.importText(t, 'square.geojson'), JSON.stringify(ring));
  await settled(n);
  const closed = await shownFit();
  assert.equal(closed.closed, true);
  assert.equal(await page.locator('#closed').isChecked(), true);
  assert.equal(await page.locator('.tp').count(), 4, 'a closed square has four legs');
  n = await fits();
  await page.evaluate((t) => window.bzEditor.importText(t, 'line.geojson'), JSON.stringify(geo));
  await settled(n);
  const [download] = await Promise.all([page.waitForEvent('download'), page.click('#export-csv')]);
  const chunks = [];
  for await (const c of await download.createReadStream()) chunks.push(c);
  assert.equal(Buffer.concat(chunks).toString(), 'x,y\n0,0\n2,1\n1,3\n-1,2\n');
  await page.evaluate(() => window.bzEditor.importText('1,2\nnot a number\n', 'bad.csv'));
  assert.match(await page.locator('#status').textContent(), /line 2/);
});

test('the background pans and the wheel zooms without touching the points', async () => {
  const points = JSON.stringify(await page.evaluate(() => window.bzEditor.state.points));
  const before = await centre('.pt[data-index="0"]');
  await page.mouse.move(640, 80);
  await page.mouse.wheel(0, -300);
  const zoomed = await centre('.pt[data-index="0"]');
  assert.notDeepEqual(zoomed, before);
  await page.click('#fit-view');
  const back = await centre('.pt[data-index="0"]');
  assert.ok(Math.abs(back[0] - before[0]) < 1 && Math.abs(back[1] - before[1]) < 1, `${back} vs ${before}`);
  assert.equal(JSON.stringify(await page.evaluate(() => window.bzEditor.state.points)), points);
});

test('a 1,000-point polygon is fitted on every move (timing reported, not asserted)', async () => {
  const times = [];
  for (let run = 0; run < 7; run++) {
    const n = await fits();
    await page.evaluate((r) => {
      const pts = Array.from({ length: 1000 }, (_, i) => [i / 10, Math.sin(i / 7 + r) * 3 + Math.cos(i / 3) * 0.5]);
      window.bzEditor.loadPoints(pts, 'function', false);
    }, run);
    await settled(n);
    const fit = await page.evaluate(() => ({ n: window.bzEditor.fit.knot_values.length, build: window.bzEditor.fit.build_ms, ms: window.bzEditor.fit.fit_ms, rt: window.bzEditor.lastRoundTripMs }));
    assert.equal(fit.n, 1000);
    times.push(fit);
  }
  const median = (xs) => xs.slice().sort((a, b) => a - b)[Math.floor(xs.length / 2)];
  console.log(`1000-point fit: library build ${median(times.map((t) => t.build)).toFixed(3)} ms, server fit + JSON ${median(times.map((t) => t.ms)).toFixed(3)} ms, browser round trip ${median(times.map((t) => t.rt)).toFixed(1)} ms (median of ${times.length})`);
  for (const line of serverLog.slice(-3)) console.log(`server log: ${line}`);
});

test('through the points: the curve passes through the dragged points; the solved polygon is faint', async () => {
  let n = await fits();
  await page.click('#reset');
  await settled(n);
  n = await fits();
  await page.check('#through');
  await settled(n);
  const points = await page.evaluate(() => window.bzEditor.state.points);
  const alphas = await page.evaluate(() => window.bzEditor.state.alphas);
  let shown = await shownFit();
  shown.knot_values.forEach((v, i) => assert.ok(Math.abs(v - points[i][1]) < 1e-12, `knot ${i}: ${v} vs ${points[i][1]}`));
  const direct = await apiFit({ points, alphas, through: true });
  assert.deepEqual(shown.values, direct.values);
  assert.equal(await curvePath(), direct.svg_path);
  assert.match(await page.locator('#polygon').getAttribute('class'), /solved/);
  // The drawn polygon runs through the solved controls, not the points.
  const d = await page.locator('#polygon').getAttribute('d');
  const drawn = d.slice(1).split(' L').map((p) => p.split(' ').map(Number));
  assert.equal(drawn.length, direct.values.length);
  // Drag a point: the curve still passes through it.
  n = await fits();
  const [x, y] = await centre('.pt[data-index="5"]');
  await drag([x, y], [x, y + 80]);
  await page.mouse.up();
  await settled(n);
  const moved = await page.evaluate(() => window.bzEditor.state.points);
  shown = await shownFit();
  assert.ok(Math.abs(shown.knot_values[5] - moved[5][1]) < 1e-12, `${shown.knot_values[5]} vs ${moved[5][1]}`);
  n = await fits();
  await page.uncheck('#through');
  await settled(n);
  assert.doesNotMatch((await page.locator('#polygon').getAttribute('class')) ?? '', /solved/);
});

test('screenshot of the editor', async () => {
  const n = await fits();
  await page.click('#reset');
  await page.check('#show-comb');
  await page.check('#show-hull');
  await settled(n);
  // Shape it a little, and hold a tangent point so that its alpha shows.
  const m = await fits();
  const [x, y] = await centre('.pt[data-index="2"]');
  await drag([x, y], [x, y - 60]);
  await page.mouse.up();
  await settled(m);
  const k = await fits();
  const from = await centre('.tp[data-leg="5"]');
  const to = await centre('.pt[data-index="5"]');
  await drag(from, [(from[0] + to[0]) / 2, (from[1] + to[1]) / 2]);
  await settled(k);
  mkdirSync(dirname(screenshot), { recursive: true });
  await page.screenshot({ path: screenshot });
  await page.mouse.up();
  assert.ok((await shownFit()).comb.length > 0);
});
