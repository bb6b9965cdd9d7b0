#!/usr/bin/env bash
# Renders every result command's HTML report in a real headless Chromium (Debian's `chromium`
# package, installed here with apt-get when missing; never a downloaded browser build) and
# checks it: no console errors, every figure present and non-empty, the numbers on the page
# equal the command's --json output. Screenshots are left in $RINS_BROWSER_OUT if set.
# Usage: tests/browser/run.sh RINS_BINARY
set -euo pipefail
cd "$(dirname "$0")/../.."
rins="${1:?usage: tests/browser/run.sh RINS_BINARY}"
if [ ! -x /usr/bin/chromium ]; then
  if command -v apt-get >/dev/null && [ "$(id -u)" = 0 ]; then
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium > /dev/null
  else
    echo "tests/browser: /usr/bin/chromium is missing (apt-get install chromium)"; exit 1
  fi
fi
python3 tests/browser/test_reports.py "$rins"
