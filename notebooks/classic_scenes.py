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
# # Veach's classic scenes
#
# Three scenes from Veach's thesis, each against its Mitsuba 3 reference (shipped with the
# package): the multiple-importance-sampling plates (fig. 9.2), the room lit indirectly by a
# shaded lamp with a glass egg (ch. 10) and the door ajar with glossy objects (ch. 11).
# `benchmarks/bench_scenes.py` measures every method on them at several budgets; here one
# budget each.

# %%
import os

import matplotlib.pyplot as plt
import numpy as np

import dualight
from dualight import metrics, scenes
from dualight.bench import REFERENCE_DIR

# The test suite runs each notebook at a tiny budget (DUALIGHT_BUDGET=tiny); by hand, in full.
TINY = os.environ.get("DUALIGHT_BUDGET") == "tiny"


def reference(name: str) -> np.ndarray:
    return np.asarray(dualight.Image.load(REFERENCE_DIR / f"{name}_mean.exr"))


def show(panels: list[tuple[str, np.ndarray]], ref: np.ndarray) -> None:
    """The panels side by side at the reference's exposure (99th percentile to white)."""
    exposure = -float(np.log2(np.percentile(dualight.Image(ref).luminance(), 99)))
    fig, axes = plt.subplots(1, len(panels), figsize=(3.6 * len(panels), 3.8))
    for ax, (title, img) in zip(axes, panels, strict=True):
        ax.imshow(dualight.Image(img).tonemap(exposure))
        ax.set_title(title, fontsize=9)
        ax.axis("off")
    plt.show()


# %% [markdown]
# ## Multiple importance sampling (Veach's figure 9.2)
#
# Four plates, smooth at the top to rough at the bottom, mirror four spheres of equal power:
# small and bright on the left, large and dim on the right. Sampling the BSDF finds the small
# lights' highlights on the smooth plates; sampling the lights finds the large lights' on the
# rough plates; MIS (the default) combines both. `render(..., strategies=...)` makes the
# three images; each is unbiased, only their noise differs.

# %%
mis_scene = scenes.veach_mis(resolution=(64, 64))
mis_ref = reference("veach_mis_64")
spp = 4 if TINY else 64
panels = []
for strategies in ("bsdf", "light", "mis"):
    img = dualight.render(
        mis_scene, "path", spp=spp, max_depth=8, seed=1, strategies=strategies, progress=False
    )
    err = metrics.relmse(img, mis_ref)
    print(f"{strategies:>5}: {img.stats['seconds']:.2f} s, relMSE {err:.3g}")
    panels.append((f"{strategies}, {spp} spp\nrelMSE {err:.3g}", np.asarray(img)))
show([*panels, ("Mitsuba reference", mis_ref)], mis_ref)

# %% [markdown]
# ## Light from a hidden lamp (Veach's thesis, ch. 10)
#
# The bulb faces the ceiling inside a glossy shade: everything the camera sees is lit
# indirectly, and the egg's caustic on the table is the ceiling's light focused by glass. A
# path tracer must bounce off the ceiling or the shade before next-event estimation can find
# the bulb; BDPT's light subpaths start there. Equal time: BDPT's.

# %%
bidir_scene = scenes.veach_bidir(resolution=(64, 64))
bidir_ref = reference("veach_bidir_64")
bdpt = dualight.render(bidir_scene, "bdpt", spp=2 if TINY else 32, max_depth=8, seed=1,
                       progress=False)
path = dualight.render(bidir_scene, "path", spp=None, time_limit=bdpt.stats["seconds"],
                       max_depth=8, seed=1, progress=False)
panels = []
for name, img in (("path", path), ("BDPT", bdpt)):
    err = metrics.relmse(img, bidir_ref)
    print(f"{name:>5}: {img.stats['spp']} spp in {img.stats['seconds']:.2f} s, relMSE {err:.3g}")
    panels.append((f"{name}, {img.stats['spp']} spp\nrelMSE {err:.3g}", np.asarray(img)))
show([*panels, ("Mitsuba reference", bidir_ref)], bidir_ref)

# %% [markdown]
# ## The glossy door (Veach's thesis, ch. 11)
#
# The dark room is lit only through the gap of a door ajar, and its copper sphere, frosted
# glass sphere and plastic block reflect that light glossily. BDPT at 40 samples per pixel
# against path-space MLT (Veach's mutations) in the same time.

# %%
door_scene = scenes.door_ajar(resolution=(64, 64), variant="glossy")
door_ref = reference("door_glossy_64")
bdpt = dualight.render(door_scene, "bdpt", spp=2 if TINY else 40, max_depth=8, seed=1,
                       progress=False)
mlt = dualight.render(door_scene, "mlt", spp=None, time_limit=bdpt.stats["seconds"],
                      max_depth=8, seed=1, progress=False)
panels = []
for name, img in (("BDPT", bdpt), ("MLT", mlt)):
    per_pixel = img.stats.get("mutations", img.stats["samples"]) / (64 * 64)
    err = metrics.relmse(img, door_ref)
    print(f"{name:>5}: {per_pixel:.1f} per pixel in {img.stats['seconds']:.2f} s, relMSE {err:.3g}")
    panels.append((f"{name}, {per_pixel:.0f} per pixel\nrelMSE {err:.3g}", np.asarray(img)))
show([*panels, ("Mitsuba reference", door_ref)], door_ref)
