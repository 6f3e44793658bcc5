#!/usr/bin/env bash
# End-to-end test of the `bzspline serve` editor in headless Chromium.
# Installs what it needs on a fresh Debian machine (the chromium package and the
# pinned playwright-core; never a downloaded browser), builds the binary unless
# BZSPLINE_BIN names one, runs editor.test.mjs with `node --test`, and prints
# "N passed, M failed".
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../../../.." && pwd)"

fail() {
    echo "e2e: $*" >&2
    echo "0 passed, 1 failed"
    exit 1
}

if [ ! -x /usr/bin/chromium ]; then
    command -v apt-get >/dev/null || fail "/usr/bin/chromium is missing and apt-get is not available"
    sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    $sudo apt-get update && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y chromium \
        || fail "could not install chromium"
fi
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
    command -v apt-get >/dev/null || fail "node and npm are missing"
    sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    $sudo apt-get update && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y nodejs npm \
        || fail "could not install node"
fi

(cd "$here" && PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --no-audit --no-fund --loglevel=error) \
    || fail "npm ci failed"
# BZSPLINE_BIN names a command built already (CI passes the one `cargo test` built).
if [ -z "${BZSPLINE_BIN:-}" ]; then
    (cd "$root" && cargo build --locked -p bzspline-cli) || fail "cargo build failed"
    BZSPLINE_BIN="$root/target/debug/bzspline"
fi
[ -x "$BZSPLINE_BIN" ] || fail "$BZSPLINE_BIN is not an executable"

log=$(mktemp)
(cd "$here" && BZSPLINE_BIN="$BZSPLINE_BIN" node --test --test-reporter=spec editor.test.mjs) 2>&1 | tee "$log"
status=${PIPESTATUS[0]}
passed=$(grep -Eo '^ℹ pass [0-9]+' "$log" | grep -Eo '[0-9]+' | tail -1)
failed=$(grep -Eo '^ℹ fail [0-9]+' "$log" | grep -Eo '[0-9]+' | tail -1)
rm -f "$log"
passed=${passed:-0}
failed=${failed:-0}
if [ "$status" -ne 0 ] && [ "$failed" -eq 0 ]; then
    failed=1
fi
echo "$passed passed, $failed failed"
exit "$status"
