"""dualight: light transport duality and Metropolis light transport.

A C++17 core (Embree, TBB) behind a small Python API::

    import dualight
    scene = dualight.scenes.cornell_box(resolution=(128, 128))
    image = dualight.render(scene, method="path", spp=256)
    image.save("cornell.exr")

Meshes are diffuse by default; ``material=dualight.Mirror()`` or ``dualight.Dielectric(ior=1.5)``
makes them specular (path tracing only: radiosity assumes diffuse surfaces).
"""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version

from dualight import emitters, guiding, io, materials, metrics, radiosity, scenes, textures
from dualight.emitters import (
    ConstantEnvironment,
    DirectionalLight,
    EnvironmentMap,
    PointLight,
    SpotLight,
)
from dualight.guiding import train_guide
from dualight.image import Image
from dualight.io import load_mitsuba_xml, load_obj, read_mitsuba_settings, save_mitsuba_xml
from dualight.materials import (
    Conductor,
    Dielectric,
    Diffuse,
    Material,
    Mirror,
    Plastic,
    RoughConductor,
    RoughDielectric,
    RoughPlastic,
    ThinDielectric,
    TwoSided,
)
from dualight.methods import METHODS
from dualight.render import render
from dualight.scene import Camera, Mesh, Scene
from dualight.textures import Bitmap, Checkerboard

try:
    __version__ = version("dualight")
except PackageNotFoundError:  # running from a source tree
    __version__ = "0.0.0"

__all__ = [
    "METHODS",
    "Bitmap",
    "Camera",
    "Checkerboard",
    "Conductor",
    "ConstantEnvironment",
    "Dielectric",
    "Diffuse",
    "DirectionalLight",
    "EnvironmentMap",
    "Image",
    "Material",
    "Mesh",
    "Mirror",
    "Plastic",
    "PointLight",
    "RoughConductor",
    "RoughDielectric",
    "RoughPlastic",
    "Scene",
    "SpotLight",
    "ThinDielectric",
    "TwoSided",
    "__version__",
    "emitters",
    "guiding",
    "io",
    "load_mitsuba_xml",
    "load_obj",
    "materials",
    "metrics",
    "radiosity",
    "read_mitsuba_settings",
    "render",
    "save_mitsuba_xml",
    "scenes",
    "textures",
    "train_guide",
]
