"""Built-in scenes.

* :func:`cornell_box`: the Cornell box from the Cornell Program of Computer Graphics'
  measured data (geometry and camera in millimetres), with the RGB reflectances and light
  radiance that Mitsuba 3's ``cornell_box()`` uses for the measured spectra.
  ``variant="caustics"`` swaps the blocks for a mirror and a glass sphere.
* :func:`furnace`: a closed cube with uniform reflectance and emission; every surface has the
  analytic radiance ``Le / (1 - rho)`` (:func:`furnace_radiance`).
* :func:`rooms` and :func:`cube`: the test scenes of importance-driven radiosity.
* :func:`door_ajar`: Veach's door, a room lit only through a door ajar (hard for path tracing);
  ``variant="glossy"`` adds glossy and frosted-glass objects to the dark room.
* :func:`veach_mis` and :func:`veach_bidir`: Veach's multiple-importance-sampling plates and his
  bidirectional room lit indirectly by a shaded lamp, with a glass egg.
* :func:`icosphere`: a sphere mesh (subdivided icosahedron) for any scene.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Literal

import numpy as np

from dualight._shapes import _axis_rect, _orient, _quads_mesh, icosphere
from dualight._veach_scenes import _ior, _scale, door_glossy_objects
from dualight._veach_scenes import veach_bidir as veach_bidir
from dualight._veach_scenes import veach_mis as veach_mis
from dualight.emitters import (
    ConstantEnvironment,
    DirectionalLight,
    EnvironmentMap,
    PointLight,
    SpotLight,
)
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
)
from dualight.scene import Camera, Scene
from dualight.textures import Bitmap, Checkerboard

# Cornell box data, www.graphics.cornell.edu/online/box/data.html (quads, millimetres).
_CORNELL_QUADS: dict[str, list[list[tuple[float, float, float]]]] = {
    "floor": [[(552.8, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 559.2), (549.6, 0.0, 559.2)]],
    "ceiling": [
        [(556.0, 548.8, 0.0), (556.0, 548.8, 559.2), (0.0, 548.8, 559.2), (0.0, 548.8, 0.0)]
    ],
    "back_wall": [
        [(549.6, 0.0, 559.2), (0.0, 0.0, 559.2), (0.0, 548.8, 559.2), (556.0, 548.8, 559.2)]
    ],
    "green_wall": [[(0.0, 0.0, 559.2), (0.0, 0.0, 0.0), (0.0, 548.8, 0.0), (0.0, 548.8, 559.2)]],
    "red_wall": [
        [(552.8, 0.0, 0.0), (549.6, 0.0, 559.2), (556.0, 548.8, 559.2), (556.0, 548.8, 0.0)]
    ],
    "short_block": [
        [(130.0, 165.0, 65.0), (82.0, 165.0, 225.0), (240.0, 165.0, 272.0), (290.0, 165.0, 114.0)],
        [(290.0, 0.0, 114.0), (290.0, 165.0, 114.0), (240.0, 165.0, 272.0), (240.0, 0.0, 272.0)],
        [(130.0, 0.0, 65.0), (130.0, 165.0, 65.0), (290.0, 165.0, 114.0), (290.0, 0.0, 114.0)],
        [(82.0, 0.0, 225.0), (82.0, 165.0, 225.0), (130.0, 165.0, 65.0), (130.0, 0.0, 65.0)],
        [(240.0, 0.0, 272.0), (240.0, 165.0, 272.0), (82.0, 165.0, 225.0), (82.0, 0.0, 225.0)],
    ],
    "tall_block": [
        [
            (423.0, 330.0, 247.0),
            (265.0, 330.0, 296.0),
            (314.0, 330.0, 456.0),
            (472.0, 330.0, 406.0),
        ],
        [(423.0, 0.0, 247.0), (423.0, 330.0, 247.0), (472.0, 330.0, 406.0), (472.0, 0.0, 406.0)],
        [(472.0, 0.0, 406.0), (472.0, 330.0, 406.0), (314.0, 330.0, 456.0), (314.0, 0.0, 456.0)],
        [(314.0, 0.0, 456.0), (314.0, 330.0, 456.0), (265.0, 330.0, 296.0), (265.0, 0.0, 296.0)],
        [(265.0, 0.0, 296.0), (265.0, 330.0, 296.0), (423.0, 330.0, 247.0), (423.0, 0.0, 247.0)],
    ],
}
# The measured light lies in the ceiling's plane; it is lowered by 0.1 mm so the two never
# compete for the same hit (Mitsuba's and pbrt's versions of the scene do the same).
_CORNELL_LIGHT = [
    (343.0, 548.7, 227.0),
    (343.0, 548.7, 332.0),
    (213.0, 548.7, 332.0),
    (213.0, 548.7, 227.0),
]
_CORNELL_ROOM_CENTRE = np.array([278.0, 274.4, 279.6])

# Mitsuba 3's RGB values for the measured Cornell spectra.
CORNELL_WHITE = (0.885809, 0.698859, 0.666422)
CORNELL_RED = (0.570068, 0.0430135, 0.0443706)
CORNELL_GREEN = (0.105421, 0.37798, 0.076425)
CORNELL_LIGHT_RADIANCE = (18.387, 13.9873, 6.75357)
CORNELL_LIGHT_REFLECTANCE = (0.78, 0.78, 0.78)


def cornell_camera(resolution: tuple[int, int] = (128, 128)) -> Camera:
    """The measured Cornell camera: 35 mm focal length on a 25 mm film, looking along +z."""
    fov = math.degrees(2.0 * math.atan(0.5 * 0.025 / 0.035))
    return Camera(
        origin=(278.0, 273.0, -800.0),
        target=(278.0, 273.0, -799.0),
        up=(0.0, 1.0, 0.0),
        fov=fov,
        resolution=resolution,
    )


#: Sphere centres and radius (mm) of ``cornell_box(variant="caustics")``: the mirror sphere
#: at the back left (the red wall's side), the glass sphere at the front right; both rest on
#: the floor, diagonally either side of the point under the light's centre.
CORNELL_MIRROR_SPHERE = ((370.0, 95.0, 370.0), 95.0)
CORNELL_GLASS_SPHERE = ((180.0, 95.0, 165.0), 95.0)
_CORNELL_SPHERE_SUBDIVISIONS = 5
CORNELL_VARIANTS = (
    "classic",
    "caustics",
    "glossy",
    "coated",
    "smooth",
    "textured",
    "point",
    "spot",
    "sun",
    "sky",
    "envmap",
    "lamp",
)
_OPEN_TOP = ("sun", "sky", "envmap")
# The open-top variants' lights: a sun 28 degrees from the zenith, leaning towards the green
# wall and the back (the blocks' shadows fall on the floor), a pale blue sky, and an
# environment image of such a sky with a sun in it (cornell_sky_image).
_CORNELL_SUN_DIRECTION = (-0.35, -1.0, 0.35)
_CORNELL_SUN_IRRADIANCE = (3.0, 2.8, 2.4)
_CORNELL_SKY_RADIANCE = (0.6, 0.75, 1.0)
# The "point" and "spot" variants' lights, below the ceiling light's centre (which stays, not
# emitting): the point light 100 mm below it (closer, the ceiling's 1 / r^2 hot spot made the
# path tracer's estimates heavy-tailed), the spot 10 mm below, shining down. The point light's
# flux is the area light's (intensity = area x radiance / 4); the spot's intensity is the
# point's times 4 / (2 (1 - cos cutoff)), so it sends about the same flux into its cone,
# which leans towards the red wall and the back.
_CORNELL_POINT_POSITION = (278.0, 448.7, 279.5)
_CORNELL_SPOT_POSITION = (278.0, 538.7, 279.5)
_CORNELL_POINT_INTENSITY = tuple(130.0 * 105.0 * c / 4.0 for c in CORNELL_LIGHT_RADIANCE)
_CORNELL_SPOT_AXIS = (0.25, -1.0, 0.15)
# The "smooth" variant's spheres: coarse (320 triangles) so that shading normals matter.
_CORNELL_SMOOTH_SUBDIVISIONS = 2


def cornell_box(
    resolution: tuple[int, int] = (128, 128),
    *,
    light_scale: float = 1.0,
    reflectance_scale: float = 1.0,
    variant: str = "classic",
    ior: float = 1.5,
    roughness_scale: float = 1.0,
    sphere_normals: bool = True,
    texture_shift: float = 0.0,
    spot_cutoff: float = 50.0,
    env_rotation: float = 0.0,
) -> Scene:
    """The Cornell box (measured geometry and camera; Mitsuba 3's RGB materials).

    Parameters
    ----------
    resolution : (int, int), optional
        Image ``(width, height)``.
    light_scale : float, optional
        Multiplies the light's radiance, finite and ``>= 0``.
    reflectance_scale : float, optional
        Multiplies every wall's and block's reflectance (and the mirror's), finite, ``>= 0``
        and small enough that every reflectance stays ``<= 1``. Tests use both scales as
        negative controls.
    variant : {"classic", "caustics", "glossy", "coated", "smooth"}, optional
        ``"classic"``: the measured box with its two white blocks. ``"caustics"``: the same
        room and light with the blocks replaced by two spheres resting on the floor (flat
        :func:`icosphere` triangles, 5 subdivisions: 20,480 each), as in the classic caustic
        scenes of pbrt and Mitsuba: ``mirror_sphere`` (a :class:`~dualight.Mirror` of
        reflectance ``reflectance_scale``, radius 95 mm, centre (370, 95, 370): back left
        in the image) and ``glass_sphere`` (a :class:`~dualight.Dielectric` of index
        ``ior``, radius 95 mm, centre (180, 95, 165): front right). The glass sphere
        focuses the light into a caustic on the floor beside it, towards the camera; the
        mirror shows the room and the light.
        ``"glossy"``: the caustic scene's spheres made rough and its floor coated, the
        materials of Mitsuba's ``roughconductor``, ``roughdielectric`` and ``roughplastic``:
        ``gold_sphere`` (a :class:`~dualight.RoughConductor` of Mitsuba's gold, GGX alpha
        0.2, in place of the mirror), ``frosted_sphere`` (a
        :class:`~dualight.RoughDielectric` of index ``ior``, Beckmann alpha 0.15, in place of
        the glass) and a :class:`~dualight.RoughPlastic` floor (the white base, GGX alpha
        0.3, IOR 1.5). ``"coated"``: the same with smooth materials, Mitsuba's ``conductor``,
        ``thindielectric`` and ``plastic``: ``copper_sphere`` (a
        :class:`~dualight.Conductor` of Mitsuba's copper), ``bubble`` (a
        :class:`~dualight.ThinDielectric` of index ``ior``) and a :class:`~dualight.Plastic`
        floor (the white base, coat of index ``ior``). ``"smooth"``: the caustic scene with
        coarse spheres (2 subdivisions, 320 triangles each) shaded smoothly by their vertex
        normals (``add_mesh(..., normals=...)``): ``white_sphere`` (a
        :class:`~dualight.Diffuse` of the walls' white) and ``glass_sphere`` (a
        :class:`~dualight.Dielectric` of index ``ior``). ``"textured"``: the classic box
        with textures (Mitsuba's ``bitmap`` and ``checkerboard``) on surfaces with texture
        coordinates (each quad spans the unit square of ``(u, v)``): a 16 x 16 bitmap on the
        back wall (bilinear), a checkerboard floor (4 x 4 squares), and the tall block a
        :class:`~dualight.RoughConductor` of Mitsuba's aluminium whose GGX roughness is a
        checkerboard of 0.05 and 0.35. ``"point"`` and ``"spot"``: the classic box lit by a
        :class:`~dualight.PointLight` (of the area light's flux) or a
        :class:`~dualight.SpotLight` (cutoff ``spot_cutoff`` degrees, beam width three
        quarters of it, leaning towards the red wall and the back) 100 mm and 10 mm below the
        ceiling light's centre, which stays as a non-emitting patch. ``"sun"``, ``"sky"`` and
        ``"envmap"``: the classic box without its ceiling and light, open at the top to a
        :class:`~dualight.DirectionalLight` (irradiance (3, 2.8, 2.4) W/m^2, travelling along
        (-0.35, -1, 0.35)), a :class:`~dualight.ConstantEnvironment` (radiance (0.6, 0.75, 1))
        or an :class:`~dualight.EnvironmentMap` of :func:`cornell_sky_image` (a sky with a sun
        in it), each times ``light_scale``. ``"lamp"``: the classic box whose ceiling light's
        radiance is a texture (Mitsuba's ``area`` emitter with a ``bitmap`` ``radiance``,
        :func:`cornell_lamp_texels`): warm at one end, cool at the other, in a checker of
        bright and dim texels, of the classic light's mean radiance times ``light_scale``.
    ior : float, optional
        The glass sphere's index of refraction (``"caustics"`` and ``"glossy"``; any value
        the material accepts).
    roughness_scale : float, optional
        Multiplies every roughness of the ``"glossy"`` variant (a negative control), in
        ``(0, 4]``.
    sphere_normals : bool, optional
        Whether the ``"smooth"`` variant's spheres carry their vertex normals; ``False``
        renders the same triangles flat (a negative control).
    texture_shift : float, optional
        Moves every texture of the ``"textured"`` and ``"lamp"`` variants along ``u`` by this
        much (1/32: half a texel of the back wall; 1/2 swaps the lamp's warm and cool ends; a
        negative control), finite.
    spot_cutoff : float, optional
        The ``"spot"`` variant's cutoff angle in degrees, in (0, 90].
    env_rotation : float, optional
        Turns the ``"envmap"`` variant's environment about the y axis by this many degrees (a
        negative control), finite.

    Returns
    -------
    Scene
        Meshes ``floor``, ``ceiling``, ``back_wall``, ``green_wall``, ``red_wall``, then
        ``short_block`` and ``tall_block`` (classic; the open-top variants have no
        ``ceiling`` and no ``light``), ``mirror_sphere`` and ``glass_sphere``
        (caustics), ``gold_sphere`` and ``frosted_sphere`` (glossy), ``copper_sphere`` and
        ``bubble`` (coated) or ``white_sphere`` and ``glass_sphere`` (smooth), then ``light``.

    Raises
    ------
    ValueError
        For an unknown ``variant``, a scale out of range, or (caustics) an invalid ``ior``.
    """
    if variant not in CORNELL_VARIANTS:
        raise ValueError(
            f"cornell_box: unknown variant {variant!r}; choose one of {', '.join(CORNELL_VARIANTS)}"
        )
    light_scale = float(light_scale)
    if not (math.isfinite(light_scale) and light_scale >= 0.0):
        raise ValueError(f"cornell_box: light_scale must be finite and >= 0, got {light_scale!r}")
    reflectance_scale = float(reflectance_scale)
    largest = 1.0 if variant == "caustics" else max(CORNELL_WHITE)  # the mirror reflects 1
    if not (math.isfinite(reflectance_scale) and 0.0 <= reflectance_scale <= 1.0 / largest):
        raise ValueError(
            f"cornell_box: reflectance_scale must be in [0, {1.0 / largest:.6g}] so every "
            f"reflectance stays <= 1, got {reflectance_scale!r}"
        )
    if not (math.isfinite(float(roughness_scale)) and 0.0 < float(roughness_scale) <= 4.0):
        raise ValueError(f"cornell_box: roughness_scale must be in (0, 4], got {roughness_scale!r}")
    if not math.isfinite(float(texture_shift)):
        raise ValueError(f"cornell_box: texture_shift must be finite, got {texture_shift!r}")
    if not math.isfinite(float(env_rotation)):
        raise ValueError(f"cornell_box: env_rotation must be finite, got {env_rotation!r}")
    if not 0.0 < float(spot_cutoff) <= 90.0:
        raise ValueError(f"cornell_box: spot_cutoff must be in (0, 90], got {spot_cutoff!r}")
    textures = _cornell_textures(float(texture_shift)) if variant == "textured" else {}
    spheres = variant not in ("classic", "textured", "point", "spot", "lamp", *_OPEN_TOP)
    if variant == "glossy":
        a = float(roughness_scale)
        sphere_materials: tuple[Material, Material] = (
            RoughConductor(material="Au", alpha=0.2 * a, distribution="ggx"),
            RoughDielectric(alpha=0.15 * a, ior=ior),
        )
        sphere_names = ("gold_sphere", "frosted_sphere")
    elif variant == "coated":
        sphere_materials = (Conductor(material="Cu"), ThinDielectric(ior=ior))
        sphere_names = ("copper_sphere", "bubble")
    elif variant == "smooth":
        white = tuple(reflectance_scale * c for c in CORNELL_WHITE)
        sphere_materials = (Diffuse(white), Dielectric(ior=ior))
        sphere_names = ("white_sphere", "glass_sphere")
    elif spheres:
        sphere_materials = (Mirror((reflectance_scale,) * 3), Dielectric(ior=ior))
        sphere_names = ("mirror_sphere", "glass_sphere")

    scene = Scene(camera=cornell_camera(resolution))
    materials = {
        "floor": CORNELL_WHITE,
        "ceiling": CORNELL_WHITE,
        "back_wall": CORNELL_WHITE,
        "green_wall": CORNELL_GREEN,
        "red_wall": CORNELL_RED,
        "short_block": CORNELL_WHITE,
        "tall_block": CORNELL_WHITE,
    }
    for name, rho in materials.items():
        if (name.endswith("block") and spheres) or (name == "ceiling" and variant in _OPEN_TOP):
            continue
        quads = [np.array(q, dtype=np.float64) for q in _CORNELL_QUADS[name]]
        if name.endswith("block"):
            centre = np.mean(np.concatenate(quads), axis=0)
            quads = [_orient(q, centre, inward=False) for q in quads]
        else:
            quads = [_orient(q, _CORNELL_ROOM_CENTRE, inward=True) for q in quads]
        v, f = _quads_mesh(quads)
        albedo = tuple(reflectance_scale * c for c in rho)
        if name in textures:
            uv = np.tile([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]], (len(quads), 1))
            scene.add_mesh(v, f, material=textures[name], name=name, uv=uv)
            continue
        if name == "floor" and variant == "glossy":
            coat = RoughPlastic(
                diffuse_reflectance=albedo,
                alpha=0.3 * float(roughness_scale),
                distribution="ggx",
                ior=1.5,
            )
            scene.add_mesh(v, f, material=coat, name=name)
            continue
        if name == "floor" and variant == "coated":
            scene.add_mesh(v, f, material=Plastic(diffuse_reflectance=albedo, ior=ior), name=name)
            continue
        scene.add_mesh(v, f, reflectance=albedo, name=name)
    if spheres:
        for name, (centre, radius), material in zip(
            sphere_names,
            (CORNELL_MIRROR_SPHERE, CORNELL_GLASS_SPHERE),
            sphere_materials,
            strict=True,
        ):
            if variant == "smooth":
                v, f = icosphere(centre, radius, _CORNELL_SMOOTH_SUBDIVISIONS)
                normals = v - np.asarray(centre) if sphere_normals else None
                scene.add_mesh(v, f, material=material, name=name, normals=normals)
                continue
            v, f = icosphere(centre, radius, _CORNELL_SPHERE_SUBDIVISIONS)
            scene.add_mesh(v, f, material=material, name=name)
    if variant in _OPEN_TOP:
        scene.add_emitter(_open_top_light(variant, light_scale, float(env_rotation)))
        return scene
    light = _orient(np.array(_CORNELL_LIGHT), _CORNELL_ROOM_CENTRE, inward=True)
    v, f = _quads_mesh([light])
    point_lit = variant in ("point", "spot")
    emission: tuple[float, ...] | Bitmap = (
        (0.0, 0.0, 0.0) if point_lit else tuple(light_scale * c for c in CORNELL_LIGHT_RADIANCE)
    )
    if variant == "lamp":
        move = [[1.0, 0.0, float(texture_shift)], [0.0, 1.0, 0.0]]
        emission = Bitmap(data=light_scale * cornell_lamp_texels(), to_uv=move)
    scene.add_mesh(
        v,
        f,
        reflectance=CORNELL_LIGHT_REFLECTANCE,
        emission=emission,
        name="light",
        uv=[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]] if variant == "lamp" else None,
    )
    intensity = tuple(light_scale * c for c in _CORNELL_POINT_INTENSITY)
    if variant == "point":
        scene.add_emitter(PointLight(_CORNELL_POINT_POSITION, intensity))
    elif variant == "spot":
        cutoff = float(spot_cutoff)
        gain = 4.0 / (2.0 * (1.0 - math.cos(math.radians(cutoff))))
        scene.add_emitter(
            SpotLight(
                _CORNELL_SPOT_POSITION,
                _CORNELL_SPOT_AXIS,
                tuple(gain * c for c in intensity),
                cutoff_angle=cutoff,
            )
        )
    return scene


def cornell_lamp_texels() -> np.ndarray:
    """The ``"lamp"`` Cornell variant's radiance texture, ``(4, 8, 3)`` linear RGB: along ``u``
    from warm (red x1.6, blue x0.4) to cool (red x0.4, blue x1.6), times 1.5 and 0.5 in a
    checker of 2 x 1 texels, so its mean is the classic light's radiance."""
    i, j = np.meshgrid(np.arange(4), np.arange(8), indexing="ij")
    t = ((j + 0.5) / 8)[..., None]
    warm_to_cool = np.concatenate([1.6 - 1.2 * t, np.ones_like(t), 0.4 + 1.2 * t], axis=2)
    checker = (1.0 + 0.5 * (-1.0) ** (i + j // 2))[..., None]
    return (np.asarray(CORNELL_LIGHT_RADIANCE) * warm_to_cool * checker).astype(np.float32)


def cornell_sky_image(width: int = 64, height: int = 32) -> np.ndarray:
    """The ``"envmap"`` Cornell variant's environment, ``(height, width, 3)`` linear radiance
    in Mitsuba's latitude-longitude layout: a sky brightening from a pale horizon to a blue
    zenith, a dark ground below the horizon, and a sun of radiance 60 about 6 degrees across,
    30 degrees from the zenith towards -z (behind the camera: through the open top it lights
    the back wall and the blocks' fronts)."""
    v = (np.arange(height) + 0.0) / (height - 1)  # rows sit at theta = pi v
    u = (np.arange(width) + 0.5) / width  # columns at their centres
    theta, phi = np.meshgrid(np.pi * v, 2 * np.pi * u, indexing="ij")
    d = np.stack([np.sin(phi) * np.sin(theta), np.cos(theta), -np.cos(phi) * np.sin(theta)], -1)
    up = np.clip(d[..., 1], 0.0, 1.0)[..., None]
    sky = (1 - up) * np.array([0.9, 0.9, 0.85]) + up * np.array([0.25, 0.45, 0.9])
    ground = np.array([0.2, 0.18, 0.15])
    img = np.where(d[..., 1:2] > 0, sky, ground)
    sun = np.array([0.0, math.cos(math.radians(30)), -math.sin(math.radians(30))])
    img = img + 60.0 * (d @ sun > math.cos(math.radians(6)))[..., None]
    return img.astype(np.float32)


def _open_top_light(
    variant: str, scale: float, rotation: float
) -> DirectionalLight | ConstantEnvironment | EnvironmentMap:
    """The light of an open-top Cornell variant, times ``scale``."""
    if variant == "sun":
        return DirectionalLight(
            _CORNELL_SUN_DIRECTION, tuple(scale * c for c in _CORNELL_SUN_IRRADIANCE)
        )
    if variant == "sky":
        return ConstantEnvironment(tuple(scale * c for c in _CORNELL_SKY_RADIANCE))
    a = math.radians(rotation)
    turn = [[math.cos(a), 0.0, math.sin(a)], [0.0, 1.0, 0.0], [-math.sin(a), 0.0, math.cos(a)]]
    return EnvironmentMap(data=cornell_sky_image(), scale=scale, to_world=turn)


def _cornell_textures(shift: float) -> dict[str, Material]:
    """The "textured" variant's materials, every texture moved by ``shift`` along u."""
    i, j = np.meshgrid(np.arange(16), np.arange(16), indexing="ij")
    texels = np.stack(
        [0.15 + 0.6 * i / 15, 0.15 + 0.6 * j / 15, 0.35 + 0.3 * ((i // 2 + j // 2) % 2)], axis=2
    )
    move = [[1.0, 0.0, shift], [0.0, 1.0, 0.0]]
    four = [[4.0, 0.0, 4.0 * shift], [0.0, 4.0, 0.0]]
    two = [[2.0, 0.0, 2.0 * shift], [0.0, 2.0, 0.0]]
    return {
        "back_wall": Diffuse(Bitmap(data=texels, to_uv=move)),
        "floor": Diffuse(Checkerboard((0.75, 0.75, 0.7), (0.2, 0.2, 0.25), to_uv=four)),
        "tall_block": RoughConductor(
            material="Al", distribution="ggx", alpha=Checkerboard(0.05, 0.35, to_uv=two)
        ),
    }


def furnace_radiance(reflectance: float, emission: float) -> float:
    """Radiance everywhere inside :func:`furnace`: ``Le / (1 - rho)``."""
    if not 0.0 <= reflectance < 1.0:
        raise ValueError(f"furnace reflectance must be in [0, 1), got {reflectance}")
    return emission / (1.0 - reflectance)


def furnace(
    reflectance: float | Sequence[float] = 0.5,
    emission: float | Sequence[float] = 1.0,
    resolution: tuple[int, int] = (64, 64),
    *,
    size: float = 1.0,
) -> Scene:
    """A closed cube of side ``size`` whose inside walls all reflect and emit alike.

    Inside, radiance is the same everywhere and in every direction: ``Le / (1 - rho)`` per
    channel. The camera sits inside, looking at a corner so three walls are in view.
    """
    rho = np.broadcast_to(np.asarray(reflectance, dtype=np.float64), (3,))
    Le = np.broadcast_to(np.asarray(emission, dtype=np.float64), (3,))
    s = float(size)
    corners = s * np.array(
        [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]],
        dtype=np.float64,
    )
    faces = [[0, 1, 2, 3], [4, 7, 6, 5], [0, 4, 5, 1], [3, 2, 6, 7], [0, 3, 7, 4], [1, 5, 6, 2]]
    centre = np.full(3, 0.5 * s)
    quads = [_orient(corners[f], centre, inward=True) for f in faces]
    v, f = _quads_mesh(quads)
    camera = Camera(
        origin=(0.2 * s, 0.3 * s, 0.25 * s),
        target=(0.8 * s, 0.7 * s, 0.9 * s),
        up=(0.0, 1.0, 0.0),
        fov=70.0,
        resolution=resolution,
    )
    scene = Scene(camera=camera)
    scene.add_mesh(v, f, reflectance=tuple(rho), emission=tuple(Le), name="furnace")
    return scene


# Rooms ----------------------------------------------------------------------------------------
# Directions in the ground plane (y is up): name -> (axis, sign). East is +x, north is +z.
_ROOM_DIRECTIONS: dict[str, tuple[int, int]] = {
    "east": (0, 1),
    "west": (0, -1),
    "north": (2, 1),
    "south": (2, -1),
}


def _rooms_grid(n: int, camera_room: int) -> tuple[int, dict[int, dict[str, int]], int]:
    """Columns, each room's neighbours by direction, and the room farthest (in doors) from
    ``camera_room`` (the highest index among ties)."""
    cols = math.ceil(math.sqrt(n))
    neighbours: dict[int, dict[str, int]] = {}
    for k in range(n):
        r, c = divmod(k, cols)
        around = {
            "east": k + 1 if c + 1 < cols else -1,
            "west": k - 1 if c > 0 else -1,
            "north": k + cols,
            "south": k - cols if r > 0 else -1,
        }
        neighbours[k] = {d: j for d, j in around.items() if 0 <= j < n}
    distance = {camera_room: 0}
    queue = [camera_room]
    for k in queue:  # breadth-first: the list grows while it is walked
        for j in neighbours[k].values():
            if j not in distance:
                distance[j] = distance[k] + 1
                queue.append(j)
    far = max(distance, key=lambda k: (distance[k], k))
    return cols, neighbours, far


def rooms(
    n: int = 10,
    *,
    resolution: tuple[int, int] = (64, 64),
    room_size: Sequence[float] = (4.0, 2.5, 4.0),
    door: Sequence[float] = (1.0, 2.0),
    lit_every: int = 3,
    reflectance: float | Sequence[float] = 0.6,
    light_radiance: float | Sequence[float] = 10.0,
    camera_room: int = 0,
    seed: int = 0,
    doors: bool = True,
    wall_thickness: float = 0.1,
    tint: float = 0.05,
    camera_room_lit: bool = True,
) -> Scene:
    """A building of ``n`` rooms joined by doors, with the camera in one of them.

    The test scene of importance-driven radiosity (Smits, Arvo and Salesin 1992): the camera
    sees one room and a little through a door, so most of the building matters little for the
    view, yet light from far rooms reaches it through the doors.

    Layout
        y is up; east is +x and north is +z. Room ``k`` is at column ``k % cols`` and row
        ``k // cols`` of a grid of ``cols = ceil(sqrt(n))`` columns, filled row by row (the last
        row may be partial). Its inside is the box ``[x0, x0 + sx] x [0, sy] x [z0, z0 + sz]``
        with ``(sx, sy, sz) = room_size``, ``x0 = col * (sx + wall_thickness)`` and
        ``z0 = row * (sz + wall_thickness)``, so the building spans ``[0, cols * sx + (cols - 1)
        * wall_thickness]`` in x (likewise in z, with the number of rows) and ``[0, sy]`` in y.
        Two rooms next to each other in the grid are separated by a wall ``wall_thickness``
        thick; with ``doors`` it has an opening ``door = (width, height)`` in its middle,
        through both rooms' walls, and the doorway's thickness is lined (two jambs, the
        lintel's underside and a sill on the floor), so the only way between rooms is through
        doors. Outer walls and (with ``doors=False``) all walls are solid.
    Surfaces
        Every room is a closed box of its own surfaces, all one-sided and facing into the room:
        the front (right-hand-rule normal, the only side radiosity patches send and receive on)
        of every floor, ceiling, wall and light faces the room's inside, and the door linings
        face into the doorway. Nothing is shared between rooms and no surface is seen from its
        back from inside the building. Walls are single quads, or three quads (left, right,
        above) around a door; meshes are named ``room{k}_floor``, ``room{k}_ceiling``,
        ``room{k}_wall_{east,west,north,south}``, ``room{k}_light`` and ``room{k}_door_east`` /
        ``room{k}_door_north`` (the lining of the doorway to the room east / north of ``k``).
        Reflectance is ``reflectance`` (grey or RGB) times a per-room tint ``1 + tint * u``,
        ``u`` uniform in ``[-1, 1]`` per channel, drawn from ``seed`` (``tint=0``: exactly
        ``reflectance``), clipped to ``[0, 1]``.
    Lights
        A square emitter of radiance ``light_radiance`` facing down, 1 cm below the ceiling in
        its middle, of a quarter of the room's width and depth (1/16 of the ceiling), in room
        ``k`` when ``k % lit_every == 0``, in ``camera_room``, and in the room farthest from
        ``camera_room`` through doors (the highest index among ties): with the defaults, rooms
        0, 3, 6, ... and the far room (n = 4: rooms 0 and 3; n = 10: 0, 3, 6, 7 and 9). Light
        reaches the unlit rooms, and the camera from the far rooms, only through doors. The
        grid, the lights and the camera do not depend on ``doors``. ``camera_room_lit=False``
        leaves ``camera_room`` dark whatever ``lit_every`` says: the camera then sees only
        light that came through doors (Veach's door at the scale of a building).
        ``light_radiance`` may be a number or RGB; the light reflects like its room.
    Camera
        In ``camera_room`` at eye height (1.6 m or 0.64 ``sy`` if lower), 10% of the room's
        depth from one wall, looking across the room at the middle of the opposite wall's door
        (the first of east, north, west, south with a neighbour), ``fov`` 70 degrees.

    Sizes (defaults): 12 triangles per room, 2 more per light and 16 per door (its two wall
    openings and its lining); n = 1, 4, 10, 25 make 14, 116, 338 and 958 triangles. Radiosity
    patches (:class:`dualight.radiosity.PatchMesh`, which splits each triangle by its longest
    edge, the quads' diagonals): n = 1, 4, 10, 25 make 352, 1,552, 4,000 and 10,272 patches at
    ``max_edge=1.0`` and 1,394, 5,780, 14,630 and 36,962 at ``max_edge=0.5`` (about 390 and
    1,460 per room). Full form factors are quadratic in the patch count.

    Form-factor row sums are 1 (to 1e-8) for a closed room without a light; the light's back,
    1 cm under the ceiling, and the edges of doors hide parts of some patches, where the shadow
    rays' visibility estimate is noisy (rows up to about 1 + 1e-2 at 4 shadow rays), and the
    ceiling patches above a light see little but its back (rows near 0).
    """
    if not isinstance(n, int | np.integer) or n < 1:
        raise ValueError(f"rooms: n must be an int >= 1, got {n!r}")
    n = int(n)
    if not isinstance(lit_every, int | np.integer) or lit_every < 1:
        raise ValueError(f"rooms: lit_every must be an int >= 1, got {lit_every!r}")
    if not isinstance(camera_room, int | np.integer) or not 0 <= camera_room < n:
        raise ValueError(f"rooms: camera_room must be in [0, {n}), got {camera_room!r}")
    sx, sy, sz = (float(v) for v in room_size)
    if not all(math.isfinite(v) and v > 0.0 for v in (sx, sy, sz)):
        raise ValueError(f"rooms: room_size must be 3 positive numbers, got {room_size!r}")
    door_w, door_h = (float(v) for v in door)
    if doors and not (0.0 < door_w < min(sx, sz) and 0.0 < door_h < sy):
        raise ValueError(
            f"rooms: door (width, height) = {door!r} must fit inside a wall "
            f"(width < {min(sx, sz)}, height < {sy})"
        )
    t = float(wall_thickness)
    if not (math.isfinite(t) and t > 0.0):
        raise ValueError(f"rooms: wall_thickness must be positive, got {wall_thickness!r}")
    if not (math.isfinite(tint) and 0.0 <= tint < 1.0):
        raise ValueError(f"rooms: tint must be in [0, 1), got {tint!r}")
    rho = np.broadcast_to(np.asarray(reflectance, dtype=np.float64), (3,))
    Le = tuple(np.broadcast_to(np.asarray(light_radiance, dtype=np.float64), (3,)).tolist())

    cols, neighbours, far = _rooms_grid(n, int(camera_room))
    lit = {k for k in range(n) if k % lit_every == 0} | {int(camera_room), far}
    if not isinstance(camera_room_lit, bool):
        raise TypeError(f"rooms: camera_room_lit must be True or False, got {camera_room_lit!r}")
    if not camera_room_lit:
        lit.discard(int(camera_room))
    if not lit:
        raise ValueError("rooms: camera_room_lit=False leaves no room lit (n = 1)")
    tints = 1.0 + tint * np.random.default_rng(seed).uniform(-1.0, 1.0, size=(n, 3))
    size = np.array([sx, sy, sz])
    half = 0.5 * size

    def lo_of(k: int) -> np.ndarray:
        r, c = divmod(k, cols)
        return np.array([c * (sx + t), 0.0, r * (sz + t)])

    def add(scene: Scene, name: str, quads: list[np.ndarray], towards: np.ndarray, **kw) -> None:
        v, f = _quads_mesh([_orient(q, towards, inward=True) for q in quads])
        scene.add_mesh(v, f, name=name, **kw)

    # Camera: across camera_room, towards the door of the first wall with a neighbour.
    k_cam = int(camera_room)
    look = next((d for d in _ROOM_DIRECTIONS if d in neighbours[k_cam]), "east")
    axis, sign = _ROOM_DIRECTIONS[look]
    side_axis = 2 - axis  # the other horizontal axis
    centre = lo_of(k_cam) + half
    eye_h = min(1.6, 0.64 * sy)
    origin = centre.copy()
    origin[axis] -= sign * 0.8 * half[axis]
    origin[side_axis] += 0.25 * half[side_axis]
    origin[1] = eye_h
    target = centre.copy()
    target[axis] += sign * half[axis]
    target[1] = 0.48 * sy
    camera = Camera(
        origin=tuple(origin), target=tuple(target), fov=70.0, resolution=tuple(resolution)
    )
    scene = Scene(camera=camera)

    for k in range(n):
        lo = lo_of(k)
        hi = lo + size
        centre = lo + half
        rho_k = tuple(np.clip(rho * tints[k], 0.0, 1.0).tolist())
        add(scene, f"room{k}_floor", [_axis_rect(1, 0.0, lo, hi)], centre, reflectance=rho_k)
        add(scene, f"room{k}_ceiling", [_axis_rect(1, sy, lo, hi)], centre, reflectance=rho_k)
        for d, (axis, sign) in _ROOM_DIRECTIONS.items():
            plane = hi[axis] if sign > 0 else lo[axis]
            along = 2 - axis
            if not (doors and d in neighbours[k]):
                quads = [_axis_rect(axis, plane, lo, hi)]
            else:
                # Left, right and above the opening, which is centred along the wall.
                u0 = centre[along] - 0.5 * door_w
                u1 = centre[along] + 0.5 * door_w
                pieces = [(lo[along], u0, 0.0, sy), (u1, hi[along], 0.0, sy), (u0, u1, door_h, sy)]
                quads = []
                for a0, a1, y0, y1 in pieces:
                    p, q = lo.copy(), hi.copy()
                    p[along], q[along], p[1], q[1] = a0, a1, y0, y1
                    quads.append(_axis_rect(axis, plane, p, q))
                if sign > 0:  # the lining of the doorway belongs to the west / south room
                    p, q = lo.copy(), hi.copy()
                    p[axis], q[axis] = plane, plane + t
                    p[along], q[along], p[1], q[1] = u0, u1, 0.0, door_h
                    inside = 0.5 * (p + q)
                    lining = [
                        _axis_rect(along, u0, p, q),  # jambs
                        _axis_rect(along, u1, p, q),
                        _axis_rect(1, door_h, p, q),  # lintel
                        _axis_rect(1, 0.0, p, q),  # sill
                    ]
                    add(scene, f"room{k}_door_{d}", lining, inside, reflectance=rho_k)
            add(scene, f"room{k}_wall_{d}", quads, centre, reflectance=rho_k)
        if k in lit:
            p, q = centre - 0.125 * size, centre + 0.125 * size
            light = _axis_rect(1, sy - min(0.01, 0.01 * sy), p, q)
            add(scene, f"room{k}_light", [light], centre, reflectance=rho_k, emission=Le)
    return scene


# Cube -----------------------------------------------------------------------------------------
def cube(
    resolution: tuple[int, int] = (64, 64),
    *,
    size: float = 1.0,
    reflectance: float | Sequence[float] = 0.7,
    light_radiance: float | Sequence[float] = 10.0,
    fov: float = 100.0,
) -> Scene:
    """A closed cube lit by a small ceiling light, seen from inside: the scene where
    everything is visible, so importance-driven refinement should change little.

    Layout
        y is up. The inside is ``[0, size]^3``; its 6 walls are single quads named ``floor``,
        ``ceiling`` and ``wall_{east,west,north,south}`` (east +x, north +z), one-sided with
        their front (right-hand-rule normal, the only side radiosity patches send and receive
        on) facing into the cube. Every wall sees every other one.
    Light
        ``light``: a square of side ``size / 3`` (1/9 of the ceiling's area) centred under the
        ceiling, ``0.01 * size`` below it, emitting ``light_radiance`` (grey or RGB)
        downwards; it reflects like the walls.
    Materials
        Walls and light reflect ``reflectance`` (grey or RGB, in ``[0, 1]``).
    Camera
        Inside, near the lower south-west corner at ``0.1 * size`` from the floor and from
        the two walls, looking at the opposite upper corner ``(size, size, size)`` with a wide
        ``fov`` (100 degrees), so it sees the ceiling with the light, the east and north
        walls and much of the floor.

    7 quads, 14 triangles (12 for the walls, 2 for the light).
    """
    s = float(size)
    if not (math.isfinite(s) and s > 0.0):
        raise ValueError(f"cube: size must be positive, got {size!r}")
    rho = tuple(np.broadcast_to(np.asarray(reflectance, dtype=np.float64), (3,)).tolist())
    Le = tuple(np.broadcast_to(np.asarray(light_radiance, dtype=np.float64), (3,)).tolist())
    lo, hi = np.zeros(3), np.full(3, s)
    centre = np.full(3, 0.5 * s)
    camera = Camera(
        origin=(0.1 * s, 0.1 * s, 0.1 * s),
        target=(s, s, s),
        up=(0.0, 1.0, 0.0),
        fov=fov,
        resolution=tuple(resolution),
    )
    scene = Scene(camera=camera)
    walls = {
        "floor": _axis_rect(1, 0.0, lo, hi),
        "ceiling": _axis_rect(1, s, lo, hi),
        "wall_east": _axis_rect(0, s, lo, hi),
        "wall_west": _axis_rect(0, 0.0, lo, hi),
        "wall_north": _axis_rect(2, s, lo, hi),
        "wall_south": _axis_rect(2, 0.0, lo, hi),
    }
    for name, quad in walls.items():
        v, f = _quads_mesh([_orient(quad, centre, inward=True)])
        scene.add_mesh(v, f, reflectance=rho, name=name)
    third = s / 3.0
    light = _axis_rect(1, s - 0.01 * s, centre - 0.5 * third, centre + 0.5 * third)
    v, f = _quads_mesh([_orient(light, centre, inward=True)])
    scene.add_mesh(v, f, reflectance=rho, emission=Le, name="light")
    return scene


# Door ajar ------------------------------------------------------------------------------------
#: Inside of each room (x, y, z) in metres, and the wall between them.
DOOR_ROOM_SIZE = (4.0, 2.5, 4.0)
DOOR_WALL_THICKNESS = 0.1
#: The doorway in the wall between the rooms: x range and height.
DOOR_DOORWAY_X = (1.55, 2.45)
DOOR_DOORWAY_HEIGHT = 2.0
#: The door leaf: thickness, clearance to the jamb at its free edge, how far it reaches past
#: the hinge axis into the wall, and how far it reaches into the floor and above the lintel.
_DOOR_THICKNESS = 0.04
_DOOR_CLEARANCE = 0.003
_DOOR_PAST_HINGE = 0.01
_DOOR_OVERLAP_Y = 0.02
#: The emitter: a panel on the bright room's side of the wall, beside the doorway on the side
#: of the door's free edge, facing away from the wall (x range, y range, distance from it).
_DOOR_LIGHT_X = (0.15, 1.25)
_DOOR_LIGHT_Y = (0.4, 2.2)
_DOOR_LIGHT_OFFSET = 0.01
DOOR_LIGHT_RADIANCE = (400.0, 340.0, 260.0)
DOOR_DEFAULT_OPENING = 10.0
_DOOR_MATERIALS: dict[str, tuple[float, float, float]] = {
    "dark_wall": (0.70, 0.68, 0.62),
    "dark_floor": (0.55, 0.42, 0.30),
    "dark_ceiling": (0.75, 0.75, 0.75),
    "door": (0.60, 0.32, 0.16),
    "bright_wall": (0.80, 0.78, 0.70),
    "bright_floor": (0.45, 0.50, 0.60),
    "bright_ceiling": (0.80, 0.80, 0.80),
    "light": (0.80, 0.80, 0.80),
}


def _door_leaf(opening: float) -> tuple[np.ndarray, np.ndarray]:
    """The door of :func:`door_ajar` opened by ``opening`` degrees: a closed box of 6 quads
    (vertices, faces) with outward normals. See :func:`door_ajar` for its placement."""
    theta = math.radians(float(opening))
    x0, x1 = DOOR_DOORWAY_X
    z_hinge = DOOR_ROOM_SIZE[2] + DOOR_WALL_THICKNESS  # the bright room's face of the wall
    hinge = np.array([x1, 0.0, z_hinge])
    # Along the leaf (hinge -> free edge) and across it (towards the dark room).
    u = np.array([-math.cos(theta), 0.0, math.sin(theta)])
    v = np.array([-math.sin(theta), 0.0, -math.cos(theta)])
    width = (x1 - x0) - _DOOR_CLEARANCE
    s_range = (-_DOOR_PAST_HINGE, width)
    t_range = (0.0, _DOOR_THICKNESS)
    y_range = (-_DOOR_OVERLAP_Y, DOOR_DOORWAY_HEIGHT + _DOOR_OVERLAP_Y)

    def corner(i: int, j: int, k: int) -> np.ndarray:
        p = hinge + s_range[i] * u + t_range[j] * v
        p[1] = y_range[k]
        return p

    c = {(i, j, k): corner(i, j, k) for i in (0, 1) for j in (0, 1) for k in (0, 1)}
    quads = (
        [np.array([c[0, j, 0], c[1, j, 0], c[1, j, 1], c[0, j, 1]]) for j in (0, 1)]
        + [np.array([c[i, 0, 0], c[i, 1, 0], c[i, 1, 1], c[i, 0, 1]]) for i in (0, 1)]
        + [np.array([c[0, 0, k], c[1, 0, k], c[1, 1, k], c[0, 1, k]]) for k in (0, 1)]
    )
    centre = np.mean(list(c.values()), axis=0)
    return _quads_mesh([_orient(q, centre, inward=False) for q in quads])


def door_ajar(
    resolution: tuple[int, int] = (128, 128),
    *,
    opening: float = DOOR_DEFAULT_OPENING,
    light_scale: float = 1.0,
    reflectance_scale: float = 1.0,
    variant: Literal["classic", "glossy"] = "classic",
    roughness_scale: float = 1.0,
    ior: float = 1.5,
) -> Scene:
    """Veach's door: a dark room lit only through a door ajar from a bright room next door.

    The hard case of Veach and Guibas, "Metropolis Light Transport" (SIGGRAPH 1997): the
    camera's room has no light of its own, and every path that carries light into it squeezes
    through the gap of a door that is barely open. A path tracer finds the gap only by chance
    (next-event estimation from the dark room never reaches the light), so it is very noisy:
    with the defaults the median relative standard deviation of one sample is about 16 times
    the pixel value (60 at 3 degrees, 30 at 5, 21 at 7).

    Layout (metres; y is up, the camera looks roughly along +z)
        The dark room (with the camera) is the box ``[0, 4] x [0, 2.5] x [0, 4]``, the bright
        room ``[0, 4] x [0, 2.5] x [4.1, 8.1]``; the wall between them is 0.1 m thick. Each
        room is a closed box of one-sided quads facing into it. The wall has a doorway
        ``x in [1.55, 2.45]``, ``y in [0, 2]`` whose thickness is lined (two jambs, the
        lintel's underside and a sill), so the doorway is the only way between the rooms.
    Door
        A closed box 0.04 m thick (``_door_leaf``), hinged on a vertical axis at the
        doorway's bright-room edge on the ``x = 2.45`` side and swung into the bright room by
        ``opening`` degrees. Closed, it would fill the doorway but for 3 mm at its free edge
        (at the ``x = 1.55`` jamb); it reaches 1 cm past the hinge axis into the wall and 2 cm
        into the floor and above the lintel, so light passes only through the gap between the
        door and its frame: the slit along its free edge, about ``0.9 sin(opening) - 0.04`` m
        wide (1 cm at 3 degrees, 4 cm at 5, 12 cm at 10, the default), and, since the door
        stands in the bright room, the wedge between the door and the wall above its top
        edge, which narrows to nothing at the hinge.
    Light
        ``light``: a 1.1 m x 1.8 m panel on the bright room's face of the wall, beside the
        doorway on the side of the door's free edge (``x in [0.15, 1.25]``, ``y in [0.4,
        2.2]``), 1 cm off the wall and facing away from it (+z), radiance ``light_scale *
        (400, 340, 260)``. Every point of the dark room and the doorway is behind the panel's
        plane, so the camera never sees the emitter and the dark room gets no direct light: a
        path to a dark-room surface reflects at least once in the bright room and once in the
        dark room, and passes the gap. Through the gap the camera sees a sliver of the bright
        room (pixels lit by paths with one reflection).
    Materials
        Two-sided diffuse, reflectances ``reflectance_scale`` times: dark room walls, jambs
        and lintel (0.70, 0.68, 0.62), its floor and the sill (0.55, 0.42, 0.30), its ceiling
        0.75; door (0.60, 0.32, 0.16); bright room walls (0.80, 0.78, 0.70), floor (0.45,
        0.50, 0.60) and ceiling 0.8; the light panel reflects 0.8. The largest is 0.8, so
        ``reflectance_scale <= 1.25``.
    Camera
        In the dark room at ``(3.3, 1.5, 0.4)``, looking at ``(1.9, 0.8, 4.0)`` with ``fov``
        65 degrees: it sees the wall with the doorway (the door's hinge on the left of the
        image, the gap on the right), the floor in front of it and the side wall.

    Meshes (names): ``dark_floor``, ``dark_ceiling``, ``dark_walls``, ``bright_floor``,
    ``bright_ceiling``, ``bright_walls`` (``dark_*`` and ``bright_*`` bound their room's box
    exactly), ``doorway`` (jambs and lintel), ``doorway_sill``, ``door`` and ``light``; 54
    triangles.

    Parameters
    ----------
    resolution : (int, int), optional
        Image ``(width, height)``.
    opening : float, optional
        The door's angle in degrees, in ``(0, 90]``. The default, 10 degrees, is hard for a
        path tracer, yet a Mitsuba ``path`` reference at 64 x 64 converges in minutes
        (``dualight/data/references/README.md``).
    light_scale : float, optional
        Multiplies the emitted radiance, ``> 0``.
    reflectance_scale : float, optional
        Multiplies every reflectance, in ``(0, 1.25]``.
    variant : {"classic", "glossy"}, optional
        ``"glossy"`` adds, as in Veach's door figure (thesis ch. 11), glossy objects to the dark
        room where the light through the gap falls (meshes ``copper_sphere``, ``frosted_sphere``,
        ``plastic_block``): a copper ``roughconductor`` sphere (radius 0.35 at ``(1.15, 0.35,
        3.2)``), a frosted-glass ``roughdielectric`` sphere (radius 0.3 at ``(2.55, 0.3, 3.05)``,
        relative IOR ``ior``), both :func:`icosphere` meshes of 4 subdivisions, and a blue
        ``roughplastic`` block ``[2.95, 3.55] x [0, 0.45] x [2.2, 2.8]`` (diffuse (0.2, 0.25, 0.5),
        IOR 1.5), all GGX of roughness ``alpha = 0.1 * roughness_scale``. Path-space MLT's relMSE is
        about 3x lower than BDPT's here at equal time (``benchmarks/bench_scenes.py``).
    roughness_scale : float, optional
        ``"glossy"`` only: multiplies the objects' roughness (a negative control), in
        ``(0, 10]``.
    ior : float, optional
        ``"glossy"`` only: the frosted sphere's relative IOR, in ``(1, 4]``.

    Returns
    -------
    Scene

    Raises
    ------
    ValueError
        If ``opening`` is outside ``(0, 90]``, a scale is out of its range, or ``variant`` is
        unknown.
    """
    if variant not in ("classic", "glossy"):
        raise ValueError(f"door_ajar: unknown variant {variant!r}; choose 'classic' or 'glossy'")
    roughness_scale = _scale(roughness_scale, "door_ajar", "roughness_scale", 10.0)
    ior = _ior(ior, "door_ajar")
    opening = float(opening)
    if not (math.isfinite(opening) and 0.0 < opening <= 90.0):
        raise ValueError(f"door_ajar: opening must be in (0, 90] degrees, got {opening!r}")
    light_scale = float(light_scale)
    if not (math.isfinite(light_scale) and light_scale > 0.0):
        raise ValueError(f"door_ajar: light_scale must be finite and > 0, got {light_scale!r}")
    reflectance_scale = float(reflectance_scale)
    largest = max(max(c) for c in _DOOR_MATERIALS.values())
    if not (math.isfinite(reflectance_scale) and 0.0 < reflectance_scale <= 1.0 / largest):
        raise ValueError(
            f"door_ajar: reflectance_scale must be in (0, {1.0 / largest:g}] so every albedo "
            f"stays <= 1, got {reflectance_scale!r}"
        )

    def rho(key: str) -> tuple[float, float, float]:
        r, g, b = (reflectance_scale * c for c in _DOOR_MATERIALS[key])
        return (r, g, b)

    sx, sy, sz = DOOR_ROOM_SIZE
    wall = DOOR_WALL_THICKNESS
    x0, x1 = DOOR_DOORWAY_X
    h = DOOR_DOORWAY_HEIGHT
    camera = Camera(
        origin=(3.3, 1.5, 0.4),
        target=(1.9, 0.8, 4.0),
        up=(0.0, 1.0, 0.0),
        fov=65.0,
        resolution=tuple(resolution),
    )
    scene = Scene(camera=camera)

    def add(name: str, quads: list[np.ndarray], towards: np.ndarray, **kw: object) -> None:
        v, f = _quads_mesh([_orient(q, towards, inward=True) for q in quads])
        scene.add_mesh(v, f, name=name, **kw)  # type: ignore[arg-type]

    for room, z0, wall_z in (("dark", 0.0, sz), ("bright", sz + wall, sz + wall)):
        lo = np.array([0.0, 0.0, z0])
        hi = lo + np.array(DOOR_ROOM_SIZE)
        centre = 0.5 * (lo + hi)
        add(f"{room}_floor", [_axis_rect(1, 0.0, lo, hi)], centre, reflectance=rho(f"{room}_floor"))
        add(f"{room}_ceiling", [_axis_rect(1, sy, lo, hi)], centre,
            reflectance=rho(f"{room}_ceiling"))  # fmt: skip
        far_z = lo[2] if room == "dark" else hi[2]
        walls = [
            _axis_rect(0, 0.0, lo, hi),
            _axis_rect(0, sx, lo, hi),
            _axis_rect(2, far_z, lo, hi),
        ]
        # The wall between the rooms: left of, right of and above the doorway.
        for a0, a1, y0, y1 in ((0.0, x0, 0.0, sy), (x1, sx, 0.0, sy), (x0, x1, h, sy)):
            walls.append(_axis_rect(2, wall_z, (a0, y0, 0.0), (a1, y1, 0.0)))
        add(f"{room}_walls", walls, centre, reflectance=rho(f"{room}_wall"))

    # The doorway's lining, facing into the doorway.
    lo, hi = np.array([x0, 0.0, sz]), np.array([x1, h, sz + wall])
    inside = 0.5 * (lo + hi)
    lining = [
        _axis_rect(0, x0, lo, hi),
        _axis_rect(0, x1, lo, hi),
        _axis_rect(1, h, lo, hi),
    ]
    add("doorway", lining, inside, reflectance=rho("dark_wall"))
    add("doorway_sill", [_axis_rect(1, 0.0, lo, hi)], inside, reflectance=rho("dark_floor"))

    v, f = _door_leaf(opening)
    scene.add_mesh(v, f, reflectance=rho("door"), name="door")

    z_light = sz + wall + _DOOR_LIGHT_OFFSET
    (lx0, lx1), (ly0, ly1) = _DOOR_LIGHT_X, _DOOR_LIGHT_Y
    light = _axis_rect(2, z_light, (lx0, ly0, 0.0), (lx1, ly1, 0.0))
    add(
        "light",
        [light],
        np.array([0.0, 0.0, z_light + 1.0]),
        reflectance=rho("light"),
        emission=tuple(light_scale * c for c in DOOR_LIGHT_RADIANCE),
    )
    if variant == "glossy":
        door_glossy_objects(scene, roughness_scale, ior)
    return scene
