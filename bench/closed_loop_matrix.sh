#!/usr/bin/env bash
# Issue 5 closed-loop target matrix: runs `rownav run` on every field x robot set-up of the
# config/fields/closed_loop_*.yaml family (default stack: hough_skew detector, model_filter
# tracker, stanley controller, OS1-16 unless stated) and prints one markdown table row per set-up
# (medians over the seeds). Usage, from the repository root:
#   bench/closed_loop_matrix.sh [BUILD_DIR=build] [OUT_DIR=/tmp/closed_loop_matrix] [SEEDS="1"]
set -euo pipefail
BIN=${1:-build}/rownav
OUT=${2:-/tmp/closed_loop_matrix}
SEEDS=${3:-1}
mkdir -p "$OUT"

# name | field | robot | mission | detect config | sensor
SETUPS=(
  "narrow|closed_loop_narrow|skid_steer|serve_all|vineyard|os1_16"
  "wide|closed_loop_wide|skid_steer|serve_all|vineyard|os1_16"
  "wide car-like|closed_loop_wide|car_like|serve_all|vineyard|os1_16"
  "wide car-like skip-row|closed_loop_wide|car_like|skip_row_5|vineyard|os1_16"
  "canopy low|closed_loop_canopy_low|skid_steer|serve_all|vineyard|os1_16"
  "canopy high|closed_loop_canopy_high|skid_steer|serve_all|vineyard|os1_16"
  "weeds none|closed_loop_weeds_none|skid_steer|serve_all|vineyard|os1_16"
  "weeds many|closed_loop_weeds_many|skid_steer|serve_all|vineyard|os1_16"
  "curved|closed_loop_curved|skid_steer|serve_all|vineyard|os1_16"
  "slope|closed_loop_slope|skid_steer|serve_all|vineyard|os1_16"
  "narrow differential|closed_loop_narrow|differential|serve_all|vineyard|os1_16"
  "orchard|closed_loop_orchard|skid_steer|serve_all|orchard|os1_16"
  "maize|closed_loop_maize|row_crop_small|serve_all|row_crop|os1_16"
)
if [[ -n "${ONLY:-}" ]]; then  # ONLY=REGEX: the set-ups whose line matches
  mapfile -t SETUPS < <(printf '%s\n' "${SETUPS[@]}" | grep -E "$ONLY")
fi

echo "| set-up | field | robot | success | served/planned | correct entries | crushed | mean / max displacement [m] | path ratio | row-end error [m] | wall [s] |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for s in "${SETUPS[@]}"; do
  IFS='|' read -r name field robot mission det sensor <<<"$s"
  dirs=()
  for seed in $SEEDS; do
    d="$OUT/${field}_${robot}_${mission}_s${seed}"
    "$BIN" run --field "config/fields/$field.yaml" --robot "config/robots/$robot.yaml" \
      --mission "config/missions/$mission.yaml" --sensor "config/sensors/$sensor.yaml" \
      --detect-config "config/detect/$det.yaml" --seed "$seed" --out "$d" --overwrite --quiet \
      >/dev/null || true
    dirs+=("$d/summary.json")
  done
  python3 - "$name" "$field" "$robot" "${dirs[@]}" <<'PY'
import json, statistics, sys
name, field, robot, files = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
runs = [json.load(open(f)) for f in files]
def med(key, fmt="{:.3f}"):
    v = [r[key] for r in runs if r.get(key) is not None]
    return fmt.format(statistics.median(v)) if v else "n/a"
ok = sum(r["success"] for r in runs)
why = ",".join(sorted({r["stop_reason"] for r in runs if not r["success"]}))
succ = f"{ok}/{len(runs)}" + (f" ({why})" if why else "")
served = "/".join(med(k, "{:.0f}") for k in ("corridors_served", "corridors_planned"))
entries = "/".join(med(k, "{:.0f}") for k in ("correct_entries", "turns"))
print(f"| {name} | {field} | {robot} | {succ} | {served} | {entries} | "
      f"{med('plants_crushed', '{:.0f}')} | {med('in_row_mean_displacement')} / "
      f"{med('in_row_max_displacement')} | {med('path_length_ratio_mean')} | "
      f"{med('row_end_error_mean')} | {med('wall_time', '{:.1f}')} |")
PY
done
