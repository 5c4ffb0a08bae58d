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
# # Path-space duality
#
# Radiance `L = Le + T L` and importance `W = We + T* W` are adjoint, and a pixel's
# measurement is `Phi = <L, We> = <Le, W>`. A **path tracer** gathers radiance from the eye; a
# **light tracer** shoots power from the lights and connects every vertex to the camera, so it
# estimates the same integral from the other end [Veach 1997, ch. 3-4]. Both must give the
# same image. **Bidirectional path tracing** builds both subpaths and joins them in every way
# `(s, t)`, weighting the strategies by multiple importance sampling [Veach and Guibas 1995].

# %%
import os

import matplotlib.pyplot as plt
import numpy as np

import dualight
from dualight import metrics, scenes

# The test suite runs each notebook at a tiny budget (DUALIGHT_BUDGET=tiny); by hand, in full.
TINY = os.environ.get("DUALIGHT_BUDGET") == "tiny"

scene = scenes.cornell_box(resolution=(32, 32) if TINY else (128, 128))
spp = 64 if TINY else 256

# %% [markdown]
# ## Gathering radiance and shooting importance give one image

# %%
images = {m: dualight.render(scene, m, spp=spp, max_depth=8, seed=1, progress=False)
          for m in ("path", "light", "bdpt")}
fig, axes = plt.subplots(1, 3, figsize=(12, 4))
for ax, (m, img) in zip(axes, images.items(), strict=True):
    ax.imshow(img.tonemap())
    ax.set_title(f"{m}: {img.stats['seconds']:.2f} s")
    ax.axis("off")
plt.show()

# %% [markdown]
# The two estimators are independent, so a Welch test per 4x4 block (family-wise 1 %) with
# each image's own per-pixel variance checks that they agree. The same test against a light
# tracer with a 10 % dimmer light must fail: the test can tell.

# %%
pt, lt = images["path"], images["light"]
same = metrics.welch_test(pt, pt.variance, lt, lt.variance, block=4)
dim = dualight.render(
    scenes.cornell_box(resolution=pt.shape[1::-1], light_scale=0.9),
    "light", spp=spp, max_depth=8, seed=2, progress=False,
)
control = metrics.welch_test(pt, pt.variance, dim, dim.variance, block=4)
print(f"path vs light: {100 * same.pass_fraction:.0f} % of blocks pass, max z {same.max_z:.2f}")
print(f"path vs dimmer light: {100 * control.pass_fraction:.0f} % pass, max z {control.max_z:.2f}")
assert same.pass_fraction == 1.0 and control.pass_fraction < 1.0

# %% [markdown]
# ## BDPT, strategy by strategy
# Each `(s, t)` uses `s` light vertices and `t` camera vertices; `t = 1` is light tracing,
# `s = 0` is pure path tracing. The MIS-weighted strategy images sum to the BDPT image. MIS
# gives the strategies shares that differ by orders of magnitude, so each panel has its own
# exposure (the factor in its title: its brightest 1 % of pixels at white).

# %%
bdpt = dualight.render(scene, "bdpt", spp=spp, max_depth=3, seed=1, progress=False,
                       strategy_images=True)
layers = {key: np.asarray(bdpt.strategies[key]) for key in sorted(bdpt.strategies)}
for (s, t), layer in layers.items():
    if not layer.any():
        print(f"s={s}, t={t} contributes nothing to this image")
shown = {key: layer for key, layer in layers.items() if layer.any()}
fig, axes = plt.subplots(1, len(shown), figsize=(2.2 * len(shown), 2.6))
for ax, ((s, t), layer) in zip(axes, shown.items(), strict=True):
    white = np.percentile(layer, 99) or layer.max()
    ax.imshow(dualight.Image(layer).tonemap(exposure=-np.log2(white)))
    ax.set_title(f"s={s}, t={t}, x{1 / white:.3g}", fontsize=8)
    ax.axis("off")
plt.show()
total = sum(bdpt.strategies.values())
print("strategies sum to the image:", np.allclose(total, np.asarray(bdpt), rtol=1e-4, atol=1e-6))
