"""The bytes of ``_core.ChainStartUp`` and ``_core.ChainPart`` (their pickled state, written by
``src/pathspace/chain_split.cpp``) as plain dicts and back, so that tests can craft the task
data a corrupt or hostile worker could send: each field decoded, changed, encoded again.

Little-endian: a u32 tag and version, then the fields in declaration order; a vector is a u64
count and its items; a string a u64 length and its bytes."""

from __future__ import annotations

import struct
from typing import Any

START_UP_TAG, PART_TAG, VERSION = 0x444C5355, 0x444C4350, 1

# RenderStats: samples, rays, skipped connections, skipped shadow rays, unoccluded (u8),
# invalid samples, spp (u32), seconds, interrupted (u8), time limited (u8).
_STATS = "<QQQQBQIdBB"
_POPULATION_COUNTS = (
    "mutations",
    "accepted",
    "large_steps",
    "large_steps_accepted",
    "zero_proposals",
)


class _Reader:
    def __init__(self, data: bytes) -> None:
        self.data, self.at = data, 0

    def get(self, fmt: str) -> tuple[Any, ...]:
        values = struct.unpack_from(fmt, self.data, self.at)
        self.at += struct.calcsize(fmt)
        return values

    def one(self, fmt: str) -> Any:
        return self.get(fmt)[0]

    def vector(self, item: str) -> list[Any]:
        """A u64 count, then that many items: plain values for a one-letter ``item``, tuples
        for a struct of several."""
        n = self.one("<Q")
        if len(item) > 1:
            return [self.get("<" + item) for _ in range(n)]
        return list(self.get(f"<{n}{item}"))

    def string(self) -> str:
        n = self.one("<Q")
        self.at += n
        return self.data[self.at - n : self.at].decode()


def _vector(item: str, values: list[Any]) -> bytes:
    if len(item) > 1:
        return struct.pack("<Q", len(values)) + b"".join(
            struct.pack("<" + item, *v) for v in values
        )
    return struct.pack(f"<Q{len(values)}{item}", len(values), *values)


def decode_start_up(data: bytes) -> dict[str, Any]:
    r = _Reader(data)
    assert r.get("<II") == (START_UP_TAG, VERSION)
    d: dict[str, Any] = {"image": r.vector("d"), "direct": r.get(_STATS), "stats": r.get(_STATS)}
    d["mlt"] = r.get("<dddQQ")
    d["populations"] = []
    for _ in range(r.one("<Q")):
        p = {"depth": r.one("<i"), "weights": r.vector("d")}
        p.update(zip(("b_splat", "first_chain", "chains", "target"), r.get("<dQQQ"), strict=True))
        p["chain_ids"] = r.vector("I")
        d["populations"].append(p)
    d["pilot"] = r.vector("d")
    d["cancelled"] = r.one("<B")
    assert r.at == len(data)
    return d


def encode_start_up(d: dict[str, Any]) -> bytes:
    out = [struct.pack("<II", START_UP_TAG, VERSION), _vector("d", d["image"])]
    out += [struct.pack(_STATS, *d["direct"]), struct.pack(_STATS, *d["stats"])]
    out += [struct.pack("<dddQQ", *d["mlt"]), struct.pack("<Q", len(d["populations"]))]
    for p in d["populations"]:
        out += [struct.pack("<i", p["depth"]), _vector("d", p["weights"])]
        out += [struct.pack("<dQQQ", p["b_splat"], p["first_chain"], p["chains"], p["target"])]
        out += [_vector("I", p["chain_ids"])]
    out += [_vector("d", d["pilot"]), struct.pack("<B", d["cancelled"])]
    return b"".join(out)


def decode_part(data: bytes) -> dict[str, Any]:
    r = _Reader(data)
    assert r.get("<II") == (PART_TAG, VERSION)
    d: dict[str, Any] = {"first_chain": r.one("<Q"), "chains": r.one("<Q"), "populations": []}
    for _ in range(r.one("<Q")):
        p = {}
        for sums in ("metropolis", "large"):
            p[sums] = (r.one("<i"), r.vector("Q"))  # grid exponent, two words per value
        p["large_f"] = r.vector("ddQ")  # sum, sum of squares, count per chain
        p.update(zip(_POPULATION_COUNTS, r.get("<QQQQQ"), strict=True))
        d["populations"].append(p)
    d["mutations"] = []
    for _ in range(r.one("<Q")):
        name = r.string()
        d["mutations"].append((name, *r.get("<QQQ")))
    d["stats"] = r.get(_STATS)
    assert r.at == len(data)
    return d


def encode_part(d: dict[str, Any]) -> bytes:
    out = [
        struct.pack(
            "<IIQQQ", PART_TAG, VERSION, d["first_chain"], d["chains"], len(d["populations"])
        )
    ]
    for p in d["populations"]:
        for sums in ("metropolis", "large"):
            exponent, words = p[sums]
            out += [struct.pack("<i", exponent), _vector("Q", words)]
        out += [_vector("ddQ", p["large_f"])]
        out += [struct.pack("<QQQQQ", *(p[k] for k in _POPULATION_COUNTS))]
    out += [struct.pack("<Q", len(d["mutations"]))]
    for name, *counts in d["mutations"]:
        raw = name.encode()
        out += [struct.pack("<Q", len(raw)), raw, struct.pack("<QQQ", *counts)]
    out += [struct.pack(_STATS, *d["stats"])]
    return b"".join(out)
