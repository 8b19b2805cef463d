"""The square root of a locus intersection, whose tangency rounding may miss.

A dyad's closed form takes a square root of a product of factors -- Heron's
half-chord ``sqrt((r0 + r1 - d)(d + r0 - r1)(d - r0 + r1)(r0 + r1 + d))``, a
circle and a line's ``sqrt((r - delta)(r + delta))`` -- which vanishes at a
limit (dead-centre) position.  There, in floating point, rounding of the
coordinates may leave a factor a few ulps below zero.  The numeric solver takes
such a miss as the tangency it is
(:func:`linkage_sym.numeric.kinematics.loci.clamp_tangent`); :func:`tangent_sqrt` lets the
generated NumPy code do the same, so both runtimes call the step singular
instead of one of them calling it unassemblable.

Mathematically (printed, differentiated, evaluated by SymPy and by mpmath) it
is ``sqrt(f_1 f_2 ... f_n)``; only its NumPy code differs.

Examples
--------
>>> import sympy as sp
>>> a, b, L = sp.symbols("a b L", real=True)
>>> e = tangent_sqrt(L, a - b, a + b)
>>> print(e)
sqrt((a - b)*(a + b))
>>> float((e.diff(a) - sp.sqrt((a - b) * (a + b)).diff(a)).subs({a: 3, b: 1, L: 1}))
0.0
"""

from __future__ import annotations

import sympy as sp


class coordinate_size(sp.Function):  # noqa: N801 - a SymPy function, named as SymPy's are
    """The largest magnitude of its arguments, for :func:`tangent_sqrt`'s rounding test.

    Unlike ``Max(Abs(...))`` it is never simplified (comparing large symbolic
    coordinates made derivation and code generation take minutes); the NumPy
    code calls ``_coordinate_size`` of :mod:`linkage_sym.codegen.runtime`.
    """

    @classmethod
    def eval(cls, *values):
        if values and all(v.is_number for v in values):
            return sp.Max(*(sp.Abs(v) for v in values))
        return None

    def _numpycode(self, printer):
        return "_coordinate_size(" + ", ".join(printer._print(a) for a in self.args) + ")"

    def _mpmathcode(self, printer):
        return printer._print(sp.Max(*(sp.Abs(v) for v in self.args)))

    def _javascript(self, printer):
        return "_coordinate_size(" + ", ".join(printer._print(a) for a in self.args) + ")"


class tangent_sqrt(sp.Function):  # noqa: N801 - a SymPy function, named as SymPy's are
    """``tangent_sqrt(scale, f_1, ..., f_n)``: ``sqrt(f_1 ... f_n)``; see the module docstring.

    ``scale`` is the size of the coordinates the factors are computed from
    (the numeric solver's ``coordinate_size``); it enters only the NumPy
    code's test of a rounding-level miss, ``_tangent_sqrt`` of
    :mod:`linkage_sym.codegen.runtime`.
    """

    is_real = True
    is_nonnegative = True

    @classmethod
    def eval(cls, scale, *factors):
        if factors and all(f.is_number for f in factors):
            return sp.sqrt(sp.Mul(*factors))
        return None

    def value(self):
        """The plain ``sqrt(f_1 ... f_n)``."""
        return sp.sqrt(sp.Mul(*self.args[1:]))

    def doit(self, **hints):
        return self.value().doit(**hints)

    def _eval_rewrite_as_sqrt(self, *args, **kwargs):
        return self.value()

    def fdiff(self, argindex=1):
        if argindex == 1:
            return sp.S.Zero
        return self / (2 * self.args[argindex - 1])

    def _eval_evalf(self, prec):
        return self.value()._eval_evalf(prec)

    def _sympystr(self, printer):
        return printer._print(self.value())

    def _latex(self, printer, exp=None):
        out = printer._print(self.value())
        return out if exp is None else rf"\left({out}\right)^{{{exp}}}"

    def _numpycode(self, printer):
        return "_tangent_sqrt(" + ", ".join(printer._print(a) for a in self.args) + ")"

    def _mpmathcode(self, printer):
        return printer._print(self.value())

    def _javascript(self, printer):
        # the same rule as the NumPy code's, in the page's runtime
        # (:mod:`linkage_sym.codegen.javascript`)
        return "_tangent_sqrt(" + ", ".join(printer._print(a) for a in self.args) + ")"


__all__ = ["coordinate_size", "tangent_sqrt"]
