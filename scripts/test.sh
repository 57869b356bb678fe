#!/usr/bin/env bash
# Every test of the project (the README's test command): Rust, Python, viewer.
# Works on a fresh Debian machine as root with only the package registries,
# and is idempotent (re-running reuses .venv, node_modules and chromium).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
export CARGO_TERM_COLOR=never
# The release profile's whole-program optimisation (Cargo.toml) only makes
# the programs faster, not different; for the tests, whose many binaries
# would each be linked that way, the quicker build of before.
export CARGO_PROFILE_RELEASE_LTO=false CARGO_PROFILE_RELEASE_CODEGEN_UNITS=4
step() { printf '\n=== %s ===\n' "$*"; }

step "Layers: no import cycle in the library (scripts/check_layers.py)"
python3 scripts/check_layers.py > /dev/null || python3 scripts/check_layers.py

step "Rust: cargo test --workspace --release (all 57 TopoCut reference cases)"
SEPTA_FULL=1 cargo test --workspace --release

step "Reproduce scripts of the seed tables at tiny sizes (scripts/reproduce/)"
cargo build --release -q -p septa-cli
R="$ROOT/target/release/septa"
python3 scripts/reproduce/du_table1_stress.py "$R" --count 50 > /dev/null
python3 scripts/reproduce/du_table2_shifted.py "$R" --inputs 1 --res 6 --eps 1e-6 > /dev/null
python3 scripts/reproduce/du_table3_per_tet.py "$R" --count 200 > /dev/null
python3 scripts/reproduce/du_figures13_15.py "$R" --res 6,8 --functions 2,3 --repeat 1 > /dev/null

step "Rust: septa-exact and septa with debug assertions and overflow checks (profile ci)"
# Release code with `debug_assert!` and integer overflow checks on: the
# library tests once more (the CLI and Python front ends add no arithmetic).
cargo test --profile ci -p septa-exact -p septa --lib --tests

step "Python: virtual environment, pip install . (maturin builds the Rust core)"
PY=${PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
  "$PY" -m venv .venv
fi
.venv/bin/python -m pip install -q --upgrade pip
.venv/bin/python -m pip install -q maturin numpy pytest meshio trimesh plyfile "dask[distributed]" pynrrd nibabel pyvista foamlib fluidfoam
rm -f python/septa/_septa*.so  # left by `maturin develop`; never package a stale one
# CARGO_TARGET_DIR shared with the cargo step above so built crates are reused.
PATH="$ROOT/.venv/bin:$PATH" CARGO_TARGET_DIR="$ROOT/target" .venv/bin/python -m pip install -q --no-build-isolation --force-reinstall --no-deps .

step "Python: the wheel for other machines (maturin build --release: stripped, manylinux, abi3)"
# Same profile and flags as the install above, so cargo reuses its build;
# scripts/check_wheel.py checks the tag, the size and that the library is
# stripped (the README and docs/distributed.md quote them).
rm -rf "$ROOT/target/wheels-ci"
PATH="$ROOT/.venv/bin:$PATH" CARGO_TARGET_DIR="$ROOT/target" .venv/bin/maturin build --release -q -o "$ROOT/target/wheels-ci"
.venv/bin/python scripts/check_wheel.py "$ROOT"/target/wheels-ci/septa-*.whl

step "Python: pytest"
# Run from tests/python so `import septa` is the installed package, not python/septa.
# -rs lists every skip with its reason; under CI=true (.ci/run) a skip fails
# the run (tests/python/conftest.py), and so does collecting no test (exit 5).
(cd tests/python && "$ROOT/.venv/bin/python" -m pytest -q -rs . --doctest-modules --pyargs septa -p no:cacheprovider)

step "Viewer: npm ci, bundle up to date"
cd "$ROOT/viewer"
# Reinstall only when the lock file changed since the last install.
if ! cmp -s package-lock.json node_modules/.septa-lock 2>/dev/null; then
  npm ci --no-audit --no-fund
  cp package-lock.json node_modules/.septa-lock
fi
node build.mjs --check

step "Viewer: headless Chromium"
if ! command -v chromium >/dev/null 2>&1; then
  apt-get update
  DEBIAN_FRONTEND=noninteractive apt-get install -y chromium
fi
cd "$ROOT"
ART="$ROOT/test-artifacts"
rm -rf "$ART/two-planes"
mkdir -p "$ART"
cp -r tests/fixtures/two-planes "$ART/two-planes"
"$ROOT/target/release/septa" view "$ART/two-planes" --no-open
# Two labels (f0, f1) and four patches: see scripts/make_fixture.py.
node viewer/test/browser.mjs "$ART/two-planes/viewer" "$ART" --label-colours 2 --patch-colours 4

# A label volume's result: the regions' ids in network.json, picking and the
# exploded view (the demo below adds a regions, an MI and a cut result).
rm -rf "$ART/labels-volume" "$ART/labels"
.venv/bin/python - "$ART/labels-volume.npy" <<'PYEOF'
import sys
import numpy as np
v = np.zeros((14, 14, 14), np.int64)
v[2:8, 2:10, 2:10] = 1
v[8:11, 2:10, 2:10] = 2
v[3:7, 3:7, 9:12] = 3
np.save(sys.argv[1], v)
PYEOF
"$ROOT/target/release/septa" labels "$ART/labels-volume.npy" -o "$ART/labels-volume" -q
"$ROOT/target/release/septa" view "$ART/labels-volume" --no-open
node viewer/test/browser.mjs "$ART/labels-volume/viewer" "$ART/labels"

# And on real results: every demo job with a viewer. Its first page view is
# the user guide's picture, written to test-artifacts/guide-images/<job>.png;
# `bash scripts/guide_images.sh --refresh` copies them over docs/images/.
bash scripts/guide_images.sh

step "all tests passed"
