"""Renders one Mitsuba 3 scene repeatedly for `cargo xtask vs-mitsuba`, timing each render.

usage: python3 mitsuba_server.py SCENE.xml VARIANT
       python3 mitsuba_server.py --check VARIANT SCENE.xml ...

Loads the scene, renders once to warm up (the first render of a JIT variant compiles its
kernels), prints "ready", then reads lines "SPP SEED OUT.exr" from standard input and for each
prints the wall-clock seconds of the render alone (loading and writing excluded) once OUT.exr
(linear RGB float32) is written. With --check, loads each scene without rendering and exits with
status 1 at the first that fails, naming it on standard error. Needs `pip install mitsuba`;
`llvm_ad_rgb` needs libLLVM (DRJIT_LIBLLVM_PATH).
"""
import sys
import time

import drjit as dr
import mitsuba as mi


def render(scene, spp, seed):
    start = time.perf_counter()
    image = mi.render(scene, spp=spp, seed=seed)
    dr.eval(image)
    dr.sync_thread()
    return image, time.perf_counter() - start


def check(variant, paths):
    mi.set_variant(variant)
    for path in paths:
        try:
            mi.load_file(path)
        except Exception as error:  # Mitsuba raises plain exceptions for scene errors.
            print(f"{path}: Mitsuba cannot load it: {error}", file=sys.stderr)
            sys.exit(1)


def main():
    if sys.argv[1] == "--check":
        check(sys.argv[2], sys.argv[3:])
        return
    scene_path, variant = sys.argv[1], sys.argv[2]
    mi.set_variant(variant)
    scene = mi.load_file(scene_path)
    render(scene, 4, 0)
    print("ready", flush=True)
    for line in sys.stdin:
        spp, seed, out_path = line.split(maxsplit=2)
        image, seconds = render(scene, int(spp), int(seed))
        mi.Bitmap(image).convert(component_format=mi.Struct.Type.Float32).write(out_path.strip())
        print(f"{seconds:.6f}", flush=True)


if __name__ == "__main__":
    main()
