"""What ``linkage-sym analyze`` adds about accuracy: ``--precision``, ``--extremes``, and the
worst step's accuracy estimate in the summary.

* ``--precision double|DIGITS``: ``double`` is the float64 solver (the default);
  ``DIGITS`` (e.g. 30, 50) evaluates the derived equations in mpmath at that many
  significant digits and writes the same result rounded to float64
  (:mod:`linkage_sym.codegen.precision`; about 10^3 to 10^4 times slower).
* ``--extremes``: the maxima and minima of every link rotation, joint coordinate, slide,
  driving effort and reaction magnitude located by root finding on their rates between
  the steps, with the driver values, each group's limit positions and where the sweep
  leaves or enters the assemblable range (:mod:`linkage_sym.numeric.extremes`, with the
  numeric solver); printed, and written to the result as ``"extremes"`` (an extension
  of the format).
* the summary's ``accuracy`` line: the largest estimated relative error of any ok step,
  per field (:mod:`linkage_sym.numeric.results.accuracy`), tallied over the chunks of the sweep.
"""

from __future__ import annotations

import math

from linkage_sym.numeric.results.wording import driver_values_text

PRECISION_HELP = (
    "double (float64, default) or a number of significant digits, e.g. 50: the derived "
    "equations evaluated in mpmath and rounded to float64 -- the answer near a dead centre "
    "or for a reference value; about 10^3-10^4 times slower")
EXTREMES_HELP = (
    "also locate the maxima and minima of link rotations, joint coordinates, slides, "
    "driving efforts and reaction magnitudes (Brent on their rates between the steps), each "
    "group's limit positions (a link that turns fully has none: its extremes are the sweep's "
    "ends) and the assembly limits; printed (a value within 1e-12 of its scale -- the "
    "mechanism's size, 1 rad, the effort's largest -- as 0), and written as 'extremes'")


def add_analyze_options(parser) -> None:
    """The options of ``analyze`` this module implements."""
    parser.add_argument("--precision", default="double", metavar="double|DIGITS", help=PRECISION_HELP)
    parser.add_argument("--extremes", action="store_true", help=EXTREMES_HELP)


def _option_error(problems):
    from linkage_sym.cli.common import OptionError

    return OptionError(problems)


def _digits(args) -> int | None:
    if args.precision is None or str(args.precision).strip().lower() == "double":
        return None
    from linkage_sym.codegen.precision import parse_precision

    try:
        digits = parse_precision(args.precision)
    except ValueError as err:
        raise _option_error([f"--{err}"]) from err
    problems = []
    if args.method != "dyad":
        problems.append(f"--precision {digits}: evaluates the derived equations itself; "
                        f"not with --method {args.method}")
    if args.disconnection is not None:
        problems.append(f"--precision {digits}: solves each group's equilibrium as one system; "
                        "not with --disconnection")
    if problems:
        raise _option_error(problems)
    return digits


def _drivers_text(scene, drivers: dict) -> str:
    return driver_values_text(drivers, {n: scene.joint(n).type for n in drivers})


class Report:
    """The worst estimated accuracy over a sweep's chunks, and the extremes' lines."""

    def __init__(self, scene, sweep):
        self.scene = scene
        self.sweep = sweep
        self.worst: dict = {}  # field -> (value, step, driver values)
        self.extreme_lines: list[str] = []

    def _step_of(self, drivers: dict) -> int | None:
        from linkage_sym.output.stats import step_at

        return step_at(self.sweep.q, drivers, self.sweep.n_steps)

    def add(self, res) -> None:
        acc = getattr(res, "accuracy", None)
        if not acc:
            return
        import numpy as np

        for name, v in acc.items():
            v = np.asarray(v, float)
            if not np.isfinite(v).any():
                continue
            i = int(np.nanargmax(v))
            if name not in self.worst or v[i] > self.worst[name][0]:
                drivers = {k: float(d["q"][i]) for k, d in res.drivers.items()}
                self.worst[name] = (float(v[i]), self._step_of(drivers), drivers)

    def lines(self) -> list[str]:
        out = []
        if self.worst:
            parts = []
            for name in ("position", "velocity", "acceleration", "forces"):
                if name in self.worst:
                    value, step, drivers = self.worst[name]
                    where = f"step {step}" if step is not None else _drivers_text(self.scene, drivers)
                    parts.append(f"{name} {value:.2g} ({where})")
            digits = -math.log10(max(w[0] for w in self.worst.values()))
            out.append("accuracy (estimated relative error, worst step): " + ", ".join(parts)
                       + f"; at least {max(0, math.floor(digits))} significant digits everywhere")
        return out + self.extreme_lines


def prepare(scene, sweep, args):
    """The sweep ``analyze`` writes, with what these options ask, and the :class:`Report`.

    ``--precision DIGITS`` replaces ``sweep`` by the arbitrary-precision one;
    ``--extremes`` locates the extremes first (a whole run of the numeric plan) and puts
    them on every chunk's result (its JSON tail); every chunk's accuracy is tallied.
    """
    digits = _digits(args)
    if digits is not None:
        from linkage_sym import output
        from linkage_sym.codegen.precision import PreciseMechanism

        pm = PreciseMechanism(scene, digits)
        precise = output.compiled_sweep(pm.cm)
        precise.run = lambda q, qd, qdd: pm.run(q, qd, qdd).analysis
        sweep = precise
    report = Report(scene, sweep)
    extremes = None
    if getattr(args, "extremes", False):
        from linkage_sym.numeric.extremes import find_extremes, summary_lines
        from linkage_sym.numeric.plan import compile_plan

        plan = compile_plan(scene, args.disconnection)
        ext = find_extremes(scene, plan, plan.run())
        extremes = ext.to_dict()
        report.extreme_lines = summary_lines(scene, ext)
    inner = sweep.run

    def run(q, qd, qdd):
        res = inner(q, qd, qdd)
        report.add(res)
        if extremes is not None:
            res.extremes = extremes
        return res

    sweep.run = run
    return sweep, report
