"""The symbolic derivation of the equations of motion (sympy): kinematics (eqs 1-17), bodies,
rods (eqs 23-46), Lagrange's equations (eqs 18-22, 47-51), the C++ printer; and an independent
second derivation (Newton-Euler, pure numpy) that the tests hold the kernel against."""
