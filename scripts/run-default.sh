#!/usr/bin/env bash
# The default job that scripts/setup.sh runs after building: render the synthetic hospital corridor
# aisle_straight, run the RGB-D SLAM on it and map its objects on the SLAM's keyframes, evaluate
# both, draw the object map (under Xvfb); then describe the shared real sequences when
# ../shared/data (or $WARDMAP_DATA) is there. Outputs in out/default/.
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
$WARDMAP run "$SEQ" --poses slam --objects --detector annotations "${EMB[@]}" --out "$OUT/run"
if command -v xvfb-run >/dev/null; then
  xvfb-run -a -s "-screen 0 1280x1024x24" $WARDMAP render-map "$OUT/run" --out "$OUT/run/map.png"
else
  echo "run-default.sh: xvfb-run not found: no map.png (install xvfb)"
fi
if [ -d "$DATA/kitti-odometry-03" ]; then
  $WARDMAP info "$DATA/kitti-odometry-03"
fi
if [ -d "$DATA/7scenes-redkitchen" ]; then
  $WARDMAP info "$DATA/7scenes-redkitchen"
fi
echo "run-default.sh: outputs in $OUT (run folder: $OUT/run: trajectory, map points, object map map.glb, map.png)"
