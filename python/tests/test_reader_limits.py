"""Issue 32, finding 1 in Python: inputs that crashed the interpreter (a stack overflow in
Model.run() and romdyn.sweep, 2^N memory) raise a romdyn error naming FILE:LINE:COLUMN,
and the interpreter carries on. The inputs are generated here, as in tests/reliability/reader_limits.rs."""

import pytest

import romdyn

HEAD = "begin: data; problem: initial value; end: data;\n"


def model(cards, force, body_mass="1."):
    """A one-body model; card k of `cards` is on line k + 1, the force's drive on line 10
    after the cards' lines."""
    return (
        f"{HEAD}{cards}"
        "begin: initial value; initial time: 0.; final time: 0.01; time step: 1.e-3; tolerance: 1.e-9; max iterations: 10; end: initial value;\n"
        "begin: control data; structural nodes: 1; rigid bodies: 1; forces: 1; end: control data;\n"
        "begin: nodes;\n    structural: 1, dynamic, null, eye, null, null;\nend: nodes;\n"
        f"begin: elements;\n    body: 1, 1, {body_mass}, null, eye;\n    force: 1, absolute, 1, position, null, 1., 0., 0.,\n        {force};\nend: elements;\n"
    )


def alive(examples):
    """The interpreter still reads and studies a model after the error."""
    study = romdyn.Model(examples / "pendulum.mbd").study(inputs=["2:Mz"], outputs=["2:rz"])
    assert study is not None


def test_a_chain_of_2000_string_drives_raises(examples, tmp_path):
    cards = 'drive caller: 1, string, "Time";\n' + "".join(f'drive caller: {k}, string, "model::drive({k - 1}, Time) + 1.";\n' for k in range(2, 2001))
    path = tmp_path / "chain.mbd"
    path.write_text(model(cards, "reference, 2000"))
    # romdyn.limits::MAX_EVALUATION_DEPTH = 64: card 65 (line 66) is the first refused.
    with pytest.raises(romdyn.ModelError, match=r"chain\.mbd:66:27: error: string drive .*nests 65 evaluations deep"):
        romdyn.Model(path).run()
    alive(examples)


def test_doubling_scalar_functions_raise(examples):
    cards = 'scalar function: "f0", const, 1.;\n' + "".join(f'scalar function: "f{k}", sum, "f{k - 1}", "f{k - 1}";\n' for k in range(1, 25))
    # f_k makes 2^(k+1) - 1 evaluations a call: f16 (131071, line 18) is the first over 1e5.
    with pytest.raises(romdyn.ModelError, match=r"m\.mbd:18:18: error: scalar function \"f16\" makes 131071 evaluations"):
        romdyn.Model.from_text(model(cards, 'scalar function, "f24"'), name="m.mbd")
    alive(examples)


def test_a_sweep_over_deeply_nested_string_drives_reports_every_point(examples, tmp_path):
    # 64 drives of 6 parentheses each: over the 200 levels one thread's evaluators may nest;
    # the sweep's worker threads overflowed their stack before the bound.
    cards = "set: real P = 1.;\n" + 'drive caller: 1, string, "Time";\n' + "".join(f'drive caller: {k}, string, "(((((model::drive({k - 1}, Time)))))) + 1.";\n' for k in range(2, 65))
    path = tmp_path / "c.mbd"
    path.write_text(model(cards, "reference, 64", body_mass="P"))
    r = romdyn.sweep(path, set={"P": [1.0, 2.0]}, inputs=["1:Fx"], outputs=["1:x"], count=1, lowest=1)
    assert list(r.ok) == [False, False]
    for _, _, message in r.failures:
        assert "c.mbd:33:27: expressions nested more than 200 levels deep" in message
    alive(examples)
