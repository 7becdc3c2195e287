"""fmpy's validation of both FMUs, and the interfaces and capabilities they declare."""

import pytest
from fmpy.validation import validate_fmu


@pytest.fixture(params=["impact", "contact"])
def unit(request):
    return request.getfixturevalue(request.param)


def test_validate_fmu_finds_no_problem(unit):
    problems = validate_fmu(str(unit.path))
    assert problems == [], f"{unit.name}: " + "\n".join(problems)


def test_declares_model_exchange_and_co_simulation(unit):
    md = unit.md
    assert md.fmiVersion == "2.0"
    assert md.modelName == unit.name
    assert md.modelExchange is not None and md.modelExchange.modelIdentifier == unit.name
    assert md.coSimulation is not None and md.coSimulation.modelIdentifier == unit.name


def test_declares_saved_states_and_variable_steps(unit):
    for interface in (unit.md.modelExchange, unit.md.coSimulation):
        assert interface.canGetAndSetFMUstate
        assert interface.canSerializeFMUstate
    assert unit.md.coSimulation.canHandleVariableCommunicationStepSize


def test_inputs_and_outputs_of_the_brief(unit):
    by_causality = {}
    for v in unit.md.modelVariables:
        by_causality.setdefault(v.causality, set()).add(v.name)
    inputs = {"wall_displacement", "wall_velocity"}
    outputs = {"force", "overlap", "contact_state", "max_overlap", "plastic_overlap", "pull_off_force", "dissipated_energy"}
    if unit.name == "ParticleWallImpact":
        # The oblique impact (issue 33): the wall's motion along itself in, the motion along the wall,
        # the spin and the tangential contact out.
        inputs |= {"wall_tangential_velocity"}
        outputs |= {"sphere_position", "sphere_velocity", "tangential_velocity", "angular_velocity", "tangential_force", "sliding", "rebound_angle"}
        assert unit.variables["sliding"].type == "Boolean"
    else:
        # ContactElement in shear (issue 33): the wall's displacement along itself and its rate in, the
        # tangential force and the spring's state out.
        inputs |= {"wall_tangential_displacement", "wall_tangential_velocity"}
        outputs |= {"tangential_force", "sliding"}
        assert unit.variables["sliding"].type == "Boolean"
    assert by_causality["input"] == inputs
    assert by_causality["output"] == outputs
    assert unit.variables["contact_state"].type == "Integer"
    assert unit.variables["contact_model"].type == "String"
    assert {"particle_radius", "surface_energy", "restitution_coefficient", "initial_gap"} <= by_causality["parameter"]
