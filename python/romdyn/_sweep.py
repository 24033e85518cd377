"""Design-point sweeps: an MBDyn file's ``set:`` variables over a grid or a list of points.

Each design point's work unit is small to ship: the file's text, the parameter names and
values and a dict of options; the worker runs romdyn's ``run_point`` on it (reference
solution, linearization, modes, ROM with the same ports) and returns plain arrays.
"""

import numpy as np

from . import _romdyn


def _point(text, name, names, values, options):
    """One design point (what an executor runs): a dict of arrays, or {"error": message}."""
    return _romdyn.run_point(text, name, list(names), [float(v) for v in values], dict(options))


def _parameters(set):
    """{"L": "0.5:4:8" | [v1, v2, ...] | (a, b, n)} as [(name, values)]."""
    out = []
    for name, spec in set.items():
        if isinstance(spec, str):
            out.append(_romdyn.parse_set(f"{name}={spec}"))
        else:
            values = [float(v) for v in np.atleast_1d(np.asarray(spec, dtype=float))]
            if not values:
                raise ValueError(f"set {name}: no values")
            out.append((name, values))
    return out


def sweep(path, set=None, points=None, names=None, executor=None, threads=None, **options):
    """Runs romdyn's ROM workflow at every design point of an MBDyn file.

    path: the MBDyn input file. set: {name: "A:B:N" | [values]} (their full grid, the first
    name varying slowest) or points: a list of value lists with names: their variable names.
    options: those of ``Model.study`` and ``Study.reduce`` (reference, load_steps, inputs,
    outputs, ports, remove_springs, imposed, route, dcoef, count, band, modes, residualize,
    by, below_band, damping, form), lowest (number of lowest modes tabulated, default 4) and
    continuation (reference="static" only: each equilibrium starts from the previous
    point's; local runs only).

    executor: None runs the points in this process on ``threads`` threads with the GIL
    released; any ``concurrent.futures.Executor``-like object with ``submit`` (a Dask
    ``Client.get_executor()``, a ProcessPoolExecutor, Ray's) runs one task per point, the
    results gathered in order. A failed point is kept with its values and error
    (``SweepResult.failures``); the others are unaffected.
    """
    with open(path, encoding="utf-8") as f:
        text = f.read()
    name = str(path)
    if set is not None:
        if points is not None or names is not None:
            raise ValueError("give set= or points= with names=, not both")
        params = _parameters(set)
        names = [n for n, _ in params]
        points = _romdyn.grid(params)
    elif points is None or names is None:
        raise ValueError("give set={name: values} or points=[[...], ...] with names=[...]")
    else:
        names = list(names)
        points = [[float(v) for v in p] for p in points]
        if any(len(p) != len(names) for p in points):
            raise ValueError(f"every point needs {len(names)} values ({', '.join(names)})")
    _romdyn.check_parameters(text, name, names)
    if executor is None:
        results = _romdyn.run_points(text, name, names, points, options, threads)
    else:
        if options.get("continuation"):
            raise ValueError("continuation runs the points one after the other: use executor=None")
        futures = [executor.submit(_point, text, name, names, p, options) for p in points]
        results = [f.result() for f in futures]
    return SweepResult(name, names, points, results, options.get("lowest", 4))


def _stack(results, key, shape):
    out = np.full(shape + (len(results),), np.nan)
    for k, r in enumerate(results):
        if "error" not in r and r[key] is not None:
            out[..., k] = r[key]
    return out


class SweepResult:
    """The outcome of every design point, stacked as MATLAB's ss arrays.

    names: parameter names; parameters: (K, P) values; ok: (K,) bool; errors: K messages
    ("" where ok); A, B, C, D, E: (n, n, K), (n, m, K), … (``A[:, :, k]`` is point k's, NaN
    where it failed); full_static_gain, rom_static_gain: (outputs, inputs, K); modes: (K,
    lowest) complex lowest dynamic eigenvalues [rad/s] (a pair by its member with Im > 0, a
    ±a pair by +a), freq_hz = |Im λ|/2π, damping = −Re λ/|λ|; inputs, outputs, states:
    names with units.
    """

    def __init__(self, file, names, points, results, lowest):
        self.file = file
        self.names = list(names)
        self.parameters = np.asarray(points, dtype=float).reshape(len(points), len(names))
        self.results = results
        self.ok = np.array(["error" not in r for r in results], dtype=bool)
        self.errors = [r.get("error", "") for r in results]
        good = [r for r in results if "error" not in r]
        K = len(results)
        self.modes = np.full((K, lowest), np.nan + 0j)
        for k, r in enumerate(results):
            if "error" not in r:
                m = np.asarray(r["modes"])[:lowest]
                self.modes[k, : len(m)] = m
        with np.errstate(invalid="ignore", divide="ignore"):
            self.freq_hz = np.abs(self.modes.imag) / (2 * np.pi)
            mag = np.abs(self.modes)
            self.damping = np.where(mag > 0, -self.modes.real / np.where(mag > 0, mag, 1), 0.0)
            self.damping[np.isnan(mag)] = np.nan
        if not good:
            self.inputs = self.outputs = self.states = []
            self.kind = None
            return
        first = good[0]
        sizes = {k: np.shape(first[k]) for k in "EABCD"}
        for k, r in enumerate(results):
            if "error" not in r and any(np.shape(r[x]) != sizes[x] for x in "EABCD"):
                raise ValueError(f"design point {k + 1} ({self.describe(k)}): its ROM has {np.shape(r['A'])[0]} states, the first {sizes['A'][0]}; stacked arrays need one size (choose count= or modes=)")
        for x in "EABCD":
            setattr(self, x, _stack(results, x, sizes[x]))
        gain = (len(first["outputs"]), len(first["inputs"]))
        self.full_static_gain = _stack(results, "full_static_gain", gain)
        self.rom_static_gain = _stack(results, "rom_static_gain", gain)
        self.inputs, self.outputs, self.states = first["inputs"], first["outputs"], first["states"]
        self.kind = first["kind"]

    def describe(self, k):
        """"L = 1.5, M = 2" for point k."""
        return ", ".join(f"{n} = {v:g}" for n, v in zip(self.names, self.parameters[k]))

    @property
    def failures(self):
        """[(k, {name: value}, message)] of the failed points."""
        return [(k, dict(zip(self.names, self.parameters[k])), e) for k, e in enumerate(self.errors) if e]

    def __repr__(self):
        return f"<romdyn SweepResult {len(self.results)} points over {', '.join(self.names)}, {int((~self.ok).sum())} failed>"
