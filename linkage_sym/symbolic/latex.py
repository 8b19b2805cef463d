"""LaTeX rendering of a mechanism's derived equations (moved to
:mod:`linkage_sym.symbolic.latex_sections`, whose names are importable from here)."""

from linkage_sym.symbolic.latex_sections import (  # noqa: F401 - the names documented here
    BIBLIOGRAPHY,
    LINE,
    MAX_ENTRY,
    MAX_EQUATION,
    MAX_MATRIX,
    MAX_MATRIX_CHARS,
    UNITS,
    _Namer,
    bibliography,
    escape_text,
    latex_document,
    scene_joint_type,
    standalone,
)
