"""Cost of the truth columns in `rins.run`: process CPU time per sample with `truth=True`
against `truth=False`, best of N interleaved runs, with the minor page faults each run takes.
A benchmark, run by hand (the figures in docs/python.md, Performance, come from it);
test_package.py checks what the columns hold.

Needs the package installed in the venv of tests/run-all.sh.

Usage: python bench_truth.py [DURATION_S] [REPEATS]
"""

import resource
import sys
import time

import rins

SCENARIO = "builtin:paper-16pos-week"


def one(duration_s, truth):
    """CPU seconds (user, system) and minor faults of one call, the arrays freed after."""
    r0 = resource.getrusage(resource.RUSAGE_SELF)
    out = rins.run(SCENARIO, duration_s=duration_s, truth=truth)
    r1 = resource.getrusage(resource.RUSAGE_SELF)
    n = len(out["t_s"])
    del out
    return (r1.ru_utime - r0.ru_utime, r1.ru_stime - r0.ru_stime, r1.ru_minflt - r0.ru_minflt, n)


def main():
    duration_s = float(sys.argv[1]) if len(sys.argv) > 1 else 14400.0
    repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    best = {}
    for _ in range(repeats):
        for truth in (False, True):
            u, s, f, n = one(duration_s, truth)
            if truth not in best or u + s < best[truth][0] + best[truth][1]:
                best[truth] = (u, s, f, n)
    for truth in (False, True):
        u, s, f, n = best[truth]
        print(f"truth={truth!s:5}: {(u + s) / n * 1e9:6.1f} ns/sample CPU "
              f"(user {u / n * 1e9:.1f}, system {s / n * 1e9:.1f}), "
              f"{f / n * 1000:.1f} minor faults per 1000 samples, {n} samples")
    ratio = sum(best[True][:2]) / best[True][3] / (sum(best[False][:2]) / best[False][3])
    print(f"truth=True / truth=False: {ratio:.2f}x ({time.strftime('%Y-%m-%d')}, load "
          f"{open('/proc/loadavg').read().split()[0]})")


if __name__ == "__main__":
    main()
