"""Frames per second of lpir_gseg.fleet on a LocalCluster of 1 worker process and of 2 (or any
counts), over the same simulated scans, and their ratio. A timing, not a test: run it by hand.

    python3 python/bench/fleet_workers.py [--frames 384] [--workers 1 2] [--repeat 3]

Each run is timed from its first task to its last result (run()'s RunStats.seconds): the cluster's
start and each worker's segmenter (made on every worker before the clock starts) are not in it.
The median over the repeats is reported; the load average beside it says what else the machine
was doing.
"""
import argparse
import os
import statistics
import sys
import tempfile

import lpir_gseg
from lpir_gseg import fleet


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--frames", type=int, default=384, help="scans (default 384)")
    parser.add_argument("--distinct", type=int, default=24,
                        help="simulated scans among them (default 24; the others link to them)")
    parser.add_argument("--sensor", default="hdl64e")
    parser.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--backend", default="cpu")
    parser.add_argument("--inputs", nargs="*", help="scans to use instead of simulated ones")
    args = parser.parse_args()

    with tempfile.TemporaryDirectory(prefix="lpir_fleet_bench_") as folder:
        inputs = args.inputs
        if not inputs:
            scans = os.path.join(folder, "scans")
            os.makedirs(scans)
            for seed in range(min(args.distinct, args.frames)):
                points, _ = lpir_gseg.simulate(args.sensor, seed)
                points.tofile(os.path.join(scans, f"{seed:05}.bin"))
            for i in range(args.distinct, args.frames):  # the rest: links to those
                os.symlink(f"{i % args.distinct:05}.bin", os.path.join(scans, f"{i:05}.bin"))
            inputs = [scans]
        frames = len(fleet.list_inputs(inputs))
        print(f"{frames} frames ({args.sensor}, backend {args.backend}), {os.cpu_count()} cores, "
              f"median of {args.repeat} runs")
        rates = {}
        for workers in args.workers:
            runs = []
            for _ in range(args.repeat):
                stats = fleet.run(inputs, args.sensor, os.path.join(folder, "out"),
                                  workers=workers, backend=args.backend, progress=False)
                if stats.failures:
                    print(stats.failures, file=sys.stderr)
                    return 1
                runs.append(stats.frames_per_second)
            rates[workers] = statistics.median(runs)
            load = ", ".join(f"{x:.1f}" for x in os.getloadavg())
            print(f"  {workers} worker{'s' if workers != 1 else ''}: {rates[workers]:6.1f} "
                  f"frames/s (runs: {', '.join(f'{r:.1f}' for r in runs)}; load {load})")
        base = rates[args.workers[0]]
        for workers in args.workers[1:]:
            print(f"  {workers} vs {args.workers[0]}: {rates[workers] / base:.2f}x")
    return 0


if __name__ == "__main__":
    sys.exit(main())
