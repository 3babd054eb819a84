#!/bin/sh
# Flips the lowest bit of the last expected pixel channel in a copy of the
# csim data and runs the testbench on it: it must report exactly that pixel
# and fail (exit 1). Usage: corrupt_one_pixel.sh TESTBENCH DATA_DIR SCRATCH_DIR
set -eu
tb=$1 data=$2 scratch=$3
rm -rf "$scratch" && mkdir -p "$scratch"
cp "$data/csim_frame.bin" "$scratch/"
f="$scratch/csim_frame.bin"
off=$(( $(stat -c %s "$f") - 8 ))           # the last 64-bit word: the last pixel's alpha
byte=$(od -An -tu1 -j "$off" -N1 "$f" | tr -d ' ')
printf "$(printf '\\%03o' $(( byte ^ 1 )))" | dd of="$f" bs=1 seek="$off" conv=notrunc 2>/dev/null
rc=0
"$tb" "$scratch" || rc=$?
if [ "$rc" -ne 1 ]; then
  echo "corrupt_one_pixel: the testbench exited $rc on a corrupted expected pixel (want 1)"
  exit 1
fi
echo "corrupt_one_pixel: the corrupted pixel was caught"
