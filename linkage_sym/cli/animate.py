"""``linkage-sym animate``: the mechanism moving over its sweep, as a GIF, an MP4 or an HTML file.

::

    linkage-sym animate SCENE.json -o motion.gif|.mp4|.html [--frames N] [--fps F]
                        [--layers velocity,acceleration,forces,centres,transmission]
                        [--method dyad|global|symbolic]

solves the scene's sweep and writes its animation
(:mod:`linkage_sym.plotting.animation`): the links as every picture draws
them, the joints' paths and the traced points' coupler curves growing, and the
layers asked for.  ``--frames N`` shows N steps spread evenly over the sweep
(first and last included; at most one frame a step; default every step up to
120); ``--fps`` their rate.  A step that cannot be assembled, or is singular,
has its frame all the same, saying so.  The layers ``velocity``,
``acceleration``, ``centres`` and ``transmission`` add the kinematics to the
scene's outputs if it lacks them; ``forces`` needs a scene whose outputs ask for
forces (reactions, driving or frame).

Every option is checked before anything is solved or written (exit status 2,
the option named): the suffix of ``-o`` (``.gif`` by Pillow, ``.mp4`` by ffmpeg
where it is found, ``.html`` one self-contained file), ``--frames`` against the
sweep's steps, ``--fps``, the layers' names; a layer the analysis has no values
for is refused once the sweep is solved, with nothing written.
"""

from __future__ import annotations

import argparse
import dataclasses
import sys

__all__ = ["LAYERS", "cmd_animate", "register"]

LAYERS = ("velocity", "acceleration", "forces", "centres", "transmission")
"""The names ``--layers`` takes (those of :data:`linkage_sym.plotting.animation.LAYERS`,
written here so that the help imports no Matplotlib)."""

KINEMATIC = ("velocity", "acceleration", "centres", "transmission")
"""Layers that need the kinematics output."""


def register(sub) -> None:
    """Add the ``animate`` command to the ``linkage-sym`` subparsers ``sub``.

    Examples
    --------
    >>> import argparse
    >>> p = argparse.ArgumentParser(prog="linkage-sym")
    >>> register(p.add_subparsers(dest="command"))
    >>> a = p.parse_args(["animate", "s.json", "-o", "m.gif", "--frames", "12",
    ...                   "--layers", "velocity,forces"])
    >>> a.command, a.output, a.frames, a.fps, a.layers, a.method, a.func is cmd_animate
    ('animate', 'm.gif', 12, 20.0, 'velocity,forces', 'dyad', True)
    """
    from linkage_sym.cli.common import EXIT_STATUS

    a = sub.add_parser(
        "animate", help="write the mechanism moving over its sweep (GIF, MP4 or HTML)",
        description="Solve a scene's sweep and write its animation: the links as the pictures "
        "draw them, the joints' paths and traced points' coupler curves growing, and the "
        "layers asked for (arrows on one scale each). Frames of steps that cannot be "
        "assembled, or are singular, say so.",
        epilog=EXIT_STATUS, formatter_class=argparse.RawDescriptionHelpFormatter)
    a.add_argument("scene", help="scene JSON file")
    a.add_argument("-o", "--output", metavar="FILE", required=True,
                   help="the animation: .gif (Pillow), .mp4 (needs ffmpeg) or .html (one "
                   "self-contained file: every frame embedded, nothing fetched)")
    a.add_argument("--frames", type=int, metavar="N",
                   help="frames, the sweep's steps sampled evenly (first and last included; at "
                   "most the sweep's steps; default every step up to 120)")
    a.add_argument("--fps", type=float, default=20.0, metavar="F",
                   help="frames per second (default 20)")
    a.add_argument("--layers", metavar="L1,L2", default="",
                   help="drawn over the mechanism, comma-separated: velocity, acceleration "
                   "(arrows of the moving joints and traced points), forces (joint reactions "
                   "and driving effort; the scene's outputs must ask for forces), centres "
                   "(instant centres, three-centre lines), transmission (angle of each RRR "
                   "dyad)")
    a.add_argument("--method", choices=("dyad", "global", "symbolic"), default="dyad",
                   help="numeric solver with forces group by group (dyad, default) or as one "
                   "sparse system (global); or the lambdified SymPy equations (symbolic)")
    a.set_defaults(func=cmd_animate)


def _layers(text: str) -> tuple:
    """The layers of ``--layers``, each once, in the order given.

    Examples
    --------
    >>> _layers("velocity, forces"), _layers("")
    (('velocity', 'forces'), ())
    >>> _layers("speed")
    Traceback (most recent call last):
    ...
    linkage_sym.cli.common.OptionError: --layers: unknown layer 'speed'; the layers: velocity, acceleration, forces, centres, transmission
    """
    from linkage_sym.cli.common import OptionError

    names = [n.strip() for n in text.split(",")] if text.strip() else []
    problems, seen = [], []
    for name in names:
        if name not in LAYERS:
            what = "an empty name" if not name else f"unknown layer {name!r}"
            problems.append(f"--layers: {what}; the layers: {', '.join(LAYERS)}")
        elif name in seen:
            problems.append(f"--layers: {name!r} is given twice")
        else:
            seen.append(name)
    if problems:
        raise OptionError(problems)
    return tuple(seen)


def cmd_animate(args) -> int:
    """Run ``linkage-sym animate`` (see the module docstring); returns the exit status."""
    from linkage_sym.cli.common import OptionError, check_outputs, load, option_error
    from linkage_sym.plotting.animation import AnimationError, check_fps, frame_steps
    from linkage_sym.plotting.animation import output_kind, require_ffmpeg

    layers = _layers(args.layers)
    if args.output == "-":
        raise OptionError("-o/--output: an animation is a file; give its name (.gif, .mp4 "
                          "or .html), not standard output")
    check_outputs(files=[("-o/--output", args.output)])
    scene = load(args.scene)
    problems = []  # every option's problem at once, before solving
    for check in (lambda: output_kind(args.output) == "mp4" and require_ffmpeg(),
                  lambda: frame_steps(scene.steps, args.frames),
                  lambda: check_fps(args.fps)):
        try:
            check()
        except AnimationError as err:
            problems += option_error(err, "animate").problems
    if problems:
        raise OptionError(problems)
    if any(layer in KINEMATIC for layer in layers) and "kinematics" not in scene.outputs:
        scene = dataclasses.replace(scene, outputs=("kinematics", *scene.outputs))
    from linkage_sym import output

    output.check_run_memory(scene, "whole", method=args.method)
    if args.method == "symbolic":
        from linkage_sym.codegen.compile import compile_mechanism

        analysis = compile_mechanism(scene).run()
    else:
        from linkage_sym.numeric.plan import compile_plan

        analysis = compile_plan(scene).run(method=args.method)
    from linkage_sym.plotting.animation import animate

    try:
        anim = animate(scene, analysis, frames=args.frames, fps=args.fps,
                       **{layer: True for layer in layers})
        path = anim.save(args.output)
    except AnimationError as err:
        raise option_error(err, "animate") from err
    steps = anim.steps
    status = analysis.status[steps]
    counts = {str(s): int((status == s).sum()) for s in dict.fromkeys(status.tolist())}
    print(f"wrote {path}: {len(steps)} frames of steps {steps[0]} to {steps[-1]} of "
          f"{scene.name!r} at {args.fps:g} frames per second"
          + (f"; layers {', '.join(anim.layers)}" if anim.layers else ""))
    if set(counts) != {"ok"}:
        print("frames by status: " + ", ".join(f"{n} {s}" for s, n in counts.items())
              + " (a frame of a step not ok says so)")
    if not analysis.ok.any() and not (analysis.status == "singular").any():
        print("linkage-sym animate: no step of the sweep could be assembled: every frame "
              "says so", file=sys.stderr)
    return 0
