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
# # Radiosity and importance
#
# For a diffuse scene cut into patches, radiosity solves `M B = E` with
# `M = I - diag(rho) F`: the light leaving each patch is its emission plus what it reflects
# of the light arriving from every other patch. The camera wants one number per pixel, a
# weighted sum of radiosities `<R, B>`, where `R_i > 0` for the patches it sees (the
# *receiver*). The dual (adjoint) system `M^T I = R` gives each patch's *importance*: how much
# light leaving it would count in the measurement. Either side answers the measurement:
#
# `<R, B> = <I, E>`
#
# Gathering radiosity (Jacobi, Gauss-Seidel) is shooting importance, and shooting radiosity
# (Southwell) is gathering importance [Smits, Arvo and Salesin 1992; Pattanaik 1993].

# %%
import os

import matplotlib.pyplot as plt
import numpy as np

import dualight
from dualight import radiosity, scenes

# The test suite runs each notebook at a tiny budget (DUALIGHT_BUDGET=tiny); by hand, in full.
TINY = os.environ.get("DUALIGHT_BUDGET") == "tiny"

scene = scenes.cornell_box(resolution=(48, 48) if TINY else (256, 256))
max_edge = 120.0 if TINY else 40.0  # patch size in mm: the box is 550 mm wide

# %% [markdown]
# ## Both systems, one measurement

# %%
solution = radiosity.solve(scene, "direct", max_edge=max_edge)
print(f"{solution.stats['patches']} patches")
print("<R, B> =", solution.measurement_primal)
print("<I, E> =", solution.measurement_dual)
print(f"duality gap {solution.duality_gap:.2e}")
assert solution.duality_gap < 1e-6

# %% [markdown]
# ## The three pictures
# Radiosity (what the camera sees), importance (where light would matter for this view) and
# their superposition: reflected light times importance, the work that matters for the view.

# %%
fig, axes = plt.subplots(1, 3, figsize=(12, 4))
for ax, mode in zip(axes, ("radiosity", "importance", "superposition"), strict=True):
    picture = solution.render(mode=mode)
    # Radiosity as 8-bit sRGB (tonemap); importance and superposition come in false colour.
    ax.imshow(picture.tonemap() if mode == "radiosity" else np.asarray(picture))
    ax.set_title(mode)
    ax.axis("off")
plt.show()

# %% [markdown]
# ## Gathering against shooting
# The same system solved by Gauss-Seidel (gathering) and Southwell (shooting). Each step
# reports its residual; both reach the direct solution.

# %%
fig, ax = plt.subplots(figsize=(6, 4))
for method in ("jacobi", "gauss_seidel", "southwell"):
    s = radiosity.solve(
        scene,
        method,
        max_edge=max_edge,
        tol=1e-6,
        max_iter=400 if TINY else 20000,
        precomputed=(solution.form_factors, solution.stats["form_factors"]),
    )
    steps = s.history["radiosity"]
    ax.semilogy([st.iteration for st in steps], [st.residual for st in steps], label=method)
    gap = np.max(np.abs(s.measurement_primal / solution.measurement_primal - 1))
    print(f"{method:13s} {len(steps):6d} steps, measurement within {gap:.1e} of LU")
ax.set_xlabel("step")
ax.set_ylabel("relative residual")
ax.legend()
plt.show()

# %% [markdown]
# ## Importance-driven hierarchical radiosity
# Links between element trees are refined only where energy transfer times importance is
# large, so the elements crowd where the camera looks.

# %%
hier = radiosity.solve(scene, "hierarchical", oracle="importance", epsilon=1e-2 if TINY else 1e-3)
print(f"{hier.stats['leaves']} leaves, {hier.stats['links']} links")
fig, axes = plt.subplots(1, 2, figsize=(8, 4))
axes[0].imshow(hier.render().tonemap())
axes[0].set_title("hierarchical radiosity")
axes[1].imshow(np.asarray(hier.render(mode="links")))
axes[1].set_title("links per unit area")
for ax in axes:
    ax.axis("off")
plt.show()
print("dualight", dualight.__version__)
