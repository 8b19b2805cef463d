"""Which shipped examples a check applies to.

Examples with cam contacts (``cam`` joints, issue 20) are left out of checks
that run the symbolic layer, which refuses them ("the symbolic method does
not support cam contacts yet"); examples with any higher pair (gear meshes,
cam contacts) are left out of checks against ``reference_kinematics.py``, an
independent solver of R and P joints only.  ``test_gears.py`` and
``test_cams.py`` check those against the Willis formula, closed forms, the
equivalent four-bar and the direct contact equations instead.  Examples
whose springs act (the contract's ``springs``) are checked like the others: the
symbolic layer derives them (``tests/codegen/test_symbolic_springs.py``).
"""

from __future__ import annotations

from linkage_sym.errors import SYMBOLIC_LACKS
from linkage_sym.examples import example_dict, example_names


def joint_types(name: str) -> set[str]:
    """The joint types of the shipped example ``name``."""
    return {j.get("type", "R") for j in example_dict(name)["joints"]}


def has_meshes(name: str) -> bool:
    """Whether the shipped example ``name`` has a gear mesh."""
    return "G" in joint_types(name)


def has_springs(name: str) -> bool:
    """Whether the shipped example ``name`` has springs that act (``effects.springs``)."""
    data = example_dict(name)
    return bool(data.get("springs")) and data.get("effects", {}).get("springs", True)


def has_friction(name: str) -> bool:
    """Whether the shipped example ``name``'s joint friction acts (``effects.friction`` and a
    joint's positive coefficient): the page leaves the friction out, so the checks over
    :func:`symbolic_examples` (the page's among them) leave such an example out; the
    compiled runtime's friction has checks of its own
    (``tests/codegen/test_symbolic_friction.py``, ``test_precision_friction.py``,
    ``tests/design/test_design_friction.py``)."""
    d = example_dict(name)
    return bool(d.get("effects", {}).get("friction")) and any(
        j.get("friction", {}).get("coefficient", 0) > 0 for j in d["joints"])


def symbolic_examples() -> list[str]:
    """The shipped examples the symbolic layer derives (no joint it refuses, no joint
    friction; acting springs it derives), sorted."""
    return [n for n in example_names()
            if not joint_types(n) & set(SYMBOLIC_LACKS) and not has_friction(n)]


def lower_pair_examples() -> list[str]:
    """The shipped examples with R and P joints only, sorted."""
    return [n for n in example_names() if joint_types(n) <= {"R", "P"}]
