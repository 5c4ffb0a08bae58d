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
# # Metropolis light transport against BDPT at equal time
#
# Veach's classic figure: a room lit only through a door left ajar. Almost all light reaches
# the camera through a narrow gap, so independent paths (BDPT) rarely find it, while MLT,
# once a chain holds a path that carries light, explores its neighbours by mutations
# [Veach and Guibas 1997]. In the paper, BDPT at 40 samples per pixel is compared with MLT at
# about 250 mutations per pixel in the same time.

# %%
import os
import time

import matplotlib.pyplot as plt
import numpy as np

import dualight
from dualight import metrics, scenes

# The test suite runs each notebook at a tiny budget (DUALIGHT_BUDGET=tiny); by hand, in full.
TINY = os.environ.get("DUALIGHT_BUDGET") == "tiny"

res = (32, 32) if TINY else (128, 128)
scene = scenes.door_ajar(resolution=res)
reference_spp = 64 if TINY else 4096

# %% [markdown]
# A reference by BDPT at many samples (for the tiny CI budget it is noisy: the figures only
# become meaningful at the full budget).

# %%
start = time.perf_counter()
reference = dualight.render(scene, "bdpt", spp=reference_spp, max_depth=8, seed=99,
                            progress=False)
print(f"reference: {reference_spp} spp in {time.perf_counter() - start:.1f} s")

# %% [markdown]
# BDPT at 40 spp, then MLT (and its flattened-importance variant) for the same wall time.

# %%
bdpt = dualight.render(scene, "bdpt", spp=4 if TINY else 40, max_depth=8, seed=1, progress=False)
budget = bdpt.stats["seconds"]
mlt = dualight.render(scene, "mlt", spp=None, time_limit=budget, max_depth=8, seed=1,
                      progress=False)
flat = dualight.render(scene, "mlt", spp=None, time_limit=budget, max_depth=8, seed=1,
                       progress=False, mlt={"importance": "flattened"})
rows = []
for name, img in (("BDPT", bdpt), ("MLT", mlt), ("MLT, flattened", flat)):
    per_pixel = img.stats["samples"] / (res[0] * res[1])
    err = metrics.relmse(img, reference)
    rows.append((name, img.stats["seconds"], per_pixel, err))
    print(f"{name:15s} {img.stats['seconds']:.2f} s, {per_pixel:6.1f} per pixel, relMSE {err:.3f}")

# %%
fig, axes = plt.subplots(1, 4, figsize=(14, 3.8))
exposure = 2.0
for ax, (name, img) in zip(
    axes,
    (("reference", reference), ("BDPT", bdpt), ("MLT", mlt), ("MLT, flattened", flat)),
    strict=True,
):
    ax.imshow(dualight.Image(np.asarray(img)).tonemap(exposure=exposure))
    ax.set_title(name)
    ax.axis("off")
plt.show()
