"""Shared fixtures: small seeded scenes and a quiet render; the `long` marker's option."""

from __future__ import annotations

import signal
from collections.abc import Iterator

import numpy as np
import pytest

import dualight


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption(
        "--long",
        action="store_true",
        help="also run the tests marked `long` (beyond make test's 15 minutes; make test-long)",
    )


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    if config.getoption("--long"):
        return
    skip = pytest.mark.skip(reason="marked long: run with --long (make test-long)")
    for item in items:
        if "long" in item.keywords:
            item.add_marker(skip)


@pytest.fixture
def ctrl_c_raises() -> Iterator[None]:
    """Python's own SIGINT handler for the test: a process started in the background by a
    non-interactive shell inherits SIGINT as ignored, and then Ctrl-C never arrives
    (ctrl_c.py sends it)."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)


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


def _nearest_hits(
    scene: dualight.Scene, origins: np.ndarray, dirs: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Nearest hit (distance, triangle normal) of each ray against all triangles (numpy)."""
    tri = np.concatenate([m.vertices[m.triangles] for m in scene.meshes])  # (T, 3, 3)
    e1, e2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    p = np.cross(dirs[:, None], e2[None])
    det = np.einsum("rtj,tj->rt", p, e1)
    inv = 1.0 / np.where(det == 0.0, np.inf, det)
    s = origins[:, None] - tri[None, :, 0]
    u = np.einsum("rtj,rtj->rt", s, p) * inv
    q = np.cross(s, e1[None])
    v = np.einsum("rj,rtj->rt", dirs, q) * inv
    t = np.einsum("rtj,tj->rt", q, e2) * inv
    hit = (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 1e-9)
    t = np.where(hit, t, np.inf)
    first = t.argmin(axis=1)
    return t[np.arange(len(t)), first], np.cross(e1, e2)[first]


@pytest.fixture
def first_hits():
    """A numpy ray-triangle intersector, independent of Embree: (distance, triangle normal) of
    each ray's nearest hit, for checking scene geometry (closedness, face orientation)."""
    return _nearest_hits
