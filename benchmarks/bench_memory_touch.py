"""What a GiB of fresh memory costs on this machine: first touch against touching it again.

    python benchmarks/bench_memory_touch.py [--gib 1]

A large numpy array comes from a fresh mmap; its pages are mapped (and zeroed) on first touch.
On a bare-metal Linux box that runs at several GiB/s; on a virtual machine whose memory the
host backs lazily, or takes back when the guest frees it, every first touch is a host fault and
costs far more. The FE modal job allocates ~3.4 GiB at 342 k DOF (the Cholesky factor alone
1.1 GiB), so on such a machine this cost is a fixed part of its wall: read FE timings with the
figure this prints.
"""

from __future__ import annotations

import argparse
import time

import numpy as np


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--gib", type=float, default=1.0)
    a = p.parse_args()
    n = int(a.gib * 2**30 / 8)
    t = time.perf_counter()
    x = np.empty(n)
    x[:] = 1.0
    first = time.perf_counter() - t
    t = time.perf_counter()
    x[:] = 2.0
    again = time.perf_counter() - t
    del x
    t = time.perf_counter()
    y = np.empty(n)
    y[:] = 1.0
    fresh_again = time.perf_counter() - t
    print(f"{a.gib:g} GiB: first touch {first:.2f} s ({first / a.gib:.2f} s/GiB), written again "
          f"{again:.2f} s, freed and allocated afresh {fresh_again:.2f} s")


if __name__ == "__main__":
    main()
