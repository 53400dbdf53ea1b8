"""Scenario files: bodies, materials, contact laws and solver settings (TOML)."""

from __future__ import annotations

import os
from typing import Iterable, Union

from . import _hcm

PathLike = Union[str, "os.PathLike[str]"]


def assignments(values: Union[dict, Iterable[str], None]) -> list[str]:
    """``--set``-style ``key=value`` texts from a mapping (values written as TOML) or
    from texts already in that form."""
    if values is None:
        return []
    if isinstance(values, dict):
        return [f"{key}={toml_value(value)}" for key, value in values.items()]
    return [str(v) for v in values]


def toml_value(value) -> str:
    """A Python value in TOML syntax (numbers, booleans, strings, lists of them)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(float(value)) if isinstance(value, float) else str(value)
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if hasattr(value, "tolist"):
        value = value.tolist()
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    raise TypeError(f"cannot write {value!r} ({type(value).__name__}) as a TOML value")


class Scenario:
    """A scenario, as the ``hcm`` commands' ``--scenario`` and ``--set`` read it."""

    def __init__(self, compiled: _hcm.Scenario) -> None:
        self._scenario = compiled

    @classmethod
    def load(cls, path: PathLike, set=None) -> "Scenario":
        """Reads the scenario file at ``path``; ``set`` overrides values, e.g.
        ``{"contact.0.parameters.damping": 500}`` or ``["body.ball.velocity=[0,0,-1]"]``."""
        return cls(_hcm.Scenario.load(os.fspath(path), assignments(set)))

    @classmethod
    def from_toml(cls, text: str, name: PathLike = "<string>", set=None) -> "Scenario":
        """Parses scenario text; ``name`` stands for its path in messages."""
        return cls(_hcm.Scenario.from_toml(text, os.fspath(name), assignments(set)))

    def with_set(self, set=None, **values) -> "Scenario":
        """This scenario with more overrides (a mapping or ``key=value`` texts)."""
        texts = assignments(set) + assignments(values or None)
        return Scenario(self._scenario.with_set(texts))

    def with_physics(self, physics) -> "Scenario":
        """This scenario with a physics file (a path, or a :class:`~hcm.Physics` from
        ``identify`` or a diagnosis) in place of its laws."""
        if hasattr(physics, "_physics"):
            return Scenario(self._scenario.with_physics_object(physics._physics))
        return Scenario(self._scenario.with_physics(os.fspath(physics)))

    @property
    def name(self) -> str:
        """The scenario's name."""
        return self._scenario.name

    @property
    def path(self) -> str:
        """The scenario file's path (or the name its text was given)."""
        return self._scenario.path

    def to_toml(self) -> str:
        """The scenario as TOML text, every override and physics file applied."""
        return self._scenario.to_toml()

    def __reduce__(self):
        # Pickled as its text (for multiprocessing, Ray, Dask): the same scenario back.
        return (Scenario.from_toml, (self.to_toml(), self.path))

    @property
    def bodies(self) -> list[str]:
        """The bodies' names, in file order."""
        return self._scenario.bodies

    @property
    def contacts(self) -> list[tuple[str, str, str]]:
        """The contacts as ``(body 1, body 2, law name)``, in file order."""
        return self._scenario.contacts

    def __repr__(self) -> str:
        return f"Scenario({self.name!r}, bodies={self.bodies!r})"
