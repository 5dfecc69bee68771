"""Generate the C++ model kernel from the symbolic equations of motion.

    python -m washer.codegen            # (re)write csrc/generated/
    python -m washer.codegen --check    # exit 1 if the committed files are stale

Writes two functions (see csrc/generated/washer_model.h):
  * washer_gen_mf:     M(q, theta) (eq 49) and f(q, q_dot, theta, w, w_dot) (eq 48);
  * washer_gen_derivs: df/dq, df/dq_dot, df/d(theta, w, w_dot), df/dP and the
    derivatives of M(q, theta) a for a given acceleration a, which is all an
    analytic Jacobian of q_ddot = M^-1 f needs without a symbolic inverse.
The mass matrix is never inverted symbolically: C++ solves M a = f (LDLT).

Differentiation and common-subexpression elimination run in symengine (sympy's
own jacobian is ~100x slower on these expressions). The
output is deterministic and stamped with a hash of its inputs, so a test can
tell when the committed code is stale.
"""
from __future__ import annotations

import argparse
import hashlib
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
OUT_DIR = ROOT / "csrc" / "generated"
#: Files whose content determines the generated code.
INPUTS = ("washer/machine/layout.py", "washer/codegen.py", "washer/symbolic/kinematics.py",
          "washer/symbolic/bodies.py", "washer/symbolic/rods.py", "washer/symbolic/lagrange.py",
          "washer/symbolic/cprinter.py")


def input_hash() -> str:
    """sha256 over the generator's input files (their bytes, in INPUTS order)."""
    h = hashlib.sha256()
    pkg = Path(__file__).resolve().parent
    for rel in INPUTS:
        h.update(rel.encode())
        h.update((pkg.parent / rel).read_bytes())
    return h.hexdigest()


def stamp_of(text: str) -> str | None:
    """The input hash recorded in a generated file, or None."""
    for line in text.splitlines()[:12]:
        if line.startswith("// inputs-sha256: "):
            return line.split(": ", 1)[1].strip()
    return None


def _emit_function(name: str, args: str, outputs: list[tuple[str, list]], printer,
                   column_of=None) -> str:
    """One C++ function: a single CSE over every output, then assignments.
    column_of(out, i): the bit of the function's `pmask` argument that output out[i]
    is computed for (None: always computed). An output whose bit is clear is 0.0, and a
    temporary only such outputs read is not computed (0.0): the outputs asked for are
    the same temporaries and expressions, so the same values bit for bit."""
    import symengine as se
    flat = [e for _, exprs in outputs for e in exprs]
    reps, reduced = se.cse(flat)
    guard = [None] * len(reps)
    if column_of is not None:
        always = -1
        where = {sym: k for k, (sym, _) in enumerate(reps)}
        need = [0] * len(reps)
        bits = [column_of(out, i) for out, exprs in outputs for i in range(len(exprs))]
        for e, bit in zip(reduced, bits):
            for sym in e.free_symbols:
                if sym in where:
                    need[where[sym]] |= always if bit is None else 1 << bit
        # a temporary reads only earlier ones: its needs reach them
        for k in range(len(reps) - 1, -1, -1):
            for sym in reps[k][1].free_symbols:
                if sym in where:
                    need[where[sym]] |= need[k]
        guard = [None if m == always or m < 0 else m for m in need]
    lines = [f"void {name}({args})", "{"]
    for (sym, expr), g in zip(reps, guard):
        if g is None:
            lines.append(f"    const double {sym} = {printer(expr)};")
        else:
            lines.append(f"    const double {sym} = (pmask & {g:#x}u) ? {printer(expr)} : 0.0;")
    k = 0
    for out, exprs in outputs:
        for i in range(len(exprs)):
            e = reduced[k]
            bit = None if column_of is None else column_of(out, i)
            k += 1
            if e == 0:
                lines.append(f"    {out}[{i}] = 0.0;")
            elif bit is None:
                lines.append(f"    {out}[{i}] = {printer(e)};")
            else:
                lines.append(f"    {out}[{i}] = (pmask & {1 << bit:#x}u) ? {printer(e)} : 0.0;")
    lines.append("}")
    return "\n".join(lines) + "\n", len(reps)


def generate() -> dict[str, str]:
    """Derive, differentiate, CSE and print. Returns {filename: text}."""
    import sympy
    import symengine as se

    from washer.machine import layout
    from washer.symbolic.bodies import default_structure, param_symbols
    from washer.symbolic.cprinter import CxxPrinter
    from washer.symbolic.lagrange import coordinates, equations_of_motion

    P = param_symbols()
    c = coordinates()
    eom = equations_of_motion(default_structure(P), c)

    q = [se.sympify(s) for s in c.q]
    qd = [se.sympify(s) for s in c.qd]
    th, w, wd = (se.sympify(s) for s in (c.theta, c.w, c.wd))
    pd = [se.sympify(P[n]) for n in layout.SYMBOLIC_DIFF_PARAMS]
    a = [se.Symbol(f"acc{i}") for i in range(6)]

    M = se.DenseMatrix(6, 6, [se.sympify(e) for e in eom.M])
    f = se.DenseMatrix(6, 1, [se.sympify(e) for e in eom.f])
    Ma = M * se.DenseMatrix(6, 1, a)

    def jac(vec, xs):      # row-major 6 x len(xs)
        J = vec.jacobian(se.DenseMatrix(len(xs), 1, xs))
        return [J[i, j] for i in range(J.rows) for j in range(J.cols)]

    names = {str(s): f"q[{i}]" for i, s in enumerate(q)}
    names |= {str(s): f"qd[{i}]" for i, s in enumerate(qd)}
    names |= {"theta": "th", "w": "w", "wd": "wd"}
    names |= {f"acc{i}": f"a[{i}]" for i in range(6)}
    names |= {n: f"P[{layout.INDEX[n]}]" for n in layout.PARAM_NAMES}
    printer = CxxPrinter(names)

    common = ("const double *q, const double *qd, double th, double w, double wd, "
              "const double *P")
    mf, n1 = _emit_function(
        "washer_gen_mf", common + ", double *M, double *f",
        [("M", [M[i, j] for i in range(6) for j in range(6)]), ("f", list(f))], printer)
    derivs, n2 = _emit_function(
        "washer_gen_derivs",
        common + ", const double *a, double *fq, double *fqd, double *fth, double *fw, "
        "double *fwd, double *fp, double *Gq, double *Gth, double *Gp, unsigned pmask",
        [("fq", jac(f, q)), ("fqd", jac(f, qd)), ("fth", list(f.diff(th))),
         ("fw", list(f.diff(w))), ("fwd", list(f.diff(wd))), ("fp", jac(f, pd)),
         ("Gq", jac(Ma, q)), ("Gth", list(Ma.diff(th))), ("Gp", jac(Ma, pd))], printer,
        column_of=lambda out, i: i % len(pd) if out in ("fp", "Gp") else None)

    stamp = [
        "// GENERATED by `python -m washer.codegen` -- do not edit by hand.",
        f"// inputs-sha256: {input_hash()}",
        f"// sympy {sympy.__version__}, symengine {se.__version__}",
        f"// structure: {len(layout.PARAM_NAMES)} parameters, {layout.N_RODS} rods; "
        f"CSE temporaries: {n1} (mf), {n2} (derivs)",
    ]
    nsd = len(layout.SYMBOLIC_DIFF_PARAMS)
    header = "\n".join(stamp + [
        "#ifndef WASHER_MODEL_H", "#define WASHER_MODEL_H", "",
        f"#define WASHER_N_PARAMS {len(layout.PARAM_NAMES)}",
        f"#define WASHER_N_RODS {layout.N_RODS}",
        f"#define WASHER_N_SYMDIFF {nsd}",
        f"#define WASHER_N_DIFF {len(layout.DIFF_PARAMS)}",
        f"#define WASHER_DIFF_OMEGA_COL {layout.DIFF_PARAMS.index('Omega')}",
        f'#define WASHER_INPUTS_SHA256 "{input_hash()}"',
        "",
        "// Kernel parameter vector P[] (order of washer/machine/layout.py).",
        *[f"#define WP_{n} {i}" for i, n in enumerate(layout.PARAM_NAMES)],
        "",
        "// Columns of fp and Gp: parameters differentiated symbolically.",
        "static const int WASHER_SYMDIFF_INDEX[WASHER_N_SYMDIFF] = {"
        + ", ".join(f"WP_{n}" for n in layout.SYMBOLIC_DIFF_PARAMS) + "};",
        "static const char *const WASHER_PARAM_NAMES[WASHER_N_PARAMS] = {"
        + ", ".join(f'"{n}"' for n in layout.PARAM_NAMES) + "};",
        "",
        "// M row-major 6x6 (eq 49); f the rest of eq 48, so that M q_ddot = f.",
        f"void washer_gen_mf({common}, double *M, double *f);",
        "// Row-major 6xN derivatives of f and of G(a) = M(q, theta) a (a held fixed).",
        "// fp and Gp: the columns j with bit j of pmask set (WASHER_SYMDIFF_INDEX[j]),",
        "// the others 0 (the work only they need is skipped; the others' values are",
        "// the same whatever the mask).",
        f"void washer_gen_derivs({common}, const double *a, double *fq, double *fqd, "
        "double *fth, double *fw, double *fwd, double *fp, double *Gq, double *Gth, double *Gp, "
        "unsigned pmask);",
        "", "#endif", ""])
    source = "\n".join(stamp + ['#include "washer_model.h"', "#include <cmath>", "",
                                mf, derivs])
    return {"washer_model.h": header, "washer_model.cpp": source}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m washer.codegen", description=__doc__.split("\n")[0])
    ap.add_argument("--check", action="store_true",
                    help="regenerate in memory and compare with csrc/generated/ (exit 1 if stale)")
    ap.add_argument("--out", type=Path, default=OUT_DIR, help="output folder")
    args = ap.parse_args(argv)
    if not (args.out.parent / "washer_api.h").exists() and args.out == OUT_DIR:
        # An installed wheel has no csrc/: the generated C++ is compiled into
        # washer/_kernel already, and regenerating it only makes sense where it
        # can be rebuilt.
        print(f"error: {OUT_DIR.parent} does not exist: `python -m washer.codegen` regenerates "
              "the C++ sources of a source checkout (git clone, then `pip install -e .`); "
              "an installed wheel has none. Use --out DIR to write the generated files "
              "elsewhere.", file=sys.stderr)
        return 2
    files = generate()
    if args.check:
        stale = [n for n, t in files.items()
                 if not (args.out / n).exists() or (args.out / n).read_text() != t]
        for n in stale:
            print(f"stale: {args.out / n} differs from the generator's output", file=sys.stderr)
        return 1 if stale else 0
    args.out.mkdir(parents=True, exist_ok=True)
    for name, text in files.items():
        (args.out / name).write_text(text)
        print(f"wrote {args.out / name} ({len(text.splitlines())} lines)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
