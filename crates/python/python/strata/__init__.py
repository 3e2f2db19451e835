"""Strata, a path tracer for Mitsuba 3 scenes that measures its own noise, from Python.

    import strata
    scene = strata.load("scenes/cbox.xml", res=256)      # keyword arguments are -D defines
    image = scene.render(spp=64)                          # float32 array (height, width, 3)
    scene.last_stats["techniques"], scene.last_stats["seconds"]
    strata.diff(image, strata.read_exr("scenes/refs/cbox.exr"))["relmse"]

`Scene.render` renders exactly as `strata render` does with the same flags: its array holds the
very values the command writes to its EXR. The scene is parsed and its BVH built once, in
`load`; every render reuses them. Rendering runs on Rayon's threads with the GIL released, and
Ctrl-C stops it at the next pass boundary (within a second) with `KeyboardInterrupt`.

`strata.sampling` exposes the random number generator, warps with their pdfs and inverses, and
the samplers; `strata.distributed` splits one render over a Dask cluster, bit-identical to a
single-machine render. The book's page "Python and Dask" (docs/src/guide/python.md) documents
all of it.
"""

import os as _os

from . import sampling
from ._strata import MergeError, Scene, SceneError, __version__, read_exr, read_record
from ._strata import diff as _diff
from ._strata import merge as _merge

__all__ = [
    "MergeError",
    "Scene",
    "SceneError",
    "__version__",
    "diff",
    "load",
    "merge",
    "read_exr",
    "read_record",
    "render",
    "sampling",
]

#: The keyword arguments of `Scene.render`; `strata.render` passes the others to `load`.
RENDER_KEYWORDS = frozenset(
    ["spp", "time", "integrator", "sampler", "seed", "threads", "adaptive", "max_depth",
     "samples", "out"]
)


def _define_value(name, value):
    """The text of a -D value: booleans as Mitsuba writes them, everything else as str()."""
    if value is None:
        raise TypeError(f"the scene parameter {name!r} is None; give it a value")
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (list, tuple)):
        return ", ".join(str(v) for v in value)
    return str(value)


def defines_list(defines):
    """`defines` (a dict of scene parameters) as the (name, text) pairs `Scene.load` takes."""
    return [(str(name), _define_value(name, value)) for name, value in defines.items()]


def load(path, **defines):
    """Loads the Mitsuba 3 scene at `path` once (parsing, meshes, textures and the BVH).

    Keyword arguments override the scene's `<default>` parameters as `strata render -D
    NAME=VALUE` does: `load("cbox.xml", res=256, max_depth=4)`. Booleans become `true`/`false`,
    sequences comma-separated lists. A name the scene does not use is an error.

    Raises `SceneError` (with `file`, `line`, `column`, `element` and `message`) when the scene
    cannot be loaded.
    """
    return Scene.load(_os.fspath(path), defines_list(defines))


def render(path, **kwargs):
    """Loads the scene at `path` and renders it once: the one-call form of `load` and
    `Scene.render`. Keyword arguments named like `Scene.render`'s (`spp`, `time`, `integrator`,
    `sampler`, `seed`, `threads`, `adaptive`, `max_depth`, `samples`, `out`) go to the render,
    all others are scene parameters (-D defines):

        image = strata.render("scenes/cbox.xml", res=64, spp=16, integrator="mis")
    """
    render_kwargs = {k: v for k, v in kwargs.items() if k in RENDER_KEYWORDS}
    defines = {k: v for k, v in kwargs.items() if k not in RENDER_KEYWORDS}
    return load(path, **defines).render(**render_kwargs)


def _image(x, name):
    """`x` as a float32 image array: read from the EXR file if it is a path."""
    import numpy as np

    if isinstance(x, (str, bytes, _os.PathLike)):
        return read_exr(_os.fspath(x))
    array = np.ascontiguousarray(x, dtype=np.float32)
    if array.ndim != 3 or array.shape[2] != 3:
        raise ValueError(f"{name} has shape {array.shape}; an image is (height, width, 3)")
    return array


def diff(a, b):
    """The error of image `a` against the reference `b`, as `strata diff` prints it: a dict of
    `rmse`, `relmse` (the mean over pixels and channels of (a - b)^2 / (b^2 + 0.01)), `mean_a`
    and `mean_b`. Each of `a` and `b` is an array of shape (height, width, 3) or an EXR path.
    """
    return _diff(_image(a, "a"), _image(b, "b"))


def merge(paths, out=None):
    """Adds up render EXRs (pieces written by `Scene.render(samples=..., out=...)` or `strata
    render --samples`) exactly, as `strata merge` does, and returns the image; writes the merged
    EXR to `out` when given. Raises `MergeError`, naming the files, for pieces of other scenes,
    settings or sizes, and for samples given twice."""
    image, _record = _merge([_os.fspath(p) for p in paths],
                            None if out is None else _os.fspath(out))
    return image


def __getattr__(name):
    # `strata.distributed` needs Dask, so it is imported on first use.
    if name == "distributed":
        import importlib

        return importlib.import_module(".distributed", __name__)
    raise AttributeError(f"module 'strata' has no attribute {name!r}")
