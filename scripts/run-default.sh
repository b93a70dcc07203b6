#!/usr/bin/env bash
# The default job that scripts/setup.sh runs after building: describe the shared sequences and
# evaluate their ground truth against itself (a smoke test of the readers and the evaluator).
# It grows with the project: synthetic hospital sequence, then the SLAM run, then the object map.
set -euo pipefail
cd "$(dirname "$0")/.."
WARDMAP=build/apps/wardmap
DATA=${WARDMAP_DATA:-../shared/data}
OUT=${WARDMAP_OUT:-out/default}
mkdir -p "$OUT"
if [ -d "$DATA/kitti-odometry-03" ]; then
  $WARDMAP info "$DATA/kitti-odometry-03"
  $WARDMAP eval --gt "$DATA/kitti-odometry-03" --est "$DATA/kitti-odometry-03/poses/03.txt" \
    --json "$OUT/kitti03-eval.json" --plot "$OUT/kitti03-eval.png"
fi
if [ -d "$DATA/7scenes-redkitchen" ]; then
  $WARDMAP info "$DATA/7scenes-redkitchen"
fi
echo "run-default.sh: outputs in $OUT"
