#!/usr/bin/env python3
"""voxcast against its peer, VTK's vtkFixedPointVolumeRayCastMapper, on one scene.

    python3 bench/run_peer_bench.py                       # scenes/colin27.toml, 5 rounds x 3 frames
    python3 bench/run_peer_bench.py --rounds 7 --repeat 5 --voxcast build/release/cosim/voxcast

Each round runs, in turn, VTK (bench/vtk_peer.py under xvfb-run) and
`voxcast bench SCENE --engines ENGINES --repeat N` with render.space_leaping
off and on, each process timing N frames after its warm-up; the order is
reversed every other round, so slow phases of a shared machine fall on every
side alike. The table gives each engine's ms per frame (median over the
rounds of each round's median) and VTK_ms / engine_ms, the median of the
rounds' paired ratios (>= 1.0: voxcast is faster), and the ratio of the
fastest frames, the better estimate on a busy machine. Before the timed rounds
both renderers write the scene's image (OUT/vtk.png, OUT/voxcast.png) and the
two are compared (PSNR, mean difference).

Needs Python 3 (stdlib only) here, and a python3 that can `import vtk` plus
xvfb-run (or a display) for the peer: without them it prints one line saying
what is missing and how to install it, and exits with status 2. It never
prints a ratio it did not measure. Other failures: one line, status 1.
"""

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
INSTALL = "apt-get install -y python3-vtk9 xvfb xauth"
MISSING_STATUS = 2


def fail(msg, status=1):
    print(f"run_peer_bench: {msg}", file=sys.stderr)
    sys.exit(status)


def missing(msg):
    fail(f"{msg}: install it with `{INSTALL}`", MISSING_STATUS)


# ------------------------------------------------------------ what is there

def find_vtk_python(explicit, module):
    """The first Python that can import VTK: --vtk-python, $VOXCAST_VTK_PYTHON,
    this interpreter, Debian's /usr/bin/python3, python3 on PATH (a pyenv or
    venv Python does not see Debian's python3-vtk9)."""
    if explicit:
        candidates = [explicit]
    elif os.environ.get("VOXCAST_VTK_PYTHON"):
        candidates = [os.environ["VOXCAST_VTK_PYTHON"]]
    else:
        candidates = [sys.executable, "/usr/bin/python3", shutil.which("python3")]
    seen = set()
    for py in candidates:
        if not py or py in seen:
            continue
        seen.add(py)
        try:
            r = subprocess.run([py, "-c", f"import {module}"], stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL, timeout=120)
        except (OSError, subprocess.TimeoutExpired):
            continue
        if r.returncode == 0:
            return py
    return None


def find_voxcast(explicit):
    if explicit:
        if not (os.path.isfile(explicit) and os.access(explicit, os.X_OK)):
            fail(f"--voxcast {explicit}: not an executable file")
        return explicit
    if os.environ.get("VOXCAST"):
        return os.environ["VOXCAST"]
    for preset in ("release", "ci", "dev"):
        path = os.path.join(ROOT, "build", preset, "cosim", "voxcast")
        if os.access(path, os.X_OK):
            return path
    path = shutil.which("voxcast")
    if path:
        return path
    fail("no voxcast binary: build it (cmake --preset release && cmake --build --preset release "
         "--target voxcast) or give --voxcast PATH")


# ------------------------------------------------------------ running

def run(cmd, what):
    try:
        r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    except OSError as e:
        fail(f"{what}: cannot run {cmd[0]}: {e.strerror}")
    if r.returncode != 0:
        last = (r.stderr.strip().splitlines() or ["(no message)"])[-1]
        fail(f"{what} failed (status {r.returncode}): {last}")
    return r.stdout


def parse_voxcast_bench(path, engines):
    """`voxcast bench --json FILE` (cosim/explore/bench.cpp, bench_json): per
    engine its samples per frame and the median and fastest wall time."""
    try:
        with open(path) as f:
            report = json.load(f)
    except (OSError, ValueError) as e:
        fail(f"voxcast bench --json {path}: cannot read it ({e})")
    out = {}
    for e in report.get("engines", []):
        if e.get("engine") in engines:
            out[e["engine"]] = {"ms": e["median_seconds"] * 1e3, "min_ms": e["min_seconds"] * 1e3,
                                "samples": e["samples"]}
    lost = [e for e in engines if e not in out]
    if lost:
        fail(f"voxcast bench --json {path} has no result for {', '.join(lost)}")
    return out


def shown(path):
    """A path as the user would type it: relative below the working folder."""
    rel = os.path.relpath(path)
    return path if rel.startswith("..") else rel


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scene", default=os.path.join(ROOT, "scenes", "colin27.toml"))
    ap.add_argument("--voxcast", help="the voxcast binary (default: $VOXCAST, build/{release,ci,dev})")
    ap.add_argument("--engines", default="ref,hls", help="voxcast engines (default ref,hls)")
    ap.add_argument("--leaping", default="off,on",
                    help="voxcast's render.space_leaping settings to time (default off,on)")
    ap.add_argument("--rounds", type=int, default=5, help="paired rounds (default 5)")
    ap.add_argument("--repeat", type=int, default=3, help="timed frames per process (default 3)")
    ap.add_argument("--threads", type=int, default=2, help="threads on both sides (default 2)")
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "peer"),
                    help="folder for vtk.png, voxcast.png and peer.json (default out/peer)")
    ap.add_argument("--no-images", action="store_true", help="skip the two images and their comparison")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="override a scene key on both sides (e.g. render.width=64)")
    ap.add_argument("--vtk-python", help="a python3 that can import vtk (default: searched)")
    ap.add_argument("--simulate-missing", choices=["vtk", "xvfb"],
                    help="tests: behave as if VTK or Xvfb were not installed")
    args = ap.parse_args()
    if args.rounds < 1 or args.repeat < 1 or args.threads < 1:
        fail("--rounds, --repeat and --threads must be at least 1")
    engines = [e for e in args.engines.split(",") if e]
    if not engines or any(e not in ("ref", "bittrue", "hls", "rtl") for e in engines):
        fail(f"--engines {args.engines}: give some of ref, bittrue, hls, rtl")
    leaping = [x for x in args.leaping.split(",") if x]
    if not leaping or any(x not in ("off", "on") for x in leaping):
        fail(f"--leaping {args.leaping}: give off, on or off,on")

    # What the peer needs, checked before any work: one line if missing.
    module = "vtk_simulated_missing" if args.simulate_missing == "vtk" else "vtk"
    vtk_python = find_vtk_python(args.vtk_python, module)
    if not vtk_python:
        missing("python3 cannot import vtk (VTK's Python bindings, for the peer)")
    xvfb = None if args.simulate_missing == "xvfb" else shutil.which("xvfb-run")
    has_display = bool(os.environ.get("DISPLAY")) and args.simulate_missing != "xvfb"
    if not xvfb and not has_display:
        missing("no xvfb-run and no display (VTK needs an X server to render)")
    voxcast = find_voxcast(args.voxcast)
    if not os.path.isfile(args.scene):
        fail(f"{args.scene}: no such scene file")

    sets = []
    for s in args.set:
        sets += ["--set", s]
    peer = ([xvfb, "-a"] if xvfb else []) + [vtk_python, os.path.join(HERE, "vtk_peer.py"),
                                             args.scene, "--threads", str(args.threads)] + sets
    os.makedirs(args.out, exist_ok=True)

    # The two pictures first (untimed): same head, same view?
    compare = None
    if not args.no_images:
        vox_png = os.path.join(args.out, "voxcast.png")
        vtk_png = os.path.join(args.out, "vtk.png")
        run([voxcast, "render", args.scene, "-o", vox_png, "--set",
             f"render.threads={args.threads}"] + sets, "voxcast render")
        r = json.loads(run(peer + ["--frames", "1", "--warmup", "1", "--png", vtk_png,
                                   "--compare", vox_png], "the VTK peer"))
        compare = r["compare"]

    def time_vtk():
        r = json.loads(run(peer + ["--frames", str(args.repeat), "--warmup", "2"], "the VTK peer"))
        return r

    def time_voxcast(leap):
        report = os.path.join(args.out, f"voxcast-bench-leaping-{leap}.json")
        run([voxcast, "bench", args.scene, "--engines", ",".join(engines), "--repeat",
             str(args.repeat), "--json", report, "--set", f"render.threads={args.threads}",
             "--set", f"render.space_leaping={'true' if leap == 'on' else 'false'}"] + sets,
            "voxcast bench")
        return parse_voxcast_bench(report, engines)

    steps = [("vtk", None)] + [("voxcast", leap) for leap in leaping]
    vtk_rounds, vtk_mins = [], []
    vox_rounds = {leap: [] for leap in leaping}
    vtk_info = None
    for rnd in range(args.rounds):
        for kind, leap in (steps if rnd % 2 == 0 else list(reversed(steps))):
            if kind == "vtk":
                vtk_info = time_vtk()
                vtk_rounds.append(vtk_info["ms_per_frame_median"])
                vtk_mins.append(vtk_info["ms_per_frame_min"])
            else:
                vox_rounds[leap].append(time_voxcast(leap))
        if sys.stderr.isatty():
            print(f"round {rnd + 1}/{args.rounds} done", file=sys.stderr, flush=True)

    rows = []
    vtk_ms = statistics.median(vtk_rounds)
    rows.append({"engine": "vtk", "leaping": "on", "ms": vtk_ms, "min_ms": min(vtk_mins),
                 "ratio": None, "min_ratio": None, "samples": None})
    for e in engines:
        for leap in leaping:
            per_round = [r[e]["ms"] for r in vox_rounds[leap]]
            ratios = [v / x for v, x in zip(vtk_rounds, per_round)]
            min_ms = min(r[e]["min_ms"] for r in vox_rounds[leap])
            rows.append({"engine": e, "leaping": leap, "ms": statistics.median(per_round),
                         "min_ms": min_ms, "ratio": statistics.median(ratios), "ratios": ratios,
                         "min_ratio": min(vtk_mins) / min_ms,
                         "samples": vox_rounds[leap][0][e]["samples"]})

    w, h = vtk_info["image"]
    print(f"peer     {shown(args.scene)}: {w}x{h}, {args.threads} threads, "
          f"{args.rounds} paired round{'s' if args.rounds > 1 else ''} x {args.repeat} "
          f"frame{'s' if args.repeat > 1 else ''}; VTK {vtk_info['vtk_version']} "
          f"vtkFixedPointVolumeRayCastMapper ({vtk_info['threads']} threads)")
    print(f"{'engine':<24}{'leaping':>8}{'samples':>11}{'ms/frame':>11}{'min ms':>10}"
          f"{'VTK/engine':>12}{'min/min':>9}")
    for r in rows:
        name = "vtk (fixed point)" if r["engine"] == "vtk" else f"voxcast {r['engine']}"
        samples = "-" if r["samples"] is None else str(r["samples"])
        ratio = "-" if r["ratio"] is None else f"{r['ratio']:.3f}"
        min_ratio = "-" if r["min_ratio"] is None else f"{r['min_ratio']:.3f}"
        print(f"{name:<24}{r['leaping']:>8}{samples:>11}{r['ms']:>11.1f}{r['min_ms']:>10.1f}"
              f"{ratio:>12}{min_ratio:>9}")
    print("VTK/engine: median of the rounds' VTK_ms / engine_ms (min/min: of the fastest frames); "
          ">= 1.0 means voxcast is faster")
    if compare:
        psnr = "identical" if compare["psnr_db"] is None else f"PSNR {compare['psnr_db']:.2f} dB"
        print(f"images   {shown(os.path.join(args.out, 'vtk.png'))} vs "
              f"{shown(compare['against'])}: {psnr}, mean |diff| "
              f"{compare['mean_abs_diff']:.2f}/255, volume covers different pixels: "
              f"{100 * compare['coverage_differs']:.2f}%")

    with open(os.path.join(args.out, "peer.json"), "w") as f:
        json.dump({"scene": args.scene, "set": args.set, "threads": args.threads,
                   "rounds": args.rounds, "repeat": args.repeat, "voxcast": voxcast,
                   "vtk_python": vtk_python, "vtk": vtk_info, "vtk_rounds_ms": vtk_rounds,
                   "rows": rows, "compare": compare}, f, indent=1)


if __name__ == "__main__":
    main()
