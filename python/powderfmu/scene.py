"""Scene JSON (the keys of `powderfmu analyze`, docs/models.md) to an FMU's start values.

Every scene key is a parameter of the same name in ParticleWallImpact and ContactElement; a key the unit
does not have is an error that names it (fmpy itself would ignore it unless validation is on)."""

from __future__ import annotations

import difflib
import json
from functools import lru_cache
from pathlib import Path
from typing import Any, Mapping

from fmpy import read_model_description


@lru_cache(maxsize=None)
def _variables(fmu: str) -> dict[str, Any]:
    return {v.name: v for v in read_model_description(fmu).modelVariables}


def read_object(path: str | Path, what: str, error: type[Exception] = ValueError) -> dict[str, Any]:
    """A JSON file holding one object, or `error` naming the file and what it should hold."""
    path = Path(path)
    try:
        data = json.loads(path.read_text())
    except FileNotFoundError:
        raise error(f"{path} does not exist") from None
    except json.JSONDecodeError as e:
        raise error(f"{path} is not JSON: {e}") from None
    if not isinstance(data, dict):
        raise error(f"{path} must hold a JSON object ({what})")
    return data


def load(scene: str | Path | Mapping[str, Any]) -> dict[str, Any]:
    """A scene as a dict: a mapping as given, or a JSON file. Keys starting with `comment` are dropped."""
    data = dict(scene) if isinstance(scene, Mapping) else read_object(scene, "scene keys")
    return {k: v for k, v in data.items() if not k.startswith("comment")}


def start_values(fmu: str | Path, scene: str | Path | Mapping[str, Any]) -> dict[str, Any]:
    """The start values of `fmu` for `scene`: every key must be a parameter of the unit, with a value of
    its type (numbers for Reals, strings for the choices)."""
    variables = _variables(str(fmu))
    out: dict[str, Any] = {}
    for key, value in load(scene).items():
        v = variables.get(key)
        if v is None or v.causality != "parameter":
            close = difflib.get_close_matches(key, [n for n, x in variables.items() if x.causality == "parameter"], n=1)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            raise ValueError(f"scene key {key!r} is not a parameter of {Path(fmu).stem}{hint}")
        if v.type == "String":
            if not isinstance(value, str):
                raise ValueError(f"scene key {key!r} = {value!r} must be a string")
        elif v.type == "Real":
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise ValueError(f"scene key {key!r} = {value!r} must be a number [{v.unit or '1'}]")
            value = float(value)
        out[key] = value
    return out
