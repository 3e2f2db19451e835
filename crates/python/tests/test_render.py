"""Scenes rendered from Python: the arrays are the command line's EXR, bit for bit; errors name
file and line; Ctrl-C interrupts promptly; the stats are those of `strata render --stats`."""

import json
import os
import shutil
import signal
import threading
import time

import numpy as np
import pytest

import strata
from conftest import SCENES, bits

# (scene, defines, flags of both interfaces): each row covers a different path through the
# renderer. manylights at 64 spp with `auto` runs the technique pilot (it chooses RIS) and
# adaptive sampling; the glass box traces caustics from the lights; veach uses Sobol points.
CASES = [
    ("cbox.xml", {"res": 24}, dict(spp=8, integrator="mis", seed=3)),
    ("cbox.xml", {"res": 20, "max_depth": 4}, dict(spp=5, integrator="reference", seed=1,
                                                   sampler="stratified")),
    ("cbox-glass.xml", {"res": 24}, dict(spp=6, integrator="auto", seed=2)),
    ("veach-mis.xml", {}, dict(spp=4, integrator="ris", sampler="sobol", seed=9)),
    ("manylights.xml", {}, dict(spp=64, integrator="auto", seed=0)),
]


def cli_flags(defines, options):
    """The `strata render` flags for scene parameters `defines` and render `options`."""
    flags = []
    for name, value in defines.items():
        flags += ["-D", f"{name}={value}"]
    for name, value in options.items():
        flags += [f"--{name.replace('_', '-')}", value]
    return flags


@pytest.mark.parametrize("scene_name, defines, options", CASES,
                         ids=[f"{c[0]}-{c[2]['integrator']}" for c in CASES])
def test_arrays_and_files_equal_the_clis_bit_for_bit(scene_name, defines, options, cli_render,
                                                     tmp_path):
    scene_path = SCENES / scene_name
    cli_exr, cli_stats = cli_render(scene_path, *cli_flags(defines, options), "--threads", "2")
    scene = strata.load(scene_path, **defines)
    out = tmp_path / "py.exr"
    image = scene.render(threads=1, out=out, **options)
    assert image.dtype == np.float32 and image.shape == (scene.size[1], scene.size[0], 3)
    expected = strata.read_exr(cli_exr)
    assert np.array_equal(bits(image), bits(expected))
    assert out.read_bytes() == cli_exr.read_bytes()
    stats = scene.last_stats
    # Not `passes`: how the samples are split into passes follows the measured speed (a pass
    # fills at most MAX_PASS_SECONDS), so one thread may take more passes than two; the image,
    # compared above, does not depend on it.
    for key in ["spp", "pilot_spp", "rays", "shadow_rays", "techniques",
                "auto_choice", "nan_count", "inf_count"]:
        assert stats.get(key) == cli_stats.get(key), key
    # The comparison can fail: another seed gives other bits.
    other = scene.render(threads=1, **{**options, "seed": options["seed"] + 1})
    assert not np.array_equal(bits(other), bits(expected))


def test_the_pilot_case_really_runs_the_pilot_and_adaptive_sampling(cli_render):
    _, stats = cli_render(SCENES / "manylights.xml", "--spp", "64", "--seed", "0")
    assert stats["auto_choice"].startswith("pilot ") and stats["pilot_spp"] > 0
    assert "adaptive" in stats["techniques"]


def test_one_scene_renders_again_without_reading_its_file(tmp_path):
    scene_path = tmp_path / "cbox.xml"
    shutil.copy(SCENES / "cbox.xml", scene_path)
    scene = strata.load(scene_path, res=16)
    first = scene.render(spp=4, integrator="nee", seed=5)
    scene_path.write_text("not a scene any more")
    again = scene.render(spp=4, integrator="nee", seed=5, threads=1)
    assert np.array_equal(bits(first), bits(again))
    with pytest.raises(strata.SceneError):
        strata.load(scene_path)


def test_the_one_call_form_splits_defines_from_render_options(cli_render):
    image = strata.render(SCENES / "cbox.xml", res=12, max_depth=3, spp=3, integrator="mis")
    expected, _ = cli_render(SCENES / "cbox.xml", "-D", "res=12", "-D", "max_depth=3",
                             "--spp", "3", "--integrator", "mis", "--seed", "0")
    assert np.array_equal(bits(image), bits(strata.read_exr(expected)))


def test_the_scenes_integrator_is_the_default_as_on_the_command_line(cli_render, tmp_path):
    """With no `integrator`, the scene's `<integrator type>` decides, as without --integrator."""
    scene_path = tmp_path / "cbox-reference.xml"
    text = (SCENES / "cbox.xml").read_text()
    assert '<integrator type="path">' in text
    scene_path.write_text(text.replace('<integrator type="path">', '<integrator type="reference">'))
    scene = strata.load(scene_path, res=12)
    image = scene.render(spp=3, seed=4, threads=1)
    expected, stats = cli_render(scene_path, "-D", "res=12", "--spp", "3", "--seed", "4")
    assert "reference" in stats["techniques"]
    assert np.array_equal(bits(image), bits(strata.read_exr(expected)))
    assert "reference" in scene.last_stats["techniques"]
    # It can fail: `auto`, which the default used to be, renders other bits.
    auto = scene.render(spp=3, seed=4, threads=1, integrator="auto")
    assert not np.array_equal(bits(auto), bits(image))


BAD_SCENE = """<scene version="3.0.0">
    <sensor type="perspective">
        <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
    </sensor>
    <shape type="teapot"/>
</scene>
"""


def test_bad_scenes_raise_scene_error_with_file_line_and_element(tmp_path):
    bad = tmp_path / "bad.xml"
    bad.write_text(BAD_SCENE)
    with pytest.raises(strata.SceneError) as raised:
        strata.load(bad)
    error = raised.value
    assert isinstance(error, ValueError)
    assert os.path.samefile(error.file, bad)
    assert (error.line, error.column) == (5, 5)
    assert error.element == '<shape type="teapot">'
    assert "teapot" in error.message
    assert str(error).startswith(f"{bad}:5:5: ")
    with pytest.raises(strata.SceneError) as raised:
        strata.render(bad, spp=1)
    assert raised.value.line == 5


def test_missing_files_and_unused_defines_are_scene_errors_naming_the_file(tmp_path):
    missing = tmp_path / "missing.xml"
    with pytest.raises(strata.SceneError) as raised:
        strata.load(missing)
    assert os.path.samefile(os.path.dirname(raised.value.file), tmp_path)
    assert raised.value.line == 0
    with pytest.raises(strata.SceneError) as raised:
        strata.load(SCENES / "cbox.xml", no_such_parameter=3)
    assert "no_such_parameter" in raised.value.message
    assert raised.value.file.endswith("cbox.xml")


def test_bad_render_arguments_are_value_errors():
    scene = strata.load(SCENES / "cbox.xml", res=8)
    with pytest.raises(ValueError, match="bogus"):
        scene.render(spp=1, integrator="bogus")
    with pytest.raises(ValueError, match="threads"):
        scene.render(spp=1, threads=0)
    with pytest.raises(ValueError, match="goes past --spp 4"):
        scene.render(spp=4, samples=(0, 8))
    with pytest.raises(ValueError, match="samples"):
        scene.render(spp=4, samples=(0, 4), adaptive=True)


def test_the_image_does_not_depend_on_the_thread_count():
    scene = strata.load(SCENES / "cbox-glass.xml", res=20)
    one = scene.render(spp=4, threads=1, seed=4)
    two = scene.render(spp=4, threads=2, seed=4)
    assert np.array_equal(bits(one), bits(two))


def test_rendering_releases_the_gil():
    scene = strata.load(SCENES / "cbox.xml", res=96)
    counted = []
    done = threading.Event()

    def count():
        n = 0
        while not done.is_set():
            n += 1
        counted.append(n)

    counter = threading.Thread(target=count)
    counter.start()
    try:
        scene.render(time=1.0, spp=None, integrator="mis")
    finally:
        done.set()
        counter.join()
    # Holding the GIL for the render's second would leave the counter a few switch intervals
    # (5 ms each) of counting; released, it counts for most of the second (millions).
    assert counted[0] > 100_000, counted


# SIGINT to this process during a long render must raise KeyboardInterrupt within a second: the
# package's passes last at most a quarter second (the first, 1 sample per pixel, takes
# milliseconds here) and the waiting thread polls every 50 ms, which leaves slack for a loaded
# CI machine. `auto` with a time budget is in its adaptive pilot when the signal comes.
INTERRUPT_LIMIT_SECONDS = 1.0


@pytest.mark.parametrize("integrator", ["mis", "auto"])
def test_ctrl_c_raises_keyboard_interrupt_within_a_second(integrator):
    scene = strata.load(SCENES / "cbox.xml", res=192)
    sent = []

    def interrupt():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(1.0, interrupt)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            # A 60 s budget: the signal surely arrives during the render.
            scene.render(spp=None, time=60.0, integrator=integrator)
        raised = time.monotonic()
    finally:
        timer.cancel()
    assert sent, "the timer never fired"
    assert raised - sent[0] < INTERRUPT_LIMIT_SECONDS, raised - sent[0]
    stats = scene.last_stats
    assert stats["interrupted"] and stats["spp"] >= 1 and stats["seconds"] < 5
    # The scene renders normally afterwards (each render has a stop signal of its own).
    scene.render(spp=1)
    assert not scene.last_stats["interrupted"]


def test_stats_report_what_was_rendered_and_chosen():
    scene = strata.load(SCENES / "cbox.xml", res=16)
    assert scene.last_stats is None
    scene.render(spp=6, integrator="mis", threads=1)
    stats = scene.last_stats
    assert stats["spp"] == 6 and stats["threads"] == 1
    assert (stats["width"], stats["height"]) == (16, 16)
    assert stats["rays"] >= 6 * 16 * 16 and stats["shadow_rays"] > 0
    assert "mis-power" in stats["techniques"] and stats.get("auto_choice") is None
    assert stats["seconds"] > 0 and stats["load_seconds"] > 0
    scene.render(spp=4, integrator="auto")
    assert "chose base" in scene.last_stats["auto_choice"] or "no pilot" in \
        scene.last_stats["auto_choice"]


def test_diff_is_strata_diffs(cli, tmp_path):
    scene = strata.load(SCENES / "cbox.xml", res=16)
    a_path, b_path = tmp_path / "a.exr", tmp_path / "b.exr"
    a = scene.render(spp=2, seed=1, out=a_path)
    b = scene.render(spp=16, seed=2, out=b_path)
    printed = json.loads(cli("diff", a_path, b_path).stdout)
    for ours in (strata.diff(a, b), strata.diff(a_path, b_path)):
        assert ours == printed
    a64, b64 = a.astype(np.float64), b.astype(np.float64)
    relmse = np.mean((a64 - b64) ** 2 / (b64 ** 2 + 0.01))
    assert printed["relmse"] == pytest.approx(relmse, rel=1e-9)
    assert printed["rmse"] == pytest.approx(np.sqrt(np.mean((a64 - b64) ** 2)), rel=1e-9)
    with pytest.raises(ValueError, match="shape"):
        strata.diff(a[:, :, :2], b)


def test_pieces_merge_into_the_whole_render_and_overlaps_are_refused(tmp_path):
    scene = strata.load(SCENES / "cbox-glass.xml", res=24)
    whole = scene.render(spp=40, seed=7, adaptive=False, out=tmp_path / "whole.exr")
    ranges = [(0, 3), (3, 25), (25, 40)]
    pieces = []
    for start, end in ranges:
        path = tmp_path / f"{start}.exr"
        piece = scene.render(spp=40, seed=7, samples=(start, end), out=path)
        assert not np.array_equal(bits(piece), bits(whole))
        pieces.append(path)
    merged_path = tmp_path / "merged.exr"
    merged = strata.merge(pieces[::-1], out=merged_path)
    assert np.array_equal(bits(merged), bits(whole))
    assert merged_path.read_bytes() == (tmp_path / "whole.exr").read_bytes()
    assert strata.read_record(merged_path)["samples"] == "seed 7: 0..40"
    overlapping = tmp_path / "overlap.exr"
    scene.render(spp=40, seed=7, samples=(20, 30), out=overlapping)
    with pytest.raises(strata.MergeError, match="both hold samples 20..25 of seed 7"):
        strata.merge([pieces[1], overlapping])
