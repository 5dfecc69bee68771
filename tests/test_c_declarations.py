"""The C interfaces declared twice say the same in both places.

The C the engine compiles at run time (the user files' bridge user_files_bridge.c, the
compiled corrector's ae_callback.c and ae_generated.c, the generated C of sympy problems)
is loaded through cffi with its declarations written again as cdef strings in Python, and
the generated sympy functions are called from C through function-pointer types declared
in ae_generated.c and csrc/cont/cont_api.h. cffi trusts a cdef: a parameter added, dropped
or retyped on one side only passes wrong arguments without an error. These tests read the
declarations from both sides and compare them (comments, preprocessor lines and white
space aside; a function's definition counts as its prototype).
"""
import re
from pathlib import Path

import pytest
import sympy

from washer.cont import corrector_algebraic
from washer.cont.user_problem import user_files_native, user_files_sympy

ROOT = Path(__file__).resolve().parent.parent
CONT = ROOT / "washer" / "cont"


def _strip(c: str) -> str:
    """C text without comments and preprocessor lines."""
    c = re.sub(r"/\*.*?\*/", " ", c, flags=re.S)
    c = re.sub(r"//[^\n]*", " ", c)
    return re.sub(r"^[ \t]*#(?:[^\n]*\\\n)*[^\n]*", " ", c, flags=re.M)


def _norm(s: str) -> str:
    """White space folded, and none around punctuation."""
    s = re.sub(r"\s+", " ", s).strip()
    return re.sub(r"\s*([(),;*{}\[\]])\s*", r"\1", s)


def declarations(c: str) -> set:
    """The top-level declarations of C text, normalised: typedefs (a struct's body kept),
    prototypes, and the signature of each function definition as a prototype."""
    c = _strip(c)
    out, buf, i = set(), [], 0
    while i < len(c):
        ch = c[i]
        if ch == ";":
            out.add(_norm("".join(buf) + ";"))
            buf = []
        elif ch == "{":
            depth, j = 1, i + 1
            while depth:
                depth += {"{": 1, "}": -1}.get(c[j], 0)
                j += 1
            head = "".join(buf)
            if _norm(head).endswith(")"):                 # a function's body: dropped
                out.add(_norm(head + ";"))
                buf = []
            else:                                          # a struct's: part of the typedef
                buf.append(c[i:j])
            i = j
            continue
        else:
            buf.append(ch)
        i += 1
    return out


def parameter_types(decl: str) -> list:
    """The parameter types of a normalised prototype or function-pointer typedef (its
    last parenthesised list), each without its parameter name."""
    end = decl.rindex(")")
    depth, start = 0, end
    while True:
        depth += {")": 1, "(": -1}.get(decl[start], 0)
        if depth == 0:
            break
        start -= 1
    return [re.sub(r"\w+$", "", p) for p in decl[start + 1:end].split(",")]


def named(decls: set, name: str) -> str:
    """The one declaration of `name` (a function or a function-pointer type)."""
    hits = [d for d in decls if re.search(rf"(\(\*|[ *]){name}\)?\(", d)]
    assert len(hits) == 1, (name, hits)
    return hits[0]


@pytest.mark.parametrize("cdef, source", [
    (user_files_native.CDEF, CONT / "user_problem" / "user_files_bridge.c"),
    (corrector_algebraic._CALLBACK_CDEF, CONT / "ae_callback.c"),
    (corrector_algebraic._GENERATED_CDEF, CONT / "ae_generated.c"),
], ids=["user_files_bridge", "ae_callback", "ae_generated"])
def test_every_cdef_declaration_is_the_c_sources(cdef, source):
    want = declarations(cdef)
    assert len(want) >= 4
    assert want <= declarations(source.read_text()), want - declarations(source.read_text())


def test_the_generated_sympy_functions_fit_the_pointers_that_call_them():
    """washer_sym_func and washer_sym_jac as user_files_sympy.generate_c writes them, as
    user_files_sympy.CDEF declares them, and the pointer types the compiled correctors call
    them through (ae_generated.c and its cdef; cont_api.h's cont_po_sym_*) take the same
    parameters."""
    u1, u2, p1 = sympy.symbols("u1 u2 p1")
    generated = declarations(user_files_sympy.generate_c([u1, u2], {1: p1}, [p1 * u1 - u2, u1 * u2]))
    assert user_files_sympy.CDEF and declarations(user_files_sympy.CDEF) <= generated
    pointers = [declarations((CONT / "ae_generated.c").read_text()),
                declarations(corrector_algebraic._GENERATED_CDEF),
                declarations((ROOT / "csrc" / "cont" / "cont_api.h").read_text())]
    for fn, types in (("washer_sym_func", ("ae_sym_func", "cont_po_sym_func")),
                      ("washer_sym_jac", ("ae_sym_jac", "cont_po_sym_jac"))):
        want = parameter_types(named(generated, fn))
        assert len(want) >= 5
        for decls, ptr in zip(pointers, (types[0], types[0], types[1])):
            assert parameter_types(named(decls, ptr)) == want, (fn, ptr)


def test_a_changed_declaration_is_seen():
    """The comparison sees a retyped parameter and a dropped one (so the tests above can
    fail)."""
    decls = declarations(corrector_algebraic._CALLBACK_CDEF)
    source = declarations((CONT / "ae_callback.c").read_text())
    retyped = {d.replace("double h2", "int h2") for d in decls}
    dropped = {d.replace(",double*work)", ")") for d in decls}
    assert retyped != decls and not retyped <= source
    assert dropped != decls and not dropped <= source
