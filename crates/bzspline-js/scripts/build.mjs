// Builds the package's WebAssembly without downloading any binary: cargo for
// wasm32-unknown-unknown (added with rustup when missing), wasm-bindgen (the
// CLI at exactly the version of the wasm-bindgen crate in Cargo.lock,
// installed from crates.io with cargo when missing) and, when npm's binaryen
// is installed (a development dependency), wasm-opt. Three modules, one per
// entry of the package: `core` (curves), `smoothing` (the smoothing fits) and
// `geo` (maps). The glue's JavaScript is written without its doc comments,
// which the package's own .d.ts files carry (a page loads the glue as it is).
//
//   node scripts/build.mjs           the three modules into wasm/
//   node scripts/build.mjs --if-missing   only when wasm/ is not built yet
import { execFileSync } from "node:child_process";
import { existsSync, mkdirSync, readFileSync, statSync, writeFileSync } from "node:fs";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";

const pkg = join(dirname(fileURLToPath(import.meta.url)), "..");
const out = join(pkg, "wasm");
const root = join(pkg, "..", "..");

const modules = [
  ["core", []],
  ["smoothing", ["--no-default-features", "--features", "smoothing"]],
  ["geo", ["--no-default-features", "--features", "geo"]],
];
if (process.argv.includes("--if-missing") && modules.every(([name]) => existsSync(join(out, `${name}_bg.wasm`)))) {
  process.exit(0);
}
if (!existsSync(join(root, "Cargo.lock"))) {
  console.error("bzspline: wasm/ is missing and there are no Rust sources to build it from");
  process.exit(1);
}

const run = (cmd, args, opts = {}) => {
  console.error(`+ ${cmd} ${args.join(" ")}`);
  return execFileSync(cmd, args, { stdio: ["ignore", "inherit", "inherit"], cwd: root, ...opts });
};

// The wasm-bindgen CLI must match the crate exactly: the glue it writes is
// specific to one version.
const lock = readFileSync(join(root, "Cargo.lock"), "utf8");
const wanted = lock.match(/name = "wasm-bindgen"\nversion = "([^"]+)"/)?.[1];
let have = "";
try {
  have = execFileSync("wasm-bindgen", ["--version"], { encoding: "utf8" }).trim().split(" ")[1];
} catch {
  have = "";
}
if (have !== wanted) {
  console.error(`bzspline: installing wasm-bindgen-cli ${wanted} (found ${have || "none"})`);
  run("cargo", ["install", "wasm-bindgen-cli", "--version", wanted]);
}
try {
  const targets = execFileSync("rustup", ["target", "list", "--installed"], { encoding: "utf8" });
  if (!targets.includes("wasm32-unknown-unknown")) run("rustup", ["target", "add", "wasm32-unknown-unknown"]);
} catch {
  // No rustup: cargo reports a missing target itself.
}

const target = process.env.CARGO_TARGET_DIR ?? join(root, "target");
const artifact = join(target, "wasm32-unknown-unknown", "wasm", "bzspline_js.wasm");
const wasmOpt = join(pkg, "node_modules", ".bin", "wasm-opt");
mkdirSync(out, { recursive: true });

for (const [name, features] of modules) {
  run("cargo", [
    "build", "--locked", "-p", "bzspline-js", "--target", "wasm32-unknown-unknown",
    "--profile", "wasm", ...features,
  ]);
  run("wasm-bindgen", [artifact, "--target", "web", "--out-dir", out, "--out-name", name]);
  const glue = join(out, `${name}.js`);
  writeFileSync(glue, readFileSync(glue, "utf8").replace(/^[ \t]*\/\*\*[^]*?\*\/\n/gm, ""));
  const file = join(out, `${name}_bg.wasm`);
  if (existsSync(wasmOpt)) {
    run(wasmOpt, ["-Oz", "--strip-producers", "--strip-target-features", "--enable-bulk-memory", "--enable-nontrapping-float-to-int",
      "--enable-sign-ext", "--enable-mutable-globals", "--enable-reference-types",
      "--enable-multivalue", file, "-o", file]);
  }
  console.error(`${name}_bg.wasm: ${statSync(file).size} bytes`);
}
