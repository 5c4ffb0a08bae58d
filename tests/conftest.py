"""Shared fixtures: small seeded scenes and a quiet render."""

from __future__ import annotations

import numpy as np
import pytest

import dualight


@pytest.fixture
def rng() -> np.random.Generator:
    return np.random.default_rng(12345)


@pytest.fixture
def quad() -> tuple[np.ndarray, np.ndarray]:
    """A unit square in the z = 0 plane, normal +z (right-hand rule)."""
    v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=np.float64)
    return v, np.array([[0, 1, 2, 3]])


@pytest.fixture
def tiny_scene(quad: tuple[np.ndarray, np.ndarray]) -> dualight.Scene:
    """An emitting square facing a camera 2 units in front of it."""
    cam = dualight.Camera(
        origin=(0.5, 0.5, 2.0), target=(0.5, 0.5, 0.0), fov=40, resolution=(16, 16)
    )
    scene = dualight.Scene(camera=cam)
    scene.add_mesh(*quad, reflectance=(0.5, 0.5, 0.5), emission=(1.0, 2.0, 3.0))
    return scene
