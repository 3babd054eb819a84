#!/usr/bin/env bash
# The rtl cycle model gives the same card before and after a change to the
# simulator (docs/performance.md, "Simulation speed of the cycle model").
#
#   tools/rtl_identity.sh record DIR [BUILD]   record every frame below into DIR
#   tools/rtl_identity.sh compare DIR1 DIR2    diff two records (exit 1 on a difference)
#
# Frames: scenes/default.toml, endoscopy.toml, colin27.toml (when mricron-data
# is installed) in the VIZARD II in-order configuration (the scenes' own [rtl])
# and in the row-hit goal configuration (rtl::bench::row_hit_goal_config()),
# default and endoscopy on the Alveo U250 board (the DDR4 card with brick
# caches, rtl_model/pipeline/burst_card.hpp: 8 pipelines, FR-FCFS), and
# heidelberg.toml (VIRIM's cycle model, its own engine). Per frame:
#   NAME.stats  voxcast_rtl_speed: every RtlStats counter (cycles, stalls, row
#               outcomes, activates per bank, FIFO occupancies) and the image hash
#   NAME.json   the report of `voxcast render --engine rtl`, host timing removed
#   NAME.png    the image written by that render
# Lines that describe the simulation rather than the card ("simulation: N of M
# cycles evaluated") and the host timing ("cpu ...") are not compared.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)

goal=(--set rtl.issue=row-hit --set rtl.issue_bypass_limit=4096 --set rtl.ray_slots=32
      --set rtl.traversal=tiles --set rtl.tile=4 --set rtl.layout=bricked-swizzled
      --set rtl.scheduler=lookahead --set rtl.auto_precharge=true)
u250=(--set rtl.board=alveo_u250 --set rtl.pipelines=8 --set rtl.scheduler=fr-fcfs
      --set rtl.queue_depth=32 --set rtl.reorder_window=32)

frames() {
  local scenes=(default endoscopy)
  [ -e /usr/share/mricron/templates/ch2.nii.gz ] && scenes+=(colin27)
  for s in "${scenes[@]}"; do echo "$s in-order"; echo "$s row-hit"; done
  echo "default u250"
  echo "endoscopy u250"
  echo "heidelberg virim"
}

record() {
  local dir=$1 build=${2:-$here/build/dev}
  mkdir -p "$dir"
  while read -r scene config; do
    local name="$scene-$config" sets=()
    [ "$config" = row-hit ] && sets=("${goal[@]}")
    [ "$config" = u250 ] && sets=("${u250[@]}")
    echo "rtl_identity: $name" >&2
    if [ "$config" != virim ]; then
      "$build/tools/rtl_speed/voxcast_rtl_speed" "$here/scenes/$scene.toml" "${sets[@]}" \
        | grep -v '^simulation: \|^cpu ' > "$dir/$name.stats"
    fi
    "$build/cosim/voxcast" render "$here/scenes/$scene.toml" --engine rtl "${sets[@]}" \
      -o "$dir/$name.png" --report "$dir/$name.json.raw" > /dev/null
    # The report names the scene by its absolute path: a record made in
    # another checkout (a worktree) must compare equal, so the path is cut.
    python3 - "$dir/$name.json.raw" "$dir/$name.json" "$here/" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
j.pop("timing", None)
j.pop("written", None)
text = json.dumps(j, indent=1, sort_keys=True).replace(sys.argv[3], "")
open(sys.argv[2], "w").write(text)
PY
    rm "$dir/$name.json.raw"
  done < <(frames)
}

compare() {
  local a=$1 b=$2 status=0
  for f in "$a"/*.stats "$a"/*.json "$a"/*.png; do
    local g="$b/$(basename "$f")"
    if [ ! -e "$g" ]; then echo "missing: $g"; status=1; continue; fi
    if ! cmp -s "$f" "$g"; then
      echo "DIFFERS: $(basename "$f")"
      # (diff's status would end the script under pipefail: every file is compared.)
      case "$f" in *.png) ;; *) diff "$f" "$g" | head -20 || true ;; esac
      status=1
    fi
  done
  [ $status -eq 0 ] && echo "rtl_identity: $(ls "$a" | wc -l) files identical"
  return $status
}

case "${1:-}" in
  record) shift; record "$@" ;;
  compare) shift; compare "$@" ;;
  *) echo "usage: $0 record DIR [BUILD] | compare DIR1 DIR2" >&2; exit 64 ;;
esac
