"""Chi-square machinery for the BSDF sampling tests (no SciPy): Pearson's statistic with
pooled sparse cells, its survival function, and the Sidak-corrected level (Mitsuba's ``chi2``
test)."""

from __future__ import annotations

import math

import numpy as np


def _gamma_q(a: float, x: float) -> float:
    """Regularised upper incomplete gamma function ``Q(a, x)`` [Numerical Recipes 6.2]."""
    if x <= 0.0:
        return 1.0
    log_prefix = -x + a * math.log(x) - math.lgamma(a)
    if x < a + 1.0:  # series for P(a, x)
        term = total = 1.0 / a
        n = a
        for _ in range(100_000):
            n += 1.0
            term *= x / n
            total += term
            if abs(term) < abs(total) * 1e-16:
                break
        return max(0.0, 1.0 - total * math.exp(log_prefix))
    tiny = 1e-300  # continued fraction for Q(a, x), modified Lentz
    b = x + 1.0 - a
    c, d = 1.0 / tiny, 1.0 / b
    h = d
    for i in range(1, 100_000):
        an = -i * (i - a)
        b += 2.0
        d = an * d + b
        d = tiny if abs(d) < tiny else d
        c = b + an / c
        c = tiny if abs(c) < tiny else c
        d = 1.0 / d
        h *= d * c
        if abs(d * c - 1.0) < 1e-16:
            break
    return math.exp(log_prefix) * h


def chi2_sf(statistic: float, dof: int) -> float:
    """P(X >= statistic) for X chi-square distributed with ``dof`` degrees of freedom."""
    return _gamma_q(0.5 * dof, 0.5 * statistic)


def sidak(alpha: float, n_tests: int) -> float:
    return -math.expm1(math.log1p(-alpha) / n_tests)


def pearson(observed: np.ndarray, expected: np.ndarray, min_expected: float = 5.0) -> tuple:
    """Pearson's statistic over cells, pooling those expecting fewer than ``min_expected``
    samples into one cell (merged with the smallest regular cell if still too small).

    Returns ``(statistic, n_cells)``, or ``(inf, n_cells)`` when a cell that expects nothing
    received samples.
    """
    obs, exp = np.ravel(observed).astype(np.float64), np.ravel(expected).astype(np.float64)
    empty = exp <= 1e-9 * exp.sum()
    if obs[empty].sum() > 0:
        return math.inf, int((~empty).sum())
    obs, exp = obs[~empty], exp[~empty]
    order = np.argsort(exp)
    obs, exp = obs[order], exp[order]
    small = exp < min_expected
    cells_obs, cells_exp = list(obs[~small]), list(exp[~small])
    if small.any():
        pooled_obs, pooled_exp = obs[small].sum(), exp[small].sum()
        if pooled_exp < min_expected and cells_exp:
            pooled_obs, pooled_exp = pooled_obs + cells_obs.pop(0), pooled_exp + cells_exp.pop(0)
        cells_obs.append(pooled_obs)
        cells_exp.append(pooled_exp)
    o, e = np.array(cells_obs), np.array(cells_exp)
    return float(np.sum((o - e) ** 2 / e)), len(e)
