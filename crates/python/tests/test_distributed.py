"""strata.distributed on a LocalCluster of two worker processes: the merged render is the
single-machine render bit for bit, also when a worker is killed mid-render or a piece raises
and is retried; a worker that reads another scene is refused; a bad scene fails before anything
is submitted."""

import concurrent.futures
import os
import signal
import time

import numpy as np
import pytest

import strata
import strata.distributed
from conftest import SCENES, bits

distributed = pytest.importorskip("dask.distributed")


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None)
    client = distributed.Client(cluster)
    yield client
    client.close()
    cluster.close()


@pytest.fixture
def two_workers(client):
    client.wait_for_workers(2, timeout=60)
    return client


def test_split_covers_the_samples_in_disjoint_ranges():
    assert strata.distributed.split(10, 3) == [(0, 3), (3, 6), (6, 10)]
    assert strata.distributed.split(5, 5) == [(i, i + 1) for i in range(5)]
    for bad in [(4, 0), (4, 5)]:
        with pytest.raises(ValueError, match="shards"):
            strata.distributed.split(*bad)


def test_the_merged_render_is_the_single_machine_render(two_workers, cli_render, tmp_path):
    # auto on the many-lights scene: every piece runs the technique pilot and must choose as
    # the whole render does (RIS); three uneven pieces, the first too short to pay for a pilot
    # of its own.
    scene_path = SCENES / "manylights.xml"
    out = tmp_path / "merged.exr"
    image = strata.distributed.render(scene_path, 64, two_workers, shards=3, seed=5, out=out,
                                      pieces_dir=tmp_path / "pieces")
    single, stats = cli_render(scene_path, "--spp", "64", "--seed", "5", "--adaptive", "off")
    assert stats["auto_choice"].endswith("chose +ris")
    assert out.read_bytes() == single.read_bytes()
    assert np.array_equal(bits(image), bits(strata.read_exr(single)))
    local = strata.load(scene_path).render(spp=64, seed=5, adaptive=False)
    assert np.array_equal(bits(image), bits(local))
    pieces = sorted(os.listdir(tmp_path / "pieces"))
    assert pieces == ["piece-0-21.exr", "piece-21-42.exr", "piece-42-64.exr"]
    assert not np.array_equal(bits(strata.read_exr(tmp_path / "pieces" / pieces[0])),
                              bits(image))


def executing(client):
    """The number of tasks each worker is running, by address."""
    return client.run(lambda dask_worker: len(dask_worker.state.executing))


def test_a_worker_killed_mid_render_has_its_piece_rerun_with_identical_result(two_workers,
                                                                              cli_render):
    client = two_workers
    scene_path = SCENES / "cbox.xml"
    # Four pieces of about 1-2 s each on one thread: long enough to be killed in the middle.
    options = dict(shards=4, seed=2, integrator="mis", threads=1, res=96)
    pids = client.run(os.getpid)
    with concurrent.futures.ThreadPoolExecutor(1) as pool:
        running = pool.submit(strata.distributed.render, scene_path, 512, client, **options)
        deadline = time.monotonic() + 60
        victim = None
        while victim is None and time.monotonic() < deadline and not running.done():
            busy = [address for address, n in executing(client).items() if n > 0]
            if busy:
                victim = busy[0]
            else:
                time.sleep(0.05)
        assert victim is not None, "no piece started"
        time.sleep(0.3)
        assert executing(client).get(victim) == 1, "the piece ended before the kill"
        os.kill(pids[victim], signal.SIGKILL)
        image = running.result(timeout=300)
    with pytest.raises(ProcessLookupError):
        os.kill(pids[victim], 0)
    single, _ = cli_render(scene_path, "-D", "res=96", "--spp", "512", "--seed", "2",
                           "--integrator", "mis")
    assert np.array_equal(bits(image), bits(strata.read_exr(single)))


def make_first_piece_fail_once_per_worker(dask_worker):
    """On a worker: the piece starting at sample 0 raises the first time this worker runs it.
    Tasks name `strata.distributed.render_piece` by reference, so replacing the module's
    function replaces what the worker runs."""
    import strata.distributed as d

    original = d.render_piece
    dask_worker.strata_failures = 0

    def flaky(scene_path, defines, start, end, spp, options):
        if start == 0 and dask_worker.strata_failures == 0:
            dask_worker.strata_failures += 1
            raise OSError("injected failure of the first piece")
        return original(scene_path, defines, start, end, spp, options)

    flaky.original = original
    d.render_piece = flaky


def restore_render_piece():
    import strata.distributed as d

    d.render_piece = getattr(d.render_piece, "original", d.render_piece)


def test_a_piece_that_raises_is_retried_with_identical_result(two_workers, cli_render):
    client = two_workers
    scene_path = SCENES / "cbox.xml"
    options = dict(shards=2, seed=3, integrator="mis", res=16)
    client.run(make_first_piece_fail_once_per_worker)
    try:
        image = strata.distributed.render(scene_path, 16, client, **options)
        failures = client.run(lambda dask_worker: dask_worker.strata_failures)
        assert sum(failures.values()) >= 1, failures
        # Without retries the same failure reaches the caller.
        client.run(restore_render_piece)
        client.run(make_first_piece_fail_once_per_worker)
        with pytest.raises(OSError, match="injected failure"):
            strata.distributed.render(scene_path, 16, client, retries=0, **options)
    finally:
        client.run(restore_render_piece)
    single, _ = cli_render(scene_path, "-D", "res=16", "--spp", "16", "--seed", "3",
                           "--integrator", "mis")
    assert np.array_equal(bits(image), bits(strata.read_exr(single)))


SCENE = """<scene version="3.0.0">
    <integrator type="path"/>
    <sensor type="perspective">
        <transform name="to_world"><lookat origin="0, 1, -4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="12"/></film>
    </sensor>
    <emitter type="constant"><rgb name="radiance" value="{radiance}"/></emitter>
    <shape type="sphere"><float name="radius" value="0.5"/>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></shape>
</scene>
"""


def test_a_worker_that_reads_another_scene_is_refused(two_workers, tmp_path, monkeypatch):
    client = two_workers
    here, there = tmp_path / "here", tmp_path / "there"
    for directory, radiance in [(here, "1"), (there, "2")]:
        directory.mkdir()
        (directory / "scene.xml").write_text(SCENE.format(radiance=radiance))
    # The same relative path names this machine's scene here and the other in the workers'
    # working directory, as a stale copy on another machine would.
    monkeypatch.chdir(here)
    before = client.run(os.getcwd)
    client.run(os.chdir, str(there))
    try:
        with pytest.raises(strata.MergeError, match="reads another scene file") as raised:
            strata.distributed.render("scene.xml", 8, client, shards=2, integrator="mis")
        assert strata.load("scene.xml").fingerprint in str(raised.value)
        # With every worker reading the same scene as this machine, the render goes through.
        client.run(os.chdir, str(here))
        strata.distributed.render("scene.xml", 8, client, shards=2, integrator="mis")
    finally:
        for address, directory in before.items():
            client.run(os.chdir, directory, workers=[address])


def test_a_bad_scene_fails_before_anything_is_submitted(two_workers, tmp_path, monkeypatch):
    bad = tmp_path / "bad.xml"
    bad.write_text('<scene version="3.0.0">\n  <shape type="teapot"/>\n</scene>\n')

    def no_submissions(*args, **kwargs):
        raise AssertionError("a task was submitted for a scene that does not load")

    monkeypatch.setattr(two_workers, "submit", no_submissions)
    with pytest.raises(strata.SceneError) as raised:
        strata.distributed.render(bad, 8, two_workers, shards=2)
    assert raised.value.line == 2
    with pytest.raises(TypeError, match="Client"):
        strata.distributed.render(SCENES / "cbox.xml", 8, "tcp://nowhere:8786")
