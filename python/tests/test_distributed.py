"""Renders on a Dask cluster of separate processes on loopback: the merged
image is one machine's render bit for bit, also when a worker is killed
while tasks run."""

import json
import os
import signal
import subprocess
import sys
import time

import pytest

import prismatic
import prismatic.distributed
from conftest import SMALL, flags
from test_render import read_exr, same_bits

SETTINGS = {**SMALL, "width": 64, "height": 48, "photons": 20000}


class Cluster:
    """A scheduler and workers, each its own process, on 127.0.0.1."""

    def __init__(self, tmp_path, workers):
        self.procs = []
        file = tmp_path / "scheduler.json"
        env = {**os.environ, "RAYON_NUM_THREADS": "1"}
        self.scheduler = self._start([sys.executable, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1",
                                      "--port", "0", "--no-dashboard", "--scheduler-file", str(file)], env)
        deadline = time.time() + 60
        while not file.exists() or not file.read_text().strip():
            assert time.time() < deadline, "the scheduler did not start"
            time.sleep(0.1)
        self.address = json.loads(file.read_text())["address"]
        for _ in range(workers):
            self._start([sys.executable, "-m", "distributed.cli.dask_worker", self.address, "--nthreads", "1",
                         "--no-nanny", "--no-dashboard", "--host", "127.0.0.1"], env)

    def _start(self, cmd, env):
        proc = subprocess.Popen(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        self.procs.append(proc)
        return proc

    def close(self):
        # Workers first, then the scheduler (started first); a process that
        # has not stopped after 5 s is killed.
        for proc in reversed(self.procs):
            if proc.poll() is None:
                proc.terminate()
            try:
                proc.wait(timeout=5)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()


@pytest.fixture
def cluster(tmp_path):
    c = Cluster(tmp_path, workers=2)
    yield c
    c.close()


def one_machine(cli, tmp_path, passes):
    cli("render", "sphere", "--passes", str(passes), *flags(SETTINGS), "-o", "one.exr", cwd=tmp_path)
    return read_exr(tmp_path / "one.exr")


def wait_for_workers(client, n):
    client.wait_for_workers(n, timeout=60)


def test_eight_passes_in_ranges_of_two_on_two_workers_are_one_render(cli, cluster, tmp_path):
    from dask.distributed import Client

    with Client(cluster.address) as client:
        wait_for_workers(client, 2)
        seen, held = [], []

        def progress(done, total):
            seen.append((done, total))
            if not held:
                # While the render runs, each worker holds the scene once: it
                # was scattered to all of them, not sent with each task.
                held.append(client.run(lambda dask_worker: [str(k) for k in dask_worker.data if str(k).startswith("tuple-")]))

        image = prismatic.distributed.render("sphere", passes=8, chunk=2, client=client, progress=progress, **SETTINGS)
        assert sorted(seen) == [(2, 8), (4, 8), (6, 8), (8, 8)]
        assert len(held[0]) == 2 and all(len(keys) == 1 for keys in held[0].values()), held
    assert same_bits(image, one_machine(cli, tmp_path, 8))


def test_a_worker_killed_while_tasks_run_changes_no_bit(cli, cluster, tmp_path):
    from dask.distributed import Client

    with Client(cluster.address) as client:
        wait_for_workers(client, 2)
        pids = client.run(os.getpid)
        killed = []

        def kill_a_busy_worker(done, total):
            # Once (the test bounds itself): after the first range is back,
            # the worker that is rendering a range now dies.
            if killed:
                return
            busy = [w for w, keys in client.processing().items() if keys]
            victim = busy[0] if busy else next(iter(pids))
            os.kill(pids[victim], signal.SIGKILL)
            killed.append(victim)

        image = prismatic.distributed.render("sphere", passes=8, chunk=2, client=client,
                                             progress=kill_a_busy_worker, **SETTINGS)
        assert len(killed) == 1
        assert len(client.run(os.getpid)) == 1, "the killed worker is gone"
    assert same_bits(image, one_machine(cli, tmp_path, 8))


def test_the_same_render_twice_in_a_row_on_one_client(cluster):
    # The second call's scene and tasks must not share keys with the first's,
    # which the scheduler may still be forgetting (the tasks were lost then).
    from dask.distributed import Client

    with Client(cluster.address) as client:
        wait_for_workers(client, 2)
        images = [prismatic.distributed.render("sphere", passes=2, chunk=1, client=client, progress=False, **SETTINGS)
                  for _ in range(3)]
    assert same_bits(images[0], images[1]) and same_bits(images[0], images[2])


def test_a_local_cluster_is_started_when_no_address_is_given(cli, tmp_path):
    image = prismatic.distributed.render("sphere", passes=3, chunk=2, workers=2, progress=False, **SETTINGS)
    assert same_bits(image, one_machine(cli, tmp_path, 3))


def test_a_bad_scene_raises_before_any_task_runs():
    with pytest.raises(prismatic.SceneError) as raised:
        prismatic.distributed.render("sphere", passes=4, client=object(), width=0)
    assert raised.value.key == "width"


def test_ranges_cover_the_passes_once():
    assert prismatic.distributed.ranges(7, 2) == [(0, 2), (2, 4), (4, 6), (6, 7)]
    with pytest.raises(ValueError):
        prismatic.distributed.ranges(4, 0)
