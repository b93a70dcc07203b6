#!/usr/bin/env bash
# The front-process's synthetic figures (issue 4's targets: 100 % tracked, ATE under 2 cm
# monocular, under 1 cm RGB-D) over scenarios x variants x layouts, as one table per mode.
# Renders the sequences it lacks with `wardmap synth` (kept in the cache folder for next time),
# runs `wardmap run` on each and reads the ATE and tracking rate it prints.
set -euo pipefail

usage() {
  cat <<'EOF'
Usage: scripts/synthetic-figures.sh [OPTIONS]

Runs the SLAM front-process on the synthetic sequences and prints, per mode, a table of ATE in cm
(rows: scenario and variant, columns: layouts), in bold each run at or above its target (RGB-D
1 cm, monocular 2 cm) or under 100 % tracked, then the sum and the count of misses.

Options:
  --mode rgbd|mono|both    modes to run (default: both)
  --layouts "1 2 3"        layouts, the `wardmap synth --seed` values (default: "1 2 3 4 5 6")
  --scenarios "a b"        scenarios (default: the issue's "ward aisle_straight aisle_left_turn")
  --variants "slow quick"  variants (default: both)
  --threaded               ordinary runs, the mapper on its own thread (default: --deterministic,
                           which repeats to the last digit)
  --frames N               render and run only the first N frames (a quick check, not the figures)
  --cache DIR              where rendered sequences are kept (default: out/synthetic)
  --out DIR                where the run folders go (default: out/synthetic-runs)
  --wardmap PATH           the wardmap binary (default: build/apps/wardmap)
  -h, --help               this text

A full table (6 layouts, 3 scenarios, 2 variants, both modes) renders 36 sequences once (about
1 GB) and takes 72 runs: about 10 minutes on a 2-core machine once rendered.
EOF
}

cd "$(dirname "$0")/.."
modes="rgbd mono"
layouts="1 2 3 4 5 6"
scenarios="ward aisle_straight aisle_left_turn"
variants="slow quick"
run_kind="--deterministic"
frames=0
cache=out/synthetic
out=out/synthetic-runs
wardmap=build/apps/wardmap
while [[ $# -gt 0 ]]; do
  case "$1" in
    --mode)
      case "${2:-}" in rgbd | mono) modes="$2" ;; both) modes="rgbd mono" ;; *)
        echo "synthetic-figures.sh: --mode takes rgbd, mono or both, not '${2:-}'" >&2
        exit 2
        ;;
      esac
      shift 2
      ;;
    --layouts) layouts="${2:?--layouts needs a list}"; shift 2 ;;
    --scenarios) scenarios="${2:?--scenarios needs a list}"; shift 2 ;;
    --variants) variants="${2:?--variants needs a list}"; shift 2 ;;
    --threaded) run_kind=""; shift ;;
    --frames) frames="${2:?--frames needs a number}"; shift 2 ;;
    --cache) cache="${2:?--cache needs a folder}"; shift 2 ;;
    --out) out="${2:?--out needs a folder}"; shift 2 ;;
    --wardmap) wardmap="${2:?--wardmap needs a path}"; shift 2 ;;
    -h | --help) usage; exit 0 ;;
    *) echo "synthetic-figures.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
for n in $layouts $frames; do
  [[ "$n" =~ ^[0-9]+$ ]] || { echo "synthetic-figures.sh: '$n' is not a whole number (--layouts, --frames)" >&2; exit 2; }
done
[[ -x "$wardmap" ]] || { echo "synthetic-figures.sh: no wardmap binary at '$wardmap' (build it: scripts/setup.sh --no-run)" >&2; exit 2; }

suffix=""
[[ "$frames" -gt 0 ]] && suffix="_f$frames"
mkdir -p "$cache" "$out"
render() {  # scenario variant layout -> the sequence folder, rendered if missing
  local seq="$cache/$1_$2_$3$suffix"
  if [[ ! -f "$seq/groundtruth.txt" ]]; then
    echo "rendering $seq" >&2
    "$wardmap" -q synth --scenario "$1" --variant "$2" --seed "$3" --frames "$frames" --out "$seq" >&2
  fi
  echo "$seq"
}

failed=0
for mode in $modes; do
  if [[ "$mode" == rgbd ]]; then target=1; align="SE(3)"; else target=2; align="Sim(3)"; fi
  header="| sequence |"
  rule="|---|"
  for l in $layouts; do header+=" layout $l |"; rule+="---|"; done
  table="$header"$'\n'"$rule"
  sum=0 runs=0 misses=0 lost=0
  for s in $scenarios; do
    for v in $variants; do
      row="| ${s} ${v} |"
      for l in $layouts; do
        seq=$(render "$s" "$v" "$l")
        dir="$out/$mode/$(basename "$seq")"
        echo "running $mode on $(basename "$seq")" >&2
        # shellcheck disable=SC2086  # run_kind is empty or one flag
        if ! log=$("$wardmap" -q run "$seq" --mode "$mode" $run_kind --out "$dir" 2>&1); then
          echo "$log" >&2
          row+=" failed |"
          failed=$((failed + 1))
          continue
        fi
        ate_m=$(sed -n 's/^ATE .* RMSE \([0-9.]*\) m.*/\1/p' <<<"$log")
        rate=$(sed -n 's/^tracking rate \([0-9.]*\) %.*/\1/p' <<<"$log")
        if [[ -z "$ate_m" || -z "$rate" ]]; then
          echo "$log" >&2
          row+=" no ATE |"
          failed=$((failed + 1))
          continue
        fi
        cell=$(awk -v m="$ate_m" 'BEGIN { printf "%.2f", 100 * m }')
        # miss: at or above the target or under 100 % tracked; then the cell gives the rate too
        read -r miss partial < <(awk -v c="$cell" -v t="$target" -v r="$rate" \
          'BEGIN { print ((c >= t || r < 100) ? 1 : 0), (r < 100 ? 1 : 0) }')
        [[ "$partial" == 1 ]] && { cell+=" (${rate} %)"; lost=$((lost + 1)); }
        [[ "$miss" == 1 ]] && { cell="**${cell}**"; misses=$((misses + 1)); }
        row+=" $cell |"
        sum=$(awk -v a="$sum" -v m="$ate_m" 'BEGIN { printf "%.2f", a + 100 * m }')
        runs=$((runs + 1))
      done
      table+=$'\n'"$row"
    done
  done
  kind=${run_kind:-threaded}
  echo
  echo "$mode, ATE ($align) in cm, ${kind#--}, target under $target cm and 100 % tracked (bold: missed):"
  echo
  echo "$table"
  echo
  echo "$mode: $runs runs, $sum cm summed, $misses at or above $target cm or under 100 % tracked ($lost under 100 %)"
done
if [[ "$failed" -gt 0 ]]; then
  echo "synthetic-figures.sh: $failed runs failed (their output is above)" >&2
  exit 1
fi
