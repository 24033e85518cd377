"""romdyn from Python against closed forms and the CLI (issue 15)."""

import re
import subprocess

import numpy as np
import pytest
import scipy.io

import romdyn

# examples/pendulum.mbd: M = 1 kg, J = 1e-3 kg m^2 about the centre of mass, L = 1 m, G = 9.81 m/s^2.
M, J, G = 1.0, 1e-3, 9.81


def omega(length, mass=M):
    """Compound pendulum about its hinge: omega^2 = M G L / (J + M L^2) (paper eq. 82 with offset L)."""
    return np.sqrt(mass * G * length / (J + mass * length**2))


def test_pendulum_eigenvalues_and_rom_gain(examples):
    study = romdyn.Model(examples / "pendulum.mbd").study(inputs=["2:Mz"], outputs=["2:rz"])
    modes = study.modes()
    dyn = modes["eigenvalues"][[k == "dynamic" for k in modes["kind"]]]
    # Paper §7.2 / CASES C2: ±3.130527 j rad/s (6 digits given).
    assert np.allclose(sorted(dyn.imag), [-3.130527, 3.130527], atol=1e-6)
    assert np.all(np.abs(dyn.real) < 1e-9)
    rom = study.reduce(count=1)
    # Static gain rz/Mz = 1/(M G L) rad/(N m): the gravity stiffness of the hanging pendulum.
    assert rom.rom_static_gain[0, 0] == pytest.approx(1 / (M * G * 1.0), rel=1e-9)
    sys = rom.to_control()
    assert sys.input_labels == ["node 2 Mz [N m]"] and sys.output_labels == ["node 2 rz [rad]"]
    assert sys.dcgain() == pytest.approx(1 / (M * G), rel=1e-9)
    ss = rom.to_scipy()
    assert np.array_equal(ss.A, rom.A) and np.array_equal(ss.D, rom.D)


def test_beam_rom_equals_the_clis_mat(examples, romdyn_cli, tmp_path):
    # The README's main job (paper §7.1, Fig. 7): one bending mode kept, the third residualized.
    out = tmp_path / "beam_rom.mat"
    subprocess.run([romdyn_cli, "rom", examples / "simply_supported_beam.mbd", "--static", "--input", "5:Fy", "--output", "5:y", "--count", "1", "--residualize-modes", "7", "-o", out], check=True, capture_output=True)
    cli = scipy.io.loadmat(out)
    study = romdyn.Model(examples / "simply_supported_beam.mbd").study(reference="static", inputs=["5:Fy"], outputs=["5:y"])
    sys = study.reduce(count=1, residualize=[7]).to_control()
    gain_cli = cli["D"] - cli["C"] @ np.linalg.solve(cli["A"], cli["B"])
    assert np.allclose(sys.dcgain(), gain_cli, rtol=1e-12, atol=0)
    poles_cli = np.sort_complex(np.linalg.eigvals(cli["A"]))
    poles = np.sort_complex(sys.poles())
    assert np.allclose(poles, poles_cli, rtol=1e-12, atol=0)
    # And the full model's static gain, paper eq. 73: L^3/(48 EJ) + L/(4 GA) = 2.108333e-5 m/N.
    assert cli["full_static_gain"][0, 0] == pytest.approx(1 / (48 * 1e3) + 1 / (4 * 1e6), rel=1e-6)


def test_model_error_names_file_line_column(tmp_path):
    bad = tmp_path / "bad.mbd"
    bad.write_text("begin: data;\n    problem: initial value;\nend: data;\nbegin: control data;\n    structural nodes: 1;\nend: control data;\nbegin: nodes;\n    structural: 1, dynamik, null, eye, null, null;\nend: nodes;\n")
    with pytest.raises(romdyn.ModelError) as e:
        romdyn.Model(bad)
    assert str(e.value).startswith(f"{bad}:8:20: error:"), str(e.value)
    assert isinstance(e.value, romdyn.RomdynError)
    with pytest.raises(romdyn.ModelError, match="declares no variable 'X'"):
        romdyn.Model(tmp_path.parent / bad, set={"X": 1.0})


def test_set_override_scales_as_the_closed_form(examples):
    freqs = {}
    for length in [0.25, 1.0, 4.0]:
        study = romdyn.Model(examples / "pendulum.mbd", set={"L": length}).study(inputs=["2:Mz"], outputs=["2:rz"])
        lam = study.reduce(count=1).full_eigenvalues
        freqs[length] = abs(lam[0].imag)
        assert freqs[length] == pytest.approx(omega(length), rel=1e-6)
    # sqrt(g/L) scaling (J = 1e-3 makes it the compound pendulum's): L x4 -> omega / 2 within J's share.
    assert freqs[4.0] / freqs[1.0] == pytest.approx(omega(4.0) / omega(1.0), rel=1e-6)


def test_run_keeps_the_hinge_constraint(examples):
    h = romdyn.Model(examples / "pendulum.mbd").run()
    assert h["position"].shape == (len(h["time"]), 2, 3)
    # MBDyn's step count: steps of 1 ms until the time passes the final time 2 s (as `romdyn run`).
    assert h["time"][0] == 0.0 and h["time"][-1] == pytest.approx(2.001, abs=1e-9)
    # Node 2 stays at L = 1 m from the hinge at the origin (tolerance 1e-9 of the file).
    r = np.linalg.norm(h["position"][:, 1, :], axis=1)
    assert np.allclose(r, 1.0, atol=1e-6)


def test_beam_update_is_the_clis(examples, romdyn_cli, tmp_path):
    # examples/cantilever.mbd with MBDyn's incremental beam update, in Python and in the CLI
    # (`romdyn run --beam-update incremental`, .mov with 16 digits): the same final tip, to
    # the .mov's 13 printed digits, and the default ("auto": MBDyn's update in a run) the
    # same; the path-independent beam ends 8.4e-6 m from it (docs/src/mbdyn/beams.md, the two
    # discretizations), so the option is applied.
    subprocess.run([romdyn_cli, "run", examples / "cantilever.mbd", "--beam-update", "incremental", "-o", tmp_path / "c"], check=True, capture_output=True)
    rows = [line.split() for line in (tmp_path / "c.mov").read_text().splitlines()]
    tip_cli = np.array([float(x) for x in rows[-1][1:4]])
    assert rows[-1][0] == "21"
    tip = {}
    for update in ["incremental", None, "path-independent"]:
        h = romdyn.load(examples / "cantilever.mbd", beam_update=update).run()
        tip[update] = h["position"][-1, list(h["labels"]).index(21)]
    assert np.allclose(tip["incremental"], tip_cli, rtol=0, atol=1e-11)
    assert np.allclose(tip[None], tip_cli, rtol=0, atol=1e-11)
    assert np.abs(tip["path-independent"] - tip_cli).max() > 1e-6
    with pytest.raises(ValueError, match="beam_update.*'sideways'"):
        romdyn.Model(examples / "cantilever.mbd", beam_update="sideways")


def test_linear_dae_and_frequency_responses(examples):
    study = romdyn.Model(examples / "simply_supported_beam.mbd").study(reference="static", inputs=["5:Fy"], outputs=["5:y"])
    lin = study.linear()
    assert lin["Fyd"].shape == (138, 138) and lin["B"].shape == (138, 1) and lin["C"].shape == (1, 138)
    assert lin["inputs"] == ["node 5 Fy [N]"] and lin["outputs"] == ["node 5 y [m]"]
    # Far below the first mode (49.3 Hz) both responses are the static gains; the full
    # model's is paper eq. 73, L^3/(48 EJ) + L/(4 GA) m/N (rel 1e-6 at 1e-3 Hz).
    rom = study.reduce(count=1, residualize=[7])
    h_full = study.frequency_response([1e-3])
    h_rom = rom.frequency_response([1e-3])
    assert h_full.shape == (1, 1, 1) and h_full.dtype == np.complex128
    assert h_full[0, 0, 0].real == pytest.approx(1 / 48e3 + 1 / 4e6, rel=1e-6)
    assert h_rom[0, 0, 0].real == pytest.approx(rom.rom_static_gain[0, 0], rel=1e-6)


def test_sparse_modes_equal_the_closed_form_and_the_dense_study(examples):
    # Shift-invert Krylov-Schur on the sparse linearization (issue 13): the pendulum's swing
    # pair, closed form ±j sqrt(M G L / (J + M L^2)) (1e-6 relative), and only that pair: no
    # constrained zero eigenvalue comes back (the dense study lists 22).
    pendulum = romdyn.Model(examples / "pendulum.mbd")
    sparse = pendulum.sparse_modes(count=1)
    assert sparse["certified"] and sparse["max_residual"] <= 1e-10
    assert all(k == "dynamic" for k in sparse["kind"])
    assert np.allclose(sorted(sparse["eigenvalues"].imag), [-omega(1.0), omega(1.0)], rtol=1e-6)
    # The README beam at its static equilibrium: the 2 lowest modes equal the dense route's to 1e-9.
    beam = romdyn.Model(examples / "simply_supported_beam.mbd")
    sparse = beam.sparse_modes(count=2, reference="static")
    dense = beam.study(reference="static").modes()
    dyn = dense["undamped_hz"][[k == "dynamic" for k in dense["kind"]]]
    assert np.allclose(np.unique(np.round(sparse["undamped_hz"], 9))[:2], np.unique(np.round(dyn, 9))[:2], rtol=1e-9)
    with pytest.raises(ValueError, match="count"):
        pendulum.sparse_modes()


def test_study_solver_sparse_gives_the_dense_modes_static_gain_and_response(examples):
    # The README beam (138 equations, so "auto" is dense): the same study on both routes of
    # the library's Study. The dense route is the one checked against paper eq. 73 above.
    beam = romdyn.Model(examples / "simply_supported_beam.mbd")
    kw = dict(reference="static", inputs=["5:Fy"], outputs=["5:y"])
    dense, sparse = beam.study(**kw), beam.study(solver="sparse", count=3, **kw)
    assert (dense.solver, sparse.solver) == ("dense", "sparse")
    rd, rs = dense.reduce(count=1), sparse.reduce(count=1, residualize=True)
    # Same kept pair to 1e-9; the sparse ROM's static gain (modes not kept corrected by one
    # sparse static solve) is the full model's, dense LU, to 1e-9.
    assert np.allclose(np.sort(rs.full_eigenvalues.imag), np.sort(rd.full_eigenvalues.imag), rtol=1e-9)
    assert rs.rom_static_gain[0, 0] == pytest.approx(rd.full_static_gain[0, 0], rel=1e-9)
    assert rs.full_static_gain[0, 0] == pytest.approx(rd.full_static_gain[0, 0], rel=1e-9)
    # The full model's response, dense LU vs sparse LU at each frequency [Hz], to 1e-9.
    f = [5.0, 20.0, 100.0, 150.0, 300.0]
    assert np.allclose(sparse.frequency_response(f), dense.frequency_response(f), rtol=1e-9, atol=0)
    # Model.sparse_modes is that study without ports.
    assert np.allclose(np.sort(beam.sparse_modes(count=3, reference="static")["eigenvalues"].imag), np.sort(sparse.modes()["eigenvalues"].imag), rtol=1e-12)
    with pytest.raises(ValueError, match="solver"):
        beam.study(solver="bogus")


def test_a_bad_setting_is_named_as_python_spells_it(examples):
    # Issue 31: the library's refusals named the CLI's flags ("--dcoef: ...") to Python users.
    model = romdyn.Model(examples / "pendulum.mbd")
    with pytest.raises(ValueError, match=r"^dcoef: dCoef must be a positive finite"):
        model.study(inputs=["2:Mz"], outputs=["2:rz"], dcoef=-1.0)
    # examples/pendulum.mbd integrates to 2 s.
    with pytest.raises(ValueError, match=r"^reference: TIME 5(\.0)? s is after the file's final time 2 s"):
        model.study(reference=5.0, inputs=["2:Mz"], outputs=["2:rz"])
    study = model.study(inputs=["2:Mz"], outputs=["2:rz"])
    with pytest.raises(ValueError, match=r"^fmin: need FMIN < FMAX"):
        study.reduce(count=1, fmin=10.0, fmax=1.0)
    # An empty band is refused by every front end (the CLI took FMIN = FMAX).
    with pytest.raises(ValueError, match=r"^band: need 0 <= FMIN < FMAX"):
        study.reduce(band=(2.0, 2.0))


def test_pid_loop_on_abstract_nodes_has_the_polynomial_poles(examples):
    # Issue 34: examples/pid_mass.mbd, a mass on a spring and damper under a PID loop with a
    # filtered derivative, written with abstract nodes and genels; ports on scalar nodes.
    # Closed-loop poles: roots of m s^4 + (m A1 + c) s^3 + (c A1 + k + B0) s^2
    # + (k A1 + B1) s + B2 (the file's header); X/F = (s^2 + A1 s)/P(s), so x/F = 0 and
    # u/F = B2/B2 = 1 statically (the integrator removes the static error).
    m, k, c, kp, ki, kd, tau = 2.0, 50.0, 0.4, 100.0, 200.0, 10.0, 0.01
    a1, b0, b1, b2 = 1 / tau, (kp * tau + kd) / tau, (kp + ki * tau) / tau, ki / tau
    poles = np.roots([m, m * a1 + c, c * a1 + k + b0, k * a1 + b1, b2])
    study = romdyn.Model(examples / "pid_mass.mbd").study(inputs=["1:abstract"], outputs=["1:abstract", "2:abstract"])
    modes = study.modes()
    dyn = modes["eigenvalues"][[kind == "dynamic" for kind in modes["kind"]]]
    assert len(dyn) == 4
    for p in poles:
        assert np.min(np.abs(dyn - p)) <= 1e-8 * abs(p), (p, dyn)
    rom = study.reduce(count=3)  # a complex pair and two real poles: three modes
    assert np.allclose(rom.rom_static_gain[:, 0], [0.0, 1.0], atol=1e-9)
    for f in (0.3, 3.0):
        s = 2j * np.pi * f
        p = np.polyval([m, m * a1 + c, c * a1 + k + b0, k * a1 + b1, b2], s)
        h = rom.frequency_response(np.array([f]))[0]
        assert h[0, 0] == pytest.approx((s * s + a1 * s) / p, rel=1e-8)
        assert h[1, 0] == pytest.approx((b0 * s * s + b1 * s + b2) / p, rel=1e-8)


def test_a_cut_pid_loop_gives_the_plant_and_the_loop_transfer_function(examples):
    # Issue 34 point 4: cut=["genel:4"] takes examples/pid_mass.mbd's link from the
    # controller to the mass out of the linearization; the plant P = 1/(m s^2 + c s + k), the
    # loop L = P C = -returned/injected with C = (B0 s^2 + B1 s + B2)/(s^2 + A1 s), and the
    # closed loop (uncut) u/F = T = P C/(1 + P C), all closed forms, 1e-8.
    m, k, c, kp, ki, kd, tau = 2.0, 50.0, 0.4, 100.0, 200.0, 10.0, 0.01
    a1, b0, b1, b2 = 1 / tau, (kp * tau + kd) / tau, (kp + ki * tau) / tau, ki / tau
    model = romdyn.Model(examples / "pid_mass.mbd")
    cut = model.study(inputs=["1:abstract"], outputs=["1:abstract", "2:abstract"], cut=["genel:4"])
    linear = cut.linear()
    assert linear["inputs"][-1] == "cut genel cross spring support 4 at abstract node 1 (injected) [-]"
    assert linear["outputs"][-1] == "cut genel cross spring support 4 at abstract node 1 (returned) [-]"
    modes = cut.modes()
    dyn = modes["eigenvalues"][[kind == "dynamic" for kind in modes["kind"]]]
    for p in list(np.roots([m, c, k])) + [-1 / tau]:
        assert np.min(np.abs(dyn - p)) <= 1e-8 * abs(p), (p, dyn)
    closed = model.study(inputs=["1:abstract"], outputs=["1:abstract", "2:abstract"])
    freqs = np.array([0.1, 0.8, 3.0, 20.0])
    h_cut = cut.frequency_response(freqs)
    h_closed = closed.frequency_response(freqs)
    for f, hc, h in zip(freqs, h_cut, h_closed):
        s = 2j * np.pi * f
        plant = 1 / np.polyval([m, c, k], s)
        controller = np.polyval([b0, b1, b2], s) / np.polyval([1, a1, 0], s)
        assert hc[0, 0] == pytest.approx(plant, rel=1e-8)
        assert -hc[2, 1] == pytest.approx(plant * controller, rel=1e-8)
        assert h[1, 0] == pytest.approx(plant * controller / (1 + plant * controller), rel=1e-8)
    with pytest.raises(ValueError, match=r"^cut: genel:9: the model has no genel 9"):
        model.study(cut=["genel:9"])
    with pytest.raises(ValueError, match=r"^cut: 'joint:4': expected genel:LABEL or force:LABEL"):
        model.study(cut=["joint:4"])


def test_a_fem_node_is_an_output(examples):
    # Issue 35 point 2: fem_outputs=["JOINT:FEM_NODE:y"], a sensor on a flexible body. On
    # tests/mbdyn_files/modal_clamped_port.mbd FEM node B moves 1 m along y per unit q1 and
    # carries node 2: its y is q1 = 1/(k - (m + m2) w^2) F (the file's closed form), its
    # velocity j w times that; 1e-12.
    path = examples.parent / "tests" / "mbdyn_files" / "modal_clamped_port.mbd"
    study = romdyn.Model(path).study(inputs=["2:Fy"], outputs=["10:q1"], fem_outputs=["10:B:y", "10:B:vy"])
    assert study.linear()["outputs"] == ["modal 10 q1 [-]", "modal 10 FEM node B y [m]", "modal 10 FEM node B vy [m/s]"]
    for f in (1.0, 7.0):
        w = 2 * np.pi * f
        h = study.frequency_response(np.array([f]))[0]
        q = 1 / (1000.0 - 2.0 * w * w)
        assert h[1, 0] == pytest.approx(q, rel=1e-12)
        assert h[2, 0] == pytest.approx(1j * w * q, rel=1e-12)
    with pytest.raises(ValueError, match=r"^fem_outputs: '10:B': expected JOINT:FEM_NODE:COMPONENT with COMPONENT one of x\|y\|z\|vx\|vy\|vz"):
        romdyn.Model(path).study(fem_outputs=["10:B"])


def test_enumerated_settings_and_sweeps_name_the_keyword(examples):
    # Issue 31: one library table of names per enum, read by clap and by Python; a bad word
    # is refused naming the Python keyword, with the names the table holds.
    model = romdyn.Model(examples / "pendulum.mbd")
    with pytest.raises(ValueError, match=r'^solver: \'bogus\': expected "auto", "dense" or "sparse"$'):
        model.study(inputs=["2:Mz"], outputs=["2:rz"], solver="bogus")
    with pytest.raises(ValueError, match=r'^route: \'qz\': expected "direct" or "lambda"$'):
        model.study(inputs=["2:Mz"], outputs=["2:rz"], route="qz")
    with pytest.raises(ValueError, match=r"^imposed: '2:q': expected NODE or NODE:COMPONENTS"):
        model.study(inputs=["2:Mz"], outputs=["2:rz"], imposed="2:q")
    study = model.study(inputs=["2:Mz"], outputs=["2:rz"])
    with pytest.raises(ValueError, match=r'^by: \'size\': expected "frequency" or "dominance"$'):
        study.reduce(count=1, by="size")
    with pytest.raises(ValueError, match=r'^below_band: \'hide\': expected "keep", "drop" or "refuse"$'):
        study.reduce(count=1, below_band="hide")
    with pytest.raises(ValueError, match=r'^form: \'state\': expected "ordinary" or "descriptor"$'):
        study.reduce(count=1, form="state")
    with pytest.raises(ValueError, match=r"^set: L: the variable is given twice$"):
        romdyn._romdyn.grid([("L", [1.0]), ("L", [2.0])])


def test_the_python_door_runs_the_three_checks(examples, tmp_path):
    # Issue 31: every door (tests/cli/study_doors.rs has the Rust and CLI ones): the reference
    # checked against the problem, an unrestrained model named, incremental beams warned about.
    model = romdyn.Model(examples / "pendulum.mbd")
    with pytest.raises(ValueError, match=r"^reference: TIME 5(\.0)? s is after the file's final time 2 s"):
        model.study(reference=5.0)
    text = (examples / "pendulum.mbd").read_text()
    spring = "joint: 2, deformable joint,\n        1, null, hinge, reference, node, eye,\n        2, 0., L, 0., hinge, reference, node, eye,\n        linear elastic generic, diag, 1.e4, 1.e4, 1.e4, 1.e4, 1.e4, 1.e4;"
    for a, b in [("    joint: 1, clamp, 1, node, node;\n", ""), ("joint: 2, revolute hinge,\n        1, position, null,\n        2, position, 0., L, 0.;", spring), ("joints: 2;", "joints: 1;")]:
        assert a in text
        text = text.replace(a, b)
    floating = romdyn.Model.from_text(text, name=str(tmp_path / "floating.mbd"))
    with pytest.raises(romdyn.RomdynError, match=r"unrestrained .*rigid-body motion of the whole model"):
        floating.study(reference="static", load_steps=1)
    beams = romdyn.Model(examples.parent / "tests" / "mbdyn_files" / "beam3_tip_couple.mbd", beam_update="incremental")
    with pytest.warns(romdyn.ReferenceWarning, match=r"^2 beam\(s\) use MBDyn's incremental update \(beam_update=\"incremental\"\)"):
        beams.study(reference="static")


def test_a_free_roms_eigenvalues_reach_python_as_the_cli_prints_them(examples, romdyn_cli):
    # Issue 31 point 4: the free ROM's eigenvalues (dummy springs removed) were assembled in
    # the CLI only. HAM-SAS, springs removed by its ports file: Python's Rom.free_eigenvalues
    # and summary carry the CLI's report, number for number (its 7 printed digits).
    ports = examples / "ham_sas_ports.json"
    cli = subprocess.run([romdyn_cli, "rom", examples / "ham_sas.mbd", "--static", "--load-steps", "1", "--ports", ports, "--band", "0:2"], check=True, capture_output=True, text=True).stderr
    report = cli[cli.index("removed from the full model"):]
    report = report[: report.index("\n", report.index("ROM eigenvalues without them"))]
    rows = [line for line in cli[cli.index("ROM eigenvalues without them"):].splitlines()[1:] if line.startswith("  ") and " Hz " in line]
    study = romdyn.Model(examples / "ham_sas.mbd").study(reference="static", load_steps=1, ports=ports)
    rom = study.reduce(band=(0.0, 2.0))
    free = rom.free_eigenvalues
    assert report in rom.summary
    assert f"{free['zero']} zero (rigid-body motion)" in report
    assert len(free["eigenvalues"]) == len(rows) > 0
    for lam, kind, motion, row in zip(free["eigenvalues"], free["kind"], free["motion"], rows):
        re, im = row.split()[:2]
        assert lam.real == pytest.approx(float(re), rel=1e-6, abs=1e-12)
        assert lam.imag == pytest.approx(float(im.rstrip("j")), rel=1e-6, abs=1e-12)
        assert row.split("Hz", 1)[1].strip() == (f"real, {motion}" if motion else kind)
    # The HAM-SAS table's tipping: a real pair, one unstable, named by its motion.
    assert any(k == "real, unstable" and m and m.startswith("tipping") for k, m in zip(free["kind"], free["motion"]))
    assert romdyn.Model(examples / "pendulum.mbd").study(inputs=["2:Mz"], outputs=["2:rz"]).reduce(count=1).free_eigenvalues is None


def test_the_sparse_target_is_checked_once_in_the_library(examples):
    # Issue 31: EigenSettings::validate checks the modes the sparse route computes for every
    # door; count=0 read "give at most one of count and band" in Python before.
    model = romdyn.Model(examples / "pendulum.mbd")
    with pytest.raises(ValueError, match=r"^count: a ROM keeps at least 1 mode$"):
        model.study(solver="sparse", count=0)
    with pytest.raises(ValueError, match=r"^band: need 0 <= FMIN < FMAX"):
        model.study(solver="sparse", band=(3.0, 3.0))
    with pytest.raises(ValueError, match=r"^band: need 0 <= FMIN < FMAX"):
        model.sparse_modes(band=(3.0, 1.0))


def test_a_beam_the_auto_update_leaves_path_independent_warns_with_the_keyword():
    # The study warning of tests/cli/study_doors.rs, spelled for Python (the advice's value
    # "path-independent" kept whole: the spelling cut it at its hyphen before).
    import pathlib

    path = pathlib.Path(__file__).resolve().parents[2] / "tests" / "mbdyn_files" / "beam3_tip_couple.mbd"
    text = path.read_text()
    assert "    beam3: 2, 3, null" in text
    model = romdyn.Model.from_text(text.replace("    beam3: 2, 3, null", "    driven: 2, const, 1., beam3: 2, 3, null"), name=str(path))
    with pytest.warns(romdyn.ReferenceWarning, match=r"^beam3 2.*keeps the path-independent update.*\(beam_update=\"path-independent\" silences this\)$"):
        model.study(reference=0.5)


def test_mode_labels_name_element_states_and_fem_rotations(examples):
    # Issues 34 and 35: Study.modes() carries the modal table's shares. On
    # tests/mbdyn_files/modal_clamped_port.mbd the one mode is 25 % the modal joint's mode 1
    # (modal mass 0.5 kg) and 75 % node 2's 1.5 kg body along y (closed form, 1e-10); on the
    # hydraulic actuator, half the piston's kinetic energy and a quarter each chamber's
    # compression energy (tests/multibody/hydraulic.rs), 1e-8.
    files = examples.parent / "tests" / "mbdyn_files"
    modes = romdyn.Model(files / "modal_clamped_port.mbd").study().modes()
    first = int(np.flatnonzero(np.array(modes["kind"]) == "dynamic")[0])
    assert modes["description"][first] == "node 2 y 75 %, modal joint 10 mode 1 25 %"
    modal = [s for s in modes["energy"][first] if s.get("element") == "modal joint"][0]
    assert (modal["node"], modal["mode"], modal["state"]) == (10, 1, "mode 1")
    assert modal["share"] == pytest.approx(0.25, abs=1e-10)
    actuator = romdyn.Model(files / "hydraulic_actuator_mass.mbd", set={"F0": 0.0}).study().modes()
    first = int(np.flatnonzero(np.array(actuator["kind"]) == "dynamic")[0])
    shares = {(s.get("element"), s.get("state"), s["component"]): s["share"] for s in actuator["energy"][first]}
    assert shares[(None, None, "z")] == pytest.approx(0.5, abs=1e-8)
    assert shares[("actuator", "chamber 1 pressure", "element")] == pytest.approx(0.25, abs=1e-8)
    assert actuator["error"][first] < 1e-8
    # A FEM node's rotation as an output [rad].
    study = romdyn.Model(files / "modal_floating_force.mbd").study(inputs=["2:Fy"], fem_outputs=["10:C:rz"])
    assert study.linear()["outputs"] == ["modal 10 FEM node C rz [rad]"]


def test_run_returns_what_the_cli_prints(examples, romdyn_cli, tmp_path):
    # Model.run() carries `romdyn run`'s counters and eigenanalyses (Python gets what the CLI
    # gets): the same steps, Newton iterations and factorizations as the CLI's summary line on
    # examples/double_pendulum.mbd, and its eigenanalysis at t = 0 the point-mass double
    # pendulum's omega^2 = (g/L)(2 -+ sqrt 2) (closed form; J = 1e-6 kg m^2 shifts it by
    # about 1e-5 relative, hence rel=1e-4).
    out = subprocess.run([romdyn_cli, "run", examples / "double_pendulum.mbd", "-o", tmp_path / "dp"], check=True, capture_output=True, text=True).stdout
    m = re.search(r"(\d+) steps to .*?, (\d+) Newton iterations \(\+(\d+) for the initial derivatives; (\d+) of all", out)
    h = romdyn.Model(examples / "double_pendulum.mbd").run()
    assert (h["steps"], h["newton_iterations"], h["derivatives_iterations"], h["factorizations"]) == tuple(int(x) for x in m.groups())
    assert len(h["time"]) == h["steps"] + 1 and h["wall_time"] > 0
    assert h["assembly"]["iterations"] >= 0 and set(h["assembly"]) >= {"moved_position", "moved_velocity"}
    [e] = h["eigenanalyses"]
    assert e["time"] == 0.0 and e["every_eigenvalue"] and e["certified"]
    assert (len(e["eigenvalues"]), e["zero"], e["infinite"]) == (4, 32, 10)
    g, length = 9.81, 0.5
    expected = sorted(np.sqrt(g / length * (2 + s * np.sqrt(2))) for s in (-1, 1))
    found = sorted(set(np.round(np.abs(e["eigenvalues"].imag), 9)))
    assert found == pytest.approx(expected, rel=1e-4)
    assert np.all(np.abs(e["eigenvalues"].real) < 1e-9)
