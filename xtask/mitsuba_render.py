"""Renders a Mitsuba 3 scene file for `cargo xtask crosscheck`.

usage: python3 mitsuba_render.py SCENE.xml OUT.exr SPP SEED [VARIANT]

Needs `pip install mitsuba` (variant scalar_rgb by default). Writes linear RGB float32.
"""
import sys

import mitsuba as mi


def main():
    scene_path, out_path, spp, seed = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
    variant = sys.argv[5] if len(sys.argv) > 5 else "scalar_rgb"
    mi.set_variant(variant)
    scene = mi.load_file(scene_path, spp=spp)
    image = mi.render(scene, seed=seed, spp=spp)
    mi.Bitmap(image).convert(component_format=mi.Struct.Type.Float32).write(out_path)


if __name__ == "__main__":
    main()
