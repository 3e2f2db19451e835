"""One render split over a Dask cluster, bit-identical to a single-machine render.

    from dask.distributed import Client
    import strata.distributed
    client = Client("tcp://scheduler:8786")       # or LocalCluster, dask-jobqueue's SLURMCluster
    image = strata.distributed.render("scenes/cbox.xml", 4096, client, shards=32,
                                      seed=1, out="cbox-4096.exr", res=512)

The sample indices [0, spp) are split into `shards` disjoint ranges. Each is one Dask task that
loads the scene on a worker and renders only those samples (`Scene.render(samples=(a, b))`, the
same as `strata render --samples a..b --spp spp`), returning the piece's EXR with its exact
sums. Dask reruns a task whose worker died or was lost, and retries a task that failed
(`retries`); pieces are keyed by their range, so a rerun replaces its piece and never adds it
twice. The client checks that every piece was rendered from this machine's scene (its
fingerprint: the scene file, included files, meshes and textures), then adds the pieces' sums
exactly (`strata.merge`): the result is the very image, bit for bit, of

    strata.load(scene_path, **defines).render(spp=spp, seed=seed, adaptive=False, ...)

or `strata render SCENE --spp N --seed S --adaptive off` (pieces cannot sample adaptively: their
samples must not depend on a pilot over the whole image). `auto` chooses its techniques in each
piece exactly as the whole render does.

Workers need this package (same version) and the scene at the same path (a shared file system,
or the same checkout everywhere); a worker that reads a different scene is refused by name.
Start workers with one thread each (`--nthreads 1`): a piece already uses all of its machine's
cores through Rayon.
"""

import os
import socket
import tempfile

from dask.distributed import Client

from . import MergeError, defines_list
from . import _strata

__all__ = ["render", "split"]


def split(spp, shards):
    """The sample ranges of `shards` pieces of an `spp`-sample render: [start, end) pairs that
    cover [0, spp) in order, their sizes differing by at most one."""
    if spp < 1:
        raise ValueError(f"spp must be at least 1, got {spp}")
    if not 1 <= shards <= spp:
        raise ValueError(f"shards must be from 1 to spp ({spp}), got {shards}")
    bounds = [spp * i // shards for i in range(shards + 1)]
    return list(zip(bounds[:-1], bounds[1:]))


def render_piece(scene_path, defines, start, end, spp, options):
    """A Dask task: renders samples [start, end) of the `spp`-sample render of the scene at
    `scene_path` (with `defines`, (name, text) pairs) and returns a dict of the piece's EXR
    bytes (`exr`), the scene's fingerprint as this worker read it, and the worker's host name."""
    scene = _strata.Scene.load(scene_path, defines)
    with tempfile.TemporaryDirectory(prefix="strata-piece-") as directory:
        out = os.path.join(directory, "piece.exr")
        scene.render(spp=spp, samples=(start, end), out=out, **options)
        with open(out, "rb") as file:
            exr = file.read()
    return {
        "exr": exr,
        "fingerprint": scene.fingerprint,
        "host": socket.gethostname(),
        "range": (start, end),
    }


def render(scene_path, spp, client, shards=None, *, seed=0, integrator=None, sampler=None,
           max_depth=None, threads=None, retries=3, out=None, pieces_dir=None, **defines):
    """Renders `spp` samples per pixel of the scene at `scene_path` as `shards` Dask tasks on
    `client` and returns the merged image, a float32 array of shape (height, width, 3),
    bit-identical to the single-machine render (see the module documentation).

    - `shards`: how many pieces (default: the cluster's worker count, at most `spp`).
    - `seed`, `integrator`, `sampler`, `max_depth`, `threads`: as for `Scene.render`
      (`threads`: Rayon threads per piece, default all of a worker's cores).
    - `retries`: how often Dask reruns a piece whose task raised (a lost worker's pieces are
      rerun by the scheduler anyway).
    - `out`: also write the merged EXR there (the file `strata render --spp N --adaptive off`
      writes, byte for byte; `strata merge` can merge it with further pieces).
    - `pieces_dir`: keep the pieces' EXRs there (`piece-START-END.exr`); by default they are
      written to a temporary directory and deleted.
    - Other keyword arguments are scene parameters (-D defines), as for `strata.load`.

    Raises `SceneError` when the scene does not load here (nothing is submitted then), and
    `MergeError` when a worker rendered a different scene, or the pieces do not add up to
    [0, spp).
    """
    if not isinstance(client, Client):
        raise TypeError(f"client must be a dask.distributed.Client, got {type(client).__name__}")
    scene_path = os.fspath(scene_path)
    defines = defines_list(defines)
    # Load here first: a bad scene fails at once, and the fingerprint checks the workers' scenes.
    scene = _strata.Scene.load(scene_path, defines)
    if shards is None:
        shards = max(1, min(spp, len(client.scheduler_info().get("workers", {}))))
    ranges = split(spp, shards)
    options = {"seed": seed, "integrator": integrator, "sampler": sampler,
               "max_depth": max_depth, "threads": threads}
    futures = [
        client.submit(render_piece, scene_path, defines, start, end, spp, options,
                      retries=retries, pure=False,
                      key=f"strata-piece-{start}-{end}-{os.urandom(6).hex()}")
        for start, end in ranges
    ]
    try:
        results = client.gather(futures)
    finally:
        client.cancel([f for f in futures if not f.done()])
    for result in results:
        if result["fingerprint"] != scene.fingerprint:
            start, end = result["range"]
            raise MergeError(
                f"the piece of samples {start}..{end} was rendered on {result['host']} from a "
                f"scene whose fingerprint is {result['fingerprint']}, but '{scene_path}' here is "
                f"{scene.fingerprint}: that worker reads another scene file (or an included "
                f"file, mesh or texture differs)"
            )
    with tempfile.TemporaryDirectory(prefix="strata-pieces-") as scratch:
        directory = scratch if pieces_dir is None else os.fspath(pieces_dir)
        os.makedirs(directory, exist_ok=True)
        paths = []
        for result in results:
            start, end = result["range"]
            path = os.path.join(directory, f"piece-{start}-{end}.exr")
            with open(path, "wb") as file:
                file.write(result["exr"])
            paths.append(path)
        image, record = _strata.merge(paths, None if out is None else os.fspath(out))
    if record["spp"] != spp:
        raise MergeError(f"the pieces hold {record['samples']}, not the {spp} samples asked for")
    return image

