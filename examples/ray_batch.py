#!/usr/bin/env python3
"""Render a manifest of meshes on a Ray cluster with the shadelab package.

One Ray task per chunk of meshes: the manifest is split into N shares of
about ``--chunk`` meshes each by ``shadelab.batch``'s stable shards (a hash of
each mesh's id, the same split as ``shadelab batch --shard I/N``), and task I
renders share I/N straight into the output folder, which must be storage
every node sees (NFS, a mounted bucket, ...). Each task writes its own index,
``index-I-of-N.jsonl``; nothing is sent back but a small summary.

Resumable the same way as ``shadelab batch``: every PNG is written atomically,
so rerunning the same command (after a crash, a preempted node, a cancelled
job) skips every output that is already complete and draws only the rest.
Ray retries a task whose worker died, and the retry resumes the same way.

    # on a cluster (or locally: omit --address and Ray starts one)
    python examples/ray_batch.py meshes.jsonl -o /shared/renders \\
        --views 6 --shading phong --size 512x512 --chunk 200 --address auto

Every shard reads the manifest once to find its meshes (a stream, not held
whole): with a million-line manifest and chunks of 1000 that is about a
second per task, small beside rendering its 1000 meshes.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from typing import Any, Dict, List, Optional

import ray

import shadelab


def count_entries(manifest: str) -> int:
    """Non-blank lines of the manifest (less the header, for CSV)."""
    with open(manifest, "rb") as f:
        lines = sum(1 for line in f if line.strip())
    return max(lines - (1 if manifest.lower().endswith(".csv") else 0), 0)


@ray.remote(max_retries=3)
def render_share(manifest: str, output: str, index: int, count: int, options: Dict[str, Any]) -> Dict[str, Any]:
    """One task: shard ``index`` of ``count`` of the manifest, into ``output``."""
    summary = shadelab.batch(manifest, output, shard=(index, count), **options)
    summary["shard"] = f"{index}/{count}"
    summary["node"] = os.uname().nodename
    return summary


def parse_args(argv: Optional[List[str]]) -> argparse.Namespace:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("manifest", help="JSON Lines or CSV manifest (paths relative to it)")
    p.add_argument("-o", "--output", required=True, help="output folder on shared storage")
    p.add_argument("--views", default="1", help="views per mesh: N on a ring, or 'cube'")
    p.add_argument("--shading", default=None, help="flat, gouraud, phong or all, comma-separated")
    p.add_argument("--size", default=None, help="WIDTHxHEIGHT")
    p.add_argument("--scene", default=None, help="scene file (TOML) with the shared settings")
    p.add_argument("--chunk", type=int, default=200, help="meshes per task (about)")
    p.add_argument("--cpus-per-task", type=int, default=1, help="CPUs each task uses (meshes in flight)")
    p.add_argument("--force", action="store_true", help="draw complete outputs again")
    p.add_argument("--address", default=None, help="Ray cluster address ('auto' for the running one)")
    return p.parse_args(argv)


def main(argv: Optional[List[str]] = None) -> Dict[str, Any]:
    """Runs the example; returns the summed summary (also printed)."""
    args = parse_args(argv)
    if not ray.is_initialized():
        ray.init(address=args.address)
    manifest = os.path.abspath(args.manifest)
    output = os.path.abspath(args.output)
    options: Dict[str, Any] = {"views": args.views, "force": args.force, "jobs": args.cpus_per_task}
    if args.shading:
        options["shading"] = args.shading
    if args.scene:
        options["scene"] = os.path.abspath(args.scene)
    if args.size:
        width, height = args.size.lower().split("x")
        options["size"] = (int(width), int(height))
    tasks = max(1, math.ceil(count_entries(manifest) / max(1, args.chunk)))
    start = time.monotonic()
    task = render_share.options(num_cpus=args.cpus_per_task)
    pending = [task.remote(manifest, output, i, tasks, options) for i in range(tasks)]
    total: Dict[str, Any] = {"meshes": 0, "written": 0, "skipped": 0, "failed": 0, "bad_lines": 0}
    while pending:
        done, pending = ray.wait(pending, num_returns=1)
        for summary in ray.get(done):
            for key in total:
                total[key] += summary[key]
            print(f"shard {summary['shard']} on {summary['node']}: {summary['text']}", file=sys.stderr)
    total["tasks"] = tasks
    total["seconds"] = time.monotonic() - start
    total["images_per_second"] = total["written"] / max(total["seconds"], 1e-9)
    print(json.dumps(total))
    return total


if __name__ == "__main__":
    main()
