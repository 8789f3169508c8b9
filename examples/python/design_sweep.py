#!/usr/bin/env python3
"""Sweep thousands of planar-arm designs on a Dask cluster and rank them.

Each design is a chain of 2 to 4 links whose lengths add up to the same reach (6 length
units: the same material), with joint ranges that are symmetric (±a) or not (lo, hi). For each
design a worker computes

- ``area``: the exact area of the region the tip reaches within the joint ranges
  (``Chain.workspace(limits=True)["area"]``, the exact region, not a sample), and
- ``success``: the share of a fixed goal set the solver reaches with the ranges enforced
  (``Chain.solve_batch(goals, threads=1, limits=True)``; unreachable goals are answered at once
  from the same exact region),

and the designs are ranked by one of them (``--rank area|success``, ties broken by the other,
then by the design's number, so that the ranking is reproducible). The designs are drawn from
``--seed`` deterministically, and so is the goal set: the same command prints the same table on
one laptop or on a hundred machines.

The work is sent to Dask (``distributed``) in chunks (``client.submit`` over batches of
designs, not one task per tiny design), and the goal set is scattered to the workers once.
Without ``--scheduler`` the script starts a ``LocalCluster`` on this machine. To use more
machines, start a scheduler on one and workers on the others (each with ``pip install
ikarus`` (this repository's crates/ikarus-py) and ``dask[distributed]``)::

    dask scheduler                          # on the scheduler's machine; prints tcp://HOST:8786
    dask worker tcp://HOST:8786 --nthreads 1 --nworkers auto   # on every worker machine
    python examples/python/design_sweep.py --designs 100000 --scheduler tcp://HOST:8786

Example (a local cluster of 2 workers)::

    python examples/python/design_sweep.py --designs 2000 --goals 400 --rank success --top 5
"""

from __future__ import annotations

import argparse
import csv
import sys
import time
from typing import Optional, Sequence

import numpy as np

REACH = 6.0


def make_designs(count: int, seed: int) -> list:
    """``count`` designs drawn deterministically from ``seed``."""
    rng = np.random.default_rng(seed)
    designs = []
    for i in range(count):
        links = int(rng.integers(2, 5))
        weights = rng.uniform(0.2, 1.0, links)
        lengths = (REACH * weights / weights.sum()).tolist()
        symmetric = bool(rng.random() < 0.5)
        limits = []
        for _ in range(links):
            if symmetric:
                a = float(rng.uniform(30.0, 180.0))
                limits.append((-a, a))
            else:
                lo, hi = sorted(rng.uniform(-180.0, 180.0, 2).tolist())
                if hi - lo < 20.0:
                    hi = min(180.0, lo + 20.0)
                    lo = hi - 20.0
                limits.append((lo, hi))
        designs.append({"id": i, "links": links, "lengths": lengths, "limits_deg": limits, "symmetric": symmetric})
    return designs


def goal_set(count: int, seed: int) -> np.ndarray:
    """``count`` goals spread uniformly over the disc of radius REACH (from ``seed``)."""
    rng = np.random.default_rng([seed, 1])
    r = REACH * np.sqrt(rng.random(count))
    t = rng.uniform(-np.pi, np.pi, count)
    return np.column_stack([r * np.cos(t), r * np.sin(t)])


def evaluate(designs: list, goals: np.ndarray) -> list:
    """Runs on a worker: area and success of each design of a chunk."""
    import ikarus

    rows = []
    for d in designs:
        # A start pose inside every range: each joint at the middle of its range.
        start = [0.5 * (lo + hi) for lo, hi in d["limits_deg"]]
        chain = ikarus.Chain(d["lengths"], angles_deg=start, limits_deg=d["limits_deg"])
        area = chain.workspace(limits=True)["area"]
        result = chain.solve_batch(goals, threads=1, limits=True)
        success = float(np.count_nonzero(result["status"] == "reached")) / len(goals)
        rows.append({**d, "area": area, "success": success})
    return rows


def rank(rows: list, by: str) -> list:
    other = "success" if by == "area" else "area"
    return sorted(rows, key=lambda r: (-r[by], -r[other], r["id"]))


def sweep(client, designs: list, goals: np.ndarray, chunk: int = 64) -> list:
    """Evaluates every design on the cluster of ``client``; rows in the designs' order."""
    goals_on_workers = client.scatter(goals, broadcast=True)
    chunks = [designs[i : i + chunk] for i in range(0, len(designs), chunk)]
    futures = [client.submit(evaluate, c, goals_on_workers, pure=False) for c in chunks]
    rows = [row for part in client.gather(futures) for row in part]
    return sorted(rows, key=lambda r: r["id"])


def table(rows: list, top: int) -> str:
    lines = [f"{'rank':>4} {'design':>6} {'links':>5} {'area':>8} {'success':>8}  lengths / ranges (deg)"]
    for i, r in enumerate(rows[:top], 1):
        parts = ", ".join(f"{l:.2f} [{lo:.0f}, {hi:.0f}]" for l, (lo, hi) in zip(r["lengths"], r["limits_deg"]))
        lines.append(f"{i:>4} {r['id']:>6} {r['links']:>5} {r['area']:>8.3f} {100 * r['success']:>7.1f}%  {parts}")
    return "\n".join(lines)


def main(argv: Optional[Sequence[str]] = None) -> list:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--designs", type=int, default=2000, help="number of designs (default 2000)")
    parser.add_argument("--seed", type=int, default=2026, help="seed of the designs and goals")
    parser.add_argument("--scheduler", help="address of a Dask scheduler (default: a LocalCluster here)")
    parser.add_argument("--workers", type=int, default=2, help="workers of the LocalCluster (default 2)")
    parser.add_argument("--processes", action="store_true", help="LocalCluster workers as processes, not threads")
    parser.add_argument("--rank", choices=["area", "success"], default="area", help="rank by reachable area or by success")
    parser.add_argument("--goals", type=int, default=400, help="goals in the success set (default 400)")
    parser.add_argument("--chunk", type=int, default=64, help="designs per task (default 64)")
    parser.add_argument("--top", type=int, default=10, help="rows of the table (default 10)")
    parser.add_argument("--out", help="write every design's row, ranked, to this CSV file")
    args = parser.parse_args(argv)
    if args.designs < 1 or args.goals < 1 or args.chunk < 1 or args.top < 0:
        parser.error("--designs, --goals and --chunk must be at least 1, --top at least 0")

    from dask.distributed import Client, LocalCluster

    designs = make_designs(args.designs, args.seed)
    goals = goal_set(args.goals, args.seed)
    started = time.perf_counter()
    if args.scheduler:
        with Client(args.scheduler) as client:
            rows = sweep(client, designs, goals, args.chunk)
    else:
        with LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=args.processes, dashboard_address=None) as cluster, Client(cluster) as client:
            rows = sweep(client, designs, goals, args.chunk)
    elapsed = time.perf_counter() - started
    ranked = rank(rows, args.rank)
    print(f"{len(rows)} designs × {len(goals)} goals ranked by {args.rank} in {elapsed:.1f} s")
    print(table(ranked, args.top))
    if args.out:
        with open(args.out, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["rank", "design", "links", "area", "success", "lengths", "limits_deg"])
            for i, r in enumerate(ranked, 1):
                w.writerow([i, r["id"], r["links"], repr(r["area"]), repr(r["success"]), " ".join(map(repr, r["lengths"])), " ".join(f"{lo!r}:{hi!r}" for lo, hi in r["limits_deg"])])
    return ranked


if __name__ == "__main__":
    main(sys.argv[1:])
