"""FMU instances the package creates: extracted once per process, model descriptions read once, the unit's
own messages kept (fmi2CallbackFunctions whose logger stores them) so that a refused call raises with the
unit's words (which parameter, which range) instead of fmpy's bare status."""

from __future__ import annotations

import atexit
import shutil
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping

from fmpy import calloc, extract, free, read_model_description
from fmpy.fmi2 import (
    FMU2Slave,
    fmi2CallbackAllocateMemoryTYPE,
    fmi2CallbackFreeMemoryTYPE,
    fmi2CallbackFunctions,
    fmi2CallbackLoggerTYPE,
)


@dataclass
class LogRecord:
    """One message the unit logged: its instance, status (fmi2OK = 0 ... fmi2Fatal = 4), category, text."""

    instance: str
    status: int
    category: str
    message: str


class Messages:
    """fmi2CallbackFunctions whose logger keeps every message in `records`. Keep this object alive while
    the instance lives: ctypes does not hold the callback for the FMU."""

    def __init__(self) -> None:
        self.records: list[LogRecord] = []

        def text(b: bytes | None) -> str:
            return b.decode("utf-8", "replace") if b is not None else ""

        def logger(_env, instance, status, category, message):
            self.records.append(LogRecord(text(instance), int(status), text(category), text(message)))

        self._logger = fmi2CallbackLoggerTYPE(logger)
        self.callbacks = fmi2CallbackFunctions()
        self.callbacks.logger = self._logger
        self.callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        self.callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)

    def messages(self, min_status: int = 0) -> list[str]:
        """The texts of the messages whose status is at least `min_status`."""
        return [r.message for r in self.records if r.status >= min_status]

    def errors(self) -> str:
        """The messages of calls that returned fmi2Error or worse, joined."""
        return "; ".join(self.messages(3))

    def clear(self) -> None:
        self.records.clear()


class RefusedStart(ValueError):
    """The unit refused its start values; the message is the unit's."""


def set_values(p, variables: Mapping[str, Any], values: Mapping[str, Any]) -> None:
    """Start values by type (fmpy's setters take lists)."""
    for key, value in values.items():
        v = variables[key]
        if v.type == "String":
            p.setString([v.valueReference], [value])
        elif v.type in ("Integer", "Enumeration"):
            p.setInteger([v.valueReference], [int(value)])
        elif v.type == "Boolean":
            p.setBoolean([v.valueReference], [bool(value)])
        else:
            p.setReal([v.valueReference], [float(value)])


def cosimulation(fmu: Path, name: str, start: Mapping[str, Any]) -> tuple[FMU2Slave, Messages]:
    """An initialized Co-Simulation instance with these start values; a refusal raises RefusedStart with
    the unit's own message."""
    md = description(fmu)
    variables = {v.name: v for v in md.modelVariables}
    log = Messages()
    p = FMU2Slave(guid=md.guid, unzipDirectory=extracted(fmu), modelIdentifier=md.coSimulation.modelIdentifier, instanceName=name)
    p.instantiate(callbacks=log.callbacks)
    p._powderfmu_log = log  # the callbacks live as long as the instance
    try:
        p.setupExperiment(startTime=0.0)
        set_values(p, variables, start)
        p.enterInitializationMode()
        p.exitInitializationMode()
    except Exception as e:  # noqa: BLE001 - the unit's message says what was wrong
        p.freeInstance()
        raise RefusedStart(log.errors() or str(e)) from None
    return p, log


_DESCRIPTIONS: dict[str, Any] = {}


def description(fmu: Path):
    key = str(Path(fmu).resolve())
    if key not in _DESCRIPTIONS:
        _DESCRIPTIONS[key] = read_model_description(key)
    return _DESCRIPTIONS[key]


_EXTRACTED: dict[str, str] = {}


def extracted(fmu: Path) -> str:
    """The FMU unzipped once per process (every instance loads the same library)."""
    key = str(fmu.resolve())
    if key not in _EXTRACTED:
        _EXTRACTED[key] = extract(key)
        atexit.register(shutil.rmtree, _EXTRACTED[key], True)
    return _EXTRACTED[key]


