"""linkage_sym: symbolic-numeric analysis of planar linkages.

The numeric core (``linkage_sym.numeric``, ``linkage_sym.structure``) uses
NumPy/SciPy only; SymPy and Matplotlib live in their own layers.

Examples
--------
>>> import linkage_sym
>>> scene = linkage_sym.load_example("crank_rocker")
>>> result = linkage_sym.analyze(scene)
>>> result.stages
('position', 'velocity', 'acceleration', 'forces')
>>> round(float(result.forces.driving["A"][0]), 4)  # crank torque at the first step (N m)
-0.0755
"""

from linkage_sym.errors import SceneError

__version__ = "0.1.0"

__all__ = ["SceneError", "analyze", "compile_plan", "decompose", "load_example", "load_scene"]


def load_scene(source):
    """Load and validate a scene from a JSON file path or a dict (see :mod:`linkage_sym.scene`)."""
    from linkage_sym.scene import load_scene as _load

    return _load(source)


def load_example(name):
    """Load one of the example scenes shipped with the package."""
    from linkage_sym.examples import load_example as _load

    return _load(name)


def decompose(scene):
    """Structural analysis: drivers and Assur groups in solving order."""
    from linkage_sym.structure import decompose as _decompose

    return _decompose(scene)


def compile_plan(scene, disconnection=None):
    """Analyse a scene once into a solving plan that runs over every step.

    ``disconnection`` picks the seed-000 disconnection of complex groups (an
    index into the list ``linkage-sym structure`` prints, or a dict
    ``{group index: choice}``); default: the best-suited one.
    """
    from linkage_sym.numeric.plan import compile_plan as _compile

    return _compile(scene, disconnection)


def analyze(scene, method="dyad", disconnection=None):
    """Compile a scene's solving plan and run it over the scene's sweep.

    ``method`` is the force method: ``"dyad"`` (group by group) or
    ``"global"`` (one sparse system of all links).
    """
    return compile_plan(scene, disconnection).run(method=method)
