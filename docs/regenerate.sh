#!/usr/bin/env bash
# Regenerates what the docs quote from the current build, in one go:
#  - the figures in the output blocks the docs mark (`<!-- doc-test: output -->`): every
#    documented command block is run as the doc test runs it, and an output line whose wording
#    is unchanged but whose numbers moved is rewritten (tests/doc_commands.py --update; a line
#    whose wording changed still fails and is left for a person);
#  - the report screenshots in docs/images: the browser test's screenshots of `rins paper`
#    (docs/images/report-paper.png) and `rins diagnose --report` (report-diagnose.png).
# Review the result with `git diff docs README.md` before committing.
# Usage: bash docs/regenerate.sh   (builds with Rerun support, as the tests do)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -p rins-scenarios --features rins-scenarios/rerun
bin="${CARGO_TARGET_DIR:-target}/release"
python3 tests/doc_commands.py --bin "$bin" --update
shots=$(mktemp -d)
RINS_BROWSER_OUT="$shots" bash tests/browser/run.sh "$bin/rins"
cp "$shots/paper.png" docs/images/report-paper.png
cp "$shots/diagnose.png" docs/images/report-diagnose.png
rm -rf "$shots"
git status --short -- docs README.md
