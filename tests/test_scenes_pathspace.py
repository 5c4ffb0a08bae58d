"""Scenes for path-space estimators: `scenes.icosphere`, `scenes.door_ajar` (Veach's door).

Icosphere: closed, outward, on the sphere, area converging to 4 pi r^2. Door: the emitter is
never seen by the camera, each room is closed, light passes from one room to the other only
through the gap at the door's free edge, a wider opening lets more light through, bad
arguments raise.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import dualight
from dualight import scenes


def _edge_counts(faces: np.ndarray) -> np.ndarray:
    """How many faces share each undirected edge."""
    edges = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
    return np.unique(edges, axis=0, return_counts=True)[1]


def _directed_edges(faces: np.ndarray) -> np.ndarray:
    return np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])


def _areas_normals(v: np.ndarray, f: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    tri = v[f]
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    return 0.5 * np.linalg.norm(n, axis=1), n


# Icosphere ------------------------------------------------------------------------------------
@pytest.mark.parametrize("subdivisions", [0, 1, 2, 3, 4])
def test_icosphere_closed_outward_on_sphere(subdivisions: int) -> None:
    centre, radius = np.array([0.3, -1.0, 2.5]), 0.7
    v, f = scenes.icosphere(centre, radius, subdivisions)
    assert v.shape == (10 * 4**subdivisions + 2, 3) and f.shape == (20 * 4**subdivisions, 3)
    assert f.dtype.kind == "i" and f.min() == 0 and f.max() == len(v) - 1
    np.testing.assert_allclose(np.linalg.norm(v - centre, axis=1), radius, rtol=1e-12)
    # Closed: every undirected edge in exactly two faces, and (consistent winding) every
    # directed edge once, so each edge is walked once in each direction.
    assert np.all(_edge_counts(f) == 2)
    directed = _directed_edges(f)
    assert len(np.unique(directed, axis=0)) == len(directed)
    # Outward: the right-hand-rule normal points away from the centre, for every face.
    areas, n = _areas_normals(v, f)
    assert np.all(areas > 0.0)
    outward = np.einsum("ij,ij->i", n / np.linalg.norm(n, axis=1)[:, None],
                        v[f].mean(axis=1) - centre)  # fmt: skip
    assert np.all(outward > 0.9 * radius * math.cos(math.radians(40.0)))
    # Euler characteristic of a sphere.
    assert len(v) - len(np.unique(np.sort(directed, axis=1), axis=0)) + len(f) == 2


def test_icosphere_area_converges_to_sphere() -> None:
    radius = 2.0
    exact = 4.0 * math.pi * radius**2
    errors = []
    for k in range(6):
        areas, _ = _areas_normals(*scenes.icosphere((1.0, 2.0, 3.0), radius, k))
        errors.append(1.0 - areas.sum() / exact)
    assert all(e > 0.0 for e in errors)  # inscribed: always a little smaller
    ratios = [a / b for a, b in zip(errors, errors[1:], strict=False)]
    assert all(3.0 < r < 4.2 for r in ratios), ratios  # second order in the edge length
    assert errors[3] < 6e-3 and errors[5] < 4e-4


def test_icosphere_renders_as_closed_mesh(first_hits) -> None:
    """Rays from inside the sphere all hit a face from its back; from outside, its front."""
    centre = np.array([0.0, 0.0, 0.0])
    v, f = scenes.icosphere(centre, 1.0, 2)
    scene = dualight.Scene()
    scene.add_mesh(v, f, reflectance=(0.5, 0.5, 0.5), name="sphere")
    rng = np.random.default_rng(3)
    dirs = rng.normal(size=(500, 3))
    dirs /= np.linalg.norm(dirs, axis=1, keepdims=True)
    t, n = first_hits(scene, np.tile(centre, (500, 1)) + 0.1 * rng.uniform(-1, 1, (500, 3)), dirs)
    assert np.all(np.isfinite(t)) and np.all(np.einsum("ij,ij->i", n, dirs) > 0.0)
    t, n = first_hits(scene, -3.0 * dirs, dirs)
    assert np.all(np.isfinite(t)) and np.all(np.einsum("ij,ij->i", n, dirs) < 0.0)


@pytest.mark.parametrize(
    ("centre", "radius", "subdivisions"),
    [
        ((0, 0), 1.0, 2),
        ((0, 0, float("nan")), 1.0, 2),
        ((0, 0, 0), 0.0, 2),
        ((0, 0, 0), -1.0, 2),
        ((0, 0, 0), float("inf"), 2),
        ((0, 0, 0), 1.0, -1),
        ((0, 0, 0), 1.0, 9),
        ((0, 0, 0), 1.0, 2.0),
        ((0, 0, 0), 1.0, True),
    ],
)
def test_icosphere_bad_arguments(centre, radius, subdivisions) -> None:
    with pytest.raises(ValueError, match="icosphere"):
        scenes.icosphere(centre, radius, subdivisions)


# Door ajar ------------------------------------------------------------------------------------
DARK = (np.array([0.0, 0.0, 0.0]), np.array([4.0, 2.5, 4.0]))
BRIGHT = (np.array([0.0, 0.0, 4.1]), np.array([4.0, 2.5, 8.1]))
JAMB = np.array([1.55, 4.1])  # (x, z) of the free-edge jamb's corner on the bright side
HINGE = np.array([2.45, 4.1])
DOOR_WIDTH = 0.9 - 0.003
DOOR_TOP = 2.02  # the door reaches 2 cm above the doorway
DOOR_THICKNESS = 0.04


def _mesh_names(scene: dualight.Scene) -> np.ndarray:
    """The mesh name of every triangle of the compiled scene."""
    _, _, mesh_index = scene.triangle_arrays()
    return np.array([m.name for m in scene.meshes])[mesh_index]


def _camera_rays(scene: dualight.Scene, per_pixel: int = 2) -> tuple[np.ndarray, np.ndarray]:
    cam = scene.camera._compile()
    w, h = scene.camera.resolution
    s = (np.arange(per_pixel) + 0.5) / per_pixel
    xs = (np.arange(w)[:, None] + s[None]).ravel()
    ys = (np.arange(h)[:, None] + s[None]).ravel()
    rays = [cam.generate_ray(x, y) for y in ys for x in xs]
    origins = np.array([o for o, _ in rays], np.float32)
    dirs = np.array([d for _, d in rays], np.float32)
    return origins, dirs


def _random_rays(
    box: tuple[np.ndarray, np.ndarray], n: int, seed: int
) -> tuple[np.ndarray, np.ndarray]:
    """Origins uniform in ``box`` shrunk by 1 cm, directions uniform on the sphere."""
    rng = np.random.default_rng(seed)
    lo, hi = box
    origins = rng.uniform(lo + 0.01, hi - 0.01, size=(n, 3))
    dirs = rng.normal(size=(n, 3))
    dirs /= np.linalg.norm(dirs, axis=1, keepdims=True)
    return origins.astype(np.float32), dirs.astype(np.float32)


def _door_frame(opening: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Top view (x, z) of the door: unit vectors along it (from the hinge) and across it
    (towards the dark room), and the dark-side corner of its free edge."""
    theta = math.radians(opening)
    u = np.array([-math.cos(theta), math.sin(theta)])
    v = np.array([-math.sin(theta), -math.cos(theta)])
    return u, v, HINGE + DOOR_WIDTH * u + DOOR_THICKNESS * v


def _in_wedge(xz: np.ndarray, opening: float) -> np.ndarray:
    """Top view: whether points lie beyond the wall's bright face ``z = 4.1``, on the dark side
    of the door's bright face, within its length, and on the hinge side of the slit (the line
    from the jamb's bright-side corner to the dark corner of the door's free edge): the wedge
    between the door and the doorway, with the door itself."""
    u, v, corner = _door_frame(opening)
    q = xz - HINGE
    slit = corner - JAMB
    r = xz - JAMB
    hinge_side = slit[0] * r[:, 1] - slit[1] * r[:, 0] <= 0.0
    return (xz[:, 1] >= 4.1) & (q @ v >= 0.0) & (q @ u <= DOOR_WIDTH) & hinge_side


def _dark_side(points: np.ndarray, opening: float) -> np.ndarray:
    """Whether points in free space are on the dark room's side of the gap: in the dark room,
    the doorway, or the wedge between the door and the doorway below the door's top."""
    xz = points[:, [0, 2]].astype(np.float64)
    return (xz[:, 1] < 4.1) | (_in_wedge(xz, opening) & (points[:, 1] < DOOR_TOP))


def _crosses_gap(
    origins: np.ndarray, dirs: np.ndarray, t_hit: np.ndarray, opening: float
) -> np.ndarray:
    """Whether each ray passes the gap between the door and its frame before its hit.

    The gap has two parts: the slit along the door's free edge (top view: the segment from the
    jamb's bright-side corner to the dark corner of the door's free edge, between the floor
    and the door's top) and, because the door stands in the bright room, the wedge above its
    top edge (the plane of the door's top over the wedge of :func:`_in_wedge`).
    """
    _, _, corner = _door_frame(opening)
    o, d = origins[:, [0, 2]].astype(np.float64), dirs[:, [0, 2]].astype(np.float64)
    e = corner - JAMB
    with np.errstate(divide="ignore", invalid="ignore"):
        # Slit: o + t d = JAMB + s e, by Cramer's rule.
        det = d[:, 0] * (-e[1]) - d[:, 1] * (-e[0])
        rhs = JAMB - o
        t = (rhs[:, 0] * (-e[1]) - rhs[:, 1] * (-e[0])) / det
        s = (d[:, 0] * rhs[:, 1] - d[:, 1] * rhs[:, 0]) / det
        y = origins[:, 1] + t * dirs[:, 1]
        slit = (t > 0) & (t < t_hit) & (s >= -1e-4) & (s <= 1 + 1e-4)
        slit &= (y > -1e-4) & (y < DOOR_TOP + 1e-4)
        # Top: where the ray crosses the plane of the door's top.
        t_top = (DOOR_TOP - origins[:, 1]) / dirs[:, 1]
        xz = o + np.where(np.isfinite(t_top), t_top, 0.0)[:, None] * d
    top = (t_top > 0) & (t_top < t_hit) & _in_wedge(xz, opening)
    return slit | top


@pytest.fixture(scope="module")
def door() -> dualight.Scene:
    return scenes.door_ajar(resolution=(64, 64))


def test_door_layout(door: dualight.Scene) -> None:
    names = [m.name for m in door.meshes]
    assert len(set(names)) == len(names)
    emitters = [m for m in door.meshes if m.is_emitter]
    assert [m.name for m in emitters] == ["light"]
    assert door.camera.resolution == (64, 64)
    origin = np.array(door.camera.origin)
    assert np.all(origin > DARK[0] + 0.1) and np.all(origin < DARK[1] - 0.1)
    for m in door.meshes:
        for room, (lo, hi) in (("dark_", DARK), ("bright_", BRIGHT)):
            if m.name.startswith(room):
                assert np.all(m.vertices >= lo - 1e-12) and np.all(m.vertices <= hi + 1e-12)
        assert max(m.reflectance) <= 0.8
    # The light panel faces away from the doorway (+z), in the bright room.
    light = emitters[0]
    _, n = _areas_normals(light.vertices, light.triangles)
    assert np.all(n[:, 2] > 0.0) and np.allclose(n[:, [0, 1]], 0.0)
    assert np.all(light.vertices[:, 2] > BRIGHT[0][2])


def test_door_emitter_never_seen_by_camera(door: dualight.Scene) -> None:
    names = _mesh_names(door)
    origins, dirs = _camera_rays(door)
    t, prim = door._compile().intersect(origins, dirs)
    assert np.all(prim >= 0) and np.all(np.isfinite(t))
    seen = names[prim]
    assert "light" not in set(seen)
    # The camera sees the dark room, the door, the doorway and (through the gap) a sliver of
    # the bright room: the test above is not vacuous.
    fractions = {k: float(np.mean(seen == k)) for k in set(seen)}
    assert fractions["door"] > 0.01 and fractions["dark_floor"] > 0.1
    opening = scenes.DOOR_DEFAULT_OPENING
    bright = ~_dark_side(origins + (t - 1e-4)[:, None] * dirs, opening)
    assert np.all(np.char.startswith(seen[bright].astype(str), "bright_"))
    assert 0.0 < bright.mean() < 0.05
    assert np.all(_crosses_gap(origins[bright], dirs[bright], t[bright], opening))


@pytest.mark.parametrize("opening", [scenes.DOOR_DEFAULT_OPENING, 3.0, 30.0, 90.0])
def test_door_rooms_closed_but_for_the_gap(opening: float) -> None:
    """Rays from either room never escape; those reaching the other room cross the gap."""
    scene = scenes.door_ajar(resolution=(8, 8), opening=opening)
    names = _mesh_names(scene)
    core = scene._compile()
    for box, seed in ((DARK, 1), (BRIGHT, 2)):
        origins, dirs = _random_rays(box, 200_000, seed)
        if box is BRIGHT:  # away from the door and the wedge in front of it
            origins = origins[np.linalg.norm(origins[:, [0, 2]] - HINGE, axis=1) > 0.95]
            dirs = dirs[: len(origins)]
        t, prim = core.intersect(origins, dirs)
        assert np.all(prim >= 0) and np.all(np.isfinite(t)), "a ray escaped to infinity"
        dark = _dark_side(origins + (t - 1e-4)[:, None] * dirs, opening)
        through = dark if box is BRIGHT else ~dark
        assert through.sum() >= 5  # light does pass
        assert np.all(_crosses_gap(origins[through], dirs[through], t[through], opening))
        # Rays from the dark room never reach the emitter's front, from the bright room some do.
        to_light = names[prim] == "light"
        facing = dirs[to_light, 2] < 0.0
        assert np.all(facing) if box is BRIGHT else not np.any(facing)


def test_door_gap_control(door: dualight.Scene) -> None:
    """`_crosses_gap` tells rays through the gap from rays through the door or a wall."""
    names = _mesh_names(door)
    rays = {  # origin, a point further along, whether it passes the gap, the mesh it hits
        "through the door": ((2.2, 1.0, 3.0), (2.2, 1.0, 5.0), False, "door"),
        "through the wall": ((1.0, 1.0, 3.8), (1.0, 1.0, 5.0), False, "dark_walls"),
        "along the free edge": ((1.7, 1.0, 3.0), (1.555, 1.0, 4.2), True, "bright_walls"),
        "over the door's top": ((1.9, 0.2, 3.9), (1.9, 2.4, 4.15), True, "bright_ceiling"),
    }
    origins = np.array([r[0] for r in rays.values()], np.float32)
    dirs = np.array([r[1] for r in rays.values()], np.float32) - origins
    t, prim = door._compile().intersect(origins, dirs)
    crosses = _crosses_gap(origins, dirs, t, scenes.DOOR_DEFAULT_OPENING)
    assert crosses.tolist() == [r[2] for r in rays.values()]
    assert names[prim].tolist() == [r[3] for r in rays.values()]


def _mean_and_error(scene: dualight.Scene, spp: int) -> tuple[float, float]:
    """The image mean of the green channel and its standard error (pixels are independent)."""
    image = dualight.render(scene, "path", spp=spp, max_depth=8, seed=5, progress=False)
    green, var = np.asarray(image)[..., 1], image.variance[..., 1]
    return float(green.mean()), float(math.sqrt(var.sum()) / green.size)


def test_door_wider_opening_lets_more_light_through() -> None:
    means = []
    for opening in (4.0, 15.0, 45.0):
        scene = scenes.door_ajar(resolution=(24, 24), opening=opening)
        mean, err = _mean_and_error(scene, 256)
        means.append((mean, err))
    for (m0, e0), (m1, e1) in zip(means, means[1:], strict=False):
        assert m1 - m0 > 5.0 * math.hypot(e0, e1), means


def test_door_scales_light_and_reflectance() -> None:
    base = scenes.door_ajar(resolution=(8, 8))
    brighter = scenes.door_ajar(resolution=(8, 8), light_scale=2.5, reflectance_scale=0.5)
    for a, b in zip(base.meshes, brighter.meshes, strict=True):
        assert a.name == b.name
        np.testing.assert_allclose(b.reflectance, 0.5 * np.array(a.reflectance))
        np.testing.assert_allclose(b.emission, 2.5 * np.array(a.emission))
        np.testing.assert_array_equal(a.vertices, b.vertices)


@pytest.mark.parametrize(
    "kwargs",
    [
        {"opening": 0.0},
        {"opening": -5.0},
        {"opening": 90.5},
        {"opening": float("nan")},
        {"light_scale": 0.0},
        {"light_scale": -1.0},
        {"light_scale": float("inf")},
        {"reflectance_scale": 0.0},
        {"reflectance_scale": 1.26},
    ],
)
def test_door_bad_arguments(kwargs: dict) -> None:
    with pytest.raises(ValueError, match="door_ajar"):
        scenes.door_ajar(**kwargs)


def test_door_largest_reflectance_scale_is_allowed() -> None:
    scene = scenes.door_ajar(resolution=(8, 8), reflectance_scale=1.25)
    assert max(max(m.reflectance) for m in scene.meshes) == pytest.approx(1.0)


# Cornell box with caustics ---------------------------------------------------------------------
CLASSIC_NAMES = [
    "floor", "ceiling", "back_wall", "green_wall", "red_wall", "short_block", "tall_block", "light"
]  # fmt: skip
# sha256 of the classic box's meshes (names, vertices, triangles, reflectance, emission,
# material) and camera as built before the caustics variant existed: stored references
# (cornell_64, cornell_64_full) depend on it.
CLASSIC_FINGERPRINT = "4b0eea9f9e4838b8f5a0a676cb73bb57683524d3acd0343d9f242e44f34a7368"


def _fingerprint(scene: dualight.Scene) -> str:
    import hashlib

    h = hashlib.sha256()
    for m in scene.meshes:
        h.update(m.name.encode())
        h.update(np.ascontiguousarray(m.vertices, np.float64).tobytes())
        h.update(np.ascontiguousarray(m.triangles, np.int64).tobytes())
        h.update(np.array(m.reflectance + m.emission, np.float64).tobytes())
        h.update(type(m.material).__name__.encode())
    c = scene.camera
    h.update(repr((c.origin, c.target, c.up, c.fov, c.resolution)).encode())
    return h.hexdigest()


def test_cornell_classic_unchanged() -> None:
    classic = scenes.cornell_box()
    assert [m.name for m in classic.meshes] == CLASSIC_NAMES
    assert all(isinstance(m.material, dualight.Diffuse) for m in classic.meshes)
    assert _fingerprint(classic) == CLASSIC_FINGERPRINT
    assert _fingerprint(scenes.cornell_box(variant="classic")) == CLASSIC_FINGERPRINT
    # The fingerprint sees a change: a negative control.
    assert _fingerprint(scenes.cornell_box(reflectance_scale=0.999)) != CLASSIC_FINGERPRINT


def test_cornell_caustics_spheres() -> None:
    scene = scenes.cornell_box(variant="caustics")
    classic = scenes.cornell_box()
    names = [m.name for m in scene.meshes]
    assert names == [
        "floor", "ceiling", "back_wall", "green_wall", "red_wall",
        "mirror_sphere", "glass_sphere", "light",
    ]  # fmt: skip
    # The room, light and camera are the classic ones.
    for name in ("floor", "ceiling", "back_wall", "green_wall", "red_wall", "light"):
        a = next(m for m in classic.meshes if m.name == name)
        b = next(m for m in scene.meshes if m.name == name)
        np.testing.assert_array_equal(a.vertices, b.vertices)
        assert a.reflectance == b.reflectance and a.emission == b.emission
    assert scene.camera == classic.camera
    mirror = next(m for m in scene.meshes if m.name == "mirror_sphere")
    glass = next(m for m in scene.meshes if m.name == "glass_sphere")
    assert mirror.material == dualight.Mirror((1.0, 1.0, 1.0))
    assert glass.material == dualight.Dielectric(ior=1.5)
    assert not mirror.is_emitter and not glass.is_emitter
    lo, hi = classic.bounds()
    for mesh, left, back in ((mirror, True, True), (glass, False, False)):
        v = mesh.vertices
        centre = 0.5 * (v.min(axis=0) + v.max(axis=0))
        radius = np.linalg.norm(v - centre, axis=1)
        assert 90.0 <= radius.mean() <= 100.0 and np.ptp(radius) < 1e-6 * radius.mean()
        # Resting on the floor (y = 0), inside the room, away from the walls.
        assert v[:, 1].min() == pytest.approx(0.0, abs=1e-9)
        assert np.all(v > lo + [60.0, -1e-9, 60.0]) and np.all(v < hi - 60.0)
        # Left in the image is +x (the red wall's side); the back is +z.
        assert (centre[0] > 278.0) == left and (centre[2] > 279.6) == back
        # Closed, and the normals point out (the dielectric's exterior side).
        assert np.all(_edge_counts(mesh.triangles) == 2)
        _, n = _areas_normals(v, mesh.triangles)
        assert np.all(np.einsum("ij,ij->i", n, v[mesh.triangles].mean(axis=1) - centre) > 0.0)
    # The two spheres are apart.
    assert np.linalg.norm(mirror.vertices.mean(axis=0) - glass.vertices.mean(axis=0)) > 250.0


def test_cornell_caustics_options() -> None:
    scene = scenes.cornell_box(variant="caustics", ior=1.33, reflectance_scale=0.9,
                               light_scale=2.0)  # fmt: skip
    by_name = {m.name: m for m in scene.meshes}
    assert by_name["glass_sphere"].material == dualight.Dielectric(ior=1.33)
    assert by_name["mirror_sphere"].material == dualight.Mirror((0.9, 0.9, 0.9))
    np.testing.assert_allclose(by_name["floor"].reflectance, 0.9 * np.array(scenes.CORNELL_WHITE))
    np.testing.assert_allclose(by_name["light"].emission,
                               2.0 * np.array(scenes.CORNELL_LIGHT_RADIANCE))  # fmt: skip


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"variant": "spheres"}, "unknown variant 'spheres'"),
        ({"variant": "Caustics"}, "unknown variant"),
        ({"light_scale": -1.0}, "light_scale"),
        ({"light_scale": float("nan")}, "light_scale"),
        ({"reflectance_scale": -0.1}, "reflectance_scale"),
        ({"reflectance_scale": 1.2}, "reflectance_scale"),
        ({"variant": "caustics", "reflectance_scale": 1.01}, "reflectance_scale"),
        ({"variant": "caustics", "ior": 0.0}, "ior"),
        ({"variant": "caustics", "ior": float("inf")}, "ior"),
    ],
)
def test_cornell_bad_arguments(kwargs: dict, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        scenes.cornell_box(**kwargs)


def test_cornell_caustics_glass_throws_a_caustic() -> None:
    """The floor just in front of the glass sphere is far brighter with glass (ior 1.5) than
    with an index-matched sphere (ior 1, which bends no light): the caustic."""
    # Pixels (rows, columns) of the caustic at 32 x 32 (projected from a 256 x 256 render).
    rows, cols = slice(28, 30), slice(20, 23)
    values = {}
    for ior in (1.5, 1.0):
        scene = scenes.cornell_box((32, 32), variant="caustics", ior=ior)
        image = dualight.render(scene, "path", spp=1024, max_depth=8, seed=3, progress=False)
        green = np.asarray(image)[rows, cols, 1]
        var = image.variance[rows, cols, 1]
        values[ior] = (float(green.mean()), float(math.sqrt(var.sum()) / green.size))
    (lens, e_lens), (flat, e_flat) = values[1.5], values[1.0]
    assert lens > 2.0 * flat, values
    assert lens - flat > 5.0 * math.hypot(e_lens, e_flat), values
