#!/usr/bin/env python3
"""Speed of the Python edge (a benchmark, not a test): run it after building the wheel.

    python crates/ikarus-py/bench.py [--goals 100000] [--batch 1000000] [--runs 3]

1. ``chain.solve((x, y))`` on the seed arm: the median of per-call times over held-out goals of
   ``ikarus bench``'s ``seed/free-position`` set (the tips of configurations drawn uniformly in
   [−π, π) with its SplitMix64 and seed, reproduced here), timed in batches of 100 calls with
   ``time.perf_counter_ns`` (a call's time = its batch's time / 100; the median over batches);
   ``--goals`` goals, after a warm-up over the first 1000.
2. ``chain.solve_batch(goals, threads=T)`` throughput (solves per second) for T = 1 and 2 on
   ``--batch`` goals of the same set, ``--runs`` runs each, the median.

The figures depend on the machine and its load: the script prints ``os.getloadavg()``.
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import time

import numpy as np

import ikarus

MASK = (1 << 64) - 1


def stable_hash(arm: str, name: str) -> int:
    """`ikarus bench`'s FNV-1a of the arm's and the set's names."""
    h = 0xCBF29CE484222325
    for b in arm.encode() + b"\0" + name.encode():
        h ^= b
        h = (h * 0x00000100000001B3) & MASK
    return h


def splitmix_units(state: int, count: int) -> np.ndarray:
    """`count` draws of ikarus::rng::SplitMix64::unit from `state`, vectorised."""
    k = np.arange(1, count + 1, dtype=np.uint64)
    with np.errstate(over="ignore"):
        z = np.uint64(state) + k * np.uint64(0x9E3779B97F4A7C15)
        z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
        z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
        z = z ^ (z >> np.uint64(31))
    return (z >> np.uint64(11)).astype(np.float64) * (1.0 / (1 << 53))


def free_position_goals(chain: ikarus.Chain, count: int, seed: int = 1) -> np.ndarray:
    """The `seed/free-position` goals of `ikarus bench --seed SEED --goals COUNT`: tips of
    configurations uniform in [−π, π) per joint (the tips by NumPy's forward kinematics)."""
    n = len(chain)
    u = splitmix_units(seed ^ stable_hash("seed", "free-position"), count * n).reshape(count, n)
    q = -math.pi + u * (2 * math.pi)
    heading = np.cumsum(q, axis=1)
    lengths = chain.lengths
    x = chain.base[0] + (lengths * np.cos(heading)).sum(axis=1)
    y = chain.base[1] + (lengths * np.sin(heading)).sum(axis=1)
    return np.column_stack([x, y])


def single(chain: ikarus.Chain, goals: np.ndarray, per_batch: int = 100) -> dict:
    pairs = [(float(x), float(y)) for x, y in goals]
    for g in pairs[:1000]:
        chain.solve(g)
    solve = chain.solve
    clock = time.perf_counter_ns
    per_call = []
    for i in range(1000, len(pairs) - per_batch + 1, per_batch):
        chunk = pairs[i : i + per_batch]
        t0 = clock()
        for g in chunk:
            solve(g)
        per_call.append((clock() - t0) / per_batch / 1000.0)
    reached = sum(solve(g).status == "reached" for g in pairs[1000:11000])
    return {"median_us": statistics.median(per_call), "p90_us": float(np.percentile(per_call, 90)), "calls": len(per_call) * per_batch, "reached_of_10000": reached}


def batch(chain: ikarus.Chain, goals: np.ndarray, threads: int, runs: int) -> dict:
    rates, cores = [], []
    for _ in range(runs):
        c0, t0 = time.process_time(), time.perf_counter()
        out = chain.solve_batch(goals, threads=threads)
        wall = time.perf_counter() - t0
        rates.append(len(goals) / wall)
        cores.append((time.process_time() - c0) / wall)
    reached = int(np.count_nonzero(out["status"] == "reached"))
    # CPU seconds per wall second: how many cores the process really had (others' load shows here).
    return {"median_per_s": statistics.median(rates), "runs": [round(r) for r in rates], "reached": reached, "cores": statistics.median(cores)}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--goals", type=int, default=101_000)
    parser.add_argument("--batch", type=int, default=1_000_000)
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    chain = ikarus.Chain()
    goals = free_position_goals(chain, max(args.goals, args.batch))
    print(f"load average before: {' '.join(f'{x:.2f}' for x in os.getloadavg())}; {os.cpu_count()} CPUs")
    s = single(chain, goals[: args.goals])
    print("| measure | result |\n| --- | --- |")
    print(f"| `chain.solve((x, y))`, seed arm, median per call ({s['calls']} calls) | {s['median_us']:.2f} µs (p90 of batch means {s['p90_us']:.2f} µs; {s['reached_of_10000']}/10000 reached) |")
    for threads in (1, 2):
        b = batch(chain, goals[: args.batch], threads, args.runs)
        print(f"| `solve_batch`, {args.batch} goals, threads={threads}, median of {args.runs} | {b['median_per_s'] / 1e6:.3f} M solves/s (runs {b['runs']}; {b['reached']} reached; {b['cores']:.2f} cores busy) |")
    print(f"load average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")


if __name__ == "__main__":
    main()
