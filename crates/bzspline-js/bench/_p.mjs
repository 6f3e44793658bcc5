import init, { initSync, splinePieces } from "../wasm/core.js";
import { readFileSync } from "node:fs";
initSync({ module: readFileSync(new URL("../wasm/core_bg.wasm", import.meta.url)) });
const n = 1000; let x = [], y = [], s = 0;
for (let i = 0; i < n; i++) { s += 0.5 + Math.random(); x.push(s); y.push(Math.sin(s / 50) * 100); }
const T = (f, r = 2000) => { f(); const t0 = performance.now(); for (let i = 0; i < r; i++) f(); return (performance.now() - t0) / r * 1000; };
console.log("splinePieces us", T(() => splinePieces(x, y, 0.5, false)).toFixed(1));
