#!/usr/bin/env bash
# Synthesizes the operators of the resource model (docs/resources.md) with
# Yosys `synth_xilinx` (7-series) and prints one line per design:
#   kind width_a width_b LUT FF DSP
# Multipliers are signed a x b -> a+b bits, registered output; adders and
# comparators are b = a bits, registered output. `-nodsp` rows map
# multipliers to LUTs (as on a part without DSP slices).
# Usage: compare.sh [OUT.tsv]   (Debian's yosys; about 10-60 s)
set -euo pipefail
out=${1:-/dev/stdout}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
run() {  # kind a b flags verilog
  local kind=$1 a=$2 b=$3 flags=$4 v=$5
  printf '%s\n' "$v" > "$tmp/d.v"
  yosys -q -p "read_verilog $tmp/d.v; synth_xilinx -family xc7 -top d $flags; tee -o $tmp/stat.txt stat" >/dev/null
  local lut ff dsp
  lut=$(awk '/LUT[1-6] /{s+=$2} END{print s+0}' "$tmp/stat.txt")
  ff=$(awk '/ FD[A-Z]* /{s+=$2} END{print s+0}' "$tmp/stat.txt")
  dsp=$(awk '/DSP48E1/{s+=$2} END{print s+0}' "$tmp/stat.txt")
  printf '%s%s\t%s\t%s\t%s\t%s\t%s\n' "$kind" "${flags:+_nodsp}" "$a" "$b" "$lut" "$ff" "$dsp"
}
{
for ab in "8 8" "12 12" "18 18" "25 18" "24 24" "32 32" "9 7" "17 9"; do
  set -- $ab
  v="module d(input clk, input signed [$1-1:0] a, input signed [$2-1:0] b, output reg signed [$1+$2-1:0] y); always @(posedge clk) y <= a * b; endmodule"
  run mul "$1" "$2" "" "$v"
done
for ab in "8 8" "12 12" "16 16"; do
  set -- $ab
  v="module d(input clk, input signed [$1-1:0] a, input signed [$2-1:0] b, output reg signed [$1+$2-1:0] y); always @(posedge clk) y <= a * b; endmodule"
  run mul "$1" "$2" "-nodsp" "$v"
done
for w in 8 16 24 32 48; do
  v="module d(input clk, input [$w-1:0] a, input [$w-1:0] b, output reg [$w:0] y); always @(posedge clk) y <= a + b; endmodule"
  run add "$w" "$w" "" "$v"
  v="module d(input clk, input [$w-1:0] a, input [$w-1:0] b, output reg y); always @(posedge clk) y <= a < b; endmodule"
  run cmp "$w" "$w" "" "$v"
done
for w in 8 16 32; do
  v="module d(input clk, input [1:0] s, input [$w-1:0] a, b, c, e, output reg [$w-1:0] y); always @(posedge clk) case (s) 0: y <= a; 1: y <= b; 2: y <= c; default: y <= e; endcase endmodule"
  run mux4 "$w" 4 "" "$v"
done
} > "$out"
