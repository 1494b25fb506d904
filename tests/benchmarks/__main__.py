"""`make bench`: run every tests/benchmarks/bench_*.py in its own process, in name order.

Each prints its figures as `metric_name: value` lines and writes its charts (PNG) and numbers
(CSV) to tests/benchmarks/results/. At the end comes a summary table of every figure, and
charts_written: how many PNG charts this run wrote.
"""

import re
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
RESULTS = HERE / "results"
FIGURE = re.compile(r"^(?P<name>[a-z][a-z0-9_]*): (?P<value>\S.*)$")


def run(script: Path) -> tuple[int, list[tuple[str, str]]]:
    """Run one benchmark, echoing its output; (exit status, its figures)."""
    module = f"tests.benchmarks.{script.stem}"
    figures = []
    with subprocess.Popen([sys.executable, "-m", module], cwd=HERE.parent.parent, text=True,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT) as process:  # fmt: skip
        for line in process.stdout:
            print(line, end="", flush=True)
            match = FIGURE.match(line.rstrip("\n"))
            if match:
                figures.append((match["name"], match["value"]))
    return process.returncode, figures


def main() -> int:
    started = time.time()
    failed, table = [], []
    for script in sorted(HERE.glob("bench_*.py")):
        print(f"== {script.stem}", flush=True)
        status, figures = run(script)
        if status:
            failed.append(script.stem)
        table += [(script.stem, name, value) for name, value in figures]
    charts = [p for p in RESULTS.glob("*.png") if p.stat().st_mtime >= started]
    table.append(("__main__", "charts_written", str(len(charts))))
    width = max(len(name) for _, name, _ in table)
    print("\n== summary")
    for bench, name, value in table:
        print(f"{name:<{width}}  {value}  ({bench})")
    print(f"charts_written: {len(charts)}")
    if failed:
        print("failed:", ", ".join(failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
