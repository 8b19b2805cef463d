"""``linkage-sym structure``: the drivers and Assur groups in solving order."""

from __future__ import annotations

from linkage_sym.cli.common import load as _load, option_of

__all__ = ["cmd_structure", "register"]


def cmd_structure(args) -> int:
    from linkage_sym.structure import decompose, structure_report

    scene = _load(args.scene)
    print(structure_report(scene, decompose(scene), pick=f"{option_of('disconnection')} K"))
    return 0



def register(sub) -> None:
    """Add the ``structure`` command to the ``linkage-sym`` subparsers ``sub``."""
    s = sub.add_parser("structure", help="print drivers and Assur groups in solving order")
    s.add_argument("scene", help="scene JSON file")
    s.set_defaults(func=cmd_structure)
