#!/usr/bin/env bash
# The user guide's pictures, made by the browser checks of the demo's results.
#
#   bash scripts/guide_images.sh            # check every demo job's viewer in headless Chromium;
#                                           # pictures in test-artifacts/guide-images/<job>.png
#   bash scripts/guide_images.sh --refresh  # the same, then copy them over docs/images/<job>.png
#
# scripts/test.sh runs the first form. Needs the release binary
# (cargo build --release -p septa-cli), viewer/node_modules (npm ci in viewer/)
# and chromium. The list of jobs with a picture is here only.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
ART="$ROOT/test-artifacts"
GUIDE="$ART/guide-images"
JOBS=(cad-part apollonius-18 sphere-plane-hole cut-torus)

refresh=0
for a in "$@"; do
  case "$a" in
    --refresh) refresh=1 ;;
    *) echo "usage: bash scripts/guide_images.sh [--refresh]" >&2; exit 2 ;;
  esac
done

rm -rf "$GUIDE"
mkdir -p "$GUIDE"
"$ROOT/target/release/septa" demo --out "$ART/demo"
for job in "${JOBS[@]}"; do
  # Checks the viewer (not blank, colours, picking) and writes its screenshots
  # to test-artifacts/<job>/, the first page view also to the guide's folder.
  node viewer/test/browser.mjs "$ART/demo/$job/viewer" "$ART/$job" --guide-image "$GUIDE/$job.png"
done
for job in "${JOBS[@]}"; do
  test -s "$GUIDE/$job.png" || { echo "no picture for $job" >&2; exit 1; }
done
echo "guide pictures in $GUIDE"
if [ "$refresh" = 1 ]; then
  cp "$GUIDE"/*.png "$ROOT/docs/images/"
  echo "copied to docs/images/ (review with git diff --stat docs/images, then commit)"
fi
