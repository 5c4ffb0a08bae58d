"""Speed-up of render(executor=...) with 2 workers, and that its image is the same.

On the Cornell box (128x128), path tracing and BDPT at a fixed spp, and PSSMLT, MMLT and
path-space MLT at a fixed number of mutations per pixel (their default options: 100,000
bootstrap samples, 256 chains, 128 spp of direct light; ``max_depth`` 8 for all MLT methods,
as MMLT needs one), the median wall time of ``--repeats`` runs (alternating) of:

* ``render(threads=1)``: one process, one thread (the baseline);
* ``render(threads=2)``: one process, two TBB threads;
* ``render(executor=client)``: a Dask ``LocalCluster`` of 2 single-threaded worker processes
  (its start-up, about a second, is timed apart and left out); each render sends the scene
  and compiles it once per worker, which is counted;
* ``render(executor=pool)``: a ``ProcessPoolExecutor(2)``, each task single-threaded.

A split MLT render runs its start-up (direct light, bootstrap) in this process on every core
(2 here), then the chains as tasks of 16 chains on the workers; the split row's speed-up is
the whole render's, start-up included.

Every split render is checked against the single-process image (``np.array_equal`` of mean
and variance, same seed and spp). Writes ``benchmarks/results/bench_executor.json`` and prints
the speed-ups (baseline time over each time).

    python benchmarks/bench_executor.py [--quick] [--repeats 3]
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path
from typing import Any

import numpy as np

import dualight as dl
from dualight import scenes

RESULTS = Path(__file__).resolve().parent / "results"
RES = (128, 128)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="smaller budgets, one repeat")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--out", type=Path, default=RESULTS / "bench_executor.json")
    args = parser.parse_args()
    from distributed import Client, LocalCluster

    repeats = 1 if args.quick else args.repeats
    budgets = (
        {"path": 64, "bdpt": 32, "pssmlt": 16, "mmlt": 16, "mlt": 32}
        if args.quick
        else {"path": 512, "bdpt": 128, "pssmlt": 128, "mmlt": 128, "mlt": 512}
    )
    scene = scenes.cornell_box(resolution=RES)
    start = time.perf_counter()
    cluster = LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0"
    )
    client = Client(cluster)
    cluster_seconds = time.perf_counter() - start
    pool = ProcessPoolExecutor(2)
    pool.submit(int).result()  # start the pool's processes outside the timings
    load_before = os.getloadavg()
    runs: dict[str, Any] = {}
    try:
        for method, spp in budgets.items():
            kwargs: dict[str, Any] = dict(spp=spp, seed=1, progress=False)
            if method in ("pssmlt", "mmlt", "mlt"):
                kwargs["max_depth"] = 8
            setups = {
                "threads=1": dict(threads=1),
                "threads=2": dict(threads=2),
                "dask 2 workers": dict(executor=client),
                "process pool 2": dict(executor=pool),
            }
            times: dict[str, list[float]] = {name: [] for name in setups}
            cpu: dict[str, list[float]] = {name: [] for name in setups}
            images: dict[str, dl.Image] = {}
            for _ in range(repeats):
                for name, extra in setups.items():
                    t0, c0 = time.perf_counter(), time.process_time()
                    images[name] = dl.render(scene, method, **kwargs, **extra)
                    times[name].append(time.perf_counter() - t0)
                    # CPU seconds: this process's, or the workers' (task_cpu_seconds) plus
                    # this process's for a split render.
                    used = time.process_time() - c0
                    cpu[name].append(used + images[name].stats.get("task_cpu_seconds", 0.0))
            base = images["threads=1"]
            median = {name: statistics.median(ts) for name, ts in times.items()}
            runs[method] = {
                "spp": spp,
                "samples": base.stats["samples"],
                "tasks": images["dask 2 workers"].stats["tasks"],
                "seconds": times,
                "median_seconds": median,
                "cpu_seconds": cpu,
                # Wall time over CPU time of the single-threaded run: above 1, other processes
                # took the CPU (the development machine is shared), and speed-ups shrink.
                "threads1_wall_over_cpu": statistics.median(
                    w / c for w, c in zip(times["threads=1"], cpu["threads=1"], strict=True)
                ),
                "speedup_over_threads1": {
                    name: median["threads=1"] / m for name, m in median.items()
                },
                "dask_over_threads2": median["threads=2"] / median["dask 2 workers"],
                # Time inside the core summed over the tasks, over 2 workers x wall time.
                "dask_worker_busy": images["dask 2 workers"].stats["task_seconds"]
                / (2 * times["dask 2 workers"][-1]),
                "bit_for_bit": {
                    name: bool(
                        np.array_equal(np.asarray(img), np.asarray(base))
                        and np.array_equal(img.variance, base.variance)
                    )
                    for name, img in images.items()
                },
            }
    finally:
        client.close()
        cluster.close()
        pool.shutdown()
    out = {
        "scene": f"cornell_box {RES[0]}x{RES[1]}",
        "repeats": repeats,
        "block_spp": int(dl._core.BLOCK_SPP),
        "dask_cluster_startup_seconds": cluster_seconds,
        "machine": {
            "platform": platform.platform(),
            "cpu_count": os.cpu_count(),
            "loadavg_before": load_before,
            "loadavg_after": os.getloadavg(),
        },
        "dualight": dl.__version__,
        "runs": runs,
    }
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(out, indent=2) + "\n")
    print(f"Dask LocalCluster start-up (not timed below): {cluster_seconds:.2f} s")
    print("| method | spp (mutations) | setup | median s | speed-up over threads=1 | same image |")
    print("|---|---|---|---|---|---|")
    for method, r in runs.items():
        for name, m in r["median_seconds"].items():
            print(
                f"| {method} | {r['spp']} | {name} | {m:.2f} | "
                f"{r['speedup_over_threads1'][name]:.2f} | {r['bit_for_bit'][name]} |"
            )
        print(f"| {method} | | dask / threads=2 | | {r['dask_over_threads2']:.2f} | |")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
