#!/usr/bin/env python3
"""Tests of bench/run_peer_bench.py (ctest, label `peer`; bench/CMakeLists.txt).

    test_peer_bench.py missing                 # no VTK / no Xvfb: one line, non-zero status
    test_peer_bench.py table VOXCAST VTK_PYTHON  # a tiny real run prints a well-formed table

`missing` needs neither VTK nor Xvfb nor voxcast; `table` needs all three and
takes a few seconds (64x64 pixels, one round of one frame).
"""

import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
DRIVER = os.path.join(HERE, "run_peer_bench.py")
SCENE = os.path.join(os.path.dirname(HERE), "scenes", "colin27.toml")


def run(args):
    return subprocess.run([sys.executable, DRIVER] + args, stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, text=True)


def check(cond, msg, r=None):
    if not cond:
        detail = f"\n--- stdout\n{r.stdout}--- stderr\n{r.stderr}" if r is not None else ""
        print(f"FAIL: {msg}{detail}")
        sys.exit(1)


def one_line_missing(args, what):
    r = run(args)
    check(r.returncode == 2, f"{what}: status {r.returncode}, expected 2", r)
    check(r.stdout == "", f"{what}: printed on stdout", r)
    lines = r.stderr.splitlines()
    check(len(lines) == 1, f"{what}: {len(lines)} lines on stderr, expected 1", r)
    check("apt-get install" in lines[0] and "python3-vtk9" in lines[0] and "xvfb" in lines[0],
          f"{what}: the line does not say how to install", r)
    check("ratio" not in lines[0].lower() and "VTK/engine" not in lines[0],
          f"{what}: printed a ratio", r)
    return lines[0]


def test_missing():
    # A Python that cannot import vtk, given explicitly (a real failed import) ...
    line = one_line_missing(["--vtk-python", "/bin/false", "--voxcast", "/nonexistent"],
                            "--vtk-python /bin/false")
    check("cannot import vtk" in line, f"names VTK: {line}")
    # ... VTK hidden (the search runs, for a module no Python has) ...
    line = one_line_missing(["--simulate-missing", "vtk"], "--simulate-missing vtk")
    check("cannot import vtk" in line, f"names VTK: {line}")
    # ... and no Xvfb and no display (checked only once VTK is there).
    r = run(["--simulate-missing", "xvfb"])
    if r.returncode == 2 and "cannot import vtk" in r.stderr:
        print("(no VTK here: the Xvfb case is reached only with VTK installed)")
    else:
        line = one_line_missing(["--simulate-missing", "xvfb"], "--simulate-missing xvfb")
        check("xvfb-run" in line, f"names Xvfb: {line}")
    print("ok: missing VTK / Xvfb is one line and status 2")


ROW = re.compile(r"^(vtk \(fixed point\)|voxcast (ref|hls))\s+(on|off)\s+(-|\d+)\s+"
                 r"(\d+\.\d)\s+(\d+\.\d)\s+(-|\d+\.\d{3})\s+(-|\d+\.\d{3})$")


def test_table(voxcast, vtk_python):
    with tempfile.TemporaryDirectory() as out:
        r = run(["--voxcast", voxcast, "--vtk-python", vtk_python, "--rounds", "1", "--repeat", "1",
                 "--set", "render.width=64", "--set", "render.height=64", "--out", out])
        check(r.returncode == 0, f"status {r.returncode}", r)
        lines = r.stdout.splitlines()
        check(len(lines) == 9, f"{len(lines)} lines, expected 9", r)
        check(lines[0].startswith("peer ") and "64x64" in lines[0] and "VTK 9" in lines[0],
              "the first line names the scene, size and VTK", r)
        check(lines[1].split() == ["engine", "leaping", "samples", "ms/frame", "min", "ms",
                                   "VTK/engine", "min/min"], "the header", r)
        rows = [ROW.match(l) for l in lines[2:7]]
        check(all(rows), "five rows engine/leaping/samples/ms/min/ratio/min ratio", r)
        names = [(m.group(1), m.group(3)) for m in rows]
        check(names == [("vtk (fixed point)", "on"), ("voxcast ref", "off"), ("voxcast ref", "on"),
                        ("voxcast hls", "off"), ("voxcast hls", "on")], f"rows {names}", r)
        check(rows[0].group(7) == "-" and rows[0].group(8) == "-" and
              all(m.group(7) != "-" and m.group(8) != "-" for m in rows[1:]),
              "ratios on every voxcast row, none on VTK's", r)
        check(all(float(m.group(5)) > 0 for m in rows), "every ms/frame > 0", r)
        for m in rows[1:]:  # the ratio is VTK's ms over the row's (one round: exactly)
            want = float(rows[0].group(5)) / float(m.group(5))
            check(abs(float(m.group(7)) - want) <= 0.02 * want + 0.002,
                  f"ratio {m.group(7)} is not VTK/engine ({want:.3f})", r)
        check(int(rows[2].group(4)) < int(rows[1].group(4)), "leaping skips samples", r)
        check(lines[7].startswith("VTK/engine: "), "the ratio's legend", r)
        check(lines[8].startswith("images ") and "PSNR" in lines[8], "the image comparison", r)
        for name in ("vtk.png", "voxcast.png", "peer.json"):
            check(os.path.getsize(os.path.join(out, name)) > 0, f"{name} written", r)
    print("ok: a well-formed table")


def main():
    if len(sys.argv) == 2 and sys.argv[1] == "missing":
        test_missing()
    elif len(sys.argv) == 4 and sys.argv[1] == "table":
        test_table(sys.argv[2], sys.argv[3])
    else:
        print(__doc__)
        sys.exit(64)


if __name__ == "__main__":
    main()
