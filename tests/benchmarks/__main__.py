"""`make bench`: run every tests/benchmarks/bench_*.py in its own process, in name order.

Each prints its figures as `metric_name: value` lines and writes its charts (PNG) and numbers
(CSV) to tests/benchmarks/results/.
"""

import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent


def main() -> int:
    failed = []
    for script in sorted(HERE.glob("bench_*.py")):
        print(f"== {script.stem}", flush=True)
        module = f"tests.benchmarks.{script.stem}"
        if subprocess.run([sys.executable, "-m", module], cwd=HERE.parent.parent).returncode:
            failed.append(script.stem)
    if failed:
        print("failed:", ", ".join(failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
