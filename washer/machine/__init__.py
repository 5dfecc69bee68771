"""The numeric machine: the parameter vector (layout), parameter sets (params), the compiled
kernel (kernel), the Model (model: right-hand sides, Jacobians, equilibria, eigenvalues),
equilibria followed from the reference set (equilibria), time responses (responses) and the
forced periodic response by shooting (forced)."""
