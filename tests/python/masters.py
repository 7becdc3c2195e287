"""Model Exchange masters that behave like other hosts than fmpy's `simulate_fmu`, built on fmpy's own
CVode (`fmpy.sundials.CVodeSolver`) with OMSimulator's minimum step:

- inputs held between samples and set in Continuous-Time Mode, with no event and no restart when they
  change (OMSimulator's sampled inputs);
- or inputs set at the samples in Event Mode (fmusim's input events);
- CVode restarted after an event only when the unit says its states changed
  (`valuesOfContinuousStatesChanged`), as fmusim does, or after every event, as fmpy does.

fmpy's `simulate_fmu` restarts after every event and treats every input sample as one."""

from __future__ import annotations

import ctypes
from dataclasses import dataclass, field

import numpy as np

from fmu_support import Unit


def read(unit: Unit, fmu, name: str) -> float:
    """One output by name, through the getter of its type."""
    v = unit.variables[name]
    return fmu.getInteger([v.valueReference])[0] if v.type == "Integer" else fmu.getReal([v.valueReference])[0]


class _NoInput:
    """The solver's input hook: the master sets the inputs itself."""

    def apply(self, time, continuous=True, discrete=True, after_event=False):
        return None


@dataclass
class HeldInputRun:
    """What one run recorded: at each sample time, the outputs with the inputs of the interval that ends
    there (before the next sample's inputs are set), and the counts."""

    time: np.ndarray
    outputs: dict[str, np.ndarray]
    steps: int
    events: int
    restarts: int
    told: int = 0
    event_times: list = field(default_factory=list)


def held_input_run(
    unit: Unit,
    start_values: dict,
    samples: np.ndarray,
    inputs: list[str],
    outputs: list[str],
    rtol: float = 1e-8,
    min_step: float = 1e-12,
    input_events: bool = False,
    restart: str = "told",
) -> HeldInputRun:
    """Runs `unit` in Model Exchange from samples["time"][0] to its last time with each input held at
    its sample value until the next sample. `input_events`: set the inputs in Event Mode (fmusim);
    otherwise in Continuous-Time Mode with no event (OMSimulator). `restart`: "told" restarts CVode after
    an event only when the unit reports valuesOfContinuousStatesChanged (fmusim); "always" after every
    event (fmpy)."""
    from fmpy.sundials import CVodeSolver
    from fmpy.sundials.libraries import sundials_cvode

    md = unit.md
    nx, nz = md.numberOfContinuousStates, md.numberOfEventIndicators
    vr_in = [unit.vr[n] for n in inputs]
    t = samples["time"]
    fmu = unit.model("held")
    fmu.setupExperiment(tolerance=rtol, startTime=float(t[0]))
    unit.set_start_values(fmu, {**unit.defaults, **start_values})
    fmu.setReal(vr_in, [float(samples[n][0]) for n in inputs])
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    run = HeldInputRun(time=t[1:].copy(), outputs={n: np.zeros(t.size - 1) for n in outputs}, steps=0, events=0, restarts=0)

    def event_iteration(time: float) -> bool:
        changed = False
        while True:
            info = fmu.newDiscreteStates()
            changed |= bool(info[2] or info[3])
            if not info[0]:
                break
        run.told += int(changed)
        run.event_times.append(time)
        return changed

    event_iteration(float(t[0]))
    fmu.enterContinuousTimeMode()
    solver = CVodeSolver(
        nx=nx, nz=nz, get_x=fmu.getContinuousStates, set_x=fmu.setContinuousStates, get_dx=fmu.getDerivatives,
        get_z=fmu.getEventIndicators, get_nominals=fmu.getNominalsOfContinuousStates, set_time=fmu.setTime,
        input=_NoInput(), startTime=float(t[0]), maxStep=float(t[-1] - t[0]) / 50.0, relativeTolerance=rtol, maxNumSteps=100_000,
    )
    set_min = sundials_cvode.CVodeSetMinStep
    set_min.argtypes = [ctypes.c_void_p, ctypes.c_double]
    assert set_min(solver.cvode_mem, min_step) == 0
    num_steps = sundials_cvode.CVodeGetNumSteps
    num_steps.argtypes = [ctypes.c_void_p, ctypes.POINTER(ctypes.c_long)]

    def cvode_steps() -> int:
        n = ctypes.c_long(0)
        num_steps(solver.cvode_mem, ctypes.byref(n))
        return n.value

    def handle_event(time: float, inputs_now: list[float] | None = None) -> None:
        """Event Mode: the inputs of this time if given (an input event), the event iteration, and the
        restart the policy asks for."""
        fmu.enterEventMode()
        if inputs_now is not None:
            fmu.setReal(vr_in, inputs_now)
        told = event_iteration(time)
        fmu.enterContinuousTimeMode()
        if restart == "always" or told:
            run.steps += cvode_steps()
            solver.reset(time)
            run.restarts += 1

    # The FMI 2.0 calling sequence (Sec. 3.2.2): after a step, the inputs of the new time, then
    # fmi2CompletedIntegratorStep, which may ask for Event Mode.
    time = float(t[0])
    for k in range(1, t.size):
        while time < t[k]:
            state_event, _, time = solver.step(time, float(t[k]))
            fmu.setTime(time)
            step_event = fmu.completedIntegratorStep()[0]
            if state_event or step_event:
                run.events += 1
                handle_event(time)
        for name in outputs:
            run.outputs[name][k - 1] = read(unit, fmu, name)
        if k + 1 < t.size:
            values = [float(samples[n][k]) for n in inputs]
            if input_events:
                handle_event(time, values)
            else:
                fmu.setReal(vr_in, values)
                if fmu.completedIntegratorStep()[0]:
                    run.events += 1
                    handle_event(time)
    run.steps += cvode_steps()
    fmu.terminate()
    fmu.freeInstance()
    return run


def held_input_cs(unit: Unit, start_values: dict, samples: np.ndarray, inputs: list[str], outputs: list[str]) -> dict[str, np.ndarray]:
    """The same held inputs through Co-Simulation: one fmi2DoStep per sample interval with the inputs of
    its start; the outputs read at its end, as `held_input_run` reads them."""
    t = samples["time"]
    vr_in = [unit.vr[n] for n in inputs]
    fmu = unit.slave("held_cs")
    fmu.setupExperiment(startTime=float(t[0]))
    unit.set_start_values(fmu, {**unit.defaults, **start_values})
    fmu.setReal(vr_in, [float(samples[n][0]) for n in inputs])
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    out = {n: np.zeros(t.size - 1) for n in outputs}
    for k in range(1, t.size):
        fmu.setReal(vr_in, [float(samples[n][k - 1]) for n in inputs])
        fmu.doStep(currentCommunicationPoint=float(t[k - 1]), communicationStepSize=float(t[k] - t[k - 1]))
        for name in outputs:
            out[name][k - 1] = read(unit, fmu, name)
    fmu.terminate()
    fmu.freeInstance()
    return out
