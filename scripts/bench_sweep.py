#!/usr/bin/env python3
"""Sweep benchmark (issue 15; not run by CI): 64 design points of the README beam (axial
compression N from 0 to 4000 N, static reference, one bending mode kept with the third
residualized) on a Dask LocalCluster of 2 worker processes against 1, and the per-point
cost of the Python call against the CLI.

    python scripts/bench_sweep.py [--points 64] [--cli target/debug/romdyn]

Needs romdyn (pip install ./python) and dask[distributed]. Wall-clock times: on a shared
machine report the ratios, not the seconds.
"""

import argparse
import pathlib
import subprocess
import time

import romdyn

ROOT = pathlib.Path(__file__).resolve().parents[1]
BEAM = ROOT / "examples" / "simply_supported_beam.mbd"
OPTIONS = dict(reference="static", inputs=["5:Fy"], outputs=["5:y"], count=1, residualize=[7], lowest=2)
CLI_ARGS = ["--static", "--input", "5:Fy", "--output", "5:y", "--count", "1", "--residualize-modes", "7"]


def timed(f):
    t = time.perf_counter()
    r = f()
    return time.perf_counter() - t, r


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--points", type=int, default=64)
    p.add_argument("--cli", default=str(ROOT / "target" / "debug" / "romdyn"))
    a = p.parse_args()
    from distributed import Client, LocalCluster

    spec = {"N": f"0:4000:{a.points}"}
    times = {}
    for workers in (1, 2):
        with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, Client(cluster) as client:
            ex = client.get_executor()
            romdyn.sweep(BEAM, set={"N": "0:0:1"}, executor=ex, **OPTIONS)  # workers import romdyn
            times[workers], r = timed(lambda: romdyn.sweep(BEAM, set=spec, executor=ex, **OPTIONS))
            assert r.ok.all(), r.failures
        print(f"dask LocalCluster, {workers} worker(s): {a.points} points in {times[workers]:.2f} s ({times[workers] / a.points * 1e3:.1f} ms/point)")
    print(f"speed-up 2 workers vs 1: {times[1] / times[2]:.2f}x")
    t_local, _ = timed(lambda: romdyn.sweep(BEAM, set=spec, threads=1, **OPTIONS))
    print(f"in-process, 1 thread: {t_local:.2f} s ({t_local / a.points * 1e3:.1f} ms/point)")
    # One point: the Python call against one `romdyn rom` process (which also starts a
    # process, compares the ROM on 400 frequencies and writes a JSON file).
    text = BEAM.read_text()
    reps = 10
    t_py, _ = timed(lambda: [romdyn._romdyn.run_point(text, str(BEAM), ["N"], [1000.0], OPTIONS) for _ in range(reps)])
    t_cli, _ = timed(lambda: [subprocess.run([a.cli, "rom", str(BEAM), *CLI_ARGS, "-o", "/tmp/romdyn_bench_rom.json"], capture_output=True) for _ in range(reps)])
    print(f"one point: Python run_point {t_py / reps * 1e3:.1f} ms; one `romdyn rom` process {t_cli / reps * 1e3:.1f} ms (it also compares the ROM with the full model on 400 frequencies)")
    t_sw, _ = timed(lambda: subprocess.run([a.cli, "sweep", str(BEAM), "--set", f"N=0:4000:{a.points}", *CLI_ARGS, "--jobs", "1", "--table", "/tmp/romdyn_bench_sweep.csv"], check=True, capture_output=True))
    print(f"CLI romdyn sweep --jobs 1: {t_sw:.2f} s ({t_sw / a.points * 1e3:.1f} ms/point); Python in-process minus CLI per point: {(t_local - t_sw) / a.points * 1e3:+.1f} ms")


if __name__ == "__main__":
    main()
