"""Scenes in and out: loading and validating scene files, and writing them back.

The layout is the contract of ``docs/scene-format.md``; the result is
the plain data of :mod:`linkage_sym.model.scene`.

- :func:`load_scene` -- a JSON file path or a parsed mapping to a validated
  :class:`~linkage_sym.model.scene.Scene`;
- :func:`parse_scene` -- a parsed mapping to a validated scene;
- :func:`dump_scene` -- a scene back to the file layout.

Every problem of an invalid scene is reported at once, in one
:class:`~linkage_sym.errors.SceneError`.

Modules: ``load`` (files, strict JSON, dumping), ``validate`` (the scene
reader: links, loads, points, effects, outputs), ``joints`` and ``drivers``
(those sections), ``checks`` (size, connectivity and mobility), ``fields``
(the field readers every section uses, with their limits and wording),
``gears``, ``cams`` and ``schedules`` (the extensions' fields).
"""

from linkage_sym.scene.load import dump_scene, load_scene
from linkage_sym.scene.validate import parse_scene

__all__ = ["dump_scene", "load_scene", "parse_scene"]
