"""The numeric core (NumPy/SciPy only, by import contract): kinematics and kinetostatics.

A scene is analysed once into a solving plan (:func:`plan.compile_plan`) whose
``run`` solves whole sweeps, every group vectorised over the steps.

Solving positions and rates
    ``constraints`` (joint and driver equations in pose coordinates),
    ``state`` (a link's pose and rates over the steps), ``loci`` (the circles
    and lines a dyad's joint lies on), ``solver`` (the ``GroupSolver``
    contract every group's solver meets), ``closed_form`` (input links and
    dyads), ``gears`` (a gear on its pivot, mesh forces), ``newton`` (groups
    by Newton's method in pose coordinates), ``loop_closure`` (groups of
    R and P joints and gear meshes -- class-III triads, the printing
    mechanism's, actuator groups, gear trains -- in their links' angles and
    slides),
    ``batched_path`` (their continuation over many path points at once).
The one sweep engine both runtimes call (this plan and
:mod:`linkage_sym.codegen.runtime`)
    ``sweep`` (the sweep, stages, solving path and unwrapping, step statuses,
    the singularity decision and its message, the ``Analysis``, what every
    run adds -- warnings, transmission angles, instant centres -- and the
    accuracy calibration), ``block`` (the result block and its records),
    ``continuation`` (the Newton continuation policy).
Forces
    ``loads`` (applied and inertia wrenches), ``statics`` (input and dyad
    routines), ``superposition`` (Dang and Zhang's disconnection and
    superposition), ``global_statics`` (every link at once: the check),
    ``kinetostatics`` (the force plan: one ``ForceRoutine`` per group).
Results and what is derived from them
    ``result`` (``Analysis`` and its JSON), ``accuracy`` (per-step relative
    accuracy), ``extremes`` (extremes located between steps),
    ``transmission`` (transmission angles).
"""
