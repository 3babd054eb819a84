#!/bin/sh
# Flips the lowest bit of the last expected pixel channel in a copy of the
# csim data and runs the testbench on it: it must report exactly that pixel
# and fail (exit 1, "1 differ"). Usage: corrupt_one_pixel.sh TESTBENCH DATA_DIR SCRATCH_DIR
set -eu
tb=$1 data=$2 scratch=$3
rm -rf "$scratch" && mkdir -p "$scratch"
cp "$data/csim_frame.bin" "$scratch/"
f="$scratch/csim_frame.bin"
off=$(( $(stat -c %s "$f") - 8 ))           # the last 64-bit word: the last pixel's alpha
byte=$(od -An -tu1 -j "$off" -N1 "$f" | tr -d ' ')
printf "$(printf '\\%03o' $(( byte ^ 1 )))" | dd of="$f" bs=1 seek="$off" conv=notrunc 2>/dev/null
rc=0
out=$("$tb" "$scratch") || rc=$?
echo "$out"
if [ "$rc" -ne 1 ] || ! echo "$out" | grep -q ' pixels, 1 differ;'; then
  echo "corrupt_one_pixel: the testbench exited $rc on one corrupted expected pixel (want 1, and 1 differ)"
  exit 1
fi
echo "corrupt_one_pixel: the corrupted pixel was caught"
