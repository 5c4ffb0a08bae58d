"""A subset of Mitsuba 3's XML scene format: :func:`load_mitsuba_xml` and
:func:`read_mitsuba_settings` (parsed with the standard library's ``xml.etree``; meshes read with
trimesh). See :func:`load_mitsuba_xml` for what is supported."""

from __future__ import annotations

import warnings
import xml.etree.ElementTree as ET
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from dualight.io._common import PathLike, _existing_file
from dualight.io._mitsuba_context import _attrs, _Context, _TopLevel
from dualight.io._mitsuba_emitters import _emitter
from dualight.io._mitsuba_materials import _bsdf, _texture
from dualight.io._mitsuba_sensor import _integrator, _sensor
from dualight.io._mitsuba_shapes import _add_meshes, _shape, _shapegroup
from dualight.io._mitsuba_survey import ROBUST_INTERSECTIONS, _Survey
from dualight.io._mitsuba_values import _boolean
from dualight.scene import Scene

__all__ = ["load_mitsuba_xml", "read_mitsuba_settings"]

# Deeper nesting than any scene needs (scene > shape > bsdf > twosided's bsdf > texture > ...
# is 6) is refused before the elements are read recursively.
_MAX_DEPTH = 64


def _check_depth(ctx: _Context, root: ET.Element) -> None:
    """Refuse elements nested deeper than ``_MAX_DEPTH``, naming the deepest one's path."""
    stack = [(root, 1)]
    while stack:
        element, depth = stack.pop()
        if depth > _MAX_DEPTH:
            raise ctx.error(
                element,
                f"elements are nested more than {_MAX_DEPTH} deep; no Mitsuba scene needs that",
            )
        stack.extend((child, depth + 1) for child in element)


# --------------------------------------------------------------------------------------------
# Mitsuba 3 XML: includes


_MAX_INCLUDES = 16  # nested <include> depth


def _read_root(ctx: _Context, path: Path) -> ET.Element:
    """A file's ``<scene>`` element, refusing malformed XML and absurd nesting."""
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as exc:
        raise ValueError(f"{str(path)!r} is not well-formed XML: {exc}") from None
    if root.tag != "scene":
        raise ValueError(
            f"{str(path)!r}: <{root.tag}{_attrs(root)}>: the root element must be <scene>"
        )
    _check_depth(ctx, root)
    return root


def _expand_includes(ctx: _Context, root: ET.Element, path: Path, chain: tuple[Path, ...]) -> None:
    """Replace each ``<include filename>`` in ``root`` (read from ``path``) by the children of the
    included file's ``<scene>``, included files first expanded the same way. ``filename`` is
    relative to ``path``'s folder, else to the scene's (where Mitsuba resolves it); the files
    they name are, as in Mitsuba, relative to the scene's folder. ``chain`` holds the including
    files, to refuse cycles."""
    for parent in [e for e in root.iter() if any(c.tag == "include" for c in e)]:
        children: list[ET.Element] = []
        for child in parent:
            if child.tag != "include":
                children.append(child)
                continue
            name = ctx.attr(child, "filename")
            found = path.parent / name
            if not found.is_file() and (ctx.folder / name).is_file():
                found = ctx.folder / name
            if not found.is_file():
                raise FileNotFoundError(
                    f"no such included XML file: {str(found)!r} (named by <include> in "
                    f"{str(path)!r})"
                )
            if found.resolve() in chain:
                cycle = " -> ".join(repr(p.name) for p in (*chain, found.resolve()))
                raise ctx.error(child, f"include cycle: {cycle}")
            if len(chain) > _MAX_INCLUDES:
                raise ctx.error(child, f"includes are nested more than {_MAX_INCLUDES} deep")
            included = _read_root(ctx, found)
            ctx.origins.update((id(e), found) for e in included.iter())
            _expand_includes(ctx, included, found, (*chain, found.resolve()))
            children.extend(included)
        parent[:] = children


class _Reader:
    """Reads a surveyed scene's top-level elements (through a _TopLevel, so that a reference
    may come before what it names) into a scene and its settings."""

    def __init__(self, ctx: _Context, build: bool, sphere_subdivisions: int, robust: bool) -> None:
        self.ctx, self.build, self.sphere_subdivisions = ctx, build, sphere_subdivisions
        self.scene = Scene(robust_intersections=robust)
        self.settings: dict[str, Any] = {}
        self.shapes = 0

    def read(self, element: ET.Element, where: str) -> Any:
        """The object a top-level element defines (for references), after adding what it
        adds to the scene or settings."""
        ctx, tag = self.ctx, element.tag
        if tag == "integrator":
            _integrator(ctx, element, self.settings)
        elif tag == "sensor":
            camera = _sensor(ctx, element, self.settings)
            if self.build:
                if self.scene.camera is not None:
                    raise ctx.error(element, "only one sensor is supported")
                self.scene.camera = camera
        elif not self.build:
            return None
        elif tag == "bsdf":
            material = _bsdf(ctx, element)
            if element.get("id") is None:
                raise ctx.error(element, "a top-level BSDF needs an id to be referenced")
            return material
        elif tag == "texture":
            if element.get("id") is None:
                raise ctx.error(element, "a top-level texture needs an id to be referenced")
            return _texture(ctx, element)
        elif tag == "shape":
            meshes = _shape(ctx, element, self.shapes, self.sphere_subdivisions)
            _add_meshes(ctx, element, self.scene, meshes)
            self.shapes += 1
        elif tag == "shapegroup":
            return _shapegroup(ctx, element, self.sphere_subdivisions)
        elif tag == "emitter":
            self.scene.add_emitter(_emitter(ctx, element))
        return None


def _parse(
    path: PathLike,
    params: Mapping[str, Any] | None,
    build: bool,
    sphere_subdivisions: int,
    strict: bool = True,
) -> tuple[Scene, dict[str, Any]]:
    xml_path = _existing_file(path, "Mitsuba XML")
    ctx = _Context(xml_path, params or {})
    root = _read_root(ctx, xml_path)
    version = root.get("version", "3.0.0")
    if version.split(".")[0] not in ("2", "3"):
        raise ctx.error(root, f"scene version {version!r}: only Mitsuba 2 and 3 files are read")
    _expand_includes(ctx, root, xml_path, (xml_path.resolve(),))
    _check_depth(ctx, root)
    survey = _Survey(ctx, strict, build)
    survey.scene(root)
    survey.report()
    robust = [e for e in root if e.tag == "boolean" and e.get("name") == ROBUST_INTERSECTIONS]
    robust_last = _boolean(ctx, robust[-1], True) if robust else True
    reader = _Reader(ctx, build, sphere_subdivisions, robust_last)
    ctx.top = _TopLevel(ctx, root, reader.read)
    for element in list(root):
        ctx.top.visit(element)
    return reader.scene, reader.settings


def load_mitsuba_xml(
    path: PathLike,
    *,
    params: Mapping[str, Any] | None = None,
    sphere_subdivisions: int = 4,
    strict: bool = True,
) -> Scene:
    """Load a scene in Mitsuba 3's XML format (a subset of it) with its camera.

    Supported:

    * ``<default name value>`` and ``$name`` substitution in attribute values (``params``
      overrides defaults, like ``mitsuba.load_file(path, **params)``);
    * ``<include filename>``: the included scene's children are read in its place
      (``filename`` relative to the including file, else to the scene's folder; the files the
      included one names are relative to the scene's folder, as in Mitsuba; cycles and more
      than 16 nested includes are refused);
    * shapes ``obj``, ``ply`` (``filename`` relative to the XML file, ``face_normals``; the
      file's vertex normals and texture coordinates: an OBJ's ``vn``/``vt``, one vertex per
      distinct ``v/vt/vn`` triple, a PLY's ``nx ny nz`` and ``u v``, ``s t``, ``texture_u
      texture_v`` or ``texture_s texture_t``, ASCII or binary), ``rectangle`` (``[-1, 1]^2``
      at ``z = 0``, normal ``+z``), ``disk`` (radius 1 at ``z = 0``, normal ``+z``: a fan of
      ``8 * 2**sphere_subdivisions`` triangles of the disk's area), ``cube``
      (``[-1, 1]^3``), ``sphere`` (``center``, ``radius``; tessellated as an icosphere of
      ``sphere_subdivisions``), each with ``flip_normals`` and a ``to_world`` ``<transform>``
      of ``translate``, ``scale``, ``rotate``, ``matrix`` and ``lookat`` operations;
    * ``<shapegroup id>`` of shapes and ``<shape type="instance">`` with a ``<ref id>`` to
      one and a ``to_world``: flattened, each instance adding copies of the group's meshes
      (materials and area emitters kept) moved by its ``to_world``, normals as normals;
    * ``<ref id>`` to a top-level BSDF, texture or shapegroup defined anywhere in the scene,
      before or after the reference or in an included file (Mitsuba 3 reads objects in the
      order their references need; so does this loader, each ``$name`` with the ``<default>``
      values in effect where the object is defined); an id defined nowhere and a cycle of
      references are refused;
    * BSDFs, inline or top-level with an ``id`` and referenced by ``<ref id>``: ``diffuse``
      (RGB ``reflectance``), ``twosided`` around any reflector, ``conductor`` (Mitsuba's
      named metals or ``eta``/``k``; ``material="none"``, a perfect mirror, by default),
      ``roughconductor``, ``dielectric``, ``thindielectric``, ``roughdielectric``,
      ``plastic`` and ``roughplastic`` with Mitsuba 3's parameters (``int_ior``/``ext_ior``
      as numbers or Mitsuba's IOR names, defaults as in Mitsuba); see
      :mod:`dualight.materials`;
    * ``<emitter type="area">`` inside a shape with an RGB ``radiance`` or a ``bitmap`` or
      ``checkerboard`` texture of it (one-sided, on the normals' side); stand-alone
      ``point`` (``position`` or ``to_world``) and ``spot`` (``to_world``, its +z the beam's
      axis; ``cutoff_angle``, ``beam_width``) emitters with an RGB or float ``intensity``
      (:mod:`dualight.emitters`);
    * ``<sensor type="perspective">`` with ``fov``, ``fov_axis`` (x, y, diagonal, smaller,
      larger; converted to dualight's fov along x), ``to_world`` (rotation and translation);
      its ``<film type="hdrfilm">`` ``width`` and ``height``; its sampler's ``sample_count``
      and the ``<integrator>`` settings are read by :func:`read_mitsuba_settings`;
    * the scene's ``<boolean name="embree_use_robust_intersections">``, as
      ``Scene(robust_intersections=...)``; without it, dualight's default (``True``, where
      Mitsuba's is ``False``: see :class:`dualight.Scene`).

    Approximations, each with a ``UserWarning``: ``sample_visible=false`` on a rough BSDF is
    ignored (dualight samples visible normals: the same BSDF, other noise); a pixel filter
    other than ``box`` (Mitsuba's default is a Gaussian) is replaced by dualight's box filter.
    As in Mitsuba, ``obj``/``ply`` meshes without ``face_normals`` are shaded smoothly, by the
    file's vertex normals or by normals computed as Mitsuba does (each face's normal weighted
    by its angle at the vertex); a ``sphere`` is an icosphere shaded by the sphere's own
    normals. Without a warning: dualight's ``diffuse`` is two-sided, so a one-sided
    Mitsuba ``diffuse`` differs only where light reaches the back of a surface (conductors and
    plastics are one-sided unless in ``twosided``, as in Mitsuba); a shape without a BSDF gets
    Mitsuba's default: diffuse 0.5, or black if it emits.

    Everything else is refused: with ``strict`` (the default) every unsupported element of
    the file (other plugin types of shapes, BSDFs, textures, emitters, sensors and films,
    unknown elements and properties) is listed in one ``ValueError``, each with its path in
    the file (``scene/shape[3]/bsdf[1]``), type and id. With ``strict=False`` the same list
    is given in one ``UserWarning`` and each is replaced by the nearest supported element:

    * ``principled`` by a GGX ``roughplastic`` over its ``base_color`` (``alpha =
      roughness**2`` as Mitsuba's principled maps it, its ``eta`` or the IOR Mitsuba derives
      from ``specular``), or if ``metallic`` is 1 by a ``roughconductor`` tinted by
      ``base_color``; its other lobes are dropped;
    * ``bumpmap``, ``normalmap``, ``mask`` and ``blendbsdf`` by the (first) BSDF they hold;
      other BSDFs by a ``diffuse`` of their ``reflectance``, ``base_color`` or
      ``diffuse_reflectance``, else 0.5;
    * other textures by the mean of their colour properties, else 0.5;
    * a ``thinlens`` sensor by a pinhole ``perspective`` one, another film by an
      ``hdrfilm`` of its size, a pixel filter other than ``box`` by ``box`` (noted in the same
      warning rather than apart);
    * other shapes (``serialized``, ``cylinder``, ...), emitters, sensors and elements are
      skipped, and unknown properties ignored.

    Values the core cannot hold (colours out of range, non-finite numbers, spectra, ...)
    raise a ``ValueError`` naming the element and the file in either mode; the integrator
    and sampler are not read here (see :func:`read_mitsuba_settings`).

    Parameters
    ----------
    path : str or pathlib.Path
        The XML file.
    params : mapping, optional
        Values for ``$name`` references, overriding ``<default>`` elements.
    sphere_subdivisions : int, optional
        Icosphere subdivisions of ``sphere`` shapes (``20 * 4**n`` triangles); a ``disk`` has
        ``8 * 2**n``.
    strict : bool, optional
        Refuse unsupported elements, all listed in one error (the default), or substitute or
        skip them with one ``UserWarning`` that lists them.

    Returns
    -------
    dualight.Scene
        The scene, with a camera if the file has a sensor.

    Raises
    ------
    FileNotFoundError
        If the XML file or a mesh file it names does not exist.
    ValueError
        On malformed XML, unsupported elements, bad or non-finite numbers.

    Examples
    --------
    >>> scene = dualight.load_mitsuba_xml("cbox.xml", params={"radiance": 10})
    >>> depth = dualight.read_mitsuba_settings("cbox.xml", keys=("max_depth", "rr_depth"))
    >>> image = dualight.render(scene, spp=256, **depth)
    """
    scene, _ = _parse(path, params, True, sphere_subdivisions, strict)
    return scene


# Mitsuba integrators and samplers and the dualight method or sampler that computes the same
# image (bdpt, pssmlt and mlt are Mitsuba 0.6's names).
_INTEGRATORS = {
    "path": "path",
    "ptracer": "light",
    "bdpt": "bdpt",
    "pssmlt": "pssmlt",
    "mlt": "mlt",
}
_SAMPLERS = ("independent", "sobol")
# Integrator properties dualight does as Mitsuba does with these values: left out silently.
_SAME_AS_MITSUBA = {"hide_emitters": False}


def _render_keywords(path: PathLike, settings: Mapping[str, Any]) -> dict[str, Any]:
    """The keywords of :func:`dualight.render` that the file's settings amount to; what has
    no keyword is left out, with a ``UserWarning`` unless dualight does it anyway."""
    out: dict[str, Any] = {}
    dropped = []
    for key, value in settings.items():
        if key == "integrator":
            if value in _INTEGRATORS:
                out["method"] = _INTEGRATORS[value]
            else:
                dropped.append(f"integrator {value!r}")
        elif key in ("spp", "max_depth", "rr_depth"):
            out[key] = value
        elif key == "_seed":
            out["seed"] = value
        elif key == "_sampler":
            if value in _SAMPLERS:
                out["sampler"] = value
            else:
                dropped.append(f"sampler {value!r}")
        elif key not in _SAME_AS_MITSUBA or _SAME_AS_MITSUBA[key] != value:
            dropped.append(f"{key}={value!r}")
    if dropped:
        warnings.warn(
            f"{str(path)!r}: no dualight.render keyword for {', '.join(dropped)}; left out "
            "(read_mitsuba_settings(..., raw=True) returns the file's settings as given)",
            UserWarning,
            stacklevel=3,
        )
    return out


def read_mitsuba_settings(
    path: PathLike,
    *,
    params: Mapping[str, Any] | None = None,
    keys: tuple[str, ...] | None = None,
    raw: bool = False,
    strict: bool = True,
) -> dict[str, Any]:
    """The render settings a Mitsuba 3 XML file asks for, as keywords of
    :func:`dualight.render`, so that ``render(scene, **read_mitsuba_settings(path))`` renders
    what ``mitsuba.render(mitsuba.load_file(path))`` would.

    Parameters
    ----------
    path : str or pathlib.Path
        The XML file.
    params : mapping, optional
        As in :func:`load_mitsuba_xml`.
    keys : tuple of str, optional
        Return only these keys (those the file gives).
    raw : bool, optional
        Return the file's settings as given (the integrator's type and properties, the
        sampler's ``sample_count`` as ``spp``), not render's keywords.
    strict : bool, optional
        As in :func:`load_mitsuba_xml`, for the sensor, its film and sampler (the only
        elements read here).

    Returns
    -------
    dict
        Of those the file gives: ``method`` (from the integrator's type: ``path`` is
        ``"path"``, ``ptracer`` is ``"light"``; Mitsuba 0.6's ``bdpt``, ``pssmlt`` and
        ``mlt`` keep their names), ``spp`` (the sampler's ``sample_count``), ``max_depth``
        and ``rr_depth`` (the integrator's), ``seed`` (the sampler's) and ``sampler``
        (``independent`` or ``sobol``). Settings without a render keyword (another
        integrator or sampler, ``hide_emitters=True``, ...) are left out with a
        ``UserWarning``; those dualight does anyway (``hide_emitters=False``) silently.
        With ``raw=True``: ``integrator`` (its type), the integrator's properties as given
        and ``spp``.
    """
    _, settings = _parse(path, params, False, 0, strict)
    if raw:
        settings = {k: v for k, v in settings.items() if not k.startswith("_")}
    else:
        settings = _render_keywords(path, settings)
    if keys is not None:
        settings = {k: v for k, v in settings.items() if k in keys}
    return settings
