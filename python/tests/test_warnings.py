"""Issue 30, finding 6: every warning the CLI prints is raised in Python through
``warnings.warn`` with a romdyn category, and ``reduce()`` runs the CLI's accuracy check
(transmissibility included, finding 5)."""

import pathlib
import subprocess
import warnings

import numpy as np
import pytest

import romdyn
from romdyn import _romdyn

ROOT = pathlib.Path(__file__).resolve().parents[2]
ISOLATOR = ROOT / "tests" / "mbdyn_files" / "isolator_imposed.mbd"
# tests/mbdyn_files/isolator_imposed.mbd: payload M on spring K and damper C over the base.
M, K, C = 10.0, 3553.0575843, 18.849555921


def cli_warnings(romdyn_cli, *args):
    """The "warning: ..." lines `romdyn` prints (their text after the prefix)."""
    r = subprocess.run([romdyn_cli, *map(str, args)], capture_output=True, text=True, cwd=ROOT)
    assert r.returncode == 0, r.stderr
    return [line[len("warning: "):] for line in r.stderr.splitlines() if line.startswith("warning: ")]


def python_warnings(call):
    """The romdyn warnings `call()` raises: (category, message) pairs, and its result."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = call()
    return [(w.category, str(w.message)) for w in caught if issubclass(w.category, romdyn.RomdynWarning)], result


def assert_cli_warnings_raised(cli, raised):
    # The same text, its command-line flags spelled as keyword arguments.
    messages = [m for _, m in raised]
    for text in cli:
        text = _romdyn.advice_for_python(text)
        assert text in messages, f"CLI warning not raised in Python: {text}\nraised: {messages}"
        assert " --" not in text, text


def test_categories_are_user_warnings_and_filterable():
    assert issubclass(romdyn.RomdynWarning, UserWarning)
    for c in (romdyn.ReferenceWarning, romdyn.PortWarning, romdyn.EigenanalysisWarning, romdyn.ModeSelectionWarning, romdyn.AccuracyWarning):
        assert issubclass(c, romdyn.RomdynWarning)
    for c in (romdyn.StaticGainWarning, romdyn.ResponseWarning, romdyn.TransmissibilityWarning):
        assert issubclass(c, romdyn.AccuracyWarning)


def test_isolator_without_its_base_mode_warns_about_the_transmissibility(romdyn_cli):
    # Finding 5: --band 1:30 drops the base (dummy-spring) mode at sqrt(K0/(M+MB))/2pi = 0.048 Hz.
    cli = cli_warnings(romdyn_cli, "rom", ISOLATOR, "--input", "3:Fx", "--output", "3:x", "--imposed", "2:x", "--band", "1:30")
    study = romdyn.Model(ISOLATOR).study(inputs=["3:Fx"], outputs=["3:x"], imposed="2:x")
    with pytest.warns(romdyn.TransmissibilityWarning, match=r"transmissibility \(eq. 100\) node 3 x \[m\] / node 2 x \[m\] departs .* mode\(s\) 1 \(0.0480 Hz\)"):
        study.reduce(band=(1, 30))
    raised, rom = python_warnings(lambda: study.reduce(band=(1, 30)))
    assert_cli_warnings_raised(cli, raised)
    kinds = {c for c, _ in raised}
    assert romdyn.StaticGainWarning in kinds and romdyn.ResponseWarning in kinds, raised
    assert "transmissibility z/z_e (eq. 100) on" in rom.summary
    # Filterable by category: the others ignored, this one an error.
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", romdyn.RomdynWarning)
        warnings.simplefilter("error", romdyn.TransmissibilityWarning)
        with pytest.raises(romdyn.TransmissibilityWarning):
            study.reduce(band=(1, 30))
    with warnings.catch_warnings():
        warnings.simplefilter("error", romdyn.AccuracyWarning)
        with pytest.raises(romdyn.AccuracyWarning):
            study.reduce(band=(1, 30))
    # The base mode kept: no accuracy warning, and the ROM's transmissibility is the closed
    # form (K + jwC)/(K - M w^2 + jwC) (Den Hartog §2.7) to 1e-9.
    raised, rom = python_warnings(lambda: study.reduce(band=(0, 30)))
    assert not [m for c, m in raised if issubclass(c, romdyn.AccuracyWarning)], raised
    f = np.array([0.5, 1.0, 3.0, 10.0])
    h = rom.frequency_response(f)  # outputs: node 3 x, node 2 x; inputs: node 3 Fx, node 2 Fx
    t = h[:, 0, 1] / h[:, 1, 1]
    w = 2 * np.pi * f
    exact = (K + 1j * w * C) / (K - M * w**2 + 1j * w * C)
    assert np.allclose(t, exact, rtol=1e-9, atol=0)


def test_a_moving_reference_warns_in_python_as_in_the_cli(romdyn_cli, tmp_path):
    # The pendulum released from 0.1 rad, linearized at t = 0.6 s while it swings.
    text = (ROOT / "examples" / "pendulum.mbd").read_text()
    node = "    structural: 2, dynamic, 0., -L, 0., eye, null, null;"
    assert node in text
    path = tmp_path / "swinging.mbd"
    path.write_text(text.replace(node, "    structural: 2, dynamic, L*sin(0.1), -L*cos(0.1), 0., euler123, 0., 0., 0.1, null, null;"))
    cli = cli_warnings(romdyn_cli, "rom", path, "--at", "0.6", "--input", "2:Mz", "--output", "2:rz", "--count", "1")
    assert any("neither an equilibrium nor a steady motion" in w for w in cli), cli
    model = romdyn.Model(path)
    with pytest.warns(romdyn.ReferenceWarning, match="neither an equilibrium nor a steady motion"):
        study = model.study(reference=0.6, inputs=["2:Mz"], outputs=["2:rz"])
    raised_study, study = python_warnings(lambda: model.study(reference=0.6, inputs=["2:Mz"], outputs=["2:rz"]))
    raised_rom, _ = python_warnings(lambda: study.reduce(count=1))
    assert_cli_warnings_raised(cli, raised_study + raised_rom)


def test_port_and_static_gain_warnings_reach_python(romdyn_cli):
    # A force on the clamped ground node: zero to rounding (a port warning, not a static-gain
    # difference); the first mode alone of the tip channel without residualization: the
    # static gain differs (a real truncation).
    cantilever = ROOT / "examples" / "cantilever.mbd"
    cli = cli_warnings(romdyn_cli, "rom", cantilever, "--static", "--input", "1:Fy", "--input", "21:Fy", "--output", "21:y", "--count", "1", "--residualize")
    assert any("no output responds to input node 1 Fy [N]" in w for w in cli), cli
    model = romdyn.Model(cantilever)
    with pytest.warns(romdyn.PortWarning, match="no output responds to input node 1 Fy"):
        study = model.study(reference="static", inputs=["1:Fy", "21:Fy"], outputs=["21:y"])
    raised_study, study = python_warnings(lambda: model.study(reference="static", inputs=["1:Fy", "21:Fy"], outputs=["21:y"]))
    raised_rom, rom = python_warnings(lambda: study.reduce(count=1, residualize=True))
    assert_cli_warnings_raised(cli, raised_study + raised_rom)
    assert not [m for c, m in raised_rom if c is romdyn.StaticGainWarning], raised_rom
    # A real departure in the band reaches Python as a ResponseWarning, advice included.
    cli = cli_warnings(romdyn_cli, "rom", cantilever, "--static", "--input", "21:Fy", "--output", "21:y", "--band", "0:100")
    study = model.study(reference="static", inputs=["21:Fy"], outputs=["21:y"])
    raised, _ = python_warnings(lambda: study.reduce(band=(0, 100)))
    assert_cli_warnings_raised(cli, raised)
    assert any(c is romdyn.ResponseWarning and "residualize=… (folds" in m for c, m in raised), raised


# tests/mbdyn_files/velocity_along_the_rod.mbd: a point on a rod pinned by a spherical hinge,
# its velocity written along the rod (0.3 m/s), the initial assembly skipped.
ALONG_THE_ROD = ROOT / "tests" / "mbdyn_files" / "velocity_along_the_rod.mbd"


def test_a_runs_warnings_reach_python_from_run_and_from_a_study(romdyn_cli, tmp_path):
    # Model.run() raised only beam notes; a study at the initial state dropped the run's
    # warnings everywhere (the CLI's `eig` too). Both now as `romdyn run` / `eig` print them.
    path = tmp_path / "rod.mbd"
    path.write_text(ALONG_THE_ROD.read_text())
    model = romdyn.Model(path)
    with pytest.warns(romdyn.ReferenceWarning, match=r"initial velocities do not satisfy the joints \(spherical hinge 2 constraint f x changes at 3.000e-1 per s\)"):
        history = model.run()
    # The run itself: the point keeps the hinge (|x| = 1 m) after the first step.
    assert np.allclose(np.linalg.norm(history["position"][-1, 1]), 1.0, atol=1e-9)
    cli = cli_warnings(romdyn_cli, "run", path, "-o", tmp_path / "rod")
    raised, _ = python_warnings(model.run)
    assert_cli_warnings_raised(cli, raised)
    cli = cli_warnings(romdyn_cli, "eig", path)
    assert any(w.startswith("reference solution: the initial velocities") for w in cli), cli
    raised, _ = python_warnings(lambda: model.study())
    assert_cli_warnings_raised(cli, raised)
    assert {c for c, m in raised if m.startswith("reference solution:")} == {romdyn.ReferenceWarning}, raised
