#!/usr/bin/env bash
# The Python package's tests (python/, docs/python.md): a fresh venv, the pinned test
# requirements, the package built by pip through maturin, then pytest on python/tests.
#
# .ci/run calls it after `cargo test`: the package is built with the settings of cargo's
# `test` profile (MATURIN_PEP517_ARGS, below), so it reuses the dependencies `cargo test` has
# just compiled into the same target directory (CARGO_TARGET_DIR, or target/ of the workspace)
# instead of compiling them again in release. Users' `pip install ./python` builds release.
#
# Environment: PYTHON (default python3, 3.9 or later, with venv and pip), VENV (default a
# temporary directory, removed at the end), SHOAL_PY_PROFILE (default test; "release" for a
# user's build).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)

python=${PYTHON:-python3}
profile=${SHOAL_PY_PROFILE:-test}
venv=${VENV:-}
if [ -z "$venv" ]; then
    venv=$(mktemp -d -t shoal-py-venv.XXXXXX)
    trap 'rm -rf "$venv"' EXIT
fi
# the workspace's target directory, absolute: maturin runs cargo in python/, where a relative
# CARGO_TARGET_DIR would name another directory
export CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-$root/target}
case "$CARGO_TARGET_DIR" in /*) ;; *) CARGO_TARGET_DIR=$root/$CARGO_TARGET_DIR ;; esac

stamp() { date +%s; }
t0=$(stamp)
if ! "$python" -m venv "$venv" 2>/dev/null; then
    # Debian's own python3 keeps venv (ensurepip) in a package of its own
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends python3-venv
    rm -rf "$venv"
    "$python" -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check --upgrade pip
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
    -r python/requirements-test.txt
t1=$(stamp)
# --locked: the build uses Cargo.lock as committed, as every cargo command of .ci/run does.
# The test profile is cargo's dev profile at opt-level 2 with line tables only (Cargo.toml,
# [profile.test]); it is given as such, because `cargo rustc --profile test`, which maturin
# runs, would build the crate as a test harness instead of a library. Cargo shares artifacts
# between profiles of equal settings, but this package's dependency features differ from the
# test build's (pyo3, numpy), so most dependencies compile again here.
if [ "$profile" = test ]; then
    export CARGO_PROFILE_DEV_OPT_LEVEL=2
    export CARGO_PROFILE_DEV_DEBUG=line-tables-only
    profile=dev
fi
MATURIN_PEP517_ARGS="--profile $profile --locked" \
    "$venv/bin/python" -m pip install --disable-pip-version-check ./python
t2=$(stamp)
MPLBACKEND=Agg "$venv/bin/pytest" -q python/tests
t3=$(stamp)
echo "ci-python: venv and test requirements $((t1 - t0)) s, build and install $((t2 - t1)) s," \
    "pytest $((t3 - t2)) s, in all $((t3 - t0)) s"
