"""python -m softplc.runtime.devices [DIR]: rewrite every file the registered
devices generate from their manual tables (ST constants, EDS files), in
place, or into DIR to compare."""

from __future__ import annotations

import sys
from pathlib import Path

from ..plugin.registry import registry


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    folder = Path(argv[0]) if argv else None
    for generated in registry().generated():
        target = generated.target.path if folder is None else folder / Path(generated.target.file).name
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(generated.render(), encoding=generated.encoding, newline="\n")
        print(f"wrote {target}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
