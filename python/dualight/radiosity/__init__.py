"""Radiosity and importance: the linear systems ``M B = E`` and ``M^T I = R``.

``M_ij = delta_ij - rho_i F_ij`` for diffuse patches; ``R_i > 0`` for patches the camera sees.
The measurement ``<R, B> = <I, E>`` can be answered by either system alone: gathering energy
is shooting importance and vice versa.

    sol = dualight.radiosity.solve(scene, method="gauss_seidel", max_edge=50.0)
    sol.measurement_primal, sol.measurement_dual      # equal to the solver tolerance
    sol.render(mode="superposition")                  # where the work matters for the view
"""

from dualight.radiosity.hierarchical import HierarchicalSolver, HierarchicalStep
from dualight.radiosity.patches import PatchMesh
from dualight.radiosity.solution import Solution, receiver
from dualight.radiosity.solve import ConvergenceWarning, form_factor_checks, form_factors, solve
from dualight.radiosity.solvers import (
    SOLVERS,
    DirectSolver,
    GaussSeidelSolver,
    JacobiSolver,
    SouthwellSolver,
    Step,
)

__all__ = [
    "SOLVERS",
    "ConvergenceWarning",
    "DirectSolver",
    "GaussSeidelSolver",
    "HierarchicalSolver",
    "HierarchicalStep",
    "JacobiSolver",
    "PatchMesh",
    "Solution",
    "SouthwellSolver",
    "Step",
    "form_factor_checks",
    "form_factors",
    "receiver",
    "solve",
]
