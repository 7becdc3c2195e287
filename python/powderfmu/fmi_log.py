"""The FMU's own messages: fmi2CallbackFunctions whose logger keeps them, so that a refused call raises
with the unit's words (which parameter, which range) instead of fmpy's bare status."""

from __future__ import annotations

from fmpy import calloc, free
from fmpy.fmi2 import fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE, fmi2CallbackFunctions, fmi2CallbackLoggerTYPE


class Messages:
    """Keep this object alive while the instance lives: ctypes does not hold the callback for the FMU."""

    def __init__(self):
        self.records: list[tuple[int, str]] = []

        def logger(_env, _instance, status, _category, message):
            self.records.append((int(status), message.decode("utf-8", "replace") if message is not None else ""))

        self._logger = fmi2CallbackLoggerTYPE(logger)
        self.callbacks = fmi2CallbackFunctions()
        self.callbacks.logger = self._logger
        self.callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        self.callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)

    def errors(self) -> str:
        """The messages of calls that returned fmi2Error or worse, joined."""
        return "; ".join(m for s, m in self.records if s >= 3)
