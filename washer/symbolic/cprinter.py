"""A small, deterministic C++ printer for symengine expressions.

Why not symengine.ccode: it prints integer powers as pow(x, 2) and keeps
rational exponents as pow(x, 3.0/2.0); gcc does not turn the latter into
sqrt without -ffast-math. This printer writes products and sqrt instead, and
every integer as a double literal (no accidental integer division).
"""
from __future__ import annotations

import symengine as se

_FUNCS = {"sin": "std::sin", "cos": "std::cos", "exp": "std::exp", "log": "std::log",
          "tan": "std::tan", "atan": "std::atan"}


class CxxPrinter:
    """Print symengine expressions with symbol names mapped through `names`."""

    def __init__(self, names: dict[str, str]):
        self.names = names

    def __call__(self, e) -> str:
        return self._p(e)

    def _number(self, e) -> str:
        if isinstance(e, se.Integer):
            return f"{int(e)}.0"
        if isinstance(e, se.Rational):
            p, q = e.get_num_den()
            return f"({int(p)}.0/{int(q)}.0)"
        return repr(float(e))

    def _pow(self, base, ex) -> str:
        b = self._p(base)
        if isinstance(ex, se.Integer):
            n = int(ex)
            if 1 <= abs(n) <= 4:
                prod = "*".join([b] * abs(n))
                return f"({prod})" if n > 0 else f"(1.0/({prod}))"
            return f"std::pow({b}, {n}.0)"
        if isinstance(ex, se.Rational):
            p, q = (int(v) for v in ex.get_num_den())
            if q == 2 and abs(p) <= 3:
                core = f"std::sqrt({b})" if abs(p) == 1 else f"({b}*std::sqrt({b}))"
                return core if p > 0 else f"(1.0/{core})"
        return f"std::pow({b}, {self._p(ex)})"

    def _p(self, e) -> str:
        if isinstance(e, se.Symbol):
            return self.names.get(str(e), str(e))
        if e.is_Number:
            return self._number(e)
        if isinstance(e, se.Add):
            return "(" + " + ".join(self._p(a) for a in e.args) + ")"
        if isinstance(e, se.Mul):
            return "(" + "*".join(self._p(a) for a in e.args) + ")"
        if isinstance(e, se.Pow):
            return self._pow(*e.args)
        name = e.get_type_name() if hasattr(e, "get_type_name") else type(e).__name__
        fname = _FUNCS.get(name.lower())
        if fname is None:
            raise NotImplementedError(f"cannot print {name}: {e}")
        return f"{fname}({self._p(e.args[0])})"
