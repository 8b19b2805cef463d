"""The cache of compiled mechanisms (no SymPy here).

A compiled mechanism is a JSON *artifact*: the Python source of its generated
functions and the layout the runtime needs.  It is keyed on the mechanism's
*topology* -- its links, joints, drivers, link frames, which points coincide
with a frame origin, which effects and outputs act -- never on its
dimensions, masses or loads, which are arguments of the generated functions.
Every scene of one topology therefore shares one artifact, and loading it
needs neither SymPy nor a derivation.

The key also holds a hash of the sources that generate and run the code
(:data:`GENERATOR_PACKAGES`) and SymPy's version, so an artifact written by
other generators is never served: no hand-bumped format number to forget.

The cache lives in memory (per process) and on disk in
``$LINKAGE_SYM_CACHE``, else the platform's per-user cache folder
(``$XDG_CACHE_HOME/linkage_sym`` or ``~/.cache/linkage_sym`` on Linux,
``~/Library/Caches/linkage_sym`` on macOS, ``%LOCALAPPDATA%\\linkage_sym\\Cache``
on Windows).  A disk cache that cannot be used -- ``$LINKAGE_SYM_CACHE`` naming a
file or a path under one, a folder that cannot be read or written -- gives one
warning and the run goes on without it (the in-memory cache still serves the
process): the cache only saves time, it never ends a run.
"""

from __future__ import annotations

import hashlib
import json
import os
import sys
import warnings
from importlib import metadata
from pathlib import Path

from linkage_sym.codegen.artifact import Artifact
from linkage_sym.model import Scene
from linkage_sym.structure.parameters import ParameterTable

GENERATOR_PACKAGES = ("symbolic", "codegen", "structure", "model")
"""Subpackages of linkage_sym whose sources shape or run the generated code."""

_MEMORY: dict[str, dict] = {}
_WARNED: set[str] = set()
_SOURCE_HASH: list[str] = []


def generator_files() -> list[Path]:
    """The source files hashed into every key, in a fixed order."""
    root = Path(__file__).resolve().parent.parent
    return sorted(f for pkg in GENERATOR_PACKAGES for f in (root / pkg).glob("*.py"))


def source_hash() -> str:
    """SHA-256 of the generator sources (:func:`generator_files`), computed once per process."""
    if not _SOURCE_HASH:
        h = hashlib.sha256()
        for f in generator_files():
            h.update(f.name.encode() + b"\0" + f.read_bytes() + b"\0")
        _SOURCE_HASH.append(h.hexdigest())
    return _SOURCE_HASH[0]


def cache_dir() -> Path:
    """Where artifacts are kept on disk (see the module docstring)."""
    env = os.environ.get("LINKAGE_SYM_CACHE")
    if env:
        return Path(env)
    home = Path(os.path.expanduser("~"))
    if sys.platform == "win32":
        return Path(os.environ.get("LOCALAPPDATA") or home / "AppData" / "Local") / "linkage_sym" / "Cache"
    if sys.platform == "darwin":
        return home / "Library" / "Caches" / "linkage_sym"
    return Path(os.environ.get("XDG_CACHE_HOME") or home / ".cache") / "linkage_sym"


def sympy_version() -> str | None:
    """The installed SymPy's version, read without importing SymPy."""
    try:
        return metadata.version("sympy")
    except metadata.PackageNotFoundError:  # pragma: no cover - SymPy is a dependency
        return None


def signature(scene: Scene) -> dict:
    """Everything about a scene that shapes its generated code, and nothing else."""
    from linkage_sym._version import __version__

    table = ParameterTable(scene)
    frames = table.frames
    at_origin = [
        [link, j.name]
        for link in frames
        for j in scene.joints
        if link in j.links and table.coincides_with_origin(link, j.at)
    ]
    eff = scene.effects
    return {
        "generators": source_hash(),
        "linkage_sym": __version__,
        "sympy": sympy_version(),
        "links": [[k.name, k.com is not None, k.mass > 0, k.inertia > 0] for k in scene.links],
        # a mesh's carrier and kind enter its rolling law
        "joints": [[j.name, j.type, list(j.links)]
                   + ([j.carrier, bool(j.internal)] if j.type == "G" else [])
                   for j in scene.joints],
        "frames": [[fr.link, fr.u, fr.v] for fr in frames.values()],
        "at_origin": at_origin,
        "drivers": [[d.joint, d.kind, d.toward] for d in scene.drivers],
        "loads": [[ld.link, ld.force is not None, bool(ld.torque)] for ld in scene.loads],
        "effects": [bool(eff.inertia), eff.gravity is not None, bool(eff.loads)],
        # the acting springs: their ends' links (or joint) and whether a damper acts
        "springs": [[k.name, list(k.links or ()), k.joint, k.damping != 0.0]
                    for k in scene.active_springs],
        "outputs": sorted(scene.outputs),
        **_friction_signature(scene),
    }


def _friction_signature(scene: Scene) -> dict:
    """The joints whose friction acts (contract part two), where any does: their friction
    enters the force blocks; a scene without it keeps the signature it had."""
    names = [j.name for j in scene.joints if scene.effects.friction and j.friction is not None
             and j.friction.coefficient > 0]
    return {"friction": names} if names else {}


def key_of(sig: dict) -> str:
    return hashlib.sha256(json.dumps(sig, sort_keys=True).encode()).hexdigest()[:24]


def load(key: str) -> dict | None:
    """The artifact stored under ``key`` (memory first, then disk), or ``None``."""
    art = _MEMORY.get(key)
    if art is not None:
        return art
    path = cache_dir() / f"{key}.json"
    try:
        text = path.read_text()
    except FileNotFoundError:
        return None
    except OSError as err:  # not a folder, not readable: run without the disk cache
        _unusable(path.parent, err)
        return None
    art = json.loads(text)
    if art.get("key") != key:  # pragma: no cover - a foreign file under our name
        return None
    _MEMORY[key] = art
    return art


def store(key: str, artifact: dict) -> None:
    """Keep ``artifact`` in memory and write it to disk (a warning if that fails)."""
    _MEMORY[key] = artifact
    d = cache_dir()
    try:
        d.mkdir(parents=True, exist_ok=True)
        tmp = d / f".{key}.{os.getpid()}.tmp"
        tmp.write_text(json.dumps(artifact))
        os.replace(tmp, d / f"{key}.json")
    except OSError as err:
        _unusable(d, err)


def _unusable(folder: Path, err: OSError) -> None:
    """The one rule for a disk cache that cannot be used: warn (once per folder) and go on."""
    if str(folder) in _WARNED:
        return
    _WARNED.add(str(folder))
    warnings.warn(f"compiled-mechanism cache {str(folder)!r} cannot be used "
                  f"({err.strerror or err}); running without it", stacklevel=3)


def clear_memory() -> None:
    """Forget the in-memory artifacts (the disk cache stays)."""
    _MEMORY.clear()
    _ARTIFACTS.clear()


_ARTIFACTS: dict = {}


def load_artifact(key: str):
    """The :class:`~linkage_sym.codegen.artifact.Artifact` stored under ``key``, or ``None``:
    :func:`load`'s JSON read into records once per process."""
    got = _ARTIFACTS.get(key)
    if got is None:
        d = load(key)
        if d is None:
            return None
        got = _ARTIFACTS[key] = Artifact.from_dict(d)
    return got


def store_artifact(key: str, artifact) -> None:
    """Keep ``artifact`` (records) in memory and its JSON (:func:`store`)."""
    _ARTIFACTS[key] = artifact
    store(key, artifact.to_dict())
