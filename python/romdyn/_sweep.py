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
    outputs, fem_outputs, ports, remove_springs, imposed, cut, route, dcoef, count, band, modes, residualize,
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
    return SweepResult(name, names, points, results, options.get("lowest", 4), text=text, options=options)


class SweepResult:
    """The outcome of every design point, stacked as MATLAB's ss arrays in one modal basis.

    The lowest ``lowest`` modes of the first point are followed through the others by the
    modal assurance criterion (MAC) of their shapes, frequency breaking ties (romdyn's
    tracking, as ``romdyn sweep``): ``modes`` (K, lowest) complex eigenvalues [rad/s] of the
    tracked modes (a pair by its member with Im > 0, a ±a pair by +a; NaN where a point failed
    or lost the mode), freq_hz = |Im λ|/2π, damping = −Re λ/|λ|, mode_labels (each mode's
    label at the first point, "node 2 x 100 %"), mode_mac (K, lowest: the MAC of each match;
    below 0.8 a veering or points too far apart), mode_crossing (K, lowest) bool, mode_flags
    (K strings), table (the CSV text of ``--table``).

    names: parameter names; parameters: (K, P) values; ok: (K,) bool; errors: K messages
    ("" where ok); A, B, C, D, E: (n, n, K), (n, m, K), … (``A[:, :, k]`` is point k's, NaN
    where it failed) with the states in the tracked modes' order and phase (state_tracks:
    (n, K), the tracked mode of each state, 0 for none, NaN where a point failed), so that
    they interpolate (``interpolate``);
    full_static_gain, rom_static_gain: (outputs, inputs, K); inputs, outputs, states: names
    with units.
    """

    def __init__(self, file, names, points, results, lowest, text=None, options=None):
        self.file = file
        self.names = list(names)
        self.parameters = np.asarray(points, dtype=float).reshape(len(points), len(names))
        self.results = results
        self.lowest = lowest
        self._text, self._options = text, dict(options or {})
        self.ok = np.array(["error" not in r for r in results], dtype=bool)
        self.errors = [r.get("error", "") for r in results]
        a = _romdyn.sweep_arrays(file, self.names, self.parameters.tolist(), results, lowest)
        self.table = a["table"]
        if "A" not in a:
            self.inputs = self.outputs = self.states = self.mode_labels = []
            self.kind = None
            self.modes = np.full((len(results), 0), np.nan + 0j)
            self.freq_hz = self.damping = self.mode_mac = np.full((len(results), 0), np.nan)
            self.mode_crossing = np.zeros((len(results), 0), dtype=bool)
            self.mode_flags = [""] * len(results)
            return
        for x in ("E", "A", "B", "C", "D", "full_static_gain", "rom_static_gain"):
            setattr(self, x, a[x])
        self.state_tracks = a["state_tracks"][:, 0, :]
        self.modes = a["mode_re"] + 1j * a["mode_im"]
        self.freq_hz, self.damping, self.mode_mac = a["mode_freq_hz"], a["mode_damping"], a["mode_mac"]
        self.mode_crossing = a["mode_crossing"] == 1
        self.mode_labels, self.mode_flags = a["mode_labels"], a["mode_flags"]
        self.inputs, self.outputs, self.states = a["inputs"], a["outputs"], a["states"]
        self.kind = a["kind"]

    def _values(self, values):
        missing = [n for n in self.names if n not in values]
        extra = [n for n in values if n not in self.names]
        if missing or extra:
            raise ValueError(f"interpolate: give one value for each swept parameter ({', '.join(self.names)})")
        return [float(values[n]) for n in self.names]

    def interpolate(self, check=False, **values):
        """The ROM at an intermediate design point, e.g. ``interpolate(K=1.25)``: the stacked
        ROMs (ordinary form) interpolated entry by entry, linearly between the grid values
        around the point (multilinear over several parameters), in the tracked modes' basis.
        A dict of E A B C D, eigenvalues, rom_static_gain, names and units. With
        ``check=True`` the ROM is also computed at the point (same options) and the dict has
        "exact" (that ROM in the same basis) and "check": relative differences of A, B, C, D,
        the eigenvalues and the static gain (and their "text"). Raises ValueError outside the
        sweep's range or when the ROMs around the point keep different tracked modes."""
        v = self._values(values)
        exact = None
        if check:
            if self._text is None:
                raise ValueError("interpolate(check=True): this SweepResult has no model text to compute the point with")
            exact = _point(self._text, self.file, self.names, v, self._options)
        return _romdyn.interpolate_sweep(self.file, self.names, self.parameters.tolist(), self.results, self.lowest, v, exact)

    def describe(self, k):
        """"L = 1.5, M = 2" for point k."""
        return ", ".join(f"{n} = {v:g}" for n, v in zip(self.names, self.parameters[k]))

    @property
    def failures(self):
        """[(k, {name: value}, message)] of the failed points."""
        return [(k, dict(zip(self.names, self.parameters[k])), e) for k, e in enumerate(self.errors) if e]

    def __repr__(self):
        return f"<romdyn SweepResult {len(self.results)} points over {', '.join(self.names)}, {int((~self.ok).sum())} failed>"
