"""Linear RGB images: numpy views, file I/O through OpenImageIO, and display in Jupyter."""

from __future__ import annotations

import json
import numbers
import os
import tempfile
from pathlib import Path
from typing import Any

import numpy as np
from numpy.lib.mixins import NDArrayOperatorsMixin

_LDR_SUFFIXES = {".png", ".jpg", ".jpeg", ".bmp", ".tga", ".gif", ".webp"}
_META_PREFIX = "dualight:"


def srgb_encode(linear: np.ndarray) -> np.ndarray:
    """The sRGB transfer function (IEC 61966-2-1) on values clipped to [0, 1]."""
    x = np.clip(linear, 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1.0 / 2.4) - 0.055)


def srgb_decode(encoded: np.ndarray) -> np.ndarray:
    """Inverse of :func:`srgb_encode`."""
    x = np.clip(encoded, 0.0, 1.0)
    return np.where(x <= 0.04045, x / 12.92, np.power((x + 0.055) / 1.055, 2.4))


# Exposures in stops that the tone mapping can apply without overflow: 2**256 times float32's
# largest value stays far inside float64's range.
_MAX_STOPS = 256.0


def _exposure(value: Any) -> float:
    """``value`` as an exposure in stops: a real number (numpy's too, not a bool), finite and
    within +-_MAX_STOPS (exposure=nan was accepted, 1e6 gave an OverflowError)."""
    if isinstance(value, bool | np.bool_) or not isinstance(value, numbers.Real):
        raise TypeError(f"exposure must be a number of stops, got {value!r}")
    stops = float(value)
    if not abs(stops) <= _MAX_STOPS:
        raise ValueError(
            f"exposure must be a finite number of stops within +-{_MAX_STOPS:g}, got {value!r}"
        )
    return stops


def _json(value: Any) -> Any:
    """numpy values in the stats as JSON (numbers and lists); anything else is a TypeError."""
    if isinstance(value, np.generic | np.ndarray):
        return value.tolist()
    raise TypeError(f"cannot save a {type(value).__name__} in the image's stats as JSON")


class Image(NDArrayOperatorsMixin):
    """An H x W x 3 float32 linear RGB image with render statistics.

    ``np.asarray(image)`` returns the pixel array itself (no copy). ``image.variance``, when
    the estimator provides it, holds the variance of each pixel's mean estimate (same shape),
    which the statistical tests in :mod:`dualight.metrics` use.

    An image computes as its pixel array does: ``image1 - image2``, ``image * 2``,
    ``image[10:20]``, ``image[y, x]``, ``image > 1``, ``np.mean(image)``, ``np.sqrt(image)``
    and every other numpy function or ufunc. Arithmetic, comparisons and indexing return
    plain numpy arrays (indexing a view of the pixels, as numpy's basic slicing does), not
    Images: an Image's ``stats``, ``variance`` and ``strategies`` describe one render, and a
    difference, a scaled copy or a crop is not that render (the variance of a difference is
    not either image's, and a crop need not be H x W x 3). Wrap a result in ``Image(...)`` to
    save or show it. In-place arithmetic (``image *= 2``) changes the pixels and keeps the
    Image and its stats as they were. As with arrays, ``==`` compares pixel by pixel, so
    Images are not hashable.
    """

    def __array_ufunc__(self, ufunc: Any, method: str, *inputs: Any, **kwargs: Any) -> Any:
        # numpy's protocol behind the operators of NDArrayOperatorsMixin: compute on the
        # pixel arrays and return plain arrays, or the Images given as ``out``.
        args = [x._pixels if isinstance(x, Image) else x for x in inputs]
        out = kwargs.get("out")
        if out is not None:
            kwargs["out"] = tuple(x._pixels if isinstance(x, Image) else x for x in out)
        result = getattr(ufunc, method)(*args, **kwargs)
        if out is not None and any(isinstance(x, Image) for x in out):
            return out[0] if len(out) == 1 else tuple(out)
        return result

    def __getitem__(self, key: Any) -> Any:
        return self._pixels[key]

    def __init__(
        self,
        pixels: Any,
        *,
        variance: np.ndarray | None = None,
        stats: dict[str, Any] | None = None,
    ) -> None:
        arr = np.asarray(pixels)
        if arr.ndim == 2:
            arr = np.repeat(arr[:, :, None], 3, axis=2)
        if arr.ndim != 3 or arr.shape[2] != 3:
            raise ValueError(f"image pixels must be H x W x 3, got shape {arr.shape}")
        if arr.dtype != np.float32:
            arr = arr.astype(np.float32)
        self._pixels = arr
        if variance is not None:
            variance = np.asarray(variance, dtype=np.float32)
            if variance.shape != arr.shape:
                raise ValueError(f"variance shape {variance.shape} differs from {arr.shape}")
        self.variance = variance
        self.stats: dict[str, Any] = dict(stats or {})
        # BDPT's per-strategy images, keyed by (s, t), when asked for.
        self.strategies: dict[tuple[int, int], np.ndarray] = {}

    # numpy interoperability -------------------------------------------------------------
    def __array__(self, dtype: Any = None, copy: bool | None = None) -> np.ndarray:
        if copy:
            return np.array(self._pixels, dtype=dtype, copy=True)
        if dtype is not None and np.dtype(dtype) != self._pixels.dtype:
            if copy is False:
                raise ValueError("cannot convert the image's float32 pixels without a copy")
            return self._pixels.astype(dtype)
        return self._pixels

    @property
    def pixels(self) -> np.ndarray:
        """The H x W x 3 float32 array (not a copy)."""
        return self._pixels

    @property
    def shape(self) -> tuple[int, int, int]:
        """``(height, width, 3)``."""
        return self._pixels.shape  # type: ignore[return-value]

    @property
    def dtype(self) -> np.dtype:
        """``float32``, the pixels' type."""
        return self._pixels.dtype

    @property
    def ndim(self) -> int:
        """3, as the pixel array's."""
        return self._pixels.ndim

    @property
    def width(self) -> int:
        """Width in pixels."""
        return self._pixels.shape[1]

    @property
    def height(self) -> int:
        """Height in pixels."""
        return self._pixels.shape[0]

    def luminance(self) -> np.ndarray:
        """Rec. 709 luminance, H x W."""
        return self._pixels @ np.array([0.2126, 0.7152, 0.0722], dtype=np.float32)

    def tonemap(self, exposure: float = 0.0) -> np.ndarray:
        """8-bit sRGB (H x W x 3 uint8) after scaling by ``2**exposure`` and clipping."""
        encoded = srgb_encode(self._pixels.astype(np.float64) * 2.0 ** _exposure(exposure))
        return np.round(encoded * 255.0).astype(np.uint8)

    # files ------------------------------------------------------------------------------
    def save(self, path: str | os.PathLike[str], *, exposure: float = 0.0) -> Path:
        """Write the image; the format follows the suffix (``.exr``, ``.hdr``, ``.png``, ...).

        EXR keeps 32-bit floats and the stats as ``dualight:*`` string attributes. 8-bit
        formats are tone mapped: scaled by ``2**exposure``, clipped, sRGB encoded.
        """
        path = Path(path)
        if "\0" in str(path):  # the core's C string would end there: another file
            raise ValueError(f"image path contains a NUL byte: {str(path)!r}")
        exposure = _exposure(exposure)
        if not path.parent.exists():
            raise FileNotFoundError(f"directory does not exist: {path.parent}")
        from dualight import _core

        metadata = {_META_PREFIX + k: json.dumps(v, default=_json) for k, v in self.stats.items()}
        if path.suffix.lower() in _LDR_SUFFIXES:
            metadata[_META_PREFIX + "exposure"] = json.dumps(exposure, default=_json)
            data = self.tonemap(exposure).astype(np.float32) / 255.0
        else:
            data = self._pixels
        _core.write_image(str(path), np.ascontiguousarray(data), metadata)
        return path

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> Image:
        """Read an image written by :meth:`save` or any file OpenImageIO reads.

        8-bit files are sRGB-decoded back to linear values (and divided by the exposure they
        were saved with, when recorded). Stats saved as metadata come back in ``.stats``.
        """
        path = Path(path)
        if not path.is_file():
            raise FileNotFoundError(f"no such image file: {path}")
        from dualight import _core

        pixels, metadata, low_dynamic_range = _core.read_image(str(path))
        stats: dict[str, Any] = {}
        for key, value in metadata.items():
            if key.startswith(_META_PREFIX):
                try:
                    stats[key[len(_META_PREFIX) :]] = json.loads(value)
                except json.JSONDecodeError:
                    stats[key[len(_META_PREFIX) :]] = value
        channels = pixels.shape[2]
        if channels == 2:
            raise ValueError(f"{path}: cannot read a {channels}-channel image as RGB")
        if low_dynamic_range:
            # In place and a block of rows at a time: decoding the whole image in float64 took
            # about 12 times the decoded image's memory (2.2 GB for a 4000 x 4000 PNG).
            try:
                exposure = _exposure(stats.pop("exposure", 0.0))
            except (TypeError, ValueError) as exc:
                raise ValueError(f"{path}: its recorded exposure is not usable: {exc}") from None
            rows = max(1, (1 << 18) // max(1, pixels.shape[1] * channels))
            for start in range(0, pixels.shape[0], rows):
                block = pixels[start : start + rows]
                block[...] = srgb_decode(block.astype(np.float64)) / 2.0**exposure
        if channels == 1:
            pixels = np.repeat(pixels, 3, axis=2)
        elif channels > 3:
            pixels = np.ascontiguousarray(pixels[:, :, :3])
        return cls(pixels, stats=stats)

    # display ----------------------------------------------------------------------------
    def _repr_png_(self) -> bytes:
        with tempfile.TemporaryDirectory() as tmp:
            path = Path(tmp) / "image.png"
            Image(self._pixels).save(path)
            return path.read_bytes()

    def __repr__(self) -> str:
        keys = ", ".join(f"{k}={self.stats[k]!r}" for k in ("method", "spp") if k in self.stats)
        return f"Image({self.width}x{self.height}{', ' + keys if keys else ''})"
