"""Structural analysis: mobility, Assur groups, disconnection choices."""

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
