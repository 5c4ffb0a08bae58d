# ---
# jupyter:
#   jupytext:
#     formats: ipynb,py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # A Metropolis sampling primer
#
# Metropolis light transport samples paths in proportion to their contribution `f(x)`
# without ever normalising `f`. This notebook shows the three ideas it rests on, on a 1D
# target as in Pharr's course notes on MLT: the **acceptance** rule that makes `f` the
# chain's stationary density, the **start-up bias** of a chain started anywhere, and how
# Veach removes it: start from a sample resampled in proportion to `f / p` and scale by an
# independent estimate of `b = integral of f`.

# %%
import os

import matplotlib.pyplot as plt
import numpy as np

# The test suite runs each notebook at a tiny budget (DUALIGHT_BUDGET=tiny); by hand, in full.
TINY = os.environ.get("DUALIGHT_BUDGET") == "tiny"

rng = np.random.default_rng(1)


def f(x: np.ndarray) -> np.ndarray:
    """An unnormalised target on [0, 1): a broad bump and a narrow peak."""
    x = np.asarray(x, dtype=float)
    inside = (x >= 0) & (x < 1)
    bumps = np.exp(-(((x - 0.3) / 0.15) ** 2)) + 3 * np.exp(-(((x - 0.8) / 0.02) ** 2))
    return np.where(inside, bumps, 0.0)


xs = np.linspace(0, 1, 2001)
b_exact = np.trapezoid(f(xs), xs)
steps = 20_000 if TINY else 400_000

# %% [markdown]
# ## Acceptance
# Propose `y` from `x` with a symmetric kernel (a small step) or an independent one (a
# uniform "large step"); accept with `a = min(1, f(y) / f(x))`. Detailed balance,
# `f(x) T(x->y) a(x->y) = f(y) T(y->x) a(y->x)`, makes `f` stationary.


# %%
def chain(x0: float, n: int, sigma: float = 0.05, large: float = 0.1):
    x, fx = x0, float(f(x0))
    out = np.empty(n)
    accepted = 0
    for i in range(n):
        y = rng.random() if rng.random() < large else x + sigma * rng.normal()
        fy = float(f(y))
        if fx == 0 or rng.random() < min(1.0, fy / fx):
            x, fx = y, fy
            accepted += 1
        out[i] = x
    return out, accepted / n


samples, rate = chain(0.5, steps)
print(f"acceptance rate {rate:.2f}")
fig, ax = plt.subplots(figsize=(6, 3.5))
ax.hist(samples, bins=200, range=(0, 1), density=True, alpha=0.6, label="chain")
ax.plot(xs, f(xs) / b_exact, label="f / b")
ax.legend()
plt.show()
hist, edges = np.histogram(samples, bins=20, range=(0, 1), density=True)
expected = [
    np.mean(f(np.linspace(a, c, 200))) / b_exact for a, c in zip(edges[:-1], edges[1:], strict=True)
]
tv = 0.5 * np.sum(np.abs(hist - np.array(expected)) * np.diff(edges))
print(f"total variation distance to f / b over 20 bins: {tv:.3f}")

# %% [markdown]
# ## Start-up bias
# A chain started at a point `f` rarely visits (here x = 0.02) spends its first steps there:
# the average of many short chains is biased towards the start. Discarding a "burn-in"
# helps but never removes the bias exactly.

# %%
short, n_chains = 50, 200 if TINY else 2000
starts = [chain(0.02, short)[0] for _ in range(n_chains)]
mean_position = np.mean(starts, axis=0)
true_mean = np.trapezoid(xs * f(xs), xs) / b_exact
fig, ax = plt.subplots(figsize=(6, 3.5))
ax.plot(mean_position, label="mean over chains started at 0.02")
ax.axhline(true_mean, color="k", ls="--", label="E_f[x]")
ax.set_xlabel("step")
ax.legend()
plt.show()

# %% [markdown]
# ## Veach's start: resampling
# Draw `N` independent samples `x_i ~ p` (uniform here); their weights `f(x_i) / p(x_i)`
# estimate `b` and, resampled in proportion to the weights, give start points distributed as
# `f` (for large `N`): no burn-in is needed. MLT then scales the chain's histogram by `b`.

# %%
n_boot = 5_000 if TINY else 100_000
x_boot = rng.random(n_boot)
w = f(x_boot)  # p = 1 on [0, 1)
b_hat = w.mean()
print(f"b estimate {b_hat:.4f} +- {1.96 * w.std() / np.sqrt(n_boot):.4f} (exact {b_exact:.4f})")
chosen = rng.choice(x_boot, size=n_chains, p=w / w.sum())
resampled = [chain(x0, short)[0] for x0 in chosen]
fig, ax = plt.subplots(figsize=(6, 3.5))
ax.plot(mean_position, label="started at 0.02")
ax.plot(np.mean(resampled, axis=0), label="started from resampled bootstrap")
ax.axhline(true_mean, color="k", ls="--", label="E_f[x]")
ax.set_xlabel("step")
ax.legend()
plt.show()
