"""Built-in scenes.

* :func:`cornell_box`: the Cornell box from the Cornell Program of Computer Graphics'
  measured data (geometry and camera in millimetres), with the RGB reflectances and light
  radiance that Mitsuba 3's ``cornell_box()`` uses for the measured spectra.
* :func:`furnace`: a closed cube with uniform reflectance and emission; every surface has the
  analytic radiance ``Le / (1 - rho)`` (:func:`furnace_radiance`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from dualight.scene import Camera, Scene

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


def _orient(quad: np.ndarray, towards: np.ndarray, inward: bool) -> np.ndarray:
    """Reverse a quad's vertex order if its normal does not face (or face away from) a point."""
    n = np.cross(quad[1] - quad[0], quad[2] - quad[0])
    facing = float(np.dot(n, towards - quad.mean(axis=0))) > 0.0
    return quad if facing == inward else quad[::-1]


def _quads_mesh(quads: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    vertices = np.concatenate(quads)
    faces = np.arange(len(vertices)).reshape(-1, 4)
    return vertices, faces


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


def cornell_box(
    resolution: tuple[int, int] = (128, 128),
    *,
    light_scale: float = 1.0,
    reflectance_scale: float = 1.0,
) -> Scene:
    """The Cornell box (measured geometry and camera; Mitsuba 3's RGB materials).

    ``light_scale`` and ``reflectance_scale`` multiply the light's radiance and every wall's
    and block's reflectance; tests use them as negative controls.
    """
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
        quads = [np.array(q, dtype=np.float64) for q in _CORNELL_QUADS[name]]
        if name.endswith("block"):
            centre = np.mean(np.concatenate(quads), axis=0)
            quads = [_orient(q, centre, inward=False) for q in quads]
        else:
            quads = [_orient(q, _CORNELL_ROOM_CENTRE, inward=True) for q in quads]
        v, f = _quads_mesh(quads)
        scene.add_mesh(v, f, reflectance=tuple(reflectance_scale * c for c in rho), name=name)
    light = _orient(np.array(_CORNELL_LIGHT), _CORNELL_ROOM_CENTRE, inward=True)
    v, f = _quads_mesh([light])
    scene.add_mesh(
        v,
        f,
        reflectance=CORNELL_LIGHT_REFLECTANCE,
        emission=tuple(light_scale * c for c in CORNELL_LIGHT_RADIANCE),
        name="light",
    )
    return scene


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


def _axis_rect(axis: int, value: float, lo: Sequence[float], hi: Sequence[float]) -> np.ndarray:
    """The axis-aligned rectangle ``coordinate[axis] == value`` spanning ``lo..hi`` in the other
    two coordinates (``lo[axis]`` and ``hi[axis]`` are ignored), as a quad."""
    a, b = (axis + 1) % 3, (axis + 2) % 3
    quad = np.empty((4, 3), dtype=np.float64)
    quad[:, axis] = value
    quad[:, a] = (lo[a], hi[a], hi[a], lo[a])
    quad[:, b] = (lo[b], lo[b], hi[b], hi[b])
    return quad


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
        grid, the lights and the camera do not depend on ``doors``.
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
