#!/usr/bin/env bash
# Issue 13 fault matrix: `rownav run --faults` on config/fields/closed_loop_narrow.yaml, skid-steer,
# the two-corridor mission (config/missions/two_corridors.yaml), default stack (hough_skew,
# model_filter, stanley, OS1-16; GNSS receiver for gnss_jump), for every config/faults/*.yaml and
# every seed, then a 2 s LiDAR dropout started every STEP seconds of the mission (every state).
# Prints the BENCHMARK.md tables. Usage, from the repository root:
#   bench/faults_matrix.sh [BUILD_DIR=build] [OUT_DIR=/tmp/faults_matrix] [SEEDS="1 2 3"]
# Environment: JOBS (parallel runs, default 2), STEP (dropout sweep step [s], default 3; 0: none).
set -euo pipefail
BIN=${1:-build}/rownav
OUT=${2:-/tmp/faults_matrix}
SEEDS=${3:-1 2 3}
JOBS=${JOBS:-2}
STEP=${STEP:-3}
mkdir -p "$OUT/sweep"

run() {  # fault_file seed out_dir [sensor]
  local sensor=${4:-}
  "$BIN" run --field config/fields/closed_loop_narrow.yaml --robot config/robots/skid_steer.yaml \
    --mission config/missions/two_corridors.yaml --faults "$1" --seed "$2" --out "$3" \
    ${sensor:+--sensor "$sensor"} --overwrite --quiet >"$3.log" 2>&1 || true
}
export -f run
export BIN

jobs=()
for f in config/faults/*.yaml; do
  name=$(basename "$f" .yaml)
  sensor=""
  [[ $name == gnss_* ]] && sensor=config/sensors/os1_16_gnss.yaml
  for seed in $SEEDS; do jobs+=("$f $seed $OUT/${name}_s$seed${sensor:+ $sensor}"); done
done
if [[ $STEP != 0 ]]; then
  for start in $(seq 6 "$STEP" 105); do
    f="$OUT/sweep/dropout_$start.yaml"
    printf 'faults:\n  lidar_dropout: {enabled: true, start: %s, duration: 2}\n' "$start" >"$f"
    for seed in $SEEDS; do jobs+=("$f $seed $OUT/sweep/dropout_${start}_s$seed"); done
  done
fi
printf '%s\n' "${jobs[@]}" | xargs -P "$JOBS" -L 1 bash -c 'run "$@"' _

python3 - "$OUT" <<'PY'
import glob, json, os, sys
out = sys.argv[1]
def load(d):
    f = os.path.join(d, "faults.json")
    return json.load(open(f)) if os.path.exists(f) else None
def s(v): return "-" if v is None else f"{v:.2f}"
print("| fault | seed | success (stop) | state at start | zero cmd after [s] | halted after [s] | "
      "moving again after its end [s] | crushed | collision | left field | person clearance [m] |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for d in sorted(glob.glob(os.path.join(out, "*_s*"))):
    if d.endswith(".log") or not os.path.isdir(d): continue
    name, seed = os.path.basename(d).rsplit("_s", 1)
    r = load(d)
    if r is None:
        print(f"| {name} | {seed} | CRASH / no output (see {d}.log) | | | | | | | | |"); continue
    f = r["faults"][0]
    ok = "yes" if r["success"] else "no"
    print(f"| {name} | {seed} | {ok} ({r['stop_reason']}) | {f['state_at_start']} | "
          f"{s(f['zero_after'])} | {s(f['halted_after'])} | {s(f['resumed_after'])} | "
          f"{r['plants_crushed']} | {'YES' if r['collision'] else 'no'} | "
          f"{'YES' if r['left_field'] else 'no'} | {s(r['min_person_clearance'])} |")
sweep = sorted(glob.glob(os.path.join(out, "sweep", "dropout_*_s*")))
sweep = [d for d in sweep if os.path.isdir(d)]
if sweep:
    by = {}
    for d in sweep:
        r = load(d)
        st = r["faults"][0]["state_at_start"] if r else "CRASH"
        by.setdefault(st, []).append((d, r))
    print()
    print("| state at dropout start | runs | success | zero cmd after [s]: max | moving again "
          "after its end [s]: max | never moved again | crushed | collision | left field |")
    print("|---|---|---|---|---|---|---|---|---|")
    for st, runs in by.items():
        rs = [r for _, r in runs if r]
        z = [r["faults"][0]["zero_after"] for r in rs if r["faults"][0]["zero_after"] is not None]
        m = [r["faults"][0]["resumed_after"] for r in rs
             if r["faults"][0]["resumed_after"] is not None]
        never = [f"{os.path.basename(d)} ({r['stop_reason']})" for d, r in runs
                 if r and r["faults"][0]["resumed_after"] is None]
        print(f"| {st} | {len(runs)} | {sum(r['success'] for r in rs)}/{len(runs)} | "
              f"{s(max(z) if z else None)} ({len(z)} zeroed) | {s(max(m) if m else None)} | "
              f"{', '.join(never) if never else 'none'} | {sum(r['plants_crushed'] for r in rs)} | "
              f"{sum(r['collision'] for r in rs)} | {sum(r['left_field'] for r in rs)} |")
PY
