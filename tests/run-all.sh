#!/usr/bin/env bash
# Runs every test of the workspace, then the command-line smoke checks. Exits non-zero on any
# failure. Used by the README and by .ci/run.
set -euo pipefail
cd "$(dirname "$0")/.."

# Every process the suite starts inherits this mark (cargo, the test binaries, Python and what
# they start pass their environment on), so the last check finds exactly the processes this run
# left behind, and none of another run on the same machine.
export RINS_SUITE_RUN="$$-$(date +%s%N)"

# The `rins` binary is built with Rerun support here (the README's first command builds without it).
features=(--features rins-scenarios/rerun)

echo "== cargo fmt --check =="
cargo fmt --all --check

echo "== import circles (tests/import_cycles.py: only those docs/architecture.md names) =="
python3 tests/import_cycles.py .

echo "== crate graph (tests/crate_graph.py: drawn from the imports, none back up; Python off the report and the app) =="
python3 tests/crate_graph.py .

echo "== cargo build (the FMI shared libraries are loaded by the tests) =="
cargo build --workspace --release "${features[@]}"
target_dir="${CARGO_TARGET_DIR:-target}"
bin="$target_dir/release"

echo "== cargo test (release: the tests integrate hours to weeks of 100 Hz samples) =="
# This also builds the examples into $bin/examples, among them carrier_imu: the in-process carrier
# -> IMU system test_masters.py compares the masters with. (A separate `cargo build -p
# rins-imu-fmu --example carrier_imu` resolved features for that package alone and recompiled
# serde, zip and the plant a second time.)
cargo test --workspace --release --no-fail-fast "${features[@]}"

echo "== Python clients (pinned, in a venv this script creates) =="
venv="${RINS_VENV:-${HOME:-/root}/.cache/rins-venv}"
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/pip" install -q --disable-pip-version-check fmpy==0.3.32 'dask[distributed]==2026.8.0' iceoryx2==0.10.0 rerun-sdk==0.36.3 libcosimpy==0.0.6 ecospy==0.7.2 tbb==2023.2.0
pytmp=$(mktemp -d)
"$bin/rins" fmu build --out "$pytmp/fmu" > /dev/null
"$venv/bin/python" tests/python/test_fmu.py "$pytmp/fmu" "$bin/rins" "$pytmp"
"$venv/bin/python" tests/python/test_masters.py "$pytmp/fmu" "$bin/rins" "$pytmp"
"$venv/bin/python" tests/python/test_transport.py "$bin/rins" "$pytmp"
"$venv/bin/python" tests/python/test_rerun.py "$bin/rins" "$pytmp"
# The rins Python package (python/, PyO3 + maturin): the wheel built by cargo, installed, tested.
"$venv/bin/pip" install -q --disable-pip-version-check maturin==1.16.0
# maturin's build backend calls the `maturin` executable: the venv's bin goes first on PATH.
PATH="$venv/bin:$PATH" "$venv/bin/pip" install -q --disable-pip-version-check --no-build-isolation ./python
"$venv/bin/python" -c "import rins"
"$venv/bin/python" tests/python/test_package.py "$bin/rins" "$pytmp"
rm -rf "$pytmp"

echo "== documented commands (README.md, docs/*.md; tests/doc_commands.py lists every block) =="
# The blocks run as written with this build's rins first on PATH and the venv's python (the
# package above, fmpy, libcosimpy, ecospy, dask, rerun-sdk); this build has Rerun, so the
# blocks marked `needs rerun` must run rather than be skipped.
python3 tests/doc_commands.py --bin "$bin" --self-test
PATH="$venv/bin:$PATH" RINS_DOC_PYTHON="$venv/bin/python" RINS_DOC_RERUN=1 \
  python3 tests/doc_commands.py --bin "$bin"

echo "== rins command line =="
# The binary the workspace build above made (with Rerun). `cargo run -p rins-scenarios` resolved
# features for that one package and compiled arrow, rerun, nalgebra and the rins crates again:
# about 6 of an empty-cache run's minutes.
rins=("$bin/rins")
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
"${rins[@]}" verify analytic --figures "$tmp/verify" > /dev/null
test -s "$tmp/verify/eq8_eq11_cycle.svg" && test -s "$tmp/verify/eq8_eq11_cycle.png" && test -s "$tmp/verify/analytic_checks.png"
"${rins[@]}" calibrate builtin:calibration-z-down --json --out "$tmp/calib" | python3 -c '
import json, sys
d = json.load(sys.stdin)
assert len(d["delta_beta_dph"]) == 3 and len(d["delta_beta_se_dph"]) == 3
assert d["down"]["position"] == "z-down" and len(d["up"]["segments"]) == 2'
test -s "$tmp/calib/calibration.json" && test -s "$tmp/calib/calibration_beta.png"
cat > "$tmp/camp.toml" <<'TOML'
[scenario]
name = "smoke-campaign"
[scheme]
kind = "z-up-calibration"
lead_dwell_s = 120.0
dwell_s = 120.0
[sensor]
preset = "nav-grade-full"
[campaign]
from_c = 10.0
to_c = 50.0
runs = 5
TOML
"${rins[@]}" campaign "$tmp/camp.toml" --out "$tmp/camp" > /dev/null
grep -q "sensor.gyro.position_bias" "$tmp/camp/dbeta-compensation.toml" && test -s "$tmp/camp/fig8_dbeta_vs_temperature.svg"
# The compensation file is a scenario fragment the plant loads too.
"${rins[@]}" run "$tmp/camp/dbeta-compensation.toml" --out "$tmp/fragment" --duration-s 1
"${rins[@]}" paper table5 --compensation "$tmp/camp/dbeta-compensation.toml" --runs 1 --days 0.05 --json --out "$tmp/t5" | python3 -c '
import json, sys
d = json.load(sys.stdin)
for case in ("uncompensated", "compensated"):
    for k in ("lat_nm", "lon_nm", "horizontal_nm", "trms_nm"):
        assert k in d[case], (case, k)
for k in ("lat", "lon", "horizontal", "trms"):
    assert k in d["improvement_pct"], k'
printf '[scenario]\nname = "bad"\n[campaign]\ntemps_c = [20.0, 30.0, 200.0, 40.0, 50.0]\n' > "$tmp/badcamp.toml"
if "${rins[@]}" campaign "$tmp/badcamp.toml" --out "$tmp/bc" 2> "$tmp/err"; then echo "a campaign at 200 C must fail"; exit 1; fi
grep -q "200" "$tmp/err"
if "${rins[@]}" run "$tmp/missing.toml" --out "$tmp/x" 2> "$tmp/err"; then
  echo "a missing scenario file must fail"; exit 1
fi
grep -q "missing.toml" "$tmp/err"
# Model vs measurements: simulate a unit with a hidden Z-down bias, diagnose, apply, compare.
"${rins[@]}" measure docs/examples/diagnosis-truth.toml --out "$tmp/unit.csv"
"${rins[@]}" diagnose --model docs/examples/diagnosis-model.toml --data "$tmp/unit.csv" --json \
  --apply gyro.position_bias --out "$tmp/fitted.toml" --report "$tmp/diag" | python3 -c '
import json, sys
d = json.load(sys.stdin)
top = d["ranking"][0]
for k in ("effect", "channel", "delta_bic", "p_value", "cv_rmse_gain_pct", "coefficient", "ci95", "confusable_with"):
    assert k in top, k
assert top["effect"] == "gyro.position_bias" and top["passes_gate"], top
assert d["flagged_cells"] and "gyro_x" in d["residual_rms_before"] and "gyro_x" in d["residual_rms_after"]'
test -s "$tmp/diag/residual_vs_temperature.svg" && test -s "$tmp/diag/navigation_error.svg"
"${rins[@]}" compare --model "$tmp/fitted.toml" --data "$tmp/unit.csv" --json | python3 -c '
import json, sys
d = json.load(sys.stdin)
assert not [c for c in d["flagged_cells"] if c["channel"].startswith("gyro")], d["flagged_cells"]
assert d["navigation"] and d["correlations"]'
if "${rins[@]}" diagnose --model docs/examples/diagnosis-model.toml --data "$tmp/unit.csv" --apply gyro.spin 2> "$tmp/err"; then
  echo "an unknown effect must fail"; exit 1
fi
grep -q "gyro.position_bias" "$tmp/err"
echo "1 passed, 0 failed: command-line smoke checks"

echo "== HTML reports in headless Chromium (tests/browser) =="
bash tests/browser/run.sh "$bin/rins"

echo "== no process the suite started is left running =="
# A process still carrying the mark was started by the suite and never stopped, such as the
# `rerun --port P --save FILE` viewer test_rerun.py once left. Zombies have no environment left to
# match; the greps below start after the list of PIDs is taken, so they are not in it.
left=()
for environ in /proc/[0-9]*/environ; do
  pid=${environ#/proc/}
  pid=${pid%/environ}
  [ "$pid" = "$$" ] && continue
  if grep -qzxF "RINS_SUITE_RUN=$RINS_SUITE_RUN" "$environ" 2> /dev/null; then
    left+=("$pid")
  fi
done
if [ "${#left[@]}" -gt 0 ]; then
  echo "processes started by the suite are still running:"
  ps -o pid=,args= -p "$(IFS=,; echo "${left[*]}")" || true
  # They are this run's own: stop them, so that a failed run leaves the machine clean too.
  kill -KILL "${left[@]}" 2> /dev/null || true
  exit 1
fi
echo "1 passed, 0 failed: no process left running"
