"""The continuation engine: AUTO-07p's algorithms on any equations, in memory first. It
knows nothing of washing machines and reads and writes no b-, s- or d-files (washer.auto
does: a run's files are sinks attached to it). Its modules:

problem       the user's equations (FUNC, STPNT, PVLS, BCND, ICND, FOPT) and their
              finite-difference derivatives; pointwise: when a Python func is
              called once on the arrays of a small stencil;
              parabolic: a parabolic PDE's user problem as the first-order system in x
              that the systems of IPS 11-17 continue
user_problem/ the user's files turned into a Problem (its own list of modules):
              user_files finds them beside the constants file (NAME.py, or AUTO's
              Fortran/C user files: user_files_native with user_files_bridge.c),
              user_files_sympy (sympy expressions generated into C), tracer and
              user_files_traced (a Python func traced into C, trusted where it is the
              Python func bit for bit), c_library (C and Fortran compiled, cached by
              content)
differences   central differences: AUTO's step, the points and the quotient, the one
              definition every finite-difference derivative of the engine uses
constants, settings
              a run's constants (every one with its default, checked as it is set) and
              AUTO's defaults (DEFAULTS), resolved into the frozen Settings
codes, record AUTO's type codes; a written point (b-row and s-record) and FINDLB
system        the contract of a continued system and the registry SYSTEMS; the systems
              themselves are in systems/
linalg, reduction, collocation, floquet, normal_form
              the numerics the systems share: bordered factorisations, AUTO's condensation
              of collocation matrices (compiled), collocation, Floquet multipliers and their
              tests, the first Lyapunov coefficient
lapack        the addresses of numpy's own LAPACK routines, for the compiled engine's
              dense solves and eigenvalues (csrc/cont/dense_lapack.cpp)
newton, corrector_algebraic, corrector_periodic, iterator, events
              the one Newton loop and its compiled forms for equilibria and the fold and
              Hopf loci (C written once in include/ae_correct.h, the GH test's l1 in
              include/ae_lyapunov.h; FUNC from user_problem/user_files_bridge.c, a
              Python func through ae_callback.c, a sympy problem's generated C through
              ae_generated.c) and for periodic orbits (C++ in csrc/cont/po_correct.cpp;
              corrector_algebraic.compiled_corrector chooses where they apply), the
              pseudo-arclength iterator (predictor, corrector, step control), test
              functions' sign changes and their location
start, runner, branch
              a run: its start from constants and restart records, labels, stops and branch
              switching (AUTO's AUTOAE/AUTOBV), its result in memory (Branch)
invariant_circle, circle_runs, pvls
              invariant circles of maps (the circle's equations; the runs of a family of
              them: its first circle, its continuation); what a periodic run's pvls receives

A new continued system (an IPS, an ISW, a locus) is a module of systems/ registering its
class (`system.register(IPS, ISW, start kind)`), named in `systems.MODULES` under its IPS
(tests/test_engine_contract.py checks both) and in systems/'s list; the contract it
implements is `system.ContinuedSystem`. A new test function is a code of `codes.Code`,
evaluated by the system's `test_functions` and accepted by its `accept`; `events`
locates it. Documentation: docs/continuation.md (its table maps each module onto
AUTO-07p's routines).
"""
