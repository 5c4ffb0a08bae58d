"""BDPT's light pool (``render(light_pool=...)``): equal-time efficiency, and where its error goes.

With ``light_pool`` k each connection of a camera vertex to a light vertex (s, t >= 2) takes a
light subpath of its pixel's group of k pixels (same tile row, same sample index) instead of
its own sample's. That lowers each pixel's error where few light subpaths reach what the camera
sees. Sharing subpaths correlates the pixels of a group, so a lower per-pixel relMSE alone could
be error moved into groups of pixels; the second part of this benchmark measures the error of
block means at equal spp, from single pixels to 32x32 blocks, and the error's correlation
between horizontal neighbours. A block mean's error is what any smoothing or downsampling of the
image keeps, so the pool is a gain only if no block shape loses.

This renders ``bench_bdpt``'s scenes (the Cornell box, its caustic variant and Veach's door;
64x64, ``max_depth`` 8), relMSE against the tests' Mitsuba references (their own noise removed,
as in ``bench_bdpt``; block means against the reference's block means):

* equal time: ``--budget`` seconds each, the pools interleaved seed by seed, efficiency
  1 / (relMSE x seconds);
* equal spp: ``--block-spp`` samples per pixel, ``--block-seeds`` seeds, relMSE of block means
  for each block shape (rows x columns) and the ratio pool / classic.

Writes ``benchmarks/results/bench_bdpt_pool.json`` (or ``--out``).

    python benchmarks/bench_bdpt_pool.py      # 8 s, seeds 1-4; 64 spp, 16 seeds; pools 1, 16
    python benchmarks/bench_bdpt_pool.py --budget 1 --seeds 1 --block-seeds 2 --out /tmp/p.json
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
from pathlib import Path
from typing import Any

import numpy as np

import dualight

HERE = Path(__file__).resolve().parent
RESULTS = HERE / "results"
sys.path[:0] = [str(HERE)]
from bench_bdpt import EPS, Prepared, bdpt_efficiency, prepared_scenes  # noqa: E402

SHAPES = ((1, 1), (1, 2), (1, 4), (1, 8), (1, 16), (2, 16), (4, 4), (8, 8), (16, 16), (32, 32))


def render(p: Prepared, pool: int, seed: int, threads: int | None, **budget: Any) -> dualight.Image:
    """BDPT on ``p``'s scene with light pool ``pool`` and the given budget (spp or time)."""
    return dualight.render(
        p.scene,
        "bdpt",
        max_depth=int(p.info["max_depth"]),
        light_pool=pool,
        seed=seed,
        threads=threads,
        progress=False,
        **budget,
    )


def efficiency(
    p: Prepared, budget: float, pool: int, seed: int, threads: int | None
) -> dict[str, Any]:
    """One render of ``budget`` seconds: its spp, seconds, relMSE and efficiency."""
    return bdpt_efficiency(p, budget, seed, threads, light_pool=pool)


def block_means(image: np.ndarray, rows: int, cols: int) -> np.ndarray:
    """Means of ``rows x cols`` blocks (trailing pixels that fill no block are dropped)."""
    h, w, c = image.shape
    cut = image[: h // rows * rows, : w // cols * cols]
    return cut.reshape(h // rows, rows, w // cols, cols, c).mean(axis=(1, 3))


def block_errors(p: Prepared, image: np.ndarray) -> dict[str, float]:
    """relMSE of each block shape's means against the reference's, and the relative error's
    correlation between horizontal neighbours."""
    reference = np.asarray(p.mean)
    out = {}
    for rows, cols in SHAPES:
        r = block_means(reference, rows, cols)
        out[f"{rows}x{cols}"] = float(
            np.mean((block_means(image, rows, cols) - r) ** 2 / (r + EPS) ** 2)
        )
    e = ((image - reference) / (reference + EPS)).mean(axis=2)
    out["neighbour_correlation"] = float(np.corrcoef(e[:, :-1].ravel(), e[:, 1:].ravel())[0, 1])
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--budget", type=float, default=8.0, help="seconds per equal-time render")
    parser.add_argument("--seeds", type=str, default="1,2,3,4", help="equal-time seeds")
    parser.add_argument("--block-spp", type=int, default=64)
    parser.add_argument("--block-seeds", type=int, default=16, help="equal-spp seeds 1..N")
    parser.add_argument("--pools", type=str, default="1,16", help="the first is the baseline")
    parser.add_argument("--threads", type=int, default=None, help="default: every core")
    parser.add_argument("--out", type=Path, default=RESULTS / "bench_bdpt_pool.json")
    args = parser.parse_args()
    seeds = [int(s) for s in args.seeds.split(",")]
    pools = [int(k) for k in args.pools.split(",")]
    summary: dict[str, Any] = {
        "machine": {"cpu_count": os.cpu_count(), "platform": platform.platform()},
        "budget_seconds": args.budget,
        "block_spp": args.block_spp,
        "block_seeds": args.block_seeds,
        "threads": args.threads,
        "seeds": seeds,
        "pools": pools,
        "scenes": {},
    }
    base = pools[0]
    for p in prepared_scenes():
        order = lambda seed: pools if seed % 2 else pools[::-1]  # noqa: E731
        runs = [
            efficiency(p, args.budget, k, seed, args.threads) for seed in seeds for k in order(seed)
        ]
        eff = {
            k: float(np.mean([r["efficiency"] for r in runs if r["light_pool"] == k]))
            for k in pools
        }
        blocks = {
            k: [
                block_errors(p, np.asarray(render(p, k, seed, args.threads, spp=args.block_spp)))
                for seed in range(1, args.block_seeds + 1)
            ]
            for k in pools
        }
        mean_blocks = {
            k: {key: float(np.mean([b[key] for b in blocks[k]])) for key in blocks[k][0]}
            for k in pools
        }
        summary["scenes"][p.name] = {
            "runs": runs,
            "mean_efficiency": eff,
            "block_relmse": mean_blocks,
        }
        for k in pools:
            ratios = " ".join(
                f"{shape} {mean_blocks[k][shape] / mean_blocks[base][shape]:.2f}"
                for shape in mean_blocks[k]
                if shape != "neighbour_correlation"
            )
            print(
                f"{p.name:>9} light_pool {k:2d}: efficiency {eff[k]:8.2f} "
                f"({eff[k] / eff[base]:.2f}x pool {base}); "
                f"block relMSE / pool {base} at {args.block_spp} spp: {ratios}; "
                f"neighbour correlation {mean_blocks[k]['neighbour_correlation']:.3f}",
                flush=True,
            )
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(summary, indent=2) + "\n")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
