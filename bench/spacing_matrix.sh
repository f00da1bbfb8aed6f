#!/usr/bin/env bash
# Issue 10 spacing bench: the row spacing each tracker reports (RowTracking::row_spacing, what the
# headland leg uses) against the field's true spacing, on the solid-hedge vineyards of
# bench/fields/solid_hedge_*.yaml. For each field: `rownav sim` drives corridor 2 (OS1-16, every
# LiDAR frame), then `rownav track` replays it with hough_skew and every tracker; errors over the
# frames in the lane with a spacing. Usage, from the repository root:
#   bench/spacing_matrix.sh [BUILD_DIR=build] [OUT_DIR=/tmp/spacing_matrix]
set -euo pipefail
BIN=${1:-build}/rownav
OUT=${2:-/tmp/spacing_matrix}
DETECTOR=${DETECTOR:-hough_skew}
TRACKERS=${TRACKERS:-"model_matching line_ekf model_filter none"}
mkdir -p "$OUT"
cat >"$OUT/path.yaml" <<'YAML'
block: 0
corridors: [2]
speed: 1.0
turn_speed: 0.5
lead_in: 2.0
lead_out: 1.5
turn: u_turn
waypoints: []
YAML
echo "| field | true spacing [m] | tracker | frames | median error [m] | max error [m] | median estimate [m] |"
echo "|---|---|---|---|---|---|---|"
for f in bench/fields/solid_hedge_*.yaml; do
  name=$(basename "$f" .yaml)
  truth=$(awk '/row_spacing:/ {print $2}' "$f")
  rec="$OUT/$name"
  [[ -d "$rec" ]] || "$BIN" sim --field "$f" --sensors config/sensors/os1_16.yaml \
    --path "$OUT/path.yaml" --out "$rec" --quiet >/dev/null
  for t in $TRACKERS; do
    csv="$OUT/${name}_${DETECTOR}_$t.csv"
    "$BIN" track --in "$rec" --detector "$DETECTOR" --detect-config "${DETECT_CONFIG:-config/detect/vineyard.yaml}" \
      --tracker "$t" --out "$csv" --overwrite >/dev/null
    python3 - "$name" "$truth" "$t" "$csv" <<'PY'
import csv, statistics, sys
name, truth, tracker, path = sys.argv[1], float(sys.argv[2]), sys.argv[3], sys.argv[4]
est = [float(r["spacing"]) for r in csv.DictReader(open(path))
       if r["spacing"] and r["true_lateral"] and float(r["spacing"]) > 0]
err = [abs(e - truth) for e in est]
if not err:
    print(f"| {name} | {truth:.2f} | {tracker} | 0 | n/a | n/a | n/a |")
else:
    print(f"| {name} | {truth:.2f} | {tracker} | {len(err)} | {statistics.median(err):.3f} | "
          f"{max(err):.3f} | {statistics.median(est):.3f} |")
PY
  done
done
