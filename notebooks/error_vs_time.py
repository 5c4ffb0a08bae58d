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
# # Error against run time, every method
#
# Each Monte Carlo method renders the Cornell box for a few wall-clock budgets and is
# compared with the Mitsuba 3 reference stored with the tests (relMSE, pbrt-v4's definition,
# minus the reference's own noise); radiosity (hierarchical, importance-driven) at a few
# refinement thresholds. On a log-log plot an unbiased estimator falls with slope -1 (error
# proportional to 1 / time); radiosity's error is discretisation bias and levels off.
# `python -m dualight bench` runs the same comparison on five scenes and writes a table.

# %%
import os
import time
import warnings
from pathlib import Path

import matplotlib.pyplot as plt

import dualight
from dualight import bench, plotting, radiosity, scenes

# The test suite runs each notebook at a tiny budget (DUALIGHT_BUDGET=tiny); by hand, in full.
TINY = os.environ.get("DUALIGHT_BUDGET") == "tiny"

scene = scenes.cornell_box(resolution=(64, 64))
reference = bench.load_reference("cornell", "test:cornell_64", scene, Path("out/cache"))
assert reference is not None, "the Mitsuba references ship with dualight (dualight/data/references)"
budgets = [0.05, 0.1] if TINY else [0.25, 0.5, 1.0, 2.0, 4.0]
methods = ("path", "bdpt", "mlt") if TINY else dualight.METHODS

# %%
curves = {}
for method in methods:
    points = []
    for budget in budgets:
        image = dualight.render(scene, method, spp=None, time_limit=budget, max_depth=8,
                                seed=1, progress=False)
        points.append((image.stats["seconds"], bench.errors(image, reference)["relmse"]))
    curves[method] = points
    print(method, [f"{e:.3g}" for _, e in points])

points = []
for eps in [1e-2] if TINY else [1e-2, 3e-3, 1e-3]:
    start = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        solution = radiosity.solve(scene, "hierarchical", epsilon=eps)
        image = solution.render()
    points.append((time.perf_counter() - start, bench.errors(image, reference)["relmse"]))
curves["radiosity (hierarchical)"] = points

# %%
fig, ax = plt.subplots(figsize=(6.5, 4.5))
plotting.relmse_against_time(
    ax, curves, title="Cornell box, 64x64, max_depth 8", xlabel="seconds",
    ylabel="relMSE against Mitsuba 3",
)
plt.show()
