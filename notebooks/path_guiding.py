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
# # Path guiding: the duality applied to path sampling
#
# Radiance tells a camera path where light comes from; importance tells a light path where it
# will be seen. `render(..., guiding=True)` first learns one of them as it traces (an SD-tree of
# Müller, Gross and Novák 2017: a binary tree over the scene with a quadtree of directions in each
# leaf), then samples each direction from the guide or the BSDF. Here, Veach's door: the camera's
# room is lit only through the gap of a door ajar.

# %%
import os

import matplotlib.pyplot as plt
import numpy as np

import dualight
from dualight import guiding, scenes
from dualight.bench import REFERENCE_DIR

# The test suite runs each notebook at a tiny budget (DUALIGHT_BUDGET=tiny); by hand, in full.
TINY = os.environ.get("DUALIGHT_BUDGET") == "tiny"
scene = scenes.door_ajar(resolution=(64, 64))
radiance = dualight.train_guide(scene, "radiance", spp=16 if TINY else 256, max_depth=8)
importance = dualight.train_guide(scene, "importance", spp=16 if TINY else 256, max_depth=8)
print("radiance guide:", radiance.stats)
print("importance guide:", importance.stats)

# %% [markdown]
# ## The spatial subdivision
#
# Seen from above (x across, z up the page; the dark room below z = 4, the bright room above):
# each leaf's box, shaded by its learnt probability of sampling the BSDF instead of the guide
# (1: the leaf learnt too little to guide).

# %%
fig, axes = plt.subplots(1, 2, figsize=(9, 5))
GUIDES = (("radiance", radiance), ("importance", importance))
for ax, (title, guide) in zip(axes, GUIDES, strict=True):
    leaves = guide.leaves()
    for lo, hi, f in zip(leaves["lo"], leaves["hi"], leaves["bsdf_fraction"], strict=True):
        ax.add_patch(
            plt.Rectangle(
                (lo[0], lo[2]),
                hi[0] - lo[0],
                hi[2] - lo[2],
                fill=True,
                facecolor=plt.cm.viridis(f),
                edgecolor="k",
                lw=0.3,
            )
        )
    ax.set_xlim(leaves["lo"][:, 0].min(), leaves["hi"][:, 0].max())
    ax.set_ylim(leaves["lo"][:, 2].min(), leaves["hi"][:, 2].max())
    ax.set_aspect("equal")
    ax.set_title(f"{title} guide: {len(leaves['lo'])} leaves")
plt.show()

# %% [markdown]
# ## Directions at a point
#
# The radiance guide on the dark room's floor points at the gap (the bright room seen through
# it); the importance guide on the bright room's floor points where particles reach the camera's
# room. The square is the cylindrical map: `(cos theta + 1) / 2` across (theta from +z, towards
# the door), `phi / 2 pi` up.

# %%
fig, axes = plt.subplots(1, 2, figsize=(10, 4.2))
guiding.plot_directional(radiance, (2.0, 0.01, 2.0), axes[0])
axes[0].set_title("radiance at (2, 0, 2), dark room")
guiding.plot_directional(importance, (2.0, 0.01, 6.0), axes[1])
axes[1].set_title("importance at (2, 0, 6), bright room")
plt.show()

# %% [markdown]
# ## Guided and unguided at equal time
#
# Training counts in the time. Each image is unbiased; the guide moves samples, and each
# direction's weight follows the mixture's density. (What the guide gains, and what it costs, at
# several budgets: `benchmarks/bench_guiding.py`.)

# %%
seconds = 0.5 if TINY else 8.0
ref = np.asarray(dualight.Image.load(REFERENCE_DIR / "door_64_mean.exr"))
exposure = -float(np.log2(np.percentile(dualight.Image(ref).luminance(), 99)))
panels = []
for method, guided in (("path", False), ("path", True), ("light", False), ("light", True)):
    image = dualight.render(
        scene, method, time_limit=seconds, spp=None, max_depth=8, guiding=guided, progress=False
    )
    rel = dualight.metrics.relmse(image, ref)
    panels.append((f"{method}{' guided' if guided else ''}: relMSE {rel:.3g}", image))
fig, axes = plt.subplots(1, 4, figsize=(14, 3.8))
for ax, (title, image) in zip(axes, panels, strict=True):
    ax.imshow(image.tonemap(exposure))
    ax.set_title(title, fontsize=9)
    ax.axis("off")
plt.show()
