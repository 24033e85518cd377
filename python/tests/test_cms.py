"""Issue 35: ``romdyn.cms`` writes the FEM file ``romdyn cms`` writes, and the FEM reader's
warnings are raised as ``romdyn.InputWarning`` (the CLI prints them)."""

import pathlib
import shutil
import subprocess
import warnings

import numpy as np
import pytest

import romdyn

ROOT = pathlib.Path(__file__).resolve().parents[2]
FILES = ROOT / "tests" / "mbdyn_files"
SUBSTRUCTURE = FILES / "cms_substructure.mbd"


def test_cms_writes_the_cli_file(tmp_path, romdyn_cli):
    r = romdyn.cms(str(SUBSTRUCTURE), interface=9, modes=5, output=tmp_path / "py")
    cli = subprocess.run([romdyn_cli, "cms", SUBSTRUCTURE, "--interface", "9", "--modes", "5", "-o", tmp_path / "cli"], capture_output=True, text=True)
    assert cli.returncode == 0, cli.stderr
    # The same numbers (the title names the source file the same way).
    assert (tmp_path / "py.fem").read_text() == (tmp_path / "cli.fem").read_text()
    assert r["nodes"] == [str(n) for n in range(9, 18)]
    # Fixed-interface modes have unit modal mass and stiffness omega^2 (left and right modes
    # paired: phi_L^T M phi_R = 1), to rounding.
    w = np.array(r["fixed_interface_omega"])
    assert np.allclose(np.diag(r["mass"])[:5], 1.0, rtol=1e-10)
    assert np.allclose(np.diag(r["stiffness"])[:5], w**2, rtol=1e-10)
    # The clamped-cantilever bending frequency of the half beam (0.5 m, EJ = 1e3 N m^2,
    # rho A = 1 kg/m): 1.875^2 sqrt(EJ / (rho A l^4)) = 444.7 rad/s; eight lumped beam3
    # nodes give 434.7 (2.2 % low).
    assert abs(w[0] / (1.8751040687**2 * np.sqrt(1e3 / 0.5**4)) - 1) < 0.03
    assert "modal, clamped, 11, from file" in r["card"] and r["summary"].replace("py.fem", "cli.fem") == cli.stdout


def test_fem_reader_warnings_are_printed_and_raised(tmp_path, romdyn_cli):
    # modal_clamped_port.mbd with zeros after record 11's values: MBDyn skips them, romdyn
    # too, with a warning naming the FEM file's line.
    shutil.copy(FILES / "modal_clamped_port.mbd", tmp_path)
    fem = (FILES / "modal_spring_mass.fem").read_text().replace("0.5 0.5 0.5 0. 0. 0.\n", "0.5 0.5 0.5 0. 0. 0.\n0. 0. 0.\n")
    (tmp_path / "modal_spring_mass.fem").write_text(fem)
    cli = subprocess.run([romdyn_cli, "eig", tmp_path / "modal_clamped_port.mbd"], capture_output=True, text=True)
    assert cli.returncode == 0, cli.stderr
    printed = [line for line in cli.stderr.splitlines() if line.startswith("warning: modal 10: ")]
    assert len(printed) == 1 and "skips them" in printed[0], cli.stderr
    model = romdyn.Model(tmp_path / "modal_clamped_port.mbd")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        model.study()
    raised = [str(w.message) for w in caught if w.category is romdyn.InputWarning]
    assert raised == [printed[0][len("warning: "):]]


def test_cms_option_errors_name_the_keyword(tmp_path):
    import pathlib
    sub = romdyn.Model(pathlib.Path(__file__).resolve().parents[2] / "tests" / "mbdyn_files" / "cms_substructure.mbd")
    # The library names the option as Python spells it, never the CLI's flag.
    with pytest.raises(ValueError, match=r"^interface: node 9 is listed twice") as e:
        romdyn.cms(sub, interface=[9, 9], modes=2, output=tmp_path / "x")
    assert "--" not in str(e.value)
