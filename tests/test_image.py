"""Images: numpy without copies, and file round trips through OpenImageIO."""

from __future__ import annotations

import numpy as np
import pytest

import dualight


@pytest.fixture
def image(rng) -> dualight.Image:
    pixels = rng.uniform(0.0, 4.0, size=(12, 20, 3)).astype(np.float32)
    return dualight.Image(pixels, stats={"method": "path", "spp": 16, "seed": 3, "seconds": 0.25})


def test_asarray_is_not_a_copy(image) -> None:
    arr = np.asarray(image)
    assert arr is image.pixels and arr.dtype == np.float32 and arr.shape == (12, 20, 3)
    assert np.shares_memory(np.asarray(image), image.pixels)
    assert not np.shares_memory(np.array(image, copy=True), image.pixels)


def test_exr_round_trip_is_exact_with_metadata(image, tmp_path) -> None:
    path = image.save(tmp_path / "a.exr")
    loaded = dualight.Image.load(path)
    assert np.array_equal(np.asarray(loaded), np.asarray(image))
    assert loaded.stats == image.stats


def test_hdr_round_trip_within_rgbe_precision(image, tmp_path) -> None:
    loaded = dualight.Image.load(image.save(tmp_path / "a.hdr"))
    # RGBE shares one exponent per pixel: 8 mantissa bits relative to the largest channel.
    bound = np.asarray(image).max(axis=2, keepdims=True) / 128.0
    assert np.all(np.abs(np.asarray(loaded) - np.asarray(image)) <= bound)


def test_png_is_srgb_tone_mapped_and_decodes_back(image, tmp_path) -> None:
    path = image.save(tmp_path / "a.png", exposure=-2.0)
    loaded = dualight.Image.load(path)
    # 8-bit sRGB: within half a code value of the clipped input. The decoding curve's slope is
    # at most 2.4 / 1.055 (at 1.0), and the exposure of -2 stops scales errors back up by 4.
    expected = np.clip(np.asarray(image) * 0.25, 0, 1) * 4.0
    np.testing.assert_allclose(np.asarray(loaded), expected, atol=4.0 * 2.28 * 0.5 / 255)
    assert loaded.stats["method"] == "path"
    png = image._repr_png_()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"


def test_bad_files_raise_clear_errors(image, tmp_path) -> None:
    with pytest.raises(FileNotFoundError, match="no such image"):
        dualight.Image.load(tmp_path / "missing.exr")
    garbage = tmp_path / "garbage.exr"
    garbage.write_bytes(b"not an image at all")
    with pytest.raises(ValueError, match="cannot read image"):
        dualight.Image.load(garbage)
    with pytest.raises(FileNotFoundError, match="directory does not exist"):
        image.save(tmp_path / "nope" / "a.exr")
    with pytest.raises(ValueError, match="cannot write"):
        image.save(tmp_path / "a.unknownformat")
    with pytest.raises(ValueError, match="H x W x 3"):
        dualight.Image(np.zeros((4, 4, 2)))


def test_arithmetic_and_indexing_as_numpy_arrays(image) -> None:
    pixels = image.pixels.copy()
    other = dualight.Image(pixels[::-1], stats={"method": "light"})
    for result, expected in [
        (image - other, pixels - pixels[::-1]),
        (image * 2, pixels * 2),
        (2 * image, pixels * 2),
        (image / other, pixels / pixels[::-1]),
        (-image, -pixels),
        (np.ones(3) + image, np.ones(3) + pixels),
        (image[3:7], pixels[3:7]),
        (image[..., 1], pixels[..., 1]),
        (np.sqrt(image), np.sqrt(pixels)),
        (image > 2, pixels > 2),
    ]:
        # plain arrays, not Images: the stats and variance describe the render, not this
        assert type(result) is np.ndarray
        np.testing.assert_array_equal(result, expected)
    assert np.mean(image) == pytest.approx(float(np.mean(pixels)))
    assert image[2, 5].tolist() == pixels[2, 5].tolist()
    assert np.shares_memory(image[3:7], image.pixels)  # a view, as numpy's slicing
    assert (image.dtype, image.ndim) == (np.float32, 3)


def test_in_place_arithmetic_keeps_the_image(image) -> None:
    before = image.pixels.copy()
    same = image
    same *= 2
    assert same is image and image.stats["spp"] == 16
    np.testing.assert_array_equal(image.pixels, before * 2)
    assert np.asarray(image) is image.pixels


def test_numpy_numbers_in_stats_and_exposure_are_saved(image, tmp_path) -> None:
    image.stats.update(seed=np.uint64(3), b=np.float32(0.5), per_depth=np.array([1.0, 2.0]))
    loaded = dualight.Image.load(image.save(tmp_path / "a.exr"))
    assert (loaded.stats["seed"], loaded.stats["b"], loaded.stats["per_depth"]) == (3, 0.5, [1, 2])
    dualight.Image.load(image.save(tmp_path / "a.png", exposure=np.float32(-1.0)))


def test_attributes_that_are_not_utf8_load_replaced(tmp_path) -> None:
    # Issue 18: an EXR attribute written by another program in another encoding gave a bare
    # UnicodeDecodeError naming no file. Undecodable bytes now become U+FFFD.
    from dualight import _core

    path = tmp_path / "latin1.exr"
    pixels = np.ones((2, 2, 3), np.float32)
    _core.write_image(str(path), pixels, {"owner": b"Andr\xe9", "dualight:note": b'\xff"x"'})
    loaded = dualight.Image.load(path)
    assert loaded.stats["note"] == '\ufffd"x"'
    assert np.array_equal(np.asarray(loaded), pixels)


def test_loading_an_8_bit_png_takes_about_its_decoded_size(tmp_path) -> None:
    # Issue 18: the sRGB decoding ran in float64 on the whole image, peaking at about 12 times
    # the decoded float32 image (2.2 GB for a 4000 x 4000 PNG of 47 KB). Now it is decoded in
    # place a block of rows at a time: what numpy allocates beyond the decoded image (which
    # the core allocates, out of tracemalloc's sight) stays below its size (the float64 copy
    # alone was twice the size, the whole decoding about 10 times).
    import tracemalloc

    pixels = np.zeros((1000, 1500, 3), np.float32)
    pixels[:500] = 0.5
    path = dualight.Image(pixels).save(tmp_path / "flat.png")
    decoded = pixels.nbytes
    tracemalloc.start()
    try:
        loaded = dualight.Image.load(path)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < decoded, f"{peak / decoded:.2f} x the decoded size"
    np.testing.assert_allclose(np.asarray(loaded)[:500], 0.5, atol=0.003)
