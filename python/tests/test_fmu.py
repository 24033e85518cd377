"""The ROM as an FMI 2.0 FMU (issue 37 point 5), simulated by FMPy, an independent FMI
importer: its co-simulation step response equals the ROM's own exact step response
(closed form through the matrix exponential) to 1e-9 of its size, model exchange integrated
by FMPy's CVode agrees to its tolerance, the discrete ROM samples at 2048 Hz (co-simulation
steps, and model exchange's time events), and FMPy's
own validation of the model description finds nothing."""

import pathlib

import numpy as np
import pytest
import scipy.linalg

import romdyn

fmpy = pytest.importorskip("fmpy")  # .ci/run installs it
from fmpy.validation import validate_fmu  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
BEAM = ROOT / "examples" / "simply_supported_beam.mbd"
FS = 2048.0
pytestmark = pytest.mark.filterwarnings("ignore::romdyn.AccuracyWarning", "ignore::romdyn.ModeSelectionWarning")


@pytest.fixture(scope="module")
def beam():
    return romdyn.Model(BEAM).study(reference="static", inputs=["5:Fy"], outputs=["5:y"])


def step_input(name, stop):
    return np.array([(0.0, 1.0), (stop, 1.0)], dtype=[("time", float), (name, float)])


def exact_step(rom, t):
    """C ∫₀ᵗ e^{As} ds B + D: the unit step response of x' = A x + B u, z = C x + D u."""
    n = rom.A.shape[0]
    out = []
    for tk in t:
        z = np.zeros((n + 1, n + 1))
        z[:n, :n], z[:n, n:] = rom.A * tk, rom.B[:, :1] * tk
        out.append((rom.C @ scipy.linalg.expm(z)[:n, n:] + rom.D[:, :1])[0, 0])
    return np.array(out)


def test_the_fmu_step_response_is_the_roms(beam, tmp_path):
    rom = beam.reduce(count=2, damping=0.02)
    path = tmp_path / "beam.fmu"
    rom.save(path)
    assert validate_fmu(str(path)) == []
    md = fmpy.read_model_description(str(path))
    inputs = [v for v in md.modelVariables if v.causality == "input"]
    outputs = [v for v in md.modelVariables if v.causality == "output"]
    assert [(v.name, v.unit) for v in inputs] == [("node 5 Fy [N]", "N")]
    assert [(v.name, v.unit) for v in outputs] == [("node 5 y [m]", "m")]
    stop, h = 0.1, 1e-4
    cs = fmpy.simulate_fmu(str(path), fmi_type="CoSimulation", stop_time=stop, output_interval=h, input=step_input(inputs[0].name, stop))
    expected = exact_step(rom, cs["time"])
    scale = np.max(np.abs(expected))
    # Issue 37: the FMU's step response equals the ROM's to 1e-9 (co-simulation steps are
    # the exact zero-order-hold solution; measured 1e-14 of the peak).
    assert np.max(np.abs(cs[outputs[0].name] - expected)) < 1e-9 * scale
    me = fmpy.simulate_fmu(str(path), fmi_type="ModelExchange", stop_time=stop, output_interval=h, input=step_input(inputs[0].name, stop), relative_tolerance=1e-10)
    # CVode at rtol 1e-10 (measured 2e-6 of the peak on the 0.05 s response).
    assert np.max(np.abs(me[outputs[0].name] - exact_step(rom, me["time"]))) < 1e-4 * scale


def test_a_discrete_fmu_samples_at_2048_hz(beam, tmp_path):
    disc = beam.reduce(count=2, damping=0.02, sample_rate=FS)
    path = tmp_path / "beam_2048.fmu"
    disc.save(path)
    assert validate_fmu(str(path)) == []
    md = fmpy.read_model_description(str(path))
    assert md.modelExchange is not None and md.coSimulation is not None
    assert float(md.defaultExperiment.stepSize) == pytest.approx(1 / FS, rel=1e-15)
    name = next(v.name for v in md.modelVariables if v.causality == "input")
    out = next(v.name for v in md.modelVariables if v.causality == "output")
    res = fmpy.simulate_fmu(str(path), fmi_type="CoSimulation", stop_time=200 / FS, output_interval=1 / FS, input=step_input(name, 1.0))
    # x[k+1] = Ad x[k] + Bd u[k], z[k] = C x[k] + D u[k] with u = 1 from k = 0.
    x = np.zeros(disc.A.shape[0])
    z = []
    for _ in range(len(res)):
        z.append((disc.C @ x + disc.D[:, 0])[0])
        x = disc.A @ x + disc.B[:, 0]
    assert np.max(np.abs(res[out] - np.array(z))) < 1e-12 * np.max(np.abs(z))
    # Model exchange: FMPy runs the samples as the time events the FMU announces; read
    # between samples (at (k + 1/2) T), where z = C x[k] + D u.
    me = fmpy.simulate_fmu(str(path), fmi_type="ModelExchange", stop_time=200 / FS, output_interval=0.5 / FS, input=step_input(name, 1.0))
    mid = [np.argmin(np.abs(me["time"] - (k + 0.5) / FS)) for k in range(199)]
    assert np.max(np.abs(me[out][mid] - np.array(z[:199]))) < 1e-12 * np.max(np.abs(z))


def test_a_descriptor_rom_is_refused_with_the_reason(beam, tmp_path):
    rom = beam.reduce(count=2, form="descriptor")
    with pytest.raises(romdyn.RomdynError, match=r"descriptor ROM .* has no FMU here: export the ordinary form"):
        rom.save(tmp_path / "descriptor.fmu")
    assert not (tmp_path / "descriptor.fmu").exists()


def test_the_report_shows_the_kept_modes_on_the_geometry(beam, tmp_path):
    import json

    rom = beam.reduce(count=3)
    page = beam.report(rom, tmp_path / "report", title="beam <3 modes>")
    assert page == tmp_path / "report" / "index.html"
    for name in ("bode.csv", "bode.svg", "bode.png"):
        assert (tmp_path / "report" / name).stat().st_size > 0
    html = page.read_text()
    assert "<title>beam &lt;3 modes&gt;</title>" in html
    data = json.loads(html.split('id="romdyn-geometry">')[1].split("</script>")[0])
    # examples/simply_supported_beam.mbd: 9 nodes on a line, 4 beam3 elements (8 segments);
    # kept modes 1, 3, 5 (romdyn eig: 49.33, 193.56, 249.76 Hz).
    assert len(data["nodes"]) == 9 and len(data["edges"]) == 8
    assert [m["label"].split(":")[0] for m in data["modes"]] == ["mode 1", "mode 3", "mode 5"]
    # The first bending mode moves mid-span (node 5) most, in y, and not the supports.
    shape = np.hypot(np.array(data["modes"][0]["shape_re"]), np.array(data["modes"][0]["shape_im"]))
    assert np.argmax(np.linalg.norm(shape, axis=1)) == data["labels"].index(5)
    assert np.linalg.norm(shape[data["labels"].index(1)]) < 1e-9 and np.linalg.norm(shape[data["labels"].index(9)][1]) < 1e-9
