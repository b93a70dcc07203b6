#!/usr/bin/env bash
# The default job that scripts/setup.sh runs after building: render the synthetic hospital corridor
# aisle_straight, map its objects on ground-truth poses, evaluate them; then describe the shared
# real sequences when ../shared/data (or $WARDMAP_DATA) is there. Outputs in out/default/.
set -euo pipefail
cd "$(dirname "$0")/.."
WARDMAP=build/apps/wardmap
DATA=${WARDMAP_DATA:-../shared/data}
OUT=${WARDMAP_OUT:-out/default}
mkdir -p "$OUT"
SEQ="$OUT/aisle_straight_slow_1"
[ -f "$SEQ/objects.json" ] || $WARDMAP synth --scenario aisle_straight --variant slow --seed 1 --out "$SEQ"
$WARDMAP info "$SEQ"
EMB=()
[ -f "${WARDMAP_MODELS:-../shared/models}/osnet-x0_25/osnet_x0_25_msmt17.onnx" ] ||
  { echo "run-default.sh: OSNet weights not found: running without appearance embeddings"; EMB=(--no-embedding); }
$WARDMAP run "$SEQ" --poses gt --detector annotations "${EMB[@]}" --out "$OUT/run"
if [ -d "$DATA/kitti-odometry-03" ]; then
  $WARDMAP info "$DATA/kitti-odometry-03"
fi
if [ -d "$DATA/7scenes-redkitchen" ]; then
  $WARDMAP info "$DATA/7scenes-redkitchen"
fi
echo "run-default.sh: outputs in $OUT (run folder: $OUT/run, object map: $OUT/run/map.glb)"
