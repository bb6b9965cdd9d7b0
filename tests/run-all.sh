#!/usr/bin/env bash
# Runs every test of the workspace, then the command-line smoke checks. Exits non-zero on any
# failure. Used by the README and by .ci/run.
set -euo pipefail
cd "$(dirname "$0")/.."

echo "== cargo test (release: the tests integrate hours to weeks of 100 Hz samples) =="
cargo test --workspace --release --no-fail-fast

echo "== rins command line =="
rins=(cargo run --release -q -p rins-scenarios --bin rins --)
"${rins[@]}" verify analytic > /dev/null
"${rins[@]}" verify analytic --json | python3 -c 'import json,sys; d=json.load(sys.stdin); assert d["eq8"]["cancellation_ratio"] <= 1e-9; assert len(d["table2"]["mismatches"]) == 2'
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"${rins[@]}" run builtin:calibration-z-up --out "$tmp/cal" --duration-s 60
test "$(wc -l < "$tmp/cal/imu.csv")" -eq 601
"${rins[@]}" paper table4 --runs 1 --days 0.05 --json --out "$tmp/t4" | python3 -c '
import json, sys
d = json.load(sys.stdin)
for case in ("uncompensated", "compensated"):
    for k in ("lat_nm", "lon_nm", "up_att_mean_deg"):
        for q in ("median", "p05", "p95"):
            assert isinstance(d[case][k][q], float), (case, k, q)
assert "lon_nm" in d["noise_free"]["compensated"]'
test -s "$tmp/t4/fig2_attitude_error.svg" && test -s "$tmp/t4/fig3_position_error.svg"
if "${rins[@]}" run "$tmp/missing.toml" --out "$tmp/x" 2> "$tmp/err"; then
  echo "a missing scenario file must fail"; exit 1
fi
grep -q "missing.toml" "$tmp/err"
echo "1 passed, 0 failed: command-line smoke checks"
