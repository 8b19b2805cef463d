"""Example scenes shipped with linkage_sym.

Each example is a JSON file in the scene format (``docs/scene-format.md``)
in this package; ``README.md`` beside them says what each one is, where it
comes from and how its dimensions were obtained.

These helpers only find and read the files; :func:`load_example` hands the file
to :func:`linkage_sym.scene.load_scene` for validation.

Examples
--------
>>> "crank_rocker" in example_names()
True
>>> example_path("shaper").name
'shaper.json'
>>> example_dict("crank_rocker")["joints"][0]["name"]
'A'
"""

from __future__ import annotations

import json
import pathlib
from importlib import resources

__all__ = ["example_names", "example_path", "example_dict", "load_example"]


def _directory() -> pathlib.Path:
    root = resources.files(__name__)
    if isinstance(root, pathlib.Path):
        return root
    return pathlib.Path(str(root))  # pragma: no cover - non-filesystem loaders


def example_names() -> list[str]:
    """Names of the shipped examples (file stems), sorted."""
    return sorted(p.stem for p in _directory().iterdir() if p.name.endswith(".json"))


def example_path(name: str) -> pathlib.Path:
    """Path of the example's JSON file; ``KeyError`` (listing the names) if unknown."""
    names = example_names()
    if name not in names:
        raise KeyError(f"unknown example {name!r}; examples are: {', '.join(names)}")
    return _directory() / f"{name}.json"


def example_dict(name: str) -> dict:
    """The example's scene as parsed JSON (a fresh dict on every call)."""
    return json.loads(example_path(name).read_text(encoding="utf-8"))


def load_example(name: str):
    """The example loaded and validated by :func:`linkage_sym.scene.load_scene`."""
    from linkage_sym.scene import load_scene

    return load_scene(example_path(name))
