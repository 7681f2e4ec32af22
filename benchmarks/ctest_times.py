#!/usr/bin/env python3
"""Per-test seconds of a ctest log: the N slowest tests and the sum over all (docs/performance.md,
"Test suite"). With two logs, each test's seconds before and after, largest change first.

    benchmarks/ctest_times.py LOG [N]
    benchmarks/ctest_times.py BEFORE_LOG AFTER_LOG [N]
"""
import re
import sys

LINE = re.compile(r"Test +#\d+: (.+?) \.{3,}.*?(?:Passed|Failed|\*\*\*\w+|Not Run)\s+([\d.]+) sec")


def seconds(path):
    times = {}
    with open(path, errors="replace") as log:
        for line in log:
            m = LINE.search(line)
            if m:
                times[m.group(1).split("  #")[0].strip()] = float(m.group(2))
    return times


def main(argv):
    logs = [a for a in argv if not a.isdigit()]
    count = int(next((a for a in argv if a.isdigit()), "30"))
    runs = [seconds(path) for path in logs]
    for path, times in zip(logs, runs):
        print(f"{path}: {sum(times.values()):.1f} s over {len(times)} tests")
    if len(runs) == 1:
        for name, s in sorted(runs[0].items(), key=lambda kv: -kv[1])[:count]:
            print(f"{s:8.2f}  {name}")
        return
    before, after = runs
    names = sorted(set(before) | set(after), key=lambda n: -abs(before.get(n, 0) - after.get(n, 0)))
    for name in names[:count]:
        b, a = before.get(name), after.get(name)
        print(f"{'-' if b is None else f'{b:.2f}':>8}  {'-' if a is None else f'{a:.2f}':>8}  {name}")


if __name__ == "__main__":
    main(sys.argv[1:])
