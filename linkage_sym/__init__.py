"""linkage_sym: symbolic-numeric analysis of planar linkages.

The numeric core (``linkage_sym.numeric``, ``linkage_sym.structure``) uses
NumPy/SciPy only; SymPy and Matplotlib live in their own layers.

Examples
--------
>>> import linkage_sym
>>> scene = linkage_sym.load_example("crank_rocker")
>>> result = linkage_sym.analyze(scene)
>>> result.stages
('position', 'velocity', 'acceleration')
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


def compile_plan(scene):
    """Analyse a scene once into a solving plan that runs over every step."""
    from linkage_sym.numeric.plan import compile_plan as _compile

    return _compile(scene)


def analyze(scene):
    """Compile a scene's solving plan and run it over the scene's sweep."""
    return compile_plan(scene).run()
