#!/usr/bin/env bash
# The test suite on a fresh machine (README, "Install and first run"): installs what the
# viewer's browser test needs when it is missing, then runs `cargo test --locked`.
#
# - Debian's Chromium (/usr/bin/chromium), through apt-get (as root, or with sudo);
# - the viewer test's pinned Node packages (playwright-core, tests/viewer/package-lock.json),
#   through `npm ci` in tests/viewer; Node.js 20 or later must be installed.
#
# Arguments go to `cargo test`, e.g. `scripts/test.sh --test cli`. The whole CI run (fmt,
# clippy, docs, Slurm, Python, GDAL) is `bash .ci/run`.
set -euo pipefail
cd "$(dirname "$0")/.."

as_root() {
    if [ "$(id -u)" -eq 0 ]; then
        "$@"
    elif command -v sudo >/dev/null; then
        sudo "$@"
    else
        echo "scripts/test.sh: '$*' needs root (or sudo)" >&2
        exit 1
    fi
}

if [ "${SHOAL_SKIP_BROWSER:-}" != 1 ]; then
    if [ ! -x /usr/bin/chromium ]; then
        echo "scripts/test.sh: installing Debian's chromium for the viewer's browser test"
        as_root apt-get update -qq
        as_root env DEBIAN_FRONTEND=noninteractive \
            apt-get install -y -qq --no-install-recommends chromium
    fi
    command -v node >/dev/null || {
        echo "scripts/test.sh: node (Node.js 20+) is required by the viewer test" \
            "(or set SHOAL_SKIP_BROWSER=1 to skip that test)" >&2
        exit 1
    }
    if [ ! -d tests/viewer/node_modules/playwright-core ]; then
        echo "scripts/test.sh: installing the viewer test's pinned Node packages (npm ci)"
        (cd tests/viewer && npm ci --no-audit --no-fund)
    fi
fi

cargo test --locked "$@"
