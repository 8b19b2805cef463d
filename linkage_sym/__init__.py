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

from linkage_sym._version import __version__

__all__ = [
    "SceneError",
    "__version__",
    "analyze",
    "animate",
    "compile_mechanism",
    "compile_plan",
    "decompose",
    "derive",
    "flywheel",
    "load_example",
    "load_scene",
    "simulate",
    "sweep",
]


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

    ``disconnection`` picks the disconnection (Dang and Zhang's method) of complex groups (an
    index into the list ``linkage-sym structure`` prints, or a dict
    ``{group index: choice}``); default: the best-suited one.
    """
    from linkage_sym.numeric.plan import compile_plan as _compile

    return _compile(scene, disconnection)


def analyze(scene, method="dyad", disconnection=None, precision="double"):
    """Compile a scene's solving plan and run it over the scene's sweep.

    ``method``: ``"dyad"`` (numeric, forces group by group), ``"global"``
    (numeric, forces as one sparse system of all links) or ``"symbolic"``
    (the SymPy-derived equations, lambdified and cached per topology).
    ``precision``: ``"double"`` (float64, the methods above) or a number of
    significant digits (e.g. 50): the derived equations evaluated in mpmath at
    each step's exact driver value (from the scene's ``start_deg``/``stop_deg``,
    not their float64 radians), the result rounded to float64
    (:mod:`linkage_sym.codegen.precision`; about 10^3--10^4 times slower;
    ``method`` and ``disconnection`` must stay at their defaults).
    """
    if not (precision is None or precision == "double"):  # SymPy and mpmath only then
        from linkage_sym.codegen.precision import analyze_precise, parse_precision

        digits = parse_precision(precision)
        if digits is not None:
            if method != "dyad" or disconnection is not None:
                raise ValueError("precision: an arbitrary-precision run evaluates the derived "
                                 "equations; it takes no method or disconnection")
            return analyze_precise(scene, digits)
    if method == "symbolic":
        return compile_mechanism(scene).run()
    return compile_plan(scene, disconnection).run(method=method)


def animate(scene, analysis, **options):
    """An animation of a scene's analysed sweep: ``.save("motion.gif")`` (or ``.mp4``,
    ``.html``), shown inline in a notebook.

    ``options``: ``frames``, ``fps``, ``dpi`` and the layers ``velocity``, ``acceleration``,
    ``forces``, ``centres``, ``transmission`` (``True`` to draw).  A function and not a
    method of the analysis: the numeric core imports no Matplotlib.  See
    :func:`linkage_sym.plotting.animation.animate`.
    """
    from linkage_sym.plotting.animation import animate as _animate

    return _animate(scene, analysis, **options)


def derive(scene, symbolic=True, forces=None):
    """Derive a scene's loop, rate and force equations with SymPy.

    See :func:`linkage_sym.symbolic.mechanism.derive`.
    """
    from linkage_sym.symbolic import derive as _derive

    return _derive(scene, symbolic, forces)


def compile_mechanism(scene, use_cache=True):
    """The lambdified equations of a scene, compiled once per topology and cached.

    See :func:`linkage_sym.codegen.compile.compile_mechanism`.
    """
    from linkage_sym.codegen.compile import compile_mechanism as _compile

    return _compile(scene, use_cache)


def sweep(scene, parameters, metrics=None, **options):
    """Evaluate many designs of a scene at once (a grid, samples, a Monte Carlo spread).

    See :func:`linkage_sym.design.api.sweep`.
    """
    from linkage_sym.design.api import sweep as _sweep

    return _sweep(scene, parameters, metrics, **options)


def simulate(scene, method="LSODA", progress=None):
    """Integrate the motion of a scene's machine driven by its motor (its ``simulate``
    section and its driver's ``motor``).

    Returns a :class:`~linkage_sym.motion.simulate.SimulationResult`: the sampled states
    analysed as :func:`analyze` analyses a sweep, their times, the periodic ``motion``
    (``.to_dict()``: the contract's JSON).  ``method``: ``"LSODA"``, ``"Radau"`` or
    ``"BDF"``.  See :func:`linkage_sym.motion.simulate.simulate`.
    """
    from linkage_sym.motion.simulate import simulate as _simulate

    return _simulate(scene, method=method, progress=progress)


def flywheel(scene, fluctuation, progress=None):
    """The moment of inertia (kg m^2) to add to the driven link so that the periodic motion's
    speed fluctuation is at most ``fluctuation``: the energy method's estimate refined by
    simulation (a :class:`~linkage_sym.motion.flywheel.FlywheelResult` with both).  See
    :func:`linkage_sym.motion.flywheel.flywheel`.
    """
    from linkage_sym.motion.flywheel import flywheel as _flywheel

    return _flywheel(scene, fluctuation, progress=progress)
