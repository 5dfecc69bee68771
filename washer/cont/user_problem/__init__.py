"""The user's problem turned into callables: the files beside a constants file (AUTO's
e='NAME') read, compiled or traced into the Problem the engine continues. Its modules:

user_files         which file e='NAME' names: NAME.py (Python func or sympy expressions),
                   else AUTO's NAME.f90, NAME.f or NAME.c; load_user_problem
user_files_native  AUTO's Fortran/C user files compiled with user_files_bridge.c (the
                   bridge; its headers are washer/cont/include/) and called through cffi
user_files_sympy   sympy expressions u, par, f generated into C with exact Jacobians
tracer             a Python func recorded on stand-ins and written as AUTO's C user file
user_files_traced  that C compiled and trusted where it is the Python func bit for bit
c_library          C and Fortran compiled into a shared library, cached by content (also
                   used by the compiled correctors for their own C)

Nothing here steps, corrects or locates: the engine above (washer.cont.start, runner,
corrector_algebraic, corrector_periodic) receives a Problem and knows no file.
"""
