"""Traces the rays `cargo xtask raycast-limit` recorded with Embree 4 (through embreex).

usage: python embree_trace.py DIR --threads 1,2 --runs N

DIR holds what the xtask wrote, as .npy files:
    vertices (V, 3) f32, triangles (T, 3) u32   the scene's triangles in world space
    closest_{origins,dirs} (N, 3) f32, closest_tfar (N,) f32     closest-hit rays (tfar = inf)
    shadow_{origins,dirs} (M, 3) f32, shadow_tfar (M,) f32       occlusion rays
    strata_closest_t (N,) f32 (inf: miss), strata_closest_tri (N,) i32 (-1: miss),
    strata_shadow (M,) u8 (1: occluded)                           Strata's answers

For each scene flag (robust: RTC_SCENE_FLAG_ROBUST, the nearest Embree comes to Strata's
watertight triangle test; fast: Embree's default flags), the scene is built once (not timed),
then, `--runs` times, every ray is traced with `EmbreeScene.run` (`rtcIntersect1` /
`rtcOccluded1`, one ray at a time, tnear = 0, tfar as recorded) on each thread count: one `run`
call over all rays on one thread, or the rays in chunks of CHUNK handed to that many Python
threads (`run` releases the GIL). Only the `run` calls are timed. Then, untimed, each ray's
answer is compared with Strata's.

Prints one line of JSON: the Embree version, and per flag the median seconds per thread count,
the build time and the agreement counts. Needs `pip install embreex numpy`; the xtask makes its
own virtual environment for it.
"""
import argparse
import json
import os
import statistics
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np
from embreex import rtcore, rtcore_scene
from embreex.mesh_construction import TriangleMesh

# Rays per `run` call when several threads trace.
CHUNK = 1 << 16

# Difference of hit distance above which the two sides are said to disagree on `t`: relative,
# with an absolute floor (world units) for hits right at the origin, which both sides place
# within rounding of each other.
T_RELATIVE = 1e-4
T_ABSOLUTE = 1e-6


def load(directory, name, dtype, columns=None):
    array = np.ascontiguousarray(np.load(os.path.join(directory, name + ".npy")), dtype=dtype)
    if columns is not None and (array.ndim != 2 or array.shape[1] != columns):
        raise SystemExit(f"{name}.npy: shape {array.shape}, expected (n, {columns})")
    return array


def trace(scene, origins, dirs, tfar, query, pool, threads):
    """Seconds to trace every ray on `threads` threads (`pool` has that many)."""
    if threads == 1:
        start = time.perf_counter()
        scene.run(origins, dirs, dists=tfar, query=query)
        return time.perf_counter() - start
    chunks = [slice(i, i + CHUNK) for i in range(0, len(origins), CHUNK)]
    start = time.perf_counter()
    for _ in pool.map(
        lambda s: scene.run(origins[s], dirs[s], dists=tfar[s], query=query), chunks
    ):
        pass
    return time.perf_counter() - start


def agreement(scene, rays, strata):
    """Counts of rays on which Embree's answer differs from Strata's."""
    closest_o, closest_d, closest_t, shadow_o, shadow_d, shadow_t = rays
    strata_t, strata_tri, strata_shadow = strata
    hit = scene.run(closest_o, closest_d, dists=closest_t.copy(), query="INTERSECT", output=1)
    embree_hits = hit["primID"] >= 0
    strata_hits = strata_tri >= 0
    both = embree_hits & strata_hits
    difference = np.abs(hit["tfar"][both] - strata_t[both])
    occluded = scene.run(shadow_o, shadow_d, dists=shadow_t, query="OCCLUDED") == 0
    return {
        "closest_hit_miss": int(np.count_nonzero(embree_hits != strata_hits)),
        "closest_triangle": int(np.count_nonzero(hit["primID"][both] != strata_tri[both])),
        "closest_t": int(
            np.count_nonzero(difference > T_RELATIVE * strata_t[both] + T_ABSOLUTE)
        ),
        "occluded": int(np.count_nonzero(occluded != (strata_shadow != 0))),
    }


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("directory")
    parser.add_argument("--threads", default="1")
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    thread_counts = [int(t) for t in args.threads.split(",")]
    d = args.directory
    vertices = load(d, "vertices", np.float32, 3)
    triangles = load(d, "triangles", np.uint32, 3)
    rays = (
        load(d, "closest_origins", np.float32, 3),
        load(d, "closest_dirs", np.float32, 3),
        load(d, "closest_tfar", np.float32),
        load(d, "shadow_origins", np.float32, 3),
        load(d, "shadow_dirs", np.float32, 3),
        load(d, "shadow_tfar", np.float32),
    )
    strata = (
        load(d, "strata_closest_t", np.float32),
        load(d, "strata_closest_tri", np.int32),
        load(d, "strata_shadow", np.uint8),
    )
    closest_o, closest_d, closest_t, shadow_o, shadow_d, shadow_t = rays
    pools = {t: ThreadPoolExecutor(max_workers=t) for t in thread_counts if t > 1}
    for t, pool in pools.items():
        # Starts the workers before anything is timed.
        list(pool.map(lambda _: None, range(4 * t)))

    device = rtcore.EmbreeDevice()
    result = {"embree": repr(device).split(":")[-1].strip(), "modes": {}}
    for mode, robust in (("robust", True), ("fast", False)):
        scene = rtcore_scene.EmbreeScene(device, robust=robust)
        start = time.perf_counter()
        TriangleMesh(scene, vertices, triangles)
        # embreex commits (builds) the scene on its first query.
        scene.run(closest_o[:1], closest_d[:1], query="OCCLUDED")
        build = time.perf_counter() - start
        times = {(q, t): [] for q in ("closest", "occluded") for t in thread_counts}
        for _ in range(args.runs):
            for t in thread_counts:
                pool = pools.get(t)
                times["closest", t].append(
                    trace(scene, closest_o, closest_d, closest_t, "INTERSECT", pool, t)
                )
                times["occluded", t].append(
                    trace(scene, shadow_o, shadow_d, shadow_t, "OCCLUDED", pool, t)
                )
        result["modes"][mode] = {
            "build_seconds": build,
            "closest_seconds": {str(t): statistics.median(times["closest", t]) for t in thread_counts},
            "occluded_seconds": {
                str(t): statistics.median(times["occluded", t]) for t in thread_counts
            },
            "disagree": agreement(scene, rays, strata),
        }
    for pool in pools.values():
        pool.shutdown()
    print(json.dumps(result))


if __name__ == "__main__":
    main()
