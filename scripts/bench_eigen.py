#!/usr/bin/env python3
"""Side by side: romdyn's sparse eigensolver and scipy's ARPACK + SuperLU on the same pencil
(issue 13 acceptance; optional, not part of CI).

For each chain size N the hanging N-link chain of the tests (17 N + 12 equations) is
linearized at rest and its pencil lambda E + K in the form of eq. 29 -- the one
linear::krylov::sparse_modes factors and iterates on -- is written as Matrix Market by
`examples/sparse_pencil.rs`. Then, each in its own process under /usr/bin/time -v (peak
memory = the process's maximum resident set):

- romdyn, right only: `sparse_pencil solve DIR COUNT --right-only` reads E.mtx, K.mtx and
  runs sparse_modes(Lowest(COUNT)) with right vectors only (true right residuals <= 1e-10;
  no adjoint run, so the count is not certified): the work scipy does;
- romdyn, right + left: the same with right and left vectors (true residuals of both
  <= 1e-10, the count checked by the right and the adjoint Krylov runs: certified);
- scipy, right: SuperLU of K + sigma E (sigma = 0) and scipy.sparse.linalg.eigs on the
  operator T = (K + sigma E)^-1 E, which='LM', tol=1e-12 (romdyn's Krylov tolerance),
  k = 2 COUNT (the chain's modes are complex pairs: COUNT modes are 2 COUNT eigenvalues).
  This is eigs(sigma=...) mode 3 with bmat='I'; eigs' own sigma=..., M=E route would use E
  as an inner product (bmat='G'), which needs a symmetric semi-definite E, and E is
  neither. lambda = sigma - 1/theta. Right vectors only;
- scipy, right + left: the same, then eigs again on the transposed pencil's operator
  (K + sigma E)^-T E^T (SuperLU's transposed solves of the same factorization), whose
  eigenvectors are the left vectors: the work romdyn's right + left column does (romdyn
  also checks each pair's residuals and that the two runs agree; scipy does not).

The COUNT lowest modes (Im lambda >= 0, by |lambda|) of all must agree to 1e-9 relative
(scipy's left run's eigenvalues too). The ratios are romdyn's time over scipy's on the same
work: right only over scipy right, right + left over scipy right + left.
Timings: the solve only (reading the files excluded), fastest of --repeat runs; the
header line gives the load average, worth reading first: other work on the machine slows
scipy's threaded BLAS more than romdyn.

    python3 scripts/bench_eigen.py                 # N = 100, 1000, 6000
    python3 scripts/bench_eigen.py --sizes 100 --repeat 5
"""

import argparse
import datetime
import os
import re
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
EXE = ROOT / "target" / "release" / "examples" / "sparse_pencil"


def timed(cmd):
    """Runs cmd under /usr/bin/time -v: (stdout, peak resident memory in MB)."""
    p = subprocess.run(["/usr/bin/time", "-v", *cmd], capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"{' '.join(map(str, cmd))} failed:\n{p.stdout}\n{p.stderr}")
    rss = re.search(r"Maximum resident set size \(kbytes\): (\d+)", p.stderr)
    return p.stdout, (int(rss.group(1)) / 1024 if rss else float("nan"))


def parse(out):
    """(seconds, [complex eigenvalues], [left run's eigenvalues]) from a worker's output."""
    lines = out.strip().splitlines()
    t = float(re.match(r"time ([0-9.eE+-]+) s", lines[0]).group(1))
    rest = lines[1:]
    cut = rest.index("left") if "left" in rest else len(rest)
    value = lambda ls: [complex(float(a), float(b)) for a, b in (l.split() for l in ls)]
    return t, value(rest[:cut]), value(rest[cut + 1:])


def scipy_worker(directory, count, repeat, left):
    import numpy as np
    from scipy.io import mmread
    from scipy.sparse.linalg import LinearOperator, eigs, splu

    e = mmread(os.path.join(directory, "E.mtx")).tocsr()
    k = mmread(os.path.join(directory, "K.mtx")).tocsr()
    et = e.transpose().tocsr()
    n = e.shape[0]
    sigma = 0.0
    best, best_cpu, lam, lam_left = float("inf"), float("inf"), None, None
    for _ in range(repeat):
        start, start_cpu = time.perf_counter(), time.process_time()
        lu = splu((k + sigma * e).tocsc())
        op = LinearOperator((n, n), matvec=lambda x: lu.solve(e @ x), dtype=float)
        # Right vectors, as the docstring says.
        theta, _vectors = eigs(op, k=2 * count, which="LM", tol=1e-12, return_eigenvectors=True)
        lam = sigma - 1.0 / theta
        if left:
            # Left vectors: the transposed pencil's operator, the same factorization.
            op_t = LinearOperator((n, n), matvec=lambda x: lu.solve(et @ x, trans="T"), dtype=float)
            theta_t, _left_vectors = eigs(op_t, k=2 * count, which="LM", tol=1e-12, return_eigenvectors=True)
            lam_left = sigma - 1.0 / theta_t
        best = min(best, time.perf_counter() - start)
        best_cpu = min(best_cpu, time.process_time() - start_cpu)
    # CPU: the process's, all BLAS threads included.
    print(f"time {best:.6f} s, cpu {best_cpu:.6f} s")
    for x in lam[lam.imag >= 0]:
        print(f"{x.real:.17e} {x.imag:.17e}")
    if left:
        print("left")
        for x in lam_left[lam_left.imag >= 0]:
            print(f"{x.real:.17e} {x.imag:.17e}")


def lowest(lam, count):
    return sorted((x for x in lam if x.imag >= 0), key=abs)[:count]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", type=int, nargs="+", default=[100, 1000, 6000], help="chain links N (17 N + 12 equations)")
    ap.add_argument("--count", type=int, default=20, help="lowest modes asked (a complex pair is one)")
    ap.add_argument("--repeat", type=int, default=3, help="runs per solver, fastest kept")
    ap.add_argument("--workdir", default="/tmp/romdyn_bench_eigen", help="where the .mtx files go")
    ap.add_argument("--no-build", action="store_true", help="use the example binary as built")
    ap.add_argument("--scipy-worker", nargs=4, metavar=("DIR", "COUNT", "REPEAT", "LEFT"), help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.scipy_worker:
        scipy_worker(a.scipy_worker[0], int(a.scipy_worker[1]), int(a.scipy_worker[2]), a.scipy_worker[3] == "left")
        return
    if not a.no_build:
        subprocess.run(["cargo", "build", "--release", "--example", "sparse_pencil"], cwd=ROOT, check=True)
    print(f"# {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, load average {os.getloadavg()[0]:.2f}, {os.cpu_count()} cores")
    print(f"# {a.count} lowest modes, fastest of {a.repeat}; memory: peak resident set of the process")
    print(f"{'N':>6} {'equations':>9} | {'right [s]':>10} {'MB':>6} | {'r+l [s]':>10} {'MB':>6} | {'scipy [s]':>10} {'MB':>6} | {'sp r+l [s]':>10} {'MB':>6} | {'right/scipy':>11} {'r+l/sp r+l':>10} | max rel. diff")
    failed = False
    for n in a.sizes:
        d = Path(a.workdir) / f"chain{n}"
        if not (d / "K.mtx").exists():
            subprocess.run([EXE, "export", str(n), d], check=True, capture_output=True)
        out, mem_o = timed([EXE, "solve", d, str(a.count), str(a.repeat), "--right-only"])
        t_o, lam_o, _ = parse(out)
        out, mem_r = timed([EXE, "solve", d, str(a.count), str(a.repeat)])
        t_r, lam_r, _ = parse(out)
        if "certified true" not in out.splitlines()[0]:
            print(f"romdyn's result for N = {n} is not certified: {out.splitlines()[0]}")
            failed = True
        out, mem_s = timed([sys.executable, __file__, "--scipy-worker", str(d), str(a.count), str(a.repeat), "right"])
        t_s, lam_s, _ = parse(out)
        out, mem_sl = timed([sys.executable, __file__, "--scipy-worker", str(d), str(a.count), str(a.repeat), "left"])
        t_sl, lam_sl, lam_sl_left = parse(out)
        o, r, s, sl, sll = (lowest(x, a.count) for x in (lam_o, lam_r, lam_s, lam_sl, lam_sl_left))
        if min(len(o), len(r), len(s), len(sl), len(sll)) < a.count:
            print(f"N = {n}: romdyn found {len(o)} (right only), {len(r)} (right + left), scipy {len(s)}, {len(sl)} and {len(sll)} (right + left) of {a.count} modes")
            failed = True
            continue
        diff = max(abs(x - y) / abs(y) for x, y in [*zip(r, s), *zip(o, s), *zip(sl, s), *zip(sll, s)])
        failed |= diff > 1e-9
        print(f"{n:>6} {17 * n + 12:>9} | {t_o:>10.4f} {mem_o:>6.0f} | {t_r:>10.4f} {mem_r:>6.0f} | {t_s:>10.4f} {mem_s:>6.0f} | {t_sl:>10.4f} {mem_sl:>6.0f} | {t_o / t_s:>11.2f} {t_r / t_sl:>10.2f} | {diff:.1e}")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
