#!/usr/bin/env python3
"""Benchmark of `centaur sweep` (docs/benchmarks.md, section "Sweeps").

Usage:  python3 tools/bench_sweep.py [--centaur build/src/cli/centaur] [--runs 12] [--rounds 3] [--work DIR]

One squat-jump plan (planned once, --plan-only), then per round, interleaved so that a change of the machine's speed
spreads over all of them:
  threads-1  `centaur sweep SPEC --jobs 1`            RUNS runs of the default 5 s squat jump, mode none
  threads-2  `centaur sweep SPEC --jobs 2`
  mpi-2      `mpirun -n 2 centaur sweep SPEC`         (1 thread per rank; rank 0 dispatches, writes and simulates)
  bare       RUNS x `centaur simulate squat-jump --primitive DB --primitive-group G --stabilizer none
             --set sensors.seed=S`, one process per run, one after the other: the same work without the sweep
Each sweep starts from a copy of the planned directory, so it only simulates. The runs are identical (no noise, no
perturbation): the work per run is the same in every configuration.
Printed: per configuration the median [min - max] over the rounds of runs per second; the parallel efficiency
rate(2) / (2 rate(1)); the sweep's wall time per run on 1 thread against a bare simulate's; and the machinery's
share of the 1-thread sweep: (simulation-phase wall time - sum of the runs' own run_time_s) / wall time, and the
writer's time (journal, results.h5, progress lines) per run.
Python 3 standard library only.
"""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import time

SPEC = """jumps: [squat-jump]
modes: [none]
seeds: {runs}
seed: 1
"""


def sweep(centaur, spec, out, launcher=None, jobs=None):
    cmd = (launcher or []) + [centaur, "sweep", spec, "--out", out, "--json"] + (["--jobs", str(jobs)] if jobs else [])
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, check=True)
    report = json.loads(p.stdout.strip().splitlines()[-1])
    with open(os.path.join(out, "journal.jsonl")) as f:
        run_time = sum(json.loads(line)["run_time_s"] for line in f)
    return report, run_time


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--centaur", default="build/src/cli/centaur")
    ap.add_argument("--runs", type=int, default=12)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--work", default="out/bench-sweep")
    a = ap.parse_args()
    centaur = os.path.abspath(a.centaur)
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    spec = os.path.join(a.work, "spec.yaml")
    with open(spec, "w") as f:
        f.write(SPEC.format(runs=a.runs))
    plan = os.path.join(a.work, "plan")
    subprocess.run([centaur, "sweep", spec, "--out", plan, "--plan-only"], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    db = os.path.join(plan, "primitives.h5")
    mpirun = ["env", "OMPI_MCA_btl=self,vader", "mpirun", "--oversubscribe", "-n", "2"]
    if os.geteuid() == 0:
        mpirun.insert(-2, "--allow-run-as-root")
    rates = {"threads-1": [], "threads-2": [], "mpi-2": [], "bare": []}
    per_run_1, bare_per_run, machinery, writer = [], [], [], []
    for r in range(a.rounds):
        for name in ("threads-1", "threads-2", "mpi-2", "bare"):
            if name == "bare":
                t0 = time.monotonic()
                for s in range(a.runs):
                    subprocess.run([centaur, "simulate", "squat-jump", "--primitive", db, "--primitive-group",
                                    "squat-jump-0000", "--stabilizer", "none", "--set", "sensors.seed=%d" % s],
                                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                wall = time.monotonic() - t0
                rates["bare"].append(a.runs / wall)
                bare_per_run.append(wall / a.runs)
                continue
            out = os.path.join(a.work, "%s-%d" % (name, r))
            shutil.copytree(plan, out)
            report, run_time = sweep(centaur, spec, out, mpirun if name == "mpi-2" else None,
                                     {"threads-1": 1, "threads-2": 2}.get(name))
            rates[name].append(report["runs_per_second"])
            if name == "threads-1":
                wall = report["runs_wall_time_s"]
                per_run_1.append(wall / report["runs_now"])
                machinery.append((wall - run_time) / wall)
                writer.append(report["writer_time_s"] / report["runs_now"])
        print("round %d: %s" % (r + 1, ", ".join("%s %.3f" % (k, v[-1]) for k, v in rates.items())), flush=True)

    def med(v):
        return "%.3f [%.3f - %.3f]" % (statistics.median(v), min(v), max(v))

    print("\nruns per second, median [min - max] of %d rounds, %d runs each:" % (a.rounds, a.runs))
    for k, v in rates.items():
        print("  %-10s %s" % (k, med(v)))
    one = statistics.median(rates["threads-1"])
    for k in ("threads-2", "mpi-2"):
        e = [x / (2 * y) for x, y in zip(rates[k], rates["threads-1"])]
        print("  efficiency %-9s %s (median of the per-round ratios; %.3f from the medians)"
              % (k, med(e), statistics.median(rates[k]) / (2 * one)))
    o = [s / b - 1 for s, b in zip(per_run_1, bare_per_run)]
    print("  sweep (1 thread) vs bare simulate, wall time per run: %s s vs %s s, overhead %s"
          % (med(per_run_1), med(bare_per_run), med(o)))
    print("  machinery share of the 1-thread sweep (wall - sum of run_time_s) / wall: %s" % med(machinery))
    print("  writer time per run (journal + results.h5 + progress): %s s" % med(writer))
    return 0


if __name__ == "__main__":
    sys.exit(main())
