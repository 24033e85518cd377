#!/usr/bin/env python3
"""The sparse whole process beside scipy's solve alone (issue 36, point 3; optional, not
part of CI).

The model: tests/mbdyn/use_arpack.rs' string of N point masses (1 kg, `dynamic
displacement` nodes 1 m apart) between two clamped walls on rods of EA = 900 N, rest length
0.9 m (tension 100 N): 12 N + 24 equations, 96,024 at the default N = 8000. Its modes have
a closed form, `w_j = 2 sqrt(k/m) sin(j pi / (2 (N + 1)))` with k = 100 N/m twice (lateral,
each a double eigenvalue) and 1000 N/m once (axial).

Alternately, RUNS times each, each its own process under /usr/bin/time -v (peak memory = the
process's maximum resident set):

- romdyn, the whole process: `romdyn run FILE` with `eigenanalysis: 0., use arpack, COUNT,
  NCV, 0.;`: reading, the reference, the sparse linearization, the shift-invert
  Krylov-Schur route with right and left vectors and its certified count, and the output
  files (.out, .mov, the eigenanalysis' .m and .json);
- scipy, the solve alone on the same pencil: `scripts/bench_eigen.py`'s worker (SuperLU of
  K, `eigs` on K^-1 E, which='LM', tol=1e-12, k = 2 COUNT; right vectors only, and right +
  left with a second `eigs` on the transposed operator), its time the factorization and
  `eigs` alone in CPU seconds of the process (its BLAS threads included; reading the Matrix
  Market files excluded), its memory the whole process's.
  The pencil `lambda E + K` (eq. 29) is written once by `examples/sparse_pencil.rs
  export-mbdyn` from the same file, linearized at the initial state as `romdyn run` does.

Checked before any ratio is printed: romdyn's COUNT lowest modes (the .json's alpha, Im > 0,
by |lambda|) and scipy's equal the closed form to 1e-9 relative, and romdyn's count is
certified. Ratios: romdyn's whole process (CPU seconds, user + system) over scipy's solve
(CPU seconds). Medians of RUNS; the header gives the load average.

With `--baseline BIN` another romdyn binary (a copy of an earlier build) runs too, in the
same alternation: its whole process is reported beside this one's, and its modes (the
.json's eigenvalues, every mode with its conjugate) must equal this build's to 1e-12
relative, its count certified as well.

    python3 scripts/bench_sparse_run.py                     # N = 8000, 20 modes, 3 runs
    python3 scripts/bench_sparse_run.py --masses 600 --runs 1
    python3 scripts/bench_sparse_run.py --baseline /tmp/romdyn-main --no-build
"""

import argparse
import datetime
import json
import math
import os
import re
import statistics
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
ROMDYN = ROOT / "target" / "release" / "romdyn"
EXPORT = ROOT / "target" / "release" / "examples" / "sparse_pencil"
WORKER = ROOT / "scripts" / "bench_eigen.py"


def string_of_masses(n, count, ncv):
    """tests/mbdyn/use_arpack.rs' file with `use arpack, COUNT, NCV, 0.` at t = 0."""
    t = f"""begin: data; problem: initial value; end: data;
begin: initial value; initial time: 0.; final time: 0.; time step: 1.e-3; tolerance: 1.e-10;
    eigenanalysis: 0., use arpack, {count}, {ncv}, 0.;
end: initial value;
begin: control data; skip initial joint assembly; structural nodes: {n + 2}; rigid bodies: {n}; joints: {n + 3}; end: control data;
begin: nodes;
    structural: 0, static, null, eye, null, null;
    structural: {n + 1}, static, {n + 1}., 0., 0., eye, null, null;
"""
    t += "".join(f"    structural: {i}, dynamic displacement, {i}., 0., 0., null;\n" for i in range(1, n + 1))
    t += f"end: nodes;\nbegin: elements;\n    joint: 0, clamp, 0, node, node;\n    joint: {n + 2}, clamp, {n + 1}, node, node;\n"
    for i in range(1, n + 2):
        if i <= n:
            t += f"    body: {i}, {i}, 1.;\n"
        t += f"    joint: {i}, rod, {i - 1}, {i}, 0.9, linear elastic, 900.;\n"
    return t + "end: elements;\n"


def closed_form(n, count):
    mode = lambda k, j: 2.0 * math.sqrt(k) * math.sin(j * math.pi / (2.0 * (n + 1)))
    return sorted(w for j in range(1, n + 1) for w in (mode(100.0, j), mode(100.0, j), mode(1000.0, j)))[:count]


def timed(cmd, cwd=None):
    """(stdout, wall s, CPU s, peak resident MB) of one process under /usr/bin/time -v."""
    p = subprocess.run(["/usr/bin/time", "-v", *map(str, cmd)], capture_output=True, text=True, cwd=cwd)
    if p.returncode != 0:
        sys.exit(f"{' '.join(map(str, cmd))} failed:\n{p.stdout[-2000:]}\n{p.stderr[-2000:]}")
    field = lambda name: re.search(name + r": ([0-9.:]+)", p.stderr).group(1)
    wall = sum(float(x) * 60 ** i for i, x in enumerate(reversed(field(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\)").split(":"))))
    cpu = float(field(r"User time \(seconds\)")) + float(field(r"System time \(seconds\)"))
    return p.stdout, wall, cpu, int(field(r"Maximum resident set size \(kbytes\)")) / 1024


def romdyn_modes(path):
    """|lambda| of the Im > 0 eigenvalues romdyn's run wrote (.json: alpha rows, dCoef)."""
    doc = json.loads(Path(path).read_text())
    c = doc["dCoef"]
    out = []
    for ar, ai, b in doc["alpha"]:
        d = c * ((ar + b) ** 2 + ai * ai)
        lam = complex((ar * ar + ai * ai - b * b) / d, 2.0 * ai * b / d)
        if lam.imag > 0:
            out.append(abs(lam))
    return sorted(out)


def json_eigenvalues(path):
    """Every eigenvalue of the run's .json (re, im), in the file's order."""
    return [complex(e["re"], e["im"]) for e in json.loads(Path(path).read_text())["eigenvalues"]]


def worst(found, want):
    return max(abs(x - y) / y for x, y in zip(found, want)) if len(found) >= len(want) else math.inf


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--masses", type=int, default=8000, help="point masses N (12 N + 24 equations)")
    ap.add_argument("--count", type=int, default=20, help="lowest modes asked (use arpack's NEV)")
    ap.add_argument("--ncv", type=int, default=50, help="use arpack's NCV (romdyn reads it, ignores it)")
    ap.add_argument("--runs", type=int, default=3, help="alternating runs of each, medians reported")
    ap.add_argument("--workdir", default="/tmp/romdyn_bench_sparse_run", help="where the files go")
    ap.add_argument("--no-build", action="store_true", help="use the binaries as built")
    ap.add_argument("--baseline", help="another romdyn binary run beside this one (its modes must equal this one's to 1e-12)")
    a = ap.parse_args()
    if not a.no_build:
        subprocess.run(["cargo", "build", "--release", "--bin", "romdyn", "--example", "sparse_pencil"], cwd=ROOT, check=True)
    work = Path(a.workdir)
    work.mkdir(parents=True, exist_ok=True)
    model = work / f"string{a.masses}.mbd"
    model.write_text(string_of_masses(a.masses, a.count, a.ncv))
    pencil = work / f"pencil{a.masses}"
    subprocess.run([EXPORT, "export-mbdyn", model, pencil], check=True, capture_output=True)
    want = closed_form(a.masses, a.count)
    rows = {"romdyn": [], "baseline": [], "scipy right": [], "scipy right + left": []}
    romdyns = [("romdyn", ROMDYN)] + ([("baseline", Path(a.baseline).resolve())] if a.baseline else [])
    failed = False
    same = 0.0
    for _ in range(a.runs):
        for name, binary in romdyns:
            out, wall, cpu, mb = timed([binary, "run", model, "-o", work / name], cwd=work)
            if "certified" not in out or "NOT certified" in out:
                print(f"{name}'s count is not certified:\n{out[-1500:]}")
                failed = True
            off = worst(romdyn_modes(work / f"{name}_0.json"), want)
            rows[name].append((wall, cpu, mb, off))
        if a.baseline:
            mine, theirs = json_eigenvalues(work / "romdyn_0.json"), json_eigenvalues(work / "baseline_0.json")
            same = max(same, math.inf if len(mine) != len(theirs) else max(abs(x - y) / abs(y) for x, y in zip(mine, theirs)))
        for name, side in (("scipy right", "right"), ("scipy right + left", "left")):
            out, wall, cpu, mb = timed([sys.executable, WORKER, "--scipy-worker", pencil, a.count, 1, side])
            lines = out.strip().splitlines()
            solve = float(re.search(r"cpu ([0-9.eE+-]+) s", lines[0]).group(1))
            cut = lines.index("left") if "left" in lines else len(lines)
            lam = sorted(abs(complex(float(x), float(y))) for x, y in (l.split() for l in lines[1:cut]) if float(y) > 0)
            rows[name].append((solve, cpu, mb, worst(lam, want)))
    print(f"# {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, load average {os.getloadavg()[0]:.2f}, {os.cpu_count()} cores")
    print(f"# string of {a.masses} masses, {12 * a.masses + 24} equations, {a.count} lowest modes; medians of {a.runs} alternating runs")
    print("# first column: romdyn's wall seconds, scipy's solve CPU seconds; proc. CPU: the whole process's")
    print(f"{'':<26} {'wall/CPU [s]':>12} {'proc. CPU':>9} {'peak MB':>8} {'vs closed form':>15}")
    med = {k: [statistics.median(x[i] for x in v) for i in range(3)] + [max(x[3] for x in v)] for k, v in rows.items() if v}
    for k, (t, cpu, mb, off) in med.items():
        label = {"romdyn": "romdyn run", "baseline": "baseline romdyn run"}.get(k, f"{k} (solve)")
        print(f"{label:<26} {t:>12.3f} {cpu:>9.3f} {mb:>8.0f} {off:>15.1e}")
        failed |= not off <= 1e-9
    r = med["romdyn"]
    if a.baseline:
        b = med["baseline"]
        print(f"romdyn / baseline whole process: CPU {r[1] / b[1]:.2f}, peak memory {r[2] / b[2]:.2f}; largest relative difference of their eigenvalues {same:.1e}")
        failed |= not same <= 1e-12
    for k in ("scipy right", "scipy right + left"):
        print(f"romdyn whole process CPU / {k} solve: {r[1] / med[k][0]:.2f}; peak memory {r[2] / med[k][2]:.2f}")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
