#!/usr/bin/env bash
# CTest browser_replay: records a short run (hexagon_static, 20 s) and a humanoid footstep run
# (nao_stairs) as HTML replays with the built `bipednav` and checks them in headless Chromium
# through playwright-core (replay_test.mjs).
# Usage: run_replay_test.sh BIPEDNAV_EXE WORK_DIR
# Exits 77 (CTest SKIP_RETURN_CODE) when chromium, node or npm is missing
# (scripts/install-deps --browser installs them) or the npm packages cannot be installed.
set -euo pipefail
exe=$1
work=$2
skip() { echo "SKIPPED: $*"; exit 77; }

chromium=${CHROMIUM:-$(command -v chromium || command -v chromium-browser || true)}
[ -n "$chromium" ] || skip "no chromium (scripts/install-deps --browser)"
command -v node >/dev/null || skip "no node (scripts/install-deps --browser)"

here=$(cd "$(dirname "$0")" && pwd)
# playwright-core goes into the build tree, pinned by package-lock.json.
mkdir -p "$work"
cp "$here/package.json" "$here/package-lock.json" "$here/replay_test.mjs" "$work/"
if [ ! -d "$work/node_modules/playwright-core" ] || ! cmp -s "$here/package-lock.json" "$work/node_modules/.bipednav-lock"; then
  command -v npm >/dev/null || skip "no npm (scripts/install-deps --browser)"
  (cd "$work" && npm ci --no-audit --no-fund --loglevel=error) || skip "npm ci failed (offline?)"
  cp "$here/package-lock.json" "$work/node_modules/.bipednav-lock"
fi

# 20 s end before the goal: the run's task fails (exit 1); only an error (2) stops the test.
"$exe" run hexagon_static --time-limit 20 --out "$work/run" --replay "$work/replay.html" || [ $? -eq 1 ]
CHROMIUM=$chromium node "$work/replay_test.mjs" "$work/replay.html" "$work/replay.png"
# The humanoid footstep loop's replay (nao_stairs: ~35 s walked, a few seconds to compute).
"$exe" run nao_stairs --out "$work/run_footsteps" --replay "$work/replay_footsteps.html"
CHROMIUM=$chromium node "$work/replay_test.mjs" "$work/replay_footsteps.html" "$work/replay_footsteps.png"
