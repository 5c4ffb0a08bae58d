"""Stepped solvers of the radiosity system ``M B = E`` and of its dual ``M^T I = R``.

Every solver has the same shape, so a notebook can watch any of them converge::

    solver = GaussSeidelSolver(system, E)            # or dual=True with R for importance
    step = solver.step()                             # Step(iteration, residual, seconds)
    history = solver.solve(tol=1e-6, max_iter=200)   # steps until the residual is below tol
    B = solver.solution                              # (N, 3)

``residual`` is ``max |b - M x| / max |b|`` for all of them. ``M = I - diag(rho) F``.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from dualight import _core


@dataclass(frozen=True)
class Step:
    """What one solver step reports."""

    iteration: int
    residual: float
    seconds: float


class _Stepped:
    """Shared ``solve`` loop over ``step``."""

    name = "solver"

    def step(self) -> Step:
        """One iteration (for the direct solver: the whole LU solve); returns its Step."""
        raise NotImplementedError

    @property
    def residual(self) -> float:
        """Relative residual ``max |b - M x| / max |b|`` of the current solution."""
        raise NotImplementedError

    @property
    def solution(self) -> np.ndarray:
        """The current solution, one RGB row per patch."""
        raise NotImplementedError

    def solve(self, tol: float = 1e-6, max_iter: int = 1000) -> list[Step]:
        """Step until ``residual <= tol`` or ``max_iter`` steps; returns the steps taken.

        Whether it converged is ``self.converged`` (never silent: see :func:`solve`).
        """
        if not tol > 0:
            raise ValueError(f"tol must be > 0, got {tol}")
        if max_iter < 1:
            raise ValueError(f"max_iter must be >= 1, got {max_iter}")
        history: list[Step] = []
        while len(history) < max_iter:
            history.append(self.step())
            if history[-1].residual <= tol or not np.isfinite(history[-1].residual):
                break
        return history

    def converged(self, tol: float) -> bool:
        return bool(np.isfinite(self.residual) and self.residual <= tol)


class _CoreStepped(_Stepped):
    def __init__(self, core_solver: object) -> None:
        self._core = core_solver

    def step(self) -> Step:
        """One iteration (for the direct solver: the whole LU solve); returns its Step."""
        s = self._core.step()
        return Step(int(s["iteration"]), float(s["residual"]), float(s["seconds"]))

    @property
    def residual(self) -> float:
        """Relative residual ``max |b - M x| / max |b|`` of the current solution."""
        return float(self._core.residual)

    @property
    def iteration(self) -> int:
        return int(self._core.iteration)

    @property
    def solution(self) -> np.ndarray:
        """The current solution, one RGB row per patch."""
        return self._core.solution


class JacobiSolver(_CoreStepped):
    """Jacobi sweeps, ``x <- b + K x`` (gathering; rows in parallel)."""

    name = "jacobi"

    def __init__(
        self,
        system: _core.RadiositySystem,
        rhs: np.ndarray,
        *,
        dual: bool = False,
        threads: int = 0,
    ) -> None:
        super().__init__(_core.JacobiSolver(system, rhs, dual=dual, threads=threads))


class GaussSeidelSolver(_CoreStepped):
    """Gauss-Seidel sweeps in patch order (gathering, each row uses the newest values)."""

    name = "gauss_seidel"

    def __init__(
        self, system: _core.RadiositySystem, rhs: np.ndarray, *, dual: bool = False
    ) -> None:
        super().__init__(_core.GaussSeidelSolver(system, rhs, dual=dual))


class SouthwellSolver(_CoreStepped):
    """Southwell iteration (progressive refinement, shooting).

    Each step shoots ``shots_per_step`` times (default: once per patch, so a step costs about
    a gathering sweep) the patch with the most unshot quantity: unshot power ``A_i |r_i|`` on
    the primal side, unshot importance ``|r_i|`` on the dual side.
    """

    name = "southwell"

    def __init__(
        self,
        system: _core.RadiositySystem,
        rhs: np.ndarray,
        *,
        dual: bool = False,
        shots_per_step: int = 0,
    ) -> None:
        super().__init__(
            _core.SouthwellSolver(system, rhs, dual=dual, shots_per_step=shots_per_step)
        )

    @property
    def unshot(self) -> np.ndarray:
        """The unshot quantity per patch (the residual ``b - M x``), ``(N, 3)``."""
        return self._core.unshot

    @property
    def ambient(self) -> np.ndarray:
        """Cohen et al.'s ambient term (per channel) for display: ``x + rho * ambient``."""
        return np.asarray(self._core.ambient)

    @property
    def shots(self) -> int:
        """Patches shot so far."""
        return int(self._core.shots)


class DirectSolver(_Stepped):
    """Dense LU (one factorisation per channel, for both sides); a step solves exactly."""

    name = "direct"

    def __init__(
        self,
        system: _core.RadiositySystem,
        rhs: np.ndarray,
        *,
        dual: bool = False,
        factors: _core.DirectSolver | None = None,
        threads: int = 0,
        progress: Callable[[int, int], None] | None = None,
    ) -> None:
        """``progress(done, total)`` is called about every 100 ms while the factors are
        computed (panels of 128 columns, three channels); Ctrl-C stops the factorisation."""
        self._system = system
        self._rhs = np.ascontiguousarray(rhs, dtype=np.float64)
        self._dual = dual
        self._factors = (
            factors if factors is not None else _core.DirectSolver(system, threads, progress)
        )
        self._x = np.zeros_like(self._rhs)
        self._residual = 1.0
        self.iteration = 0

    @property
    def factors(self) -> _core.DirectSolver:
        """The LU factors, reusable for the other side of the system."""
        return self._factors

    def step(self) -> Step:
        """One iteration (for the direct solver: the whole LU solve); returns its Step."""
        start = time.perf_counter()
        self._x = self._factors.solve(self._rhs, dual=self._dual)
        self._residual = self._system.residual(self._x, self._rhs, dual=self._dual)
        self.iteration += 1
        return Step(self.iteration, self._residual, time.perf_counter() - start)

    @property
    def residual(self) -> float:
        """Relative residual ``max |b - M x| / max |b|`` of the current solution."""
        return self._residual

    @property
    def solution(self) -> np.ndarray:
        """The current solution, one RGB row per patch."""
        return self._x


SOLVERS: dict[str, type[_Stepped]] = {
    "direct": DirectSolver,
    "jacobi": JacobiSolver,
    "gauss_seidel": GaussSeidelSolver,
    "southwell": SouthwellSolver,
}
