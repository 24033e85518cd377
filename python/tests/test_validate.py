"""romdyn.validate(): `romdyn validate` from Python (issue 33)."""
import numpy as np
import pytest
from pathlib import Path

import romdyn


def test_validate_returns_arrays_and_the_verdict(examples):
    # Mass 3 of mass_on_springs.mbd along x: M = 2 kg, K = 100 N/m, C = 1 N s/m (the file's),
    # H = 1/(K - M w^2 + j C w) in closed form.
    model = romdyn.Model(examples / "mass_on_springs.mbd")
    v = romdyn.validate(model, inputs=["3:Fx"], outputs=["3:x"], modes=[3], resolution=0.02, averages=8)
    f = v["freq_hz"]
    assert v["estimate"].shape == (1, f.size, 1, 1) and v["coherence"].shape == (1, f.size, 1, 1)
    w = 2 * np.pi * f
    exact = 1.0 / (100.0 - 2.0 * w**2 + 1j * w)
    # The library's full model is the closed form to round-off.
    assert np.max(np.abs(v["full"][0, :, 0, 0] - exact) / np.abs(exact)) < 1e-9
    # The estimate within three times Bendat and Piersol's random error plus 2 % (the
    # window's resolution bias at 0.02 Hz bins on the 0.08 Hz wide peak) where coherent.
    g = v["coherence"][0, :, 0, 0]
    eps = np.sqrt(1 - g) / (np.sqrt(g) * np.sqrt(2 * 8))
    err = np.abs(v["estimate"][0, :, 0, 0] - exact) / np.abs(exact)
    coherent = g >= 0.9
    assert coherent.sum() > f.size // 2
    assert np.all(err[coherent] <= 3 * eps[coherent] + 0.02), np.max(err[coherent] - 3 * eps[coherent])
    assert v["represents"] and "represents the nonlinear model" in v["verdict"]
    assert v["nonlinear"].shape == v["rom_time"].shape == (1, 1, v["time"].size)


def test_validate_refuses_bad_options(examples):
    model = romdyn.Model(examples / "mass_on_springs.mbd")
    with pytest.raises(ValueError, match="averages"):
        romdyn.validate(model, inputs=["3:Fx"], outputs=["3:x"], modes=[3], averages=1)
    with pytest.raises(ValueError, match="signal"):
        romdyn.validate(model, inputs=["3:Fx"], outputs=["3:x"], modes=[3], signal="noise")
    # The keyword as Python spells it, not the CLI's flag.
    with pytest.raises(ValueError, match=r"^validation_band: ") as e:
        romdyn.validate(model, inputs=["3:Fx"], outputs=["3:x"], modes=[3], validation_band=(5.0, 1.0))
    assert "--" not in str(e.value)


def test_a_refused_port_names_the_python_keyword(tmp_path):
    # An imposed motion (from a ports file) has no nonlinear counterpart to validate; the
    # refusal names the keyword `imposed` (romdyn::study::Setting), not the CLI's `--imposed`.
    root = Path(__file__).resolve().parents[2]
    ports = tmp_path / "ports.json"
    ports.write_text('{"inputs": ["3:Fx"], "outputs": ["3:x"], "imposed": "2:x"}')
    model = romdyn.Model(root / "tests" / "mbdyn_files" / "isolator_imposed.mbd")
    with pytest.raises(ValueError, match=r"^imposed: an imposed motion is not validated") as e:
        romdyn.validate(model, ports=ports, count=2)
    assert "--" not in str(e.value)


def test_a_rom_that_misses_the_port_is_warned_as_the_cli_does(examples):
    # Mass 3 of mass_on_springs.mbd seen along y while the ROM keeps only its x oscillator
    # (mode 3; tests/application/validate.rs has the same case): the CLI prints "warning: the
    # ROM does not represent ..."; Python raises it. 0.4 N RMS on K = 400 N/m: 1 mm static.
    model = romdyn.Model(examples / "mass_on_springs.mbd")
    with pytest.warns(romdyn.AccuracyWarning, match="does not represent the nonlinear model"):
        v = romdyn.validate(model, inputs=["3:Fy"], outputs=["3:y"], modes=[3], validation_band=(0.0, 4.0), resolution=0.05, amplitudes=[0.4])
    assert not v["represents"]


def test_validate_is_a_method_of_the_model(examples):
    # Model.validate(**options) is romdyn.validate(model, **options): the same seeded run,
    # so the same estimate to the last bit, and the same refusals.
    model = romdyn.Model(examples / "mass_on_springs.mbd")
    options = dict(inputs=["3:Fx"], outputs=["3:x"], modes=[3], signal="multisine", resolution=0.05, averages=2)
    a, b = model.validate(**options), romdyn.validate(model, **options)
    assert np.array_equal(a["estimate"], b["estimate"]) and a["verdict"] == b["verdict"]
    w = 2 * np.pi * a["freq_hz"]
    exact = 1.0 / (100.0 - 2.0 * w**2 + 1j * w)
    below = a["freq_hz"] < 1.05
    # 0.2 %: the integrator's period error below the 1.125 Hz peak (no window on a multisine).
    assert np.max(np.abs(a["estimate"][0, below, 0, 0] - exact[below]) / np.abs(exact[below])) < 2e-3
    with pytest.raises(ValueError, match="averages"):
        model.validate(inputs=["3:Fx"], outputs=["3:x"], modes=[3], averages=1)
