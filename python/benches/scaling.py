"""What the Python package and the distributed render cost, in one run:

- the package's overhead against the CLI for one render (same scene, settings, backend);
- the local cluster's speed-up over one process on this machine;
- tasks a second the Dask scheduler sustains for tiny pass ranges;
- merging a partial render, against image size.

    target/python/bin/python python/benches/scaling.py [--quick]

Prints a Markdown table per measurement (the README quotes them).
"""

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

import prismatic
import prismatic.distributed

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CLI = os.environ.get("PRISMATIC", os.path.join(ROOT, "target", "release", "prismatic"))


def median_time(f, repeats):
    """Median of `repeats` wall times of f()."""
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def overhead(repeats):
    """The CLI and the package, alternately (so that drift in the machine hits both alike)."""
    settings = ["sphere", "--backend", "cpu"]
    cli, py = [], []
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "x.exr")
        for _ in range(repeats):
            cli.append(median_time(lambda: subprocess.run([CLI, "render", *settings, "-o", out], check=True,
                                                   capture_output=True), 1))
            py.append(median_time(lambda: prismatic.render("sphere", backend="cpu", progress=False), 1))
    cli, py = statistics.median(cli), statistics.median(py)
    print(f"| one render of `sphere` (16 passes × 65k photons, 400×400, cpu) | median of {repeats}, alternating |")
    print("|---|---:|")
    print(f"| `prismatic render sphere --backend cpu -o x.exr` | {cli:.3f} s |")
    print(f"| `prismatic.render('sphere', backend='cpu')` | {py:.3f} s ({100 * (py / cli - 1):+.1f} %) |")
    print()


def speedup(passes, chunks, workers):
    from dask.distributed import Client, LocalCluster

    one = median_time(lambda: prismatic.render("sphere", passes=passes, backend="cpu", progress=False), 3)
    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None,
                           env={"RAYON_NUM_THREADS": "1"})
    print(f"| `sphere`, {passes} passes, cpu | wall (median of 3) |")
    print("|---|---:|")
    print(f"| one process, {os.cpu_count()} threads | {one:.2f} s |")
    with Client(cluster) as client:
        client.wait_for_workers(workers)
        # Warm the workers (the module imported).
        prismatic.distributed.render("sphere", passes=workers, chunk=1, client=client, backend="cpu", progress=False)
        for chunk in chunks:
            dist = median_time(lambda: prismatic.distributed.render("sphere", passes=passes, chunk=chunk, client=client,
                                                             backend="cpu", progress=False), 3)
            print(f"| local cluster, {workers} workers × 1 thread, ranges of {chunk} | {dist:.2f} s ({one / dist:.2f}×) |")
    cluster.close()
    print()


def tasks_per_second(tasks, workers):
    from dask.distributed import Client, LocalCluster

    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None,
                           env={"RAYON_NUM_THREADS": "1"})
    tiny = {"width": 8, "height": 8, "photons": 100, "backend": "cpu"}
    with Client(cluster) as client:
        client.wait_for_workers(workers)
        prismatic.distributed.render("sphere", passes=workers, chunk=1, client=client, progress=False, **tiny)
        one_task = median_time(lambda: prismatic.render_partial("sphere", (0, 1), **tiny), 5)
        wall = median_time(lambda: prismatic.distributed.render("sphere", passes=tasks, chunk=1, client=client,
                                                         progress=False, **tiny), 1)
    cluster.close()
    print("| scheduling | figure |")
    print("|---|---:|")
    print(f"| {tasks} one-pass tasks of an 8×8 render on {workers} workers | {tasks / wall:.0f} tasks/s |")
    print(f"| one such task in-process | {1e3 * one_task:.1f} ms |")
    print()


def merge_cost(sizes, repeats):
    """What the client pays per partial render that comes back: adding it to the merge."""
    print("| image | partial | add one to a merge | image of the merge |")
    print("|---|---:|---:|---:|")
    for w, h in sizes:
        s = {"width": w, "height": h, "photons": 1000, "backend": "cpu"}
        parts = [prismatic.render_partial("sphere", (k, k + 1), **s) for k in range(repeats + 1)]
        merged = prismatic._prismatic.Merge()
        merged.add(parts[0])
        add = statistics.median(median_time(lambda: merged.add(p), 1) for p in parts[1:])
        image = median_time(merged.image, repeats)
        print(f"| {w}×{h} | {len(parts[0]) / 1e6:.1f} MB | {1e3 * add:.1f} ms | {1e3 * image:.1f} ms |")
    print()


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--quick", action="store_true", help="fewer repeats and smaller sizes")
    args = p.parse_args()
    repeats = 1 if args.quick else 9
    print(f"# prismatic {prismatic.__version__}, Python {sys.version.split()[0]}, {os.cpu_count()} cores, "
          f"{time.strftime('%Y-%m-%d')}\n")
    overhead(repeats)
    speedup(passes=16, chunks=[2, 8], workers=os.cpu_count() or 1)
    tasks_per_second(tasks=40 if args.quick else 200, workers=os.cpu_count() or 1)
    merge_cost([(400, 400), (1920, 1080)] if args.quick else [(400, 400), (1920, 1080), (3840, 2160)], repeats)


if __name__ == "__main__":
    main()
