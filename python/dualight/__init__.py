"""dualight: light transport duality and Metropolis light transport.

A C++17 core (Embree, TBB) behind a small Python API::

    import dualight
    scene = dualight.scenes.cornell_box(resolution=(128, 128))
    image = dualight.render(scene, method="path", spp=256)
    image.save("cornell.exr")
"""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version

from dualight import metrics, radiosity, scenes
from dualight.image import Image
from dualight.render import METHODS, render
from dualight.scene import Camera, Mesh, Scene

try:
    __version__ = version("dualight")
except PackageNotFoundError:  # running from a source tree
    __version__ = "0.0.0"

__all__ = [
    "METHODS",
    "Camera",
    "Image",
    "Mesh",
    "Scene",
    "__version__",
    "metrics",
    "radiosity",
    "render",
    "scenes",
]
