"""Structural analysis: mobility, Assur groups, disconnection choices.

Modules: ``groups`` (mobility and the decomposition into Assur groups),
``disconnection`` (Dang and Zhang's disconnection choices of complex
groups), ``parameters`` (link frames and the scene's named parameters),
``grashof`` (the Grashof class of four-bar loops), ``report`` (the
``structure`` command's text).
"""

from linkage_sym.structure.disconnection import Disconnection, disconnections
from linkage_sym.structure.groups import Decomposition, Group, decompose, mobility
from linkage_sym.structure.report import structure_report

__all__ = [
    "Decomposition",
    "Disconnection",
    "Group",
    "decompose",
    "disconnections",
    "mobility",
    "structure_report",
]
