"""The numeric core (NumPy/SciPy only, by import contract): kinematics and kinetostatics.

A scene is analysed once into a solving plan (:func:`plan.compile_plan`) whose
``run`` solves whole sweeps, every group vectorised over the steps.  Its
sub-packages, from the bottom up (each imports only those before it, by
import contract):

``results``
    ``result`` (``Analysis`` and its JSON), ``strict_json`` (non-finite values
    left out), ``accuracy`` (per-step relative accuracy), ``transmission``
    (transmission angles), ``cycle_average`` (averages over a sweep's cycle),
    ``wording`` (how warnings name steps).
``continuation``
    The Newton continuation policy both runtimes call (this plan and
    :mod:`linkage_sym.codegen.runtime`): the walk along the path (the
    package's own module), ``roots`` (Newton's iteration and the root
    searches), ``batched_path`` (many path points at once), ``messages``.
``kinematics``
    Solving positions and rates: ``constraints``, ``joint_rows``, ``state``,
    ``loci``, ``solver`` (the ``GroupSolver`` contract), ``closed_form``
    (input links and dyads), ``gears``, ``cams`` and ``cam_profile``,
    ``newton`` (groups by Newton's method in pose coordinates),
    ``loop_closure`` (groups of R and P joints and gear meshes in their links'
    angles and slides).
``forces``
    ``loads``, ``statics`` (input and dyad routines), ``superposition`` (Dang
    and Zhang's disconnection and superposition), ``global_statics`` (every
    link at once: the check), ``friction`` and ``global_friction`` (joint friction in
    both methods), ``kinetostatics`` (the force plan).
``engine``
    The one sweep engine both runtimes call: ``run`` (a run's bookkeeping: the
    scene's sweep, stages, solving path and unwrapping, step statuses, the singularity
    decision, the ``Analysis``, what every run adds, the accuracy calibration), ``block``
    (the result block and its records), ``heap`` (the allocator's state).

On top, ``plan`` (the numeric runtime: a scene compiled into its groups'
solvers and force routines, run over sweeps) and ``extremes`` (extremes
located between steps, re-solved with the plan).
"""
