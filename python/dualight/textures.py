"""Textures: BSDF parameters that vary over a surface, with Mitsuba 3's semantics.

* :class:`Bitmap` -- an image (EXR, PNG, JPEG, ... through OpenImageIO, or an array) looked up
  at the surface's ``(u, v)``: Mitsuba's ``bitmap`` plugin.
* :class:`Checkerboard` -- two colours alternating over the unit square of ``(u, v)``:
  Mitsuba's ``checkerboard``.

A texture stands wherever a material takes a colour that may vary (``Diffuse(reflectance=...)``,
``Mirror(reflectance=...)``, ``Plastic(diffuse_reflectance=...)``, every
``specular_reflectance``) or a roughness (``RoughConductor`` and ``RoughDielectric``'s
``alpha``, ``alpha_u``, ``alpha_v``, which take the texture's luminance as Mitsuba does).
Surface coordinates come from the mesh (``Scene.add_mesh(..., uv=...)``, an OBJ's ``vt``, a
PLY's texture coordinates, Mitsuba's ``rectangle``); a mesh without them uses each triangle's
barycentrics, as Mitsuba does.

Conventions (Mitsuba 3's): image row 0 is at ``v = 0``, column 0 at ``u = 0``; 8-bit and 16-bit
images (PNG, JPEG) are sRGB-decoded to linear values when loaded unless ``raw``; bilinear
filtering interpolates between texel centres; ``to_uv`` maps ``(u, v)`` before the lookup.
Textures compare equal only to themselves.
"""

from __future__ import annotations

import functools
import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal

import numpy as np

__all__ = ["Bitmap", "Checkerboard", "Texture"]

WrapMode = Literal["repeat", "mirror", "clamp"]
FilterType = Literal["bilinear", "nearest"]
_IDENTITY = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0)


def _uv_matrix(value: Any, owner: str) -> tuple[float, ...]:
    """``to_uv`` as the 6 numbers of a 2x3 affine map: from None, a 2x3 or 3x3 matrix (2D
    homogeneous) or a 4x4 one (Mitsuba's XML transforms: rows and columns 0, 1 and 3)."""
    if value is None:
        return _IDENTITY
    try:
        m = np.array(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError(f"{owner} to_uv must be a 2x3, 3x3 or 4x4 matrix, got {value!r}") from None
    if m.shape == (4, 4):
        m = m[np.ix_([0, 1, 3], [0, 1, 3])]
    if m.shape == (3, 3):
        if not np.allclose(m[2], (0.0, 0.0, 1.0)):
            raise ValueError(f"{owner} to_uv must be affine (last row 0 0 1), got {m.tolist()}")
        m = m[:2]
    if m.shape != (2, 3):
        raise ValueError(f"{owner} to_uv must be a 2x3, 3x3 or 4x4 matrix, got shape {m.shape}")
    if not np.all(np.isfinite(m)) or np.abs(m).max() > 1e30:
        raise ValueError(f"{owner} to_uv must be finite, got {m.tolist()}")
    return tuple(float(x) for x in m.ravel())


class Texture:
    """Base class of :class:`Bitmap` and :class:`Checkerboard`."""

    __slots__ = ()
    to_uv: Any

    @property
    def mean(self) -> tuple[float, float, float]:
        """The mean RGB (of the texels, or of the checkerboard's two colours)."""
        return tuple(float(c) for c in self._core_texture().mean)  # type: ignore[return-value]

    @property
    def value_range(self) -> tuple[float, float]:
        """The smallest and largest value of any channel anywhere."""
        raise NotImplementedError

    def eval(self, uv: Any) -> np.ndarray:
        """RGB at each row ``(u, v)`` of an ``(N, 2)`` array: ``(N, 3)``, as renders see it."""
        return self._core_texture().eval(np.asarray(uv, dtype=np.float32))

    def eval_scalar(self, uv: Any) -> np.ndarray:
        """The value a roughness takes at each row ``(u, v)``: ``(N,)``."""
        return self._core_texture().eval_scalar(np.asarray(uv, dtype=np.float32))

    def _core_texture(self) -> Any:
        raise NotImplementedError

    def __getstate__(self) -> dict[str, Any]:
        # Picklable (render(executor=...) sends scenes to workers): the core texture is
        # rebuilt where it is needed.
        state = dict(self.__dict__)
        state.pop("_core", None)
        return state

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__dict__.update(state)
        texels = state.get("texels")
        if isinstance(texels, np.ndarray):
            texels.flags.writeable = False

    def _mitsuba_dict(self) -> dict[str, Any]:
        """The Mitsuba 3 texture as a plain dict: ``mitsuba.load_dict``'s form except that
        ``to_uv`` is the 6 numbers of the affine map and an array's texels come as ``texels``
        (``dualight.mitsuba`` and the XML writer turn those into Mitsuba objects or files)."""
        raise NotImplementedError

    def _to_uv_entry(self) -> dict[str, Any]:
        return {} if self.to_uv == _IDENTITY else {"to_uv": self.to_uv}


def _decode_srgb(x: np.ndarray) -> np.ndarray:
    from dualight.image import srgb_decode

    return srgb_decode(x.astype(np.float64))


@dataclass(frozen=True, eq=False)
class Bitmap(Texture):
    """An image texture, Mitsuba 3's ``bitmap``.

    Parameters
    ----------
    filename : str or os.PathLike, optional
        An image file OpenImageIO reads (EXR, HDR, PNG, JPEG, ...). Give it or ``data``.
    data : array_like, optional
        ``(height, width)`` or ``(height, width, 1 or 3)`` texels: floats are linear values,
        ``uint8`` ones are sRGB-encoded (decoded unless ``raw``), as Mitsuba's ``Bitmap``.
    raw : bool, optional
        Keep 8/16-bit values as they are stored (no sRGB decoding), for roughness maps.
    filter_type : {"bilinear", "nearest"}, optional
    wrap_mode : {"repeat", "mirror", "clamp"}, optional
    to_uv : matrix, optional
        A 2x3, 3x3 or 4x4 affine map applied to ``(u, v)`` first.

    Raises
    ------
    FileNotFoundError
        If ``filename`` does not exist.
    ValueError
        If neither or both of ``filename`` and ``data`` are given, the image is not 1 to 4
        channels, has non-finite values, or an option is unknown.
    """

    filename: str | os.PathLike[str] | None = None
    data: Any = field(default=None, repr=False)
    raw: bool = False
    filter_type: FilterType = "bilinear"
    wrap_mode: WrapMode = "repeat"
    to_uv: Any = None
    texels: np.ndarray = field(init=False, repr=False)

    def __post_init__(self) -> None:
        if (self.filename is None) == (self.data is None):
            raise ValueError("Bitmap: give either filename or data")
        if self.filter_type not in ("bilinear", "nearest"):
            raise ValueError(
                f"Bitmap filter_type must be 'bilinear' or 'nearest', got {self.filter_type!r}"
            )
        if self.wrap_mode not in ("repeat", "mirror", "clamp"):
            raise ValueError(
                f"Bitmap wrap_mode must be 'repeat', 'mirror' or 'clamp', got {self.wrap_mode!r}"
            )
        object.__setattr__(self, "raw", bool(self.raw))
        object.__setattr__(self, "to_uv", _uv_matrix(self.to_uv, "Bitmap"))
        if self.filename is not None:
            path = Path(self.filename).resolve()
            if not path.is_file():
                raise FileNotFoundError(f"no such image file: {str(path)!r}")
            object.__setattr__(self, "filename", path)
            texels = self._read(path)
        else:
            texels = self._from_data(self.data)
        texels = np.ascontiguousarray(texels, dtype=np.float32)
        if not np.all(np.isfinite(texels)):
            raise ValueError(f"Bitmap {self._label()}: texels must be finite")
        texels.flags.writeable = False
        object.__setattr__(self, "texels", texels)

    def _label(self) -> str:
        return repr(str(self.filename)) if self.filename is not None else "data"

    def _read(self, path: Path) -> np.ndarray:
        from dualight import _core

        try:
            pixels, _, low_dynamic_range = _core.read_image(str(path))
        except ValueError as exc:
            raise ValueError(f"Bitmap: cannot read {str(path)!r}: {exc}") from None
        texels = self._channels(np.asarray(pixels))
        return _decode_srgb(texels) if low_dynamic_range and not self.raw else texels

    def _from_data(self, data: Any) -> np.ndarray:
        arr = np.asarray(data)
        if arr.dtype.kind not in "uif":
            raise ValueError(f"Bitmap data must be numbers, got {arr.dtype}")
        if arr.ndim == 2:
            arr = arr[:, :, None]
        if arr.ndim != 3 or arr.shape[0] < 1 or arr.shape[1] < 1:
            raise ValueError(f"Bitmap data must be (height, width[, channels]), got {arr.shape}")
        texels = self._channels(arr.astype(np.float64))
        if arr.dtype == np.uint8:
            texels = texels / 255.0
            return texels if self.raw else _decode_srgb(texels)
        return texels

    def _channels(self, arr: np.ndarray) -> np.ndarray:
        """1 (grey) or 3 (RGB) channels: alpha is dropped, as Mitsuba's RGB lookups do."""
        n = arr.shape[2]
        if n in (1, 3):
            return arr
        if n == 2:
            return arr[:, :, :1]
        if n == 4:
            return arr[:, :, :3]
        raise ValueError(f"Bitmap {self._label()}: {n} channels (1 to 4 are supported)")

    @property
    def value_range(self) -> tuple[float, float]:
        """The smallest and largest texel value of any channel."""
        return float(self.texels.min()), float(self.texels.max())

    @functools.cached_property
    def _core(self) -> Any:
        from dualight import _core

        return _core.Texture.bitmap(
            self.texels,
            wrap_mode=self.wrap_mode,
            filter_type=self.filter_type,
            to_uv=self.to_uv,
        )

    def _core_texture(self) -> Any:
        return self._core

    def _mitsuba_dict(self) -> dict[str, Any]:
        options = {"filter_type": self.filter_type, "wrap_mode": self.wrap_mode}
        if self.filename is not None:
            source: dict[str, Any] = {"filename": str(self.filename), "raw": self.raw}
        else:  # the linear texels dualight uses: float32, which Mitsuba takes as linear
            source = {"texels": self.texels, "raw": True}
        return {"type": "bitmap", **source, **options, **self._to_uv_entry()}


@dataclass(frozen=True, eq=False)
class Checkerboard(Texture):
    """Two colours in a checkerboard over ``(u, v)``, Mitsuba 3's ``checkerboard``:
    ``color0`` where the fractional parts of ``u`` and ``v`` are both below or both above 1/2,
    ``color1`` elsewhere (2 x 2 squares per unit of ``(u, v)``).

    Parameters
    ----------
    color0, color1 : float or 3 floats, optional
        Linear RGB, finite and ``>= 0`` (Mitsuba's defaults 0.4 and 0.2).
    to_uv : matrix, optional
        As for :class:`Bitmap`.
    """

    color0: Any = 0.4
    color1: Any = 0.2
    to_uv: Any = None

    def __post_init__(self) -> None:
        for name in ("color0", "color1"):
            given = getattr(self, name)
            try:
                c = np.broadcast_to(np.asarray(given, dtype=np.float64), (3,))
            except (TypeError, ValueError):
                raise ValueError(
                    f"Checkerboard {name} must be a number or 3 numbers, got {given!r}"
                ) from None
            if not np.all(np.isfinite(c)) or np.any(c < 0.0) or np.abs(c).max() > 1e30:
                raise ValueError(f"Checkerboard {name} must be finite and >= 0, got {c.tolist()}")
            object.__setattr__(self, name, tuple(float(x) for x in c))
        object.__setattr__(self, "to_uv", _uv_matrix(self.to_uv, "Checkerboard"))

    @property
    def value_range(self) -> tuple[float, float]:
        """The smallest and largest channel of the two colours."""
        values = self.color0 + self.color1
        return min(values), max(values)

    @functools.cached_property
    def _core(self) -> Any:
        from dualight import _core

        return _core.Texture.checkerboard(self.color0, self.color1, to_uv=self.to_uv)

    def _core_texture(self) -> Any:
        return self._core

    def _mitsuba_dict(self) -> dict[str, Any]:
        colours = {
            name: {"type": "rgb", "value": list(getattr(self, name))}
            for name in ("color0", "color1")
        }
        return {"type": "checkerboard", **colours, **self._to_uv_entry()}


def check_texture_range(texture: Texture, owner: str, name: str, low: float, high: float) -> None:
    """A ValueError naming the parameter if the texture's values leave ``[low, high]``."""
    lo, hi = texture.value_range
    if not (lo >= low and hi <= high and math.isfinite(hi)):
        raise ValueError(
            f"{owner} {name}: the texture's values must lie in [{low:g}, {high:g}], "
            f"got [{lo:g}, {hi:g}]"
        )


def uv_matrix4(to_uv: tuple[float, ...]) -> list[list[float]]:
    """A 2x3 affine map of (u, v) as the 4x4 matrix Mitsuba's ``to_uv`` transforms hold."""
    a, b, c, d, e, f = to_uv
    return [[a, b, 0.0, c], [d, e, 0.0, f], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]]
