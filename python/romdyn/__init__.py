"""romdyn: linear reduced-order models (ROMs) from MBDyn multibody models, for control design.

The same library workflow as the ``romdyn`` command line: read an MBDyn input file
(``set:`` variables overridden from Python), solve a reference (initial state, static
equilibrium or a time of the file's problem), linearize with inputs and outputs, run the
eigenanalysis and build ordinary or descriptor ROMs. SI units throughout: eigenvalues in
rad/s, frequencies in Hz, forces in N, moments in N m, displacements in m, rotations in rad,
times and dCoef in s.

>>> import romdyn
>>> study = romdyn.Model("examples/pendulum.mbd").study(inputs=["2:Mz"], outputs=["2:rz"])
>>> rom = study.reduce(count=1)
>>> sys = rom.to_control()          # python-control StateSpace with input/output names

Warnings: every warning the CLI prints is raised with ``warnings.warn`` under
``RomdynWarning`` (a ``UserWarning``): ``InputWarning`` (what a reader let pass in an
input file: a FEM file's skipped zeros, unequal lumped masses), ``ReferenceWarning`` (not an equilibrium, beams'
update), ``PortWarning`` (an input that moves nothing, an output that sees nothing),
``EigenanalysisWarning`` (sparse route not certified), ``ModeSelectionWarning`` (modes below
the band, modes that add nothing, damping not applied) and ``AccuracyWarning`` with
``StaticGainWarning``, ``ResponseWarning`` and ``TransmissibilityWarning`` (the ROM departs
from the full model: ``Study.reduce()`` runs the CLI's check on the response grid). Filter
them as any warning, e.g. ``warnings.simplefilter("error", romdyn.AccuracyWarning)``.

Errors carry the CLI's messages: ``ModelError`` (a subclass of ``RomdynError``) for an
input file reads ``FILE:LINE:COLUMN: error: ...`` with the line and a caret.
"""

from ._romdyn import (
    AccuracyWarning,
    InputWarning,
    EigenanalysisWarning,
    Model,
    ModelError,
    ModeSelectionWarning,
    PortWarning,
    ReferenceWarning,
    ResponseWarning,
    Rom,
    RomdynError,
    RomdynWarning,
    StaticGainWarning,
    Study,
    TransmissibilityWarning,
    validate,
)
from ._romdyn import cms as _cms
from ._sweep import SweepResult, sweep

__all__ = [
    "Model", "Study", "Rom", "RomdynError", "ModelError", "load", "sweep", "SweepResult", "validate", "cms",
    "RomdynWarning", "InputWarning", "ReferenceWarning", "PortWarning", "EigenanalysisWarning", "ModeSelectionWarning",
    "AccuracyWarning", "StaticGainWarning", "ResponseWarning", "TransmissibilityWarning",
]


def load(path, set=None, beam_update=None):
    """Reads the MBDyn input file ``path``; ``set`` maps ``set:`` variables to the values
    replacing the file's (its SI units); ``beam_update``: "auto" (default: MBDyn 1.7.3's beam
    update in ``run()`` and at a reference time, path independent otherwise), "path-independent"
    or "incremental" (the CLI's ``--beam-update``). Same as
    ``Model(path, set=set, beam_update=beam_update)``."""
    return Model(path, set=set, beam_update=beam_update)


def cms(model, interface, modes, output, reference=None, load_steps=10, set=None):
    """Reduces a substructure to MBDyn's modal-joint FEM file ``OUTPUT.fem`` with Craig–Bampton
    modes, as ``romdyn cms MODEL --interface … --modes N -o OUTPUT``: ``model`` a ``Model`` or
    the path of an MBDyn file (nodes, bodies, beams, deformable springs; no joints), ``interface``
    structural node labels (six constraint modes each: unit displacement [m], rotation [rad]),
    ``modes`` fixed-interface normal modes (the lowest, unit modal mass). ``reference``,
    ``load_steps`` as for ``Model.study()``; ``set`` as for ``load`` when ``model`` is a path.
    Returns {"path", "nodes", "fixed_interface_omega" [rad/s], "mass", "stiffness", "card",
    "summary"}."""
    if not isinstance(model, Model):
        model = Model(model, set=set)
    if isinstance(interface, int):
        interface = [interface]
    return _cms(model, list(interface), modes, output, reference=reference, load_steps=load_steps)
