"""The scene you edit: a camera and triangle meshes, each with a material and maybe an emission.

`Scene` is a plain Python description, validated as it is built. Rendering turns it into the
immutable compiled scene (`dualight._core.Scene`), which commits Embree once and is cached until
the description changes.

Conventions (the same as Mitsuba 3):

* A triangle's normal follows the right-hand rule on its vertex order,
  ``n = (v1 - v0) x (v2 - v0)``. Emitters are one-sided: they emit on the normal's side only.
* A mesh's material is one of :mod:`dualight.materials`: :class:`~dualight.Diffuse` (the
  default: a two-sided Lambertian BRDF, Mitsuba's ``twosided`` around ``diffuse``),
  :class:`~dualight.Mirror` or :class:`~dualight.Dielectric`, whose exterior is on the normal's
  side.
* The camera's ``fov`` is the full angle along x in degrees; row 0 of an image is its top.
"""

from __future__ import annotations

import contextlib
import functools
import itertools
import math
import threading
import warnings
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal, ParamSpec, TypeVar

import numpy as np

from dualight.emitters import EMITTER_TYPES as _EMITTER_TYPES
from dualight.emitters import ENVIRONMENTS, Emitter
from dualight.materials import Diffuse, Material
from dualight.textures import Texture, check_texture_range

if TYPE_CHECKING:
    from dualight import _core

Vec3 = tuple[float, float, float]

_DEFAULT_REFLECTANCE: Vec3 = (0.5, 0.5, 0.5)

# The core computes in float32. Coordinates beyond 1e12 (squared distances, areas and their
# pdfs' products leave its range: a Cornell box 5.6e12 across renders wrong by light tracing
# and BDPT, 5.6e11 right), and scenes smaller than 1e-7 across (5.6e-9: wrong, 5.6e-8: right)
# are refused. Before, a camera at 3e19 was "parallel to its up vector" (issue 18).
COORDINATE_LIMIT = 1e12
SMALLEST_EXTENT = 1e-7
EMISSION_LIMIT = 1e12


def _vec3(value: Any, name: str) -> Vec3:
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be 3 numbers, got {value!r}") from None
    if arr.shape != (3,):
        raise ValueError(f"{name} must be 3 numbers, got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be finite, got {arr.tolist()}")
    return (float(arr[0]), float(arr[1]), float(arr[2]))


def _resolution(value: Any) -> tuple[int, ...]:
    """A camera's ``(width, height)``: two positive integers (numpy's too, not bools)."""
    if isinstance(value, str | bytes) or not isinstance(value, Sequence | np.ndarray):
        hint = ""
        if isinstance(value, int | np.integer) and not isinstance(value, bool):
            hint = f"; for a square image pass resolution=({value}, {value})"
        raise ValueError(
            f"camera resolution must be a pair (width, height) of positive ints, got "
            f"{value!r}{hint}"
        )
    res = tuple(value)
    if len(res) != 2 or not all(
        isinstance(v, int | np.integer) and not isinstance(v, bool) and v >= 1 for v in res
    ):
        raise ValueError(f"camera resolution must be (width, height) positive ints, got {res}")
    return res


@dataclass(frozen=True)
class Camera:
    """A pinhole camera.

    Parameters
    ----------
    origin, target, up:
        Eye position, a point it looks at, and the up direction (need not be orthogonal to the
        view direction, but not parallel to it).
    fov:
        Full field of view along x, in degrees (Mitsuba's default ``fov_axis="x"``).
    resolution:
        ``(width, height)`` in pixels.
    """

    origin: Vec3 = (0.0, 0.0, 0.0)
    target: Vec3 = (0.0, 0.0, 1.0)
    up: Vec3 = (0.0, 1.0, 0.0)
    fov: float = 40.0
    resolution: tuple[int, int] = (128, 128)

    def __post_init__(self) -> None:
        origin = _position(self.origin, "camera origin")
        target = _position(self.target, "camera target")
        up = _position(self.up, "camera up")
        object.__setattr__(self, "origin", origin)
        object.__setattr__(self, "target", target)
        object.__setattr__(self, "up", up)
        try:
            fov = float(self.fov)
        except (TypeError, ValueError):
            fov = None
        if fov is None or isinstance(self.fov, bool | np.bool_):  # True was taken as 1 degree
            raise ValueError(f"camera fov must be a number of degrees, got {self.fov!r}")
        if not (math.isfinite(fov) and 0.0 < fov < 180.0):
            raise ValueError(f"camera fov must be in (0, 180) degrees, got {self.fov}")
        if not 0.0 < float(np.float32(fov)) < 180.0:  # the core's float32 fov
            raise ValueError(
                f"camera fov {self.fov!r} rounds to {float(np.float32(fov))} degrees in the "
                "core's float32: it must be in (0, 180) there"
            )
        object.__setattr__(self, "fov", fov)
        res = _resolution(self.resolution)
        if res[0] * res[1] > 1 << 28:
            raise ValueError(f"camera resolution {res} is too large")
        object.__setattr__(self, "resolution", (int(res[0]), int(res[1])))
        view = np.subtract(target, origin)
        if np.linalg.norm(view) == 0.0:
            raise ValueError("camera target equals its origin")
        side = np.cross(view / np.linalg.norm(view), up)
        if np.linalg.norm(up) == 0.0 or np.linalg.norm(side) < 1e-6 * np.linalg.norm(up):
            raise ValueError("camera up is zero or parallel to the view direction")

    @property
    def width(self) -> int:
        """Image width in pixels."""
        return self.resolution[0]

    @property
    def height(self) -> int:
        """Image height in pixels."""
        return self.resolution[1]

    def with_resolution(self, width: int, height: int) -> Camera:
        """The same camera with another resolution (the fov along x is kept)."""
        return Camera(self.origin, self.target, self.up, self.fov, (width, height))

    def _compile(self) -> _core.PinholeCamera:
        from dualight import _core

        return _core.PinholeCamera(
            self.origin, self.target, self.up, self.fov, self.resolution[0], self.resolution[1]
        )


@dataclass(frozen=True)
class Mesh:
    """A triangle mesh with one material and an emission (maybe zero). Arrays are read-only
    copies.

    Attributes
    ----------
    vertices, triangles : numpy.ndarray
        ``(V, 3)`` float64 positions and ``(T, 3)`` int64 vertex indices.
    reflectance : tuple of 3 float
        The material's reflectance: the albedo of a :class:`~dualight.Diffuse`, the reflectance
        of a :class:`~dualight.Mirror`, ``(1, 1, 1)`` for a :class:`~dualight.Dielectric`; a
        texture's mean where the material is textured.
    emission : tuple of 3 float
        Radiance leaving the front side; a texture's mean where ``emission_texture`` is given.
    name : str
    areas : numpy.ndarray
        ``(T,)`` float64 triangle areas.
    material : Diffuse, Mirror or Dielectric
        ``Diffuse(reflectance)`` when not given.
    normals : numpy.ndarray or None
        ``(V, 3)`` unit shading normals (smooth shading), or ``None`` for flat triangles.
    uv : numpy.ndarray or None
        ``(V, 2)`` surface coordinates for textures, or ``None`` (each triangle's barycentrics).
    emission_texture : Bitmap, Checkerboard or None
        The radiance leaving each point of the front side, looked up at its ``(u, v)``
        (Mitsuba's ``area`` emitter with a ``radiance`` texture), or ``None``: ``emission``
        everywhere.
    """

    vertices: np.ndarray  # (V, 3) float64
    triangles: np.ndarray  # (T, 3) int64
    reflectance: Vec3
    emission: Vec3
    name: str
    areas: np.ndarray = field(repr=False)  # (T,) float64
    material: Material = None  # type: ignore[assignment]  # None: Diffuse(reflectance)
    normals: np.ndarray | None = field(default=None, repr=False)  # (V, 3) float64, unit
    uv: np.ndarray | None = field(default=None, repr=False)  # (V, 2) float64
    emission_texture: Texture | None = None

    def __post_init__(self) -> None:
        if self.material is None:
            object.__setattr__(self, "material", Diffuse(self.reflectance))
        elif not isinstance(self.material, Material):
            raise TypeError(
                f"{self.name}: material must be a dualight material (Diffuse, Mirror, "
                f"Dielectric, ...), got {type(self.material).__name__}"
            )
        elif tuple(self.reflectance) != self.material.rgb_reflectance:
            raise ValueError(
                f"{self.name}: reflectance {self.reflectance} disagrees with {self.material!r}"
            )

    @property
    def is_emitter(self) -> bool:
        """Whether the mesh emits (some emission channel > 0)."""
        return any(e > 0.0 for e in self.emission)

    def _mitsuba_emitter(self) -> dict[str, Any]:
        """Its Mitsuba 3 ``area`` emitter as a plain plugin dict (textures as
        :meth:`dualight.textures.Texture._mitsuba_dict` gives them)."""
        radiance = (
            {"type": "rgb", "value": [float(c) for c in self.emission]}
            if self.emission_texture is None
            else self.emission_texture._mitsuba_dict()
        )
        return {"type": "area", "radiance": radiance}


def _triangulate(faces: Any, n_vertices: int, name: str) -> np.ndarray:
    f = np.asarray(faces)
    if f.ndim != 2 or f.shape[1] not in (3, 4):
        raise ValueError(f"{name}: faces must have shape (F, 3) or (F, 4), got {f.shape}")
    if f.shape[0] == 0:
        raise ValueError(f"{name}: faces is empty")
    if not (np.issubdtype(f.dtype, np.number) and not np.issubdtype(f.dtype, np.complexfloating)):
        raise ValueError(f"{name}: faces must hold integer vertex indices, got dtype {f.dtype}")
    if not np.issubdtype(f.dtype, np.integer):
        if not np.all(np.isfinite(f)) or np.any(f != np.round(f)):
            raise ValueError(f"{name}: faces must hold integer vertex indices")
    f = f.astype(np.int64)
    bad = (f < 0) | (f >= n_vertices)
    if np.any(bad):
        row = int(np.argwhere(bad)[0][0])
        raise ValueError(
            f"{name}: face {row} has index {f[row].tolist()} out of range for {n_vertices} vertices"
        )
    if f.shape[1] == 4:  # quads (v0, v1, v2, v3) -> (v0, v1, v2), (v0, v2, v3)
        f = np.stack([f[:, [0, 1, 2]], f[:, [0, 2, 3]]], axis=1).reshape(-1, 3)
    return f


def _per_vertex(value: Any, n_vertices: int, columns: int, name: str, what: str) -> np.ndarray:
    """A per-vertex attribute as an (V, columns) float64 copy, its shape and type checked."""
    given = np.asarray(value).dtype
    if given.kind not in "iuf":
        raise ValueError(f"{name}: {what} must be (V, {columns}) real numbers, got {given}")
    values = np.array(value, dtype=np.float64, copy=True)
    if values.shape != (n_vertices, columns):
        raise ValueError(
            f"{name}: {what} must have shape ({n_vertices}, {columns}), one per vertex, "
            f"got {values.shape}"
        )
    return values


def _bad_row(bad: np.ndarray, values: np.ndarray, name: str, what: str, rule: str) -> None:
    if np.any(bad):
        row = int(np.argmax(bad))
        raise ValueError(f"{name}: {what} {row} is {values[row].tolist()}; {rule}")


def _unit_normals(value: Any, n_vertices: int, name: str) -> np.ndarray:
    """Per-vertex shading normals as unit float64 rows, checked."""
    ns = _per_vertex(value, n_vertices, 3, name, "normals")
    with np.errstate(over="ignore", invalid="ignore"):
        length = np.linalg.norm(ns, axis=1)
    bad = ~(np.isfinite(length) & (length > 1e-30) & (length < 1e30))
    _bad_row(bad, ns, name, "normal", "normals must be finite and non-zero")
    return ns / length[:, None]


def _surface_uv(value: Any, n_vertices: int, name: str) -> np.ndarray:
    """Per-vertex surface coordinates as float64 rows, checked."""
    uv = _per_vertex(value, n_vertices, 2, name, "uv")
    bad = ~(np.isfinite(uv).all(axis=1) & (np.abs(uv).max(axis=1) <= 1e12))
    _bad_row(bad, uv, name, "uv", "uv must be finite, |uv| <= 1e12")
    return uv


def _colour(value: Any, name: str, *, upper: float | None) -> Vec3:
    rgb = _vec3(value, name)
    if any(c < 0.0 for c in rgb):
        raise ValueError(f"{name} must be >= 0, got {rgb}")
    if upper is not None and any(c > upper for c in rgb):
        raise ValueError(f"{name} must be <= {upper} (energy conservation), got {rgb}")
    if upper is None and any(
        c != 0.0 and not 1 / EMISSION_LIMIT <= c <= EMISSION_LIMIT for c in rgb
    ):
        raise ValueError(
            f"{name} must be 0 or within [1e-12, 1e12], got {rgb}: the core renders in float32, "
            "and the squares of such values (the variance) overflow or underflow it"
        )
    return rgb


def _position(value: Any, name: str) -> Vec3:
    """A point or direction of the camera: 3 finite numbers within +-COORDINATE_LIMIT."""
    xyz = _vec3(value, name)
    if max(abs(c) for c in xyz) > COORDINATE_LIMIT:
        raise ValueError(
            f"{name} {xyz} lies beyond 1e12: the core computes in float32, which cannot "
            "render such coordinates"
        )
    return xyz


def _faces_something(
    mesh: Mesh, points: np.ndarray, lo: np.ndarray, hi: np.ndarray, tolerance: float
) -> bool:
    """Whether some point lies in front of the plane of some triangle of ``mesh`` (by more
    than ``tolerance``). Triangles are grouped by their unit normal, so a flat light costs
    one pass over the points; the bounding box ``lo, hi`` answers first when it can."""
    tri = mesh.vertices[mesh.triangles]
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    normals, group = np.unique(np.round(n, 6), axis=0, return_inverse=True)
    group = group.reshape(-1)
    # Per group, the lowest plane offset of its triangles: the most permissive plane.
    offset = np.full(len(normals), np.inf)
    np.minimum.at(offset, group, np.einsum("ij,ij->i", normals[group], tri[:, 0]))
    corners = np.array(list(itertools.product(*zip(lo, hi, strict=True))))
    maybe = (normals @ corners.T).max(axis=1) > offset + tolerance
    for start in range(0, len(normals), 64):  # bounded memory: 64 planes x V at a time
        rows = np.flatnonzero(maybe[start : start + 64]) + start
        if len(rows) and np.any((normals[rows] @ points.T).max(axis=1) > offset[rows] + tolerance):
            return True
    return False


_P = ParamSpec("_P")
_R = TypeVar("_R")


def _freezes_scene(function: Callable[_P, _R]) -> Callable[_P, _R]:
    """``function(scene, ...)`` with ``scene`` frozen while it runs (when it is a Scene)."""

    @functools.wraps(function)
    def wrapper(*args: _P.args, **kwargs: _P.kwargs) -> _R:
        scene = args[0] if args else kwargs.get("scene")
        if not isinstance(scene, Scene):
            return function(*args, **kwargs)
        with scene._in_use():
            return function(*args, **kwargs)

    return wrapper


def _checked_bool(value: Any, name: str) -> bool:
    if not isinstance(value, bool):
        raise TypeError(f"{name} must be True or False, got {value!r}")
    return value


class Scene:
    """A camera and triangle meshes with materials, some of them emitters.

    Examples
    --------
    >>> scene = dualight.Scene(camera=dualight.Camera(origin=(0, 1, -3), target=(0, 1, 0)))
    >>> scene.add_mesh(vertices, faces, reflectance=(0.7, 0.7, 0.7))
    >>> scene.add_mesh(light_v, light_f, reflectance=(0, 0, 0), emission=(10, 10, 10))
    >>> scene.add_mesh(ball_v, ball_f, material=dualight.Dielectric(ior=1.5), name="glass")
    >>> image = dualight.render(scene, spp=64)

    Parameters
    ----------
    camera : Camera, optional
        The camera renders and solves use (else they need ``camera=``).
    robust_intersections : bool, optional
        Embree's robust mode (the default): ray queries without the optimisations that lower
        its arithmetic accuracy, so that no ray slips through where triangles meet. ``False``
        renders 8-19 % more samples per second, but light leaks through the edges of closed
        meshes (a camera inside a closed cube within the lit Cornell box saw pixels of 1.4e-4,
        where the cube lit inside averages 2, instead of black). It is Mitsuba 3's scene property
        ``embree_use_robust_intersections``, whose default is ``False``.
    """

    def __init__(self, camera: Camera | None = None, *, robust_intersections: bool = True) -> None:
        if camera is not None and not isinstance(camera, Camera):
            raise TypeError(f"camera must be a dualight.Camera, got {type(camera).__name__}")
        self._camera = camera
        self._robust_intersections = _checked_bool(robust_intersections, "robust_intersections")
        self._meshes: list[Mesh] = []
        self._emitters: list[Emitter] = []
        self._compiled: _core.Scene | None = None
        # Camera origins (None: no camera) the emitters were checked against (render time).
        self._checked_facing: set[Vec3 | None] = set()
        # Renders and solves using the scene now (in any thread); add_mesh refuses meanwhile.
        self._lock = threading.Lock()
        self._users = 0

    def __getstate__(self) -> dict[str, Any]:
        # Picklable (render(executor=...) sends the description to workers): the compiled
        # scene and the in-use count stay behind; the compiled scene is rebuilt where needed.
        state = self.__dict__.copy()
        state["_compiled"] = None
        del state["_lock"], state["_users"]
        return state

    def __setstate__(self, state: dict[str, Any]) -> None:
        defaults = {"_checked_facing": set(), "_emitters": [], "_robust_intersections": True}
        self.__dict__.update({**defaults, **state})
        self._lock = threading.Lock()
        self._users = 0
        for mesh in self._meshes:
            for value in vars(mesh).values():
                if isinstance(value, np.ndarray):
                    value.flags.writeable = False

    @property
    def camera(self) -> Camera | None:
        """The scene's camera, or None (then render and solve need ``camera=``)."""
        return self._camera

    @camera.setter
    def camera(self, camera: Camera) -> None:
        if not isinstance(camera, Camera):
            raise TypeError(f"camera must be a dualight.Camera, got {type(camera).__name__}")
        with self._lock:
            self._refuse_while_in_use("camera")
            self._camera = camera

    @property
    def robust_intersections(self) -> bool:
        """Whether ray queries use Embree's robust mode (see the class's parameters); set it
        to change that for the renders and solves started after (a
        :class:`~dualight.radiosity.HierarchicalSolver` keeps the scene it was built on)."""
        return self._robust_intersections

    @robust_intersections.setter
    def robust_intersections(self, robust: bool) -> None:
        robust = _checked_bool(robust, "robust_intersections")
        with self._lock:
            self._refuse_while_in_use("robust_intersections")
            if robust != self._robust_intersections:
                self._robust_intersections = robust
                self._compiled = None

    @property
    def meshes(self) -> tuple[Mesh, ...]:
        """The meshes in the order they were added."""
        return tuple(self._meshes)

    @property
    def triangle_count(self) -> int:
        """Triangles over all meshes."""
        return sum(len(m.triangles) for m in self._meshes)

    @property
    def emitters(self) -> tuple[Emitter, ...]:
        """The emitters without a surface (point, spot and directional lights, environments) in
        the order they were added; area lights are the meshes with emission."""
        return tuple(self._emitters)

    @property
    def has_emitters(self) -> bool:
        """Whether some mesh emits or the scene has an emitter without a surface."""
        return bool(self._emitters) or any(m.is_emitter for m in self._meshes)

    def add_emitter(self, emitter: Emitter) -> int:
        """Add a point, spot or directional light or an environment (:mod:`dualight.emitters`);
        returns its index in :attr:`emitters`. Radiosity takes them as a first shot (the
        irradiance they give each patch directly, or each element of hierarchical radiosity
        as refinement creates it)."""
        if not isinstance(emitter, _EMITTER_TYPES):
            raise TypeError(
                "emitter must be a dualight.PointLight, SpotLight, DirectionalLight, "
                f"ConstantEnvironment or EnvironmentMap, got {type(emitter).__name__} (area lights "
                "are meshes with emission)"
            )
        if isinstance(emitter, ENVIRONMENTS) and any(
            isinstance(e, ENVIRONMENTS) for e in self._emitters
        ):
            raise ValueError(
                "the scene has an environment already: a scene takes one (constant or envmap), "
                "as in Mitsuba 3"
            )
        with self._lock:
            self._refuse_while_in_use("add_emitter")
            self._emitters.append(emitter)
            self._compiled = None
            return len(self._emitters) - 1

    @property
    def has_specular(self) -> bool:
        """Whether some mesh is a :class:`~dualight.Mirror` or :class:`~dualight.Dielectric`
        (delta BSDFs, which radiosity cannot handle)."""
        return any(m.material.has_specular for m in self._meshes)

    @property
    def features(self) -> dict[str, Any]:
        """What the scene holds, computed once when it is compiled (renders and solves use it
        to skip work that cannot contribute):

        ``specular`` (some mirror or glass), ``dielectric``, ``all_diffuse``,
        ``emitter_triangles``, ``closed`` (every edge shared by exactly two triangles, in
        opposite directions: watertight and consistently oriented), ``convex_enclosure``
        (every vertex on or in front of every triangle's plane, to 1e-5 of the scene's size:
        two surface points that face each other always see each other; ``False`` too when a
        very large scene was not checked, see ``convexity_checked``) and ``unoccluded`` (a
        convex enclosure without glass: renders with the camera inside need no shadow rays).
        """
        return dict(self._compile().features)

    def emitters_facing(self, point: Any) -> int:
        """How many emitter triangles turn their emitting (front) side towards ``point``."""
        p = np.asarray(point, dtype=np.float64).reshape(3)
        count = 0
        for m in self._meshes:
            if not m.is_emitter:
                continue
            tri = m.vertices[m.triangles]
            n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
            count += int(np.count_nonzero(np.einsum("ij,ij->i", n, p - tri[:, 0]) > 0))
        return count

    def add_mesh(
        self,
        vertices: Any,
        faces: Any,
        reflectance: Sequence[float] = _DEFAULT_REFLECTANCE,
        emission: Sequence[float] | Texture = (0.0, 0.0, 0.0),
        *,
        material: Material | None = None,
        name: str | None = None,
        degenerate: Literal["raise", "drop"] = "raise",
        normals: Any = None,
        uv: Any = None,
    ) -> int:
        """Add a triangle or quad mesh with one material; returns its index.

        Parameters
        ----------
        vertices:
            ``(V, 3)`` finite positions.
        faces:
            ``(F, 3)`` triangles or ``(F, 4)`` quads of vertex indices. Quads are split along
            their ``v0-v2`` diagonal and should be planar.
        reflectance:
            Diffuse albedo per RGB channel, each in ``[0, 1]``: shorthand for
            ``material=Diffuse(reflectance)``. Leave it at its default when giving ``material``.
        emission:
            Radiance (W m^-2 sr^-1) leaving the front side (the right-hand-rule normal), ``>= 0``:
            three numbers, or a :class:`~dualight.textures.Bitmap` or
            :class:`~dualight.textures.Checkerboard` of radiance looked up at each point's
            ``(u, v)`` (Mitsuba's ``area`` emitter with a ``radiance`` texture; values
            ``>= 0`` and at most 1e12, not all 0). Every estimator samples a textured light's
            triangles in proportion to their texture's mean over them and points uniformly
            on each (as Mitsuba); radiosity takes each patch's mean.
        material:
            A :class:`~dualight.Diffuse`, :class:`~dualight.Mirror` or
            :class:`~dualight.Dielectric` (whose exterior is on the normals' side). ``None``
            means ``Diffuse(reflectance)``.
        name:
            Shown in error messages and used by exporters; ``"mesh<index>"`` by default.
        degenerate:
            Zero-area triangles are an error (``"raise"``, the default, naming the first one) or
            are removed with a warning (``"drop"``, for meshes loaded from files).
        normals:
            ``(V, 3)`` shading normals, one per vertex (normalised here; any length but 0):
            every estimator then shades the mesh smoothly, evaluating BSDFs around the
            interpolated normal (Phong's normal interpolation, Mitsuba's smooth shading), with
            the adjoint correction for light paths [Veach 1997, sec. 5.3]. ``None`` (the
            default) shades every triangle flat, like Mitsuba's ``face_normals``.
        uv:
            ``(V, 2)`` surface coordinates, one ``(u, v)`` per vertex, where textures are
            looked up (:mod:`dualight.textures`); ``None`` (the default) gives each triangle
            its barycentrics, as Mitsuba does for meshes without them.

        Returns
        -------
        int
            The mesh's index in :attr:`meshes`.

        Raises
        ------
        TypeError
            If ``material`` is not a Diffuse, Mirror or Dielectric.
        ValueError
            On malformed geometry, colours out of range, or both a non-default ``reflectance``
            and a ``material``.
        """
        name = name or f"mesh{len(self._meshes)}"
        if material is not None and not isinstance(material, Material):
            raise TypeError(
                f"{name}: material must be a dualight.Diffuse, Mirror or Dielectric (a "
                f"dualight.Material), got {type(material).__name__}"
            )
        if degenerate not in ("raise", "drop"):
            raise ValueError(f"degenerate must be 'raise' or 'drop', got {degenerate!r}")
        given = np.asarray(vertices).dtype
        if given.kind in "bcmMUSV":  # complex parts and datetimes were dropped or taken as numbers
            raise ValueError(f"{name}: vertices must be (V, 3) real numbers, got {given}")
        try:
            v = np.array(vertices, dtype=np.float64, copy=True)
        except (TypeError, ValueError):
            raise ValueError(f"{name}: vertices must be (V, 3) numbers") from None
        if v.ndim != 2 or v.shape[1] != 3 or v.shape[0] == 0:
            raise ValueError(f"{name}: vertices must have shape (V, 3) with V > 0, got {v.shape}")
        if not np.all(np.isfinite(v)):
            row = int(np.argwhere(~np.isfinite(v))[0][0])
            raise ValueError(f"{name}: vertex {row} is not finite (NaN or Inf): {v[row].tolist()}")
        if np.abs(v).max() > COORDINATE_LIMIT:
            raise ValueError(
                f"{name}: vertex coordinates beyond 1e12 cannot be rendered in float32 "
                "(distances, areas and pdfs leave its range)"
            )
        tris = _triangulate(faces, len(v), name)
        ns = None if normals is None else _unit_normals(normals, len(v), name)
        uvs = None if uv is None else _surface_uv(uv, len(v), name)
        rho = _colour(reflectance, f"{name}: reflectance", upper=1.0)
        if material is None:
            material = Diffuse(rho)
        elif rho != _DEFAULT_REFLECTANCE:
            raise ValueError(
                f"{name}: give either reflectance={rho} or material={material!r}, not both "
                "(a material carries its own reflectance)"
            )
        rho = material.rgb_reflectance
        emission_texture = emission if isinstance(emission, Texture) else None
        if emission_texture is not None:
            check_texture_range(emission_texture, f"{name}:", "emission", 0.0, EMISSION_LIMIT)
            if not max(emission_texture.mean) > 0.0:
                raise ValueError(f"{name}: the emission texture is black (every value 0)")
            emission = emission_texture.mean
        Le = _colour(emission, f"{name}: emission", upper=None)

        # Areas in float32, as the renderer will see the triangles.
        v32 = v.astype(np.float32)
        cr = np.cross(v32[tris[:, 1]] - v32[tris[:, 0]], v32[tris[:, 2]] - v32[tris[:, 0]])
        areas = 0.5 * np.linalg.norm(cr.astype(np.float64), axis=1)
        zero = ~(areas > 0.0)
        if np.any(zero):
            if degenerate == "raise":
                first = int(np.argmax(zero))
                raise ValueError(
                    f"{name}: {int(zero.sum())} zero-area triangle(s), the first is triangle "
                    f"{first} with vertices {tris[first].tolist()}; pass degenerate='drop' to "
                    "remove them"
                )
            warnings.warn(f"{name}: dropped {int(zero.sum())} zero-area triangle(s)", stacklevel=2)
            tris, areas = tris[~zero], areas[~zero]
            if len(tris) == 0:
                raise ValueError(f"{name}: every triangle has zero area")
        for arr in (v, tris, areas, ns, uvs):
            if arr is not None:
                arr.flags.writeable = False
        with self._lock:
            self._refuse_while_in_use("add_mesh")
            self._meshes.append(
                Mesh(v, tris, rho, Le, name, areas, material, ns, uvs, emission_texture)
            )
            self._compiled = None
            self._checked_facing = set()
            return len(self._meshes) - 1

    def _refuse_while_in_use(self, what: str) -> None:
        if self._users:
            raise RuntimeError(
                f"Scene.{what}: the scene is being rendered or solved (in another thread); "
                "a scene is frozen while a render or solve uses it, change it before or after"
            )

    @contextlib.contextmanager
    def _in_use(self) -> Iterator[None]:
        """Freeze the description while a render or solve reads it (add_mesh raises)."""
        with self._lock:
            self._users += 1
        try:
            yield
        finally:
            with self._lock:
                self._users -= 1

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """Axis-aligned bounding box ``(min, max)`` of all vertices."""
        if not self._meshes:
            raise ValueError("scene is empty: add a mesh first")
        lo = np.min([m.vertices.min(axis=0) for m in self._meshes], axis=0)
        hi = np.max([m.vertices.max(axis=0) for m in self._meshes], axis=0)
        return lo, hi

    def validate_for_rendering(self, camera: Camera | None = None) -> None:
        """Raise ``ValueError`` if the scene cannot be rendered (empty, no emitter, no camera);
        warn (``UserWarning``) of an emitter that faces nothing (see
        :meth:`emitters_facing_nothing`), once per scene and camera.

        ``camera`` stands in for a missing ``scene.camera``.
        """
        if not self._meshes:
            raise ValueError("scene is empty: add a mesh with Scene.add_mesh")
        if not self.has_emitters:
            raise ValueError(
                "scene has no emitter: give some mesh a positive emission or add a light "
                "with Scene.add_emitter"
            )
        if self._camera is None and camera is None:
            raise ValueError("scene has no camera: pass camera=dualight.Camera(...)")
        lo, hi = self.bounds()
        if float(np.max(hi - lo)) < SMALLEST_EXTENT:
            raise ValueError(
                f"scene is {float(np.max(hi - lo)):.3g} across: the float32 core cannot "
                f"resolve scenes smaller than {SMALLEST_EXTENT:g}; scale it up (radiance does "
                "not depend on scale)"
            )
        self._warn_emitters_facing_nothing(camera or self._camera)

    def emitters_facing_nothing(self, camera: Camera | None = None) -> list[str]:
        """The names of the emitting meshes whose emitting (front) side faces nothing: every
        vertex of the scene and the camera's origin lie on or behind the plane of each of
        their triangles (to 1e-5 of the scene's size), so their light leaves the scene
        unseen and unreflected (most often a light whose vertex order, and so its normal, is
        the wrong way round, facing out of a closed room). ``camera`` defaults to the scene's.
        :func:`dualight.render` warns of each with a ``UserWarning`` naming it."""
        if not self._meshes:
            return []
        points = np.concatenate([m.vertices for m in self._meshes])
        lo, hi = points.min(axis=0), points.max(axis=0)
        cam = camera or self._camera
        if cam is not None:  # a light the camera sees directly is not lost
            points = np.vstack([points, cam.origin])
            lo, hi = np.minimum(lo, cam.origin), np.maximum(hi, cam.origin)
        tolerance = 1e-5 * max(float(np.max(hi - lo)), 1e-30)
        return [
            m.name
            for m in self._meshes
            if m.is_emitter and not _faces_something(m, points, lo, hi, tolerance)
        ]

    def _warn_emitters_facing_nothing(self, camera: Camera | None) -> None:
        """Warn of each emitter facing nothing, once per description and camera origin."""
        key = None if camera is None else camera.origin
        if key in self._checked_facing:
            return
        self._checked_facing.add(key)
        for name in self.emitters_facing_nothing(camera):
            warnings.warn(
                f"emitter {name!r} faces nothing: every vertex of the scene and the camera are "
                "behind its emitting side (the right-hand-rule normal (v1 - v0) x (v2 - v0)), "
                "so its light leaves the scene; reverse its faces' vertex order to turn it round",
                UserWarning,
                stacklevel=4,
            )

    def _compile(self) -> _core.Scene:
        """The immutable compiled scene (cached until the description changes)."""
        if self._compiled is None:
            from dualight import _core

            positions, triangles, material_of = self.triangle_arrays()
            reflectance = np.array([m.reflectance for m in self._meshes], np.float32)
            emission = np.array([m.emission for m in self._meshes], np.float32)
            bsdfs = [m.material._core_bsdf() for m in self._meshes]
            self._compiled = _core.Scene(
                positions.astype(np.float32),
                triangles.astype(np.uint32),
                material_of.astype(np.uint32),
                reflectance,
                emission,
                bsdfs=bsdfs,
                normals=self._vertex_normals(),
                uvs=self._vertex_uvs(),
                textures=self._material_textures(),
                emitters=[e._core_emitter() for e in self._emitters] or None,
                emission_textures=self._emission_textures(),
                robust_intersections=self._robust_intersections,
            )
        return self._compiled

    def _vertex_normals(self) -> np.ndarray | None:
        """Shading normals of all vertices as float32 (zero on flat meshes), or None."""
        if all(m.normals is None for m in self._meshes):
            return None
        parts = [
            np.zeros((len(m.vertices), 3)) if m.normals is None else m.normals for m in self._meshes
        ]
        return np.concatenate(parts).astype(np.float32)

    def _vertex_uvs(self) -> np.ndarray | None:
        """Surface coordinates of all vertices as float32 (NaN on meshes without), or None."""
        if all(m.uv is None for m in self._meshes):
            return None
        parts = [
            np.full((len(m.vertices), 2), np.nan) if m.uv is None else m.uv for m in self._meshes
        ]
        return np.concatenate(parts).astype(np.float32)

    def _material_textures(self) -> list[list[tuple[str, Any]]] | None:
        """Per mesh, its material's ``(parameter, core texture)`` pairs, or None if none has any."""
        textures = [m.material._textures() for m in self._meshes]
        return textures if any(textures) else None

    def _emission_textures(self) -> list[Any] | None:
        """Per mesh, its core emission texture or None; None if no mesh has one."""
        if all(m.emission_texture is None for m in self._meshes):
            return None
        return [
            None if m.emission_texture is None else m.emission_texture._core_texture()
            for m in self._meshes
        ]

    def triangle_arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """All meshes as one triangle list, in the compiled scene's order: positions ``(V, 3)``,
        triangles ``(T, 3)`` and the mesh index of each triangle ``(T,)``."""
        if not self._meshes:
            raise ValueError("scene is empty: add a mesh with Scene.add_mesh")
        offsets = np.cumsum([0] + [len(m.vertices) for m in self._meshes[:-1]])
        positions = np.concatenate([m.vertices for m in self._meshes])
        triangles = np.concatenate(
            [m.triangles + off for m, off in zip(self._meshes, offsets, strict=True)]
        )
        mesh_index = np.concatenate(
            [np.full(len(m.triangles), i, np.int64) for i, m in enumerate(self._meshes)]
        )
        return positions, triangles, mesh_index

    def to_mitsuba(self, **kwargs: Any) -> dict[str, Any]:
        """A dict for ``mitsuba.load_dict`` describing this scene with matching conventions.

        Keywords are those of :func:`dualight.mitsuba.scene_dict` (``spp``, ``max_depth``,
        ``rr_depth``, ``integrator``, ...).
        """
        from dualight import mitsuba

        return mitsuba.scene_dict(self, **kwargs)

    def __repr__(self) -> str:
        return (
            f"Scene({len(self._meshes)} meshes, {self.triangle_count} triangles, "
            f"camera={self._camera})"
        )
