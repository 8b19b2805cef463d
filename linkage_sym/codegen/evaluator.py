"""One evaluator of a compiled mechanism's generated functions, with backends (no SymPy).

A compiled mechanism (:class:`~linkage_sym.codegen.artifact.Artifact`) is a handful of
generated functions with one fixed signature::

    f(X, XD, XDD, Q, QD, QDD, FORCES, P, CX=None, SX=None)

(the coordinates and their rates, the drivers' values and rates, the reactions and
efforts, the parameters then the assembly-mode and flank signs, the cosines and sines of
``X``; :mod:`linkage_sym.codegen.compile` writes the order into every docstring).
:class:`Evaluator` is the one place that calls them and does what every use of them
does -- the walk over the position steps, the rate problems ``A xd = B qd`` and
``A xdd = rhs`` group block by group block, the force blocks
``A_g F_g = b_g - C_g F_later`` from the last group back, the loads scaled over the
cycle, the reactions and efforts by joint type, a link's frame and its traced points
carried along -- written once for any number type.  A *backend* says what a number is
and how a block is solved, through named hooks (:meth:`Evaluator.newton_step`,
:meth:`Evaluator.block_system`, :meth:`Evaluator.dense_solve`...), as pydy's
``ODEFunctionGenerator`` has Lambdify and Cython backends:

- :class:`NumpyEvaluator` -- arrays over the steps (a whole sweep per call):
  :class:`~linkage_sym.codegen.runtime.CompiledMechanism` (the runtime, one scene) and
  :class:`~linkage_sym.design.evaluate.Model` (chunks of designs: (n, 1) parameters
  broadcast against (N,) steps) build on it;
- :class:`~linkage_sym.codegen.precision.PreciseMechanism` -- mpmath numbers, one step
  at a time, at any precision (``--precision``).
"""

from __future__ import annotations

import linecache
from abc import ABC, abstractmethod

import numpy as np

from linkage_sym.codegen.artifact import Artifact
from linkage_sym.codegen.blocks import BlockSystem, full
from linkage_sym.codegen.friction import NumpyOps, solve_with_friction
from linkage_sym.numeric.forces.loads import load_factor
from linkage_sym.numeric.kinematics.loci import Size, clamp_tangent
from linkage_sym.structure.parameters import ident

__all__ = ["Evaluator", "NumpyEvaluator", "frame_motion", "rigid_point", "unit_direction"]


class Evaluator(ABC):
    """The generated functions of one topology with one set of parameter values.

    Parameters
    ----------
    artifact : Artifact
    functions : dict of str to callable
        The artifact's functions, compiled for this backend's numbers.
    params : list
        The ``P`` argument: the parameters' values, then the signs.
    """

    def __init__(self, artifact: Artifact, functions: dict, params: list):
        self.art = artifact
        self.functions = functions
        self.params = params
        self.m = len(artifact.x)

    # -- the generated functions ---------------------------------------------------------
    def call(self, name, P=None, X=None, XD=None, XDD=None, Q=None, QD=None, QDD=None, F=None,
             CS=(None, None)):
        """Generated function ``name`` (the fixed argument order above); ``P`` is
        :attr:`params` unless given."""
        return self.functions[name](X, XD, XDD, Q, QD, QDD, F, self.params if P is None else P,
                                    CS[0], CS[1])

    # -- positions -----------------------------------------------------------------------
    def walk(self, X: list, ctx) -> list:
        """Every position step in solving order, each by its kind's hook
        (:meth:`closed_step`, :meth:`newton_step`), filling ``X`` (a list over the
        coordinates); ``ctx`` is the backend's (driver values, parameters...)."""
        for step in self.art.steps:
            step.solve(self, X, ctx)
        return X

    def closed_step(self, step, X, ctx):
        """A run of closed forms: one call at ``ctx.Q`` with ``ctx.P``; each value through
        :meth:`coordinate`."""
        for c, v in zip(step.x, self.call(step.function, ctx.P, X=X, Q=ctx.Q)):
            X[c] = self.coordinate(c, v, ctx)

    def coordinate(self, c, value, ctx):
        """A closed form's value of coordinate ``c`` as the backend keeps it."""
        return value

    @abstractmethod
    def newton_step(self, step, X, ctx):
        """A group without a closed form: the backend's root finder fills ``step.x``."""

    # -- the rate problems ---------------------------------------------------------------
    def rate_system(self, X, Q, QD, CS, P=None, shape=None):
        """``A`` (the backend's :meth:`block_system`) and ``B qd`` (list over the rows)."""
        entries, Bqd = self.rate_entries(X, Q, QD, CS, P)
        return self.block_system(entries, shape), self.vector(Bqd, shape)

    def rate_entries(self, X, Q, QD, CS, P=None):
        """The generated ``rates``: ``A``'s non-zero entries ``{(i, j): value}`` and ``B qd``,
        as the function returns them (for a caller that needs ``B qd`` alone, no system)."""
        out = self.call("rates", P, X=X, Q=Q, QD=QD, CS=CS)
        n = len(self.art.pattern)
        return dict(zip(self.art.pattern, out[:n])), out[n:]

    def accelerations_rhs(self, X, XD, Q, QD, QDD, CS, P=None, shape=None):
        """The right-hand side of ``A xdd = rhs``."""
        return self.vector(self.call("accelerations", P, X=X, XD=XD, Q=Q, QD=QD, QDD=QDD, CS=CS),
                           shape)

    def vector(self, values, shape):
        """A generated function's outputs as the backend's vector."""
        return list(values)

    @abstractmethod
    def block_system(self, entries: dict, shape):
        """``A`` from its non-zero entries ``{(i, j): value}``: an object with
        ``solve(rhs)`` (the block lower-triangular solve, group by group) and
        ``ratios()`` (each block's Hadamard ratio)."""

    # -- forces --------------------------------------------------------------------------
    @abstractmethod
    def dense_solve(self, pattern, values, b):
        """The solution (list of ``n``) of one group's ``A_g F_g = b``: ``A_g``'s non-zero
        entries ``pattern`` ``(i, j)`` with ``values``, ``b`` a list of ``n``."""

    @abstractmethod
    def force_zeros(self, like):
        """The forces before any group is solved (a list over the force names), each the
        backend's zero shaped as ``like``."""

    def solve_forces(self, pts, take=lambda v: v):
        """Reactions and efforts (a list over the force names): each group's block from
        the last group back, ``b_g - C_g F_later`` with the later groups' forces.
        ``take`` selects the entries of each ``points`` output (the steps solved)."""
        art = self.art
        F = None
        for g, blk in reversed(list(zip(art.groups, art.forces))):
            k = g.index
            A = [take(v) for v in art.rows(pts, f"A:{k}")]
            b = [take(v) for v in art.rows(pts, f"b:{k}")]
            if F is None:
                F = self.force_zeros(b[0])
            for (i, fi), v in zip(blk.C, art.rows(pts, f"C:{k}")):
                b[i] = b[i] - take(v) * F[fi]
            for u, s in zip(blk.unknowns, self.dense_solve(blk.A, A, b)):
                F[u] = s
        return F

    def forces_and_friction(self, pts, take=lambda v: v, P=None):
        """:meth:`solve_forces` with the joints' friction where it acts: ``(F, friction)``,
        ``friction`` the :class:`~linkage_sym.codegen.friction.FrictionSolution` (``None``
        without friction); ``P`` the parameters (:attr:`params` unless given) from which
        the frictions' coefficients and pin radii are read."""
        if not self.art.friction:
            return self.solve_forces(pts, take), None
        sol = solve_with_friction(self, pts, take, self.params if P is None else P,
                                  self.friction_ops())
        return sol.F, sol

    def friction_ops(self):
        """The arithmetic of the friction's solve on this backend's numbers."""
        return NumpyOps

    def pulling(self, F) -> list:
        """The gear meshes (indices into ``art.flanks``) whose tooth load pulls: ``Fn < 0``
        (per entry, for arrays)."""
        fidx = self.art.force_index()
        return [F[fidx[f"Fn_{ident(name)}"]] < 0 for name in self.art.flanks]

    def with_flanks(self, P, flanks):
        """``P`` with each gear mesh's flank sign set."""
        P = list(self.params if P is None else P)
        at = self.art.flank_at
        P[at:at + len(flanks)] = list(flanks)
        return P

    def scaled_loads(self, P, factors: dict):
        """``P`` with each load's force and torque times its factor ``factors[load]``
        (loads over the cycle, at the steps' driver values); ``None`` for no factor."""
        entries = self.art.load_entries()
        todo = [(i, k) for i, k in factors.items() if i in entries]
        if not todo:
            return None
        P = list(self.params if P is None else P)
        for i, k in todo:
            for j in entries[i]:
                P[j] = P[j] * k
        return P

    def reactions(self, scene, F, rows, zero):
        """``{joint: (fx, fy, moment)}`` of every joint (the force of ``links[0]`` on
        ``links[1]``, a ``P`` joint's normal force and moment, a mesh's tooth load on its
        line of action) and ``{driver: effort}``, from the solved forces ``F``; ``rows(key)``
        gives the ``points`` outputs under a layout key, ``zero`` the backend's zero."""
        fidx = self.art.force_index()
        out = {}
        for j in scene.joints:
            n = ident(j.name)
            if j.type == "R":
                out[j.name] = (F[fidx[f"R_{n}x"]], F[fidx[f"R_{n}y"]], zero)
            elif j.type == "G":  # the tooth load on the line of action (gear a on gear b)
                ux, uy = rows(f"mesh:{j.name}")
                Fn = F[fidx[f"Fn_{n}"]]
                out[j.name] = (ux * Fn, uy * Fn, zero)
            else:
                ux, uy = rows(f"slide:{j.name}")
                Nn = F[fidx[f"N_{n}"]]
                out[j.name] = (-uy * Nn, ux * Nn, F[fidx[f"M_{n}"]])
        driving = {d.joint: F[fidx[("tau_" if d.kind == "R" else "f_") + ident(d.joint)]]
                   for d in scene.drivers}
        return out, driving


def frame_motion(cr, sr, origin, rows, w=None, al=None):
    """A link's frame carried to the global origin: ``[cr, sr, ox, oy(, w, vx, vy(, al,
    ax, ay))]`` from the cosine and sine of its rotation, its frame origin's assembly
    coordinates ``origin`` and ``rows(level)``, the generated motion of its frame origin
    (``ux, uy`` at level 0, velocity at 1, acceleration at 2); any number type."""
    Ux, Uy = origin
    dx, dy = -(cr * Ux - sr * Uy), -(sr * Ux + cr * Uy)
    ux, uy = rows(0)
    m = [cr, sr, ux + dx, uy + dy]
    if w is not None:
        vx, vy = rows(1)
        m += [w, vx - w * dy, vy + w * dx]
        if al is not None:
            ax, ay = rows(2)
            m += [al, ax - al * dy - w * w * dx, ay + al * dx - w * w * dy]
    return m


def rigid_point(motion, at):
    """A point fixed to a link (``at`` in its assembly position's global axes from the link
    point at the origin), from :func:`frame_motion`'s list: ``[position(, velocity(,
    acceleration))]``, each a pair."""
    cr, sr = motion[0], motion[1]
    rx, ry = cr * at[0] - sr * at[1], sr * at[0] + cr * at[1]
    out = [(motion[2] + rx, motion[3] + ry)]
    if len(motion) > 4:
        w = motion[4]
        out.append((motion[5] - w * ry, motion[6] + w * rx))
        if len(motion) > 7:
            al = motion[7]
            out.append((motion[8] - al * ry - w * w * rx, motion[9] + al * rx - w * w * ry))
    return out


# ---------------------------------------------------------------------------------- NumPy


def _tangent_sqrt(scale, *factors):
    """``sqrt`` of the product of ``factors``, a rounding-level miss of a tangency taken as
    the tangency (0) and a real miss as NaN: the numeric solver's rule
    (:func:`~linkage_sym.numeric.kinematics.loci.clamp_tangent`), for the generated code's
    :func:`~linkage_sym.symbolic.tangent.tangent_sqrt`."""
    prod = factors[0]
    for f in factors[1:]:
        prod = prod * f
    own = len(factors) > 1 and isinstance(prod, np.ndarray)  # a product made here
    prod = clamp_tangent(prod, factors, scale if isinstance(scale, Size) else lambda: scale,
                         inplace=own)
    with np.errstate(invalid="ignore"):
        return np.sqrt(prod)


def _coordinate_size(*values):
    """The size of the coordinates ``values`` for :func:`_tangent_sqrt`, computed only where
    a product is negative (:class:`~linkage_sym.numeric.kinematics.loci.Size`)."""
    return Size(values)


def numpy_namespace() -> dict:
    """The names the generated NumPy code reads (``from numpy import *``, as lambdify's
    NumPy printer assumes, and the two helpers the derivation prints)."""
    ns: dict = {}
    exec("from numpy import *", ns)
    ns["numpy"] = np
    ns["_tangent_sqrt"] = _tangent_sqrt
    ns["_coordinate_size"] = _coordinate_size
    return ns


def load_functions(artifact: Artifact, label: str, namespace: dict | None = None) -> dict:
    """Execute the generated sources in ``namespace`` (NumPy's unless given); their text
    stays readable by ``inspect``."""
    ns = numpy_namespace() if namespace is None else namespace
    out = {}
    for name, src in artifact.functions.items():
        fname = f"<linkage_sym {label}:{name}>"
        linecache.cache[fname] = (len(src), None, src.splitlines(True), fname)
        exec(compile(src, fname, "exec"), ns)
        out[name] = ns[name]
    return out


def unit_direction(Y, X, cr, sr, out=None):
    """Cosine and sine of ``atan2(Y, X) + r`` from ``Y``, ``X``, ``cos r`` and ``sin r``
    without an arctangent: ``(X, Y)`` over its length, turned by ``r`` (a closed step's
    ``"atan2"`` form, :class:`~linkage_sym.codegen.artifact.ClosedStep`); ``arctan2``'s
    own where the length is 0 or overflows.  NaN where ``Y`` or ``X`` is.  ``out``: two
    arrays of the broadcast shape to write into.

    Examples
    --------
    >>> c, s = unit_direction(np.array([1.0, 0.0]), np.array([1.0, 0.0]), -1, 0)
    >>> np.allclose(c, np.cos(np.arctan2([1.0, 0.0], [1.0, 0.0]) - np.pi), atol=1e-15)
    True
    """
    half = isinstance(sr, (int, float)) and sr == 0 and isinstance(cr, (int, float)) and abs(cr) == 1
    sign = cr if half else 1  # r a multiple of pi: the length's sign turns (X, Y)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        h = np.add(np.multiply(X, X), np.multiply(Y, Y))
        lo, hi = np.fmin.reduce(h, axis=None), np.fmax.reduce(h, axis=None)
        odd = (h == 0) | (h == np.inf) if lo == 0 or hi == np.inf else None
        np.sqrt(h, out=h)
        np.divide(sign, h, out=h)  # the reciprocal length, signed
        c = np.multiply(X, h, out=None if out is None else out[0])
        s = np.multiply(Y, h, out=None if out is None else out[1])
        if odd is not None:  # a zero length (or one that overflows): arctan2's direction
            a = np.arctan2(Y, X)
            np.copyto(c, sign * np.cos(a), where=odd)
            np.copyto(s, sign * np.sin(a), where=odd)
        if not half:
            c, s = c * cr - s * sr, s * cr + c * sr
            if out is not None:
                out[0][...], out[1][...] = c, s
                c, s = out
    return c, s


class NumpyEvaluator(Evaluator):
    """The NumPy backend: every number an array over entries (steps, or designs x steps)
    that broadcast; ``shape`` is the entries' shape (an int, or a tuple)."""

    def block_system(self, entries, shape):
        return BlockSystem.of(entries, self.art.blocks, self.m, shape)

    def vector(self, values, shape):
        return [full(v, shape) for v in values] if shape is not None else list(values)

    def dense_solve(self, pattern, values, b):
        n = len(b)
        bb = np.stack(b, axis=1) if b[0].ndim == 1 else np.stack(b, axis=-1)
        A = np.zeros(bb.shape[:-1] + (n, n))
        for (i, j), v in zip(pattern, values):
            A[..., i, j] = v
        with np.errstate(invalid="ignore", divide="ignore"):
            x = np.linalg.solve(A, bb[..., None])[..., 0]
        return list(np.moveaxis(x, -1, 0))

    def force_zeros(self, like):
        return list(np.zeros((len(self.art.force_names),) + np.shape(like)))

    def loads_at(self, scene, q: dict, P=None):
        """``P`` (:attr:`params` unless given) with the forces and torques of the loads that
        vary over the cycle scaled by their factors at the driver values ``q`` (arrays over
        the entries, :func:`~linkage_sym.numeric.forces.loads.load_factor`); ``None`` when
        the scene has no such load."""
        return self.scaled_loads(P, {i: load_factor(ld, q) for i, ld in enumerate(scene.loads)
                                     if ld.driver is not None})

    def condition_numbers(self, A, L):
        """Dimensionless condition numbers of ``A`` (K, m, m): rows of lengths over ``L``,
        columns of slides times ``L`` (``L`` a number or (K,))."""
        art = self.art
        L = np.asarray(L, float)
        if L.ndim:
            rl = np.where(np.array(art.rows_length)[None, :], 1.0 / L[:, None], 1.0)
            cl = np.where(np.array(art.cols_length)[None, :], L[:, None], 1.0)
            As = A * rl[:, :, None] * cl[:, None, :]
        else:
            rl = np.where(art.rows_length, 1.0 / L, 1.0)
            cl = np.where(art.cols_length, L, 1.0)
            As = A * rl[None, :, None] * cl[None, None, :]
        good = np.isfinite(As).all(axis=(1, 2))
        cond = np.full(len(As), np.inf)
        if good.any():
            sv = np.linalg.svd(As if good.all() else As[good], compute_uv=False)
            with np.errstate(divide="ignore"):
                cond[good] = sv[:, 0] / sv[:, -1]
        return cond
