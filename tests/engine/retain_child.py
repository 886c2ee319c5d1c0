"""Child process for the retain kill test (tests/engine/test_retain.py).

    python retain_child.py <file>

For every counter the test sends on stdin, this process forks a writer that
writes the retain file in a tight loop (counter, counter + 1, ...) until the
test kills it with SIGKILL, and prints the writer's pid. Forking instead of
starting a new interpreter per kill keeps the test fast; the writer is still
a real process killed in the middle of whatever write_file was doing.

Each file holds the counter and a ~40 kB block derived from it, so a reader
can tell a complete file from a mix of two writes.
"""

import os
import sys
from pathlib import Path

from softplc.runtime.engine.retain import RetainData
from softplc.runtime.engine.retain_file import write_file


def block(counter: int) -> list:
    return [(counter * 7919 + i) % 1_000_003 for i in range(5000)]


def data(counter: int) -> RetainData:
    return RetainData(
        layout="kill-test",
        saved_ns=counter,
        cycle=counter,
        vars={
            "Main.counter": {"kind": "RETAIN", "type": "LINT", "value": counter},
            "Main.block": {"kind": "RETAIN", "type": "ARRAY[0..4999] OF DINT", "value": block(counter)},
        },
    )


def write_forever(path: Path, counter: int) -> None:
    try:
        while True:
            write_file(path, data(counter))
            counter += 1
    except BaseException as exc:  # only the kill should end a writer
        print(f"writer failed: {exc!r}", file=sys.stderr, flush=True)
        os._exit(1)


def main() -> None:
    path = Path(sys.argv[1])
    for line in sys.stdin:  # one line per round; EOF ends the test
        pid = os.fork()
        if pid == 0:
            write_forever(path, int(line))
        print(pid, flush=True)
        os.waitpid(pid, 0)  # the test kills it
        print("reaped", flush=True)


if __name__ == "__main__":
    main()
