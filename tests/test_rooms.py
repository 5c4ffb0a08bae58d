"""`scenes.rooms`: a building of rooms joined by doors (the importance-driven radiosity scene).

Layout, names, lights and camera; every surface facing into its room; rays from inside every
room ending on the front of a surface (closed geometry); radiosity: light reaching unlit rooms
through doors, none at all with the doors closed (no leaks), form-factor row sums; a path-traced
picture.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

import dualight
from dualight import scenes
from dualight.radiosity import PatchMesh, solve

SIZE = np.array([4.0, 2.5, 4.0])  # the default room_size
WALL = 0.1  # the default wall_thickness
MAX_EDGE = 1.0  # 1,552 patches for rooms(4)
NAME = re.compile(r"room(\d+)_(\w+)")


def _box(n: int, k: int) -> tuple[np.ndarray, np.ndarray]:
    """Room k's inside, from the documented layout (not from the scene)."""
    cols = math.ceil(math.sqrt(n))
    r, c = divmod(k, cols)
    lo = np.array([c * (SIZE[0] + WALL), 0.0, r * (SIZE[2] + WALL)])
    return lo, lo + SIZE


def _room_of(name: str) -> tuple[int, str]:
    m = NAME.fullmatch(name)
    assert m, name
    return int(m.group(1)), m.group(2)


def _room_per_patch(scene: dualight.Scene, patches: PatchMesh) -> np.ndarray:
    rooms = np.array([_room_of(m.name)[0] for m in scene.meshes])
    return rooms[patches.mesh_index]


def _face_normals(mesh: dualight.Mesh) -> tuple[np.ndarray, np.ndarray]:
    v = mesh.vertices[mesh.triangles]
    return np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]), v.mean(axis=1)


# Layout -------------------------------------------------------------------------------------
@pytest.mark.parametrize("n", [1, 4, 10, 25])
def test_layout_names_bounds_and_camera(n: int) -> None:
    scene = scenes.rooms(n)
    cols = math.ceil(math.sqrt(n))
    rows = math.ceil(n / cols)
    lo, hi = scene.bounds()
    np.testing.assert_allclose(lo, 0.0, atol=1e-12)
    np.testing.assert_allclose(
        hi, [cols * SIZE[0] + (cols - 1) * WALL, SIZE[1], rows * SIZE[2] + (rows - 1) * WALL]
    )
    names = [m.name for m in scene.meshes]
    assert len(set(names)) == len(names)
    for k in range(n):
        for part in ("floor", "ceiling", "wall_east", "wall_west", "wall_north", "wall_south"):
            assert f"room{k}_{part}" in names
        b_lo, b_hi = _box(n, k)
        for m in scene.meshes:
            if _room_of(m.name)[0] == k and "door" not in m.name:
                assert np.all(m.vertices >= b_lo - 1e-9) and np.all(m.vertices <= b_hi + 1e-9)
    # Doors: one per pair of rooms next to each other in the grid.
    doors = sum(1 for k in range(n) if k % cols + 1 < cols and k + 1 < n) + max(n - cols, 0)
    assert sum("_door_" in name for name in names) == doors
    # The camera is inside room 0 (not on a wall), at eye height.
    b_lo, b_hi = _box(n, 0)
    origin = np.array(scene.camera.origin)
    assert np.all(origin > b_lo + 0.1) and np.all(origin < b_hi - 0.1)
    assert scene.camera.fov == 70.0 and scene.camera.resolution == (64, 64)
    assert scene.triangle_count < 40 * n


def test_counts_grow_with_n() -> None:
    sizes = [scenes.rooms(n) for n in (1, 4, 10, 25)]
    meshes = [len(s.meshes) for s in sizes]
    triangles = [s.triangle_count for s in sizes]
    assert meshes == sorted(meshes) and len(set(meshes)) == 4
    assert triangles == [14, 116, 338, 958]  # the docstring's numbers


def test_lights() -> None:
    def lit(scene: dualight.Scene) -> list[int]:
        return sorted(_room_of(m.name)[0] for m in scene.meshes if m.is_emitter)

    assert lit(scenes.rooms(1)) == [0]
    assert lit(scenes.rooms(2)) == [0, 1]
    assert lit(scenes.rooms(4)) == [0, 3]
    assert lit(scenes.rooms(10)) == [0, 3, 6, 7, 9]  # 7 is the farthest from room 0
    assert lit(scenes.rooms(10, lit_every=100)) == [0, 7]
    assert lit(scenes.rooms(10, camera_room=7)) == [0, 3, 6, 7, 8, 9]
    # A dark camera room, whatever lit_every says (room 0 is lit by it otherwise).
    assert lit(scenes.rooms(10, camera_room_lit=False)) == [3, 6, 7, 9]
    assert lit(scenes.rooms(10, camera_room=1, camera_room_lit=False)) == [0, 3, 6, 8, 9]
    scene = scenes.rooms(4, light_radiance=(1.0, 2.0, 3.0))
    for m in scene.meshes:
        if m.is_emitter:
            assert m.name.endswith("_light") and m.emission == (1.0, 2.0, 3.0)
            assert len(m.triangles) == 2
            assert m.areas.sum() == pytest.approx(SIZE[0] * SIZE[2] / 16)
            assert m.vertices[:, 1] == pytest.approx(SIZE[1] - 0.01)
            n, _ = _face_normals(m)
            assert np.all(n[:, 1] < 0)  # facing down


def test_camera_room_and_materials() -> None:
    scene = scenes.rooms(10, camera_room=5, resolution=(32, 16))
    b_lo, b_hi = _box(10, 5)
    origin = np.array(scene.camera.origin)
    assert np.all(origin > b_lo) and np.all(origin < b_hi)
    assert scene.camera.resolution == (32, 16)
    assert "room5_light" in [m.name for m in scene.meshes]
    # Deterministic tints around the reflectance; tint=0 gives it exactly, RGB accepted.
    a, b = scenes.rooms(4, seed=1), scenes.rooms(4, seed=1)
    assert [m.reflectance for m in a.meshes] == [m.reflectance for m in b.meshes]
    c = scenes.rooms(4, seed=2)
    assert [m.reflectance for m in a.meshes] != [m.reflectance for m in c.meshes]
    assert all(np.allclose(m.reflectance, 0.6, rtol=0.05 + 1e-12) for m in a.meshes)
    flat = scenes.rooms(4, tint=0.0, reflectance=(0.1, 0.2, 0.3))
    assert all(m.reflectance == (0.1, 0.2, 0.3) for m in flat.meshes)
    with pytest.raises(ValueError, match="n must be"):
        scenes.rooms(0)
    with pytest.raises(ValueError, match="camera_room"):
        scenes.rooms(4, camera_room=4)
    with pytest.raises(ValueError, match="door"):
        scenes.rooms(4, door=(1.0, 3.0))
    with pytest.raises(ValueError, match="leaves no room lit"):
        scenes.rooms(1, camera_room_lit=False)
    with pytest.raises(TypeError, match="camera_room_lit"):
        scenes.rooms(4, camera_room_lit=1)  # type: ignore[arg-type]


# Closedness ---------------------------------------------------------------------------------
@pytest.mark.parametrize("doors", [True, False])
def test_every_surface_faces_into_its_room(doors: bool) -> None:
    n = 10
    cols = math.ceil(math.sqrt(n))
    scene = scenes.rooms(n, doors=doors)
    for m in scene.meshes:
        k, part = _room_of(m.name)
        rooms = [k]
        if part == "door_east":
            rooms.append(k + 1)
        elif part == "door_north":
            rooms.append(k + cols)
        normals, centroids = _face_normals(m)
        for j in rooms:
            b_lo, b_hi = _box(n, j)
            dots = np.einsum("ij,ij->i", normals, 0.5 * (b_lo + b_hi) - centroids)
            assert np.all(dots > 0), (m.name, j)


@pytest.mark.parametrize("doors", [True, False])
def test_rays_from_inside_end_on_front_faces(doors: bool, first_hits) -> None:
    # Closed geometry: from anywhere inside any room, any ray ends on a surface seen from its
    # front, through doors too; nothing is open, and no back of a surface is in view.
    n = 4
    scene = scenes.rooms(n, doors=doors)
    rng = np.random.default_rng(7)
    per_room = 400
    origins = np.concatenate(
        [
            b_lo + [0.05, 0.05, 0.05] + rng.random((per_room, 3)) * (b_hi - b_lo - 0.1)
            for b_lo, b_hi in (_box(n, k) for k in range(n))
        ]
    )
    dirs = rng.normal(size=origins.shape)
    dirs /= np.linalg.norm(dirs, axis=1, keepdims=True)
    dirs[::8] = [1.0, 0.0, 0.0]  # some rays straight east and north, through doors
    dirs[1::8] = [0.0, 0.0, 1.0]
    t, normal = first_hits(scene, origins, dirs)
    assert np.all(np.isfinite(t))
    assert np.all(np.einsum("ij,ij->i", normal, dirs) < 0)
    hit = origins + t[:, None] * dirs
    left_room = np.zeros(len(hit), dtype=bool)
    for k in range(n):
        b_lo, b_hi = _box(n, k)
        mine = slice(k * per_room, (k + 1) * per_room)
        left_room[mine] = np.any((hit[mine] < b_lo - 1e-9) | (hit[mine] > b_hi + 1e-9), axis=1)
    assert left_room.any() == doors  # only doors let a ray out of its room


# Radiosity ----------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def open_building() -> tuple[dualight.Scene, dualight.radiosity.Solution]:
    scene = scenes.rooms(4)
    return scene, solve(scene, "gauss_seidel", max_edge=MAX_EDGE)


@pytest.fixture(scope="module")
def closed_building() -> tuple[dualight.Scene, dualight.radiosity.Solution]:
    scene = scenes.rooms(4, doors=False)
    return scene, solve(scene, "gauss_seidel", max_edge=MAX_EDGE)


def test_light_reaches_every_room_through_doors(open_building) -> None:
    scene, sol = open_building
    assert len(sol.patches) == 1552  # the docstring's number
    room = _room_per_patch(scene, sol.patches)
    floor = np.array([m.name.endswith("_floor") for m in scene.meshes])[sol.patches.mesh_index]
    for k in range(4):  # rooms 1 and 2 have no light of their own
        assert np.all(sol.B[(room == k) & floor] > 0), k
    # The camera sees mostly its own room, and a little of the next one through the door.
    R = sol.R[:, 0]
    share = R[room == 0].sum() / R.sum()
    print(f"receiver share of room 0: {share:.4f}")
    assert 0.85 < share < 1.0
    assert R[room == 1].sum() > 0


def test_closed_doors_leak_nothing(closed_building) -> None:
    # Without doors, not one form factor links two rooms: the unlit rooms stay exactly dark
    # and only the camera's room has importance.
    scene, sol = closed_building
    room = _room_per_patch(scene, sol.patches)
    for k in (1, 2):
        assert np.all(sol.B[room == k] == 0.0), k
    for k in (0, 3):
        assert np.all(sol.B[room == k] > 0), k
    assert np.all(sol.I[room != 0] == 0.0)
    assert np.all(sol.I[room == 0] > 0)
    F = sol.form_factors
    rows = np.repeat(np.arange(F.n), np.diff(np.asarray(F.indptr)).astype(np.int64))
    assert np.all(room[rows] == room[np.asarray(F.indices)])


def test_form_factor_row_sums(open_building, closed_building) -> None:
    # A closed room without a light is a convex box: its rows sum to 1 (to 1e-8, as the
    # cube's in test_form_factors). The light (1 cm under the ceiling) and door edges hide
    # parts of patches, where 4 shadow rays estimate visibility with noise: rows there
    # reach about 1 + 1e-2 (a leak through a missing face would add far more, e.g. 0.4 for a
    # wall) and average 1 within 1e-3 in rooms without a light.
    report = {}
    for label, (scene, sol) in (("doors", open_building), ("closed", closed_building)):
        sums = np.asarray(sol.form_factors.row_sums())
        room = _room_per_patch(scene, sol.patches)
        areas = sol.patches.areas
        report[label] = float(sums.max())
        assert sums.max() <= 1.02, label
        for k in (1, 2):
            mine = room == k
            mean = np.average(sums[mine], weights=areas[mine])
            assert abs(mean - 1.0) <= 1e-3, (label, k, mean)
            if label == "closed":
                assert np.abs(sums[mine] - 1.0).max() <= 1e-6, k
    print(f"form-factor row sum max: {report}")


# Path tracing -------------------------------------------------------------------------------
def test_path_traced_picture() -> None:
    image = dualight.render(scenes.rooms(4), spp=16, progress=False)
    pixels = np.asarray(image.pixels)
    assert pixels.shape == (64, 64, 3)
    assert np.all(np.isfinite(pixels))
    assert pixels.mean() > 0.05
    assert (pixels.sum(axis=2) > 0).mean() > 0.99  # every wall in view is lit
