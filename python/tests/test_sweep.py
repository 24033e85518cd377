"""romdyn.sweep locally and on Dask (issue 15)."""

import pathlib

import numpy as np
import pytest

import romdyn

from test_study import omega

OPTIONS = dict(inputs=["2:Mz"], outputs=["2:rz"], count=1, lowest=1)


def test_length_sweep_matches_the_closed_form(examples):
    r = romdyn.sweep(examples / "pendulum.mbd", set={"L": "0.5:4:8"}, **OPTIONS)
    assert r.A.shape == (2, 2, 8) and r.ok.all()
    lengths = r.parameters[:, 0]
    assert np.allclose(lengths, np.linspace(0.5, 4, 8), rtol=0, atol=1e-15)
    # omega = sqrt(M G L / (J + M L^2)) at each point, 1e-6 relative.
    assert np.allclose(r.modes[:, 0].imag, omega(lengths), rtol=1e-6, atol=0)
    # ROM static gain 1/(M G L) at each point.
    assert np.allclose(r.rom_static_gain[0, 0, :], 1 / (9.81 * lengths), rtol=1e-6, atol=0)


def test_failing_point_is_reported_and_the_others_kept(examples):
    r = romdyn.sweep(examples / "pendulum.mbd", set={"M": [1.0, -1.0, 2.0]}, **OPTIONS)
    assert list(r.ok) == [True, False, True]
    [(k, values, message)] = r.failures
    assert (k, values) == (1, {"M": -1.0})
    assert "pendulum.mbd:45:17: error: negative mass -1" in message
    assert np.isnan(r.A[:, :, 1]).all() and not np.isnan(r.A[:, :, [0, 2]]).any()
    assert np.allclose(r.modes[[0, 2], 0].imag, [omega(1.0, 1.0), omega(1.0, 2.0)], rtol=1e-6)


def test_beam_update_option_is_checked(examples):
    # The CLI's --beam-update; the pendulum has no beams, so both updates give its closed form.
    r = romdyn.sweep(examples / "pendulum.mbd", set={"L": [1.0]}, beam_update="incremental", **OPTIONS)
    assert r.ok.all() and np.allclose(r.modes[:, 0].imag, omega(np.array([1.0])), rtol=1e-6, atol=0)
    with pytest.raises(Exception, match="beam_update.*'sideways'"):
        romdyn.sweep(examples / "pendulum.mbd", set={"L": [1.0]}, beam_update="sideways", **OPTIONS)


def test_dask_local_cluster_gives_byte_identical_arrays(examples):
    distributed = pytest.importorskip("distributed")
    local = romdyn.sweep(examples / "pendulum.mbd", set={"L": "0.5:4:8", "M": [1.0, -1.0]}, **OPTIONS)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        remote = romdyn.sweep(examples / "pendulum.mbd", set={"L": "0.5:4:8", "M": [1.0, -1.0]}, executor=client.get_executor(), **OPTIONS)
    for name in ["A", "B", "C", "D", "E", "modes", "parameters", "rom_static_gain", "full_static_gain", "mode_mac", "state_tracks"]:
        assert getattr(local, name).tobytes() == getattr(remote, name).tobytes(), name
    assert local.errors == remote.errors and sum(1 for e in remote.errors if e) == 8
    assert remote.inputs == ["node 2 Mz [N m]"]


def test_threads_and_lowest_are_bounded_as_the_cli_bounds_jobs_and_lowest(examples):
    # The CLI's --jobs and --lowest checks (romdyn::sweep::worker_threads, check_lowest).
    path = examples / "pendulum.mbd"
    options = dict(OPTIONS, lowest=1)
    with pytest.raises(ValueError, match="threads: 0: need at least 1 job"):
        romdyn.sweep(path, set={"L": "1:2:2"}, threads=0, **options)
    with pytest.raises(ValueError, match="lowest: 20000: at most 10000 modes"):
        romdyn.sweep(path, set={"L": "1:2:2"}, **dict(OPTIONS, lowest=20000))
    # More threads than cores: reduced to the cores, with a RomdynWarning, and the sweep runs.
    with pytest.warns(romdyn.RomdynWarning, match="threads: 1000: this machine runs"):
        r = romdyn.sweep(path, set={"L": "1:2:2"}, threads=1000, **options)
    assert r.ok.all()


CROSSING = dict(inputs=["2:Fx", "2:Fy"], outputs=["2:x", "2:y"], count=2, lowest=2)


def crossing_file():
    # A mass M = 2 kg on springs KX = 250 N/m (x) and KY (y): modes ±j sqrt(KX/M), ±j sqrt(KY/M).
    return pathlib.Path(__file__).resolve().parents[2] / "tests" / "mbdyn_files" / "crossing_modes.mbd"


def test_tracked_modes_follow_the_crossing_with_their_labels():
    r = romdyn.sweep(crossing_file(), set={"KY": "100:400:8"}, **CROSSING)
    ky = r.parameters[:, 0]
    assert list(r.mode_labels) == ["node 2 y 100 %", "node 2 x 100 %"]
    # Closed form along each branch, 1e-8 relative: the y mode keeps its column after the crossing.
    assert np.allclose(r.modes[:, 0].imag, np.sqrt(ky / 2.0), rtol=1e-8, atol=0)
    assert np.allclose(r.modes[:, 1].imag, np.sqrt(250.0 / 2.0), rtol=1e-8, atol=0)
    assert (r.mode_mac > 1 - 1e-12).all()
    assert list(r.mode_crossing[:, 0]) == [False] * 4 + [True] + [False] * 3
    assert r.mode_flags[4] == "modes 1, 2 crossed"
    assert (r.state_tracks == np.array([[1], [1], [2], [2]])).all()
    assert "mode 1 (node 2 y 100 %) freq [Hz]" in r.table.splitlines()[0]


def test_interpolated_rom_at_a_midpoint_has_the_closed_form_error():
    r = romdyn.sweep(crossing_file(), set={"KY": "100:400:8"}, **CROSSING)
    rom = r.interpolate(KY=250.0, check=True)
    # Linear interpolation of A's entries ±ω between KY = 228.57 and 271.43 gives the mean
    # of the two ω: eigenvalue error |mean − ω(250)|/ω(250) = 9.20e-4 (ω = sqrt(KY/M)).
    w = lambda k: np.sqrt(k / 2.0)
    a, b = r.parameters[3, 0], r.parameters[4, 0]
    expected = abs((w(a) + w(b)) / 2 - w(250.0)) / w(250.0)
    assert abs(rom["check"]["eigenvalues"] - expected) < 1e-6 * expected
    assert max(rom["check"][x] for x in "ABCD") < 5e-3
    assert rom["A"].shape == (4, 4) and rom["exact"]["A"].shape == (4, 4) and rom["states"][0] == "mode 1 re"
    # At a design point the interpolation is that point's ROM.
    at = r.interpolate(KY=r.parameters[2, 0])
    assert np.array_equal(at["A"], r.A[:, :, 2])
    with pytest.raises(ValueError, match="outside the sweep's values 100 to 400"):
        r.interpolate(KY=450.0)
    with pytest.raises(ValueError, match="one value for each swept parameter"):
        r.interpolate(KX=1.0)


def test_a_sweep_of_discrete_roms_and_the_refused_reductions(examples):
    import scipy.linalg

    cont = romdyn.sweep(examples / "pendulum.mbd", set={"L": [1.0, 2.0]}, **OPTIONS)
    disc = romdyn.sweep(examples / "pendulum.mbd", set={"L": [1.0, 2.0]}, sample_rate=2048.0, **OPTIONS)
    # Zero-order hold on the same modal states: Ad = expm(A / 2048) point by point (1e-12).
    for k in range(2):
        assert np.allclose(disc.A[:, :, k], scipy.linalg.expm(cont.A[:, :, k] / 2048.0), rtol=0, atol=1e-12)
    with pytest.raises(ValueError, match=r"^balanced: "):
        romdyn.sweep(examples / "pendulum.mbd", set={"L": [1.0]}, balanced=1, **OPTIONS)
