"""The compiled-mechanism cache cannot serve code from other generators.

The key holds a hash of the generator sources (``cache.generator_files``) and
SymPy's version: an artifact written before a generator changed is not found
afterwards, with no format number to bump by hand.
"""

from __future__ import annotations

import pytest

from linkage_sym.codegen import cache
from linkage_sym.codegen.compile import compile_mechanism
from linkage_sym.examples import load_example


@pytest.fixture
def fresh_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("LINKAGE_SYM_CACHE", str(tmp_path / "cache"))
    monkeypatch.setattr(cache, "_SOURCE_HASH", [])
    cache.clear_memory()
    yield tmp_path
    cache.clear_memory()


def test_every_generator_source_is_hashed():
    names = {f"{f.parent.name}/{f.name}" for f in cache.generator_files()}
    assert {"codegen/compile.py", "codegen/runtime.py", "symbolic/mechanism.py",
            "structure/parameters.py"} <= names


def test_a_changed_generator_invalidates_the_entry(fresh_cache, monkeypatch):
    scene = load_example("crank_rocker")
    compile_mechanism(scene)  # derived and stored
    key = cache.key_of(cache.signature(scene))
    assert (fresh_cache / "cache" / f"{key}.json").exists()
    cache.clear_memory()
    assert cache.load(key) is not None  # found again while the sources are the same
    # one generator source edited (a copy stands in for it)
    files = cache.generator_files()
    edited = fresh_cache / files[0].name
    edited.write_bytes(files[0].read_bytes() + b"\n# changed\n")
    monkeypatch.setattr(cache, "generator_files", lambda: [edited, *files[1:]])
    monkeypatch.setattr(cache, "_SOURCE_HASH", [])
    new_key = cache.key_of(cache.signature(scene))
    assert new_key != key
    assert cache.load(new_key) is None


def test_another_sympy_version_invalidates_the_entry(fresh_cache, monkeypatch):
    scene = load_example("crank_rocker")
    key = cache.key_of(cache.signature(scene))
    monkeypatch.setattr(cache, "sympy_version", lambda: "0.0.1")
    assert cache.key_of(cache.signature(scene)) != key


def test_the_cache_folder_follows_the_platform(monkeypatch, tmp_path):
    monkeypatch.delenv("LINKAGE_SYM_CACHE", raising=False)
    monkeypatch.setenv("HOME", str(tmp_path))
    monkeypatch.delenv("XDG_CACHE_HOME", raising=False)
    monkeypatch.setattr(cache.sys, "platform", "linux")
    assert cache.cache_dir() == tmp_path / ".cache" / "linkage_sym"
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "x"))
    assert cache.cache_dir() == tmp_path / "x" / "linkage_sym"
    monkeypatch.setattr(cache.sys, "platform", "darwin")
    assert cache.cache_dir() == tmp_path / "Library" / "Caches" / "linkage_sym"
    monkeypatch.setattr(cache.sys, "platform", "win32")
    monkeypatch.setenv("LOCALAPPDATA", str(tmp_path / "L"))
    assert cache.cache_dir() == tmp_path / "L" / "linkage_sym" / "Cache"


@pytest.mark.parametrize("where", ["a file", "under a file", "read-only folder"])
def test_an_unusable_cache_folder_warns_once_and_is_not_used(fresh_cache, monkeypatch, where):
    """``$LINKAGE_SYM_CACHE`` naming a file (or a path under one) ended the run with
    'Not a directory' (exit 1 on the command line) where a read-only folder only warned:
    one rule now, a single warning and the run goes on without the disk cache.  The
    read-only folder is simulated (writing refused), as root may write in any folder."""
    blocker = fresh_cache / "blocker"
    blocker.write_text("not a folder")
    if where == "a file":
        monkeypatch.setenv("LINKAGE_SYM_CACHE", str(blocker))
    elif where == "under a file":
        monkeypatch.setenv("LINKAGE_SYM_CACHE", str(blocker / "cache"))
    else:
        def refuse(self, *args, **kwargs):
            raise PermissionError(13, "Permission denied", str(self))
        monkeypatch.setattr(cache.Path, "write_text", refuse)
    monkeypatch.setattr(cache, "_WARNED", set())
    key = "0" * 24
    with pytest.warns(UserWarning, match="cannot be used .*running without it") as got:
        assert cache.load(key) is None
        cache.store(key, {"key": key})
    assert len(got) == 1  # once, however often the disk cache is tried
    assert cache.load(key) == {"key": key}  # the in-memory cache still serves the process
    assert blocker.read_text() == "not a folder"


@pytest.mark.slow
def test_the_page_artifact_is_cached_apart_from_numpys(fresh_cache, monkeypatch):
    """The page's JavaScript artifact is stored under its own key (never served as the
    NumPy one, nor the reverse); read back from disk it prints the same page script as a
    fresh derivation, and a scene of the same topology with other dimensions derives
    nothing (the derivation's builder is never called)."""
    from linkage_sym.codegen import javascript
    from linkage_sym.codegen.javascript import mechanism_script, page_artifact
    from linkage_sym.examples import example_dict
    from linkage_sym.scene import parse_scene

    scene = load_example("watt_sixbar")
    fresh = mechanism_script(scene, page_artifact(scene))
    numpy_key = cache.key_of(cache.signature(scene))
    compile_mechanism(scene)
    files = sorted(p.name for p in (fresh_cache / "cache").glob("*.json"))
    assert len(files) == 2 and f"{numpy_key}.json" in files
    cache.clear_memory()

    def no_derivation(*args, **kwargs):
        raise AssertionError("derived again: the cached artifact was not used")

    monkeypatch.setattr(javascript, "_Builder", no_derivation)
    assert mechanism_script(scene, page_artifact(scene)) == fresh
    d = example_dict("watt_sixbar")
    d["joints"][1]["at"] = [v * 1.1 for v in d["joints"][1]["at"]]
    other = parse_scene(d)
    assert mechanism_script(other, page_artifact(other)) != fresh  # its own numbers
    assert javascript.POSITION_POINTS in page_artifact(scene).functions
    assert javascript.POSITION_POINTS not in cache.load_artifact(numpy_key).functions
