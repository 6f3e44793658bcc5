#!/usr/bin/env bash
# The npm package's checks, on a fresh machine: installs the wasm32 target and
# wasm-bindgen-cli at the version of Cargo.lock (and Chromium for the page
# test), packs the package (its prepack script builds the WebAssembly), runs
# the Node tests on that build (d3, Observable Plot, Recharts in jsdom, Chart.js
# on a recording canvas, the command's smoothing bit for bit, a page in
# headless Chromium), checks the TypeScript declarations with tsc, then
# installs the tarball in a fresh folder outside the repository and runs a
# smoke test there. Prints "N passed, M failed".
set -uo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
root="$(cd "$here/../.." && pwd)"

fail() {
    echo "bzspline-js: $*" >&2
    echo "0 passed, 1 failed"
    exit 1
}

sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
if [ ! -x /usr/bin/chromium ]; then
    $sudo apt-get update -qq && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq chromium >/dev/null \
        || fail "could not install chromium"
fi
rustup target list --installed | grep -q wasm32-unknown-unknown \
    || rustup target add wasm32-unknown-unknown || fail "could not add the wasm32 target"
want=$(grep -A1 '^name = "wasm-bindgen"$' "$root/Cargo.lock" | sed -n 's/^version = "\(.*\)"/\1/p')
if [ "$(wasm-bindgen --version 2>/dev/null | awk '{print $2}')" != "$want" ]; then
    cargo install -q wasm-bindgen-cli --version "$want" || fail "could not install wasm-bindgen-cli $want"
fi

cd "$here" || fail "no package folder"
PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --ignore-scripts --no-audit --no-fund --loglevel=error || fail "npm ci failed"
# The package as a user gets it: npm pack, whose prepack script builds the
# WebAssembly into wasm/ (a fresh checkout has none: it is built, not
# committed) and into the tarball. The tests below run on that build; the
# tarball is installed into a folder of its own at the end.
rm -rf wasm
smoke=$(mktemp -d)
# (The build's own output may come first; npm prints the tarball's name last.)
tarball=$(npm pack --silent --pack-destination "$smoke" | tail -n 1) || tarball=""
[ -n "$tarball" ] && [ -f "$smoke/$tarball" ] || fail "npm pack (and the WebAssembly build in it) failed"
[ -x "$root/target/debug/bzspline" ] || (cd "$root" && cargo build -q --locked -p bzspline-cli) || fail "cargo build failed"

log=$(mktemp)
node --test --test-reporter=spec test/*.test.mjs 2>&1 | tee "$log"
status=${PIPESTATUS[0]}
passed=$(grep -Eo '^ℹ pass [0-9]+' "$log" | grep -Eo '[0-9]+' | tail -1)
failed=$(grep -Eo '^ℹ fail [0-9]+' "$log" | grep -Eo '[0-9]+' | tail -1)
passed=${passed:-0}
failed=${failed:-0}
if [ "$status" -ne 0 ] && [ "$failed" -eq 0 ]; then failed=1; fi

# The TypeScript declarations, against what the README shows.
if npx tsc --noEmit --strict --target es2022 --module nodenext --moduleResolution nodenext test/types.ts; then
    echo "types: ok"
    passed=$((passed + 1))
else
    echo "types: FAILED"
    failed=$((failed + 1))
    status=1
fi

# The tarball, installed into a folder of its own.
if (cd "$smoke" && npm init -y >/dev/null && npm install --no-audit --no-fund --loglevel=error "./$tarball" d3-shape@3) &&
    cp "$here/test/smoke.mjs" "$smoke/" && (cd "$smoke" && node smoke.mjs); then
    echo "pack smoke: ok ($tarball, $(du -k "$smoke/$tarball" | cut -f1) kB)"
    passed=$((passed + 1))
else
    echo "pack smoke: FAILED"
    failed=$((failed + 1))
    status=1
fi
rm -rf "$smoke" "$log"
echo "$passed passed, $failed failed"
exit "$status"
