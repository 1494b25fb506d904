"""Every number a user can type on the command line, hostile values and random ones: a
message in the option's terms, at once (exit 2, argparse's), or a finite picture — never a
traceback. Before, `--script-seconds 1e300` and `--script-memory 1e20` overflowed the
operating system's limits in the script's process ("this is Whitted's fault")."""

import os
import random
import subprocess
import sys
import time

import numpy as np
import pytest
from PIL import Image

from tests.support import ROOT, hostile

SCRIPT = """r = gr.node('r')
r:add_child(gr.sphere('s'))
gr.render(r, 'o.png', 8, 8, {0, 0, 5}, {0, 0, -1}, {0, 1, 0}, 50, {0.2, 0.2, 0.2}, {})
"""
# The render command's numeric options, each with values a user might type by mistake
OPTIONS = {
    "--script-seconds": ["1e300", "0", "-1", "nan", "inf", "1e-9", "86401", "2", "0x10", "٣"],
    "--script-memory": ["100000000000000000000", "0", "-1", "15", "1e3", "16", "64.5", "2**40"],
    "--threads": ["-1", str(2**64), "1025", "0", "1", "1.5", "two", ""],
    "--region": ["0,0,99999999999999999999,1", "=-5,0,1,1", "0,0,0,0", "0,0,8,8", "1,1,2,2",
                 "0,0,8", "a,b,c,d", "0,0,-1,-1", "7,7,1,1", "8,8,1,1"],
}  # fmt: skip
RANDOM_VALUES = 40  # besides those above, random numbers of every size and sign


def render(folder, *args):
    """The command line, leaving no temporary file or process (checked by `hostile.run`)."""
    return hostile.run(folder, "scene.lua", *args)


def random_values(seed: int) -> list[tuple[str, str]]:
    rng = random.Random(seed)
    found = []
    for _ in range(RANDOM_VALUES):
        option = rng.choice(list(OPTIONS))
        number = lambda: rng.choice([  # noqa: E731
            str(rng.randint(-(10**rng.randint(0, 30)), 10 ** rng.randint(0, 30))),
            repr(rng.uniform(-1, 1) * 10.0 ** rng.randint(-300, 300)),
            rng.choice(["nan", "-inf", "1e309", "-0", "0.0"]),
        ])  # fmt: skip
        value = ",".join(number() for _ in range(4)) if option == "--region" else number()
        found.append((option, value))
    return found


CASES = [(o, v) for o, values in OPTIONS.items() for v in values] + random_values(40)


@pytest.mark.parametrize("option, value", CASES)
def test_a_number_is_refused_in_the_options_terms_or_renders_finitely(tmp_path, option, value):
    (tmp_path / "scene.lua").write_text(SCRIPT)
    start = time.monotonic()
    argument = f"{option}{value}" if value.startswith("=") else None
    result = render(tmp_path, *((argument,) if argument else (option, value)))
    assert time.monotonic() - start < 60
    assert "Traceback" not in result.stderr and "fault" not in result.stderr, result.stderr
    if result.returncode == 0:
        picture = np.asarray(Image.open(tmp_path / "o.png"))
        assert picture.shape[2] == 4 and picture[..., 3].max() == 255
        return
    assert result.returncode in (1, 2), result.stderr
    last = result.stderr.strip().splitlines()[-1]
    assert option in last, last  # named in the option's terms
    assert not (tmp_path / "o.png").exists()


def test_a_long_running_script_says_at_once_how_to_stop_it_and_where_its_limit_is(tmp_path):
    (tmp_path / "scene.lua").write_text("local n = 0\nwhile true do n = n + 1 end\n")
    process = subprocess.Popen(
        [sys.executable, "-m", "core", "render", "scene.lua", "--script-seconds", "60"],
        cwd=tmp_path, stderr=subprocess.PIPE, text=True,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
    )  # fmt: skip
    start = time.monotonic()
    line = process.stderr.readline()
    waited = time.monotonic() - start
    process.kill()
    process.wait()
    assert waited < 20  # at once, not at the limit
    assert line.strip() == (
        "scene.lua is still running after 3 s: Ctrl-C stops it; it is stopped at 60 s "
        "(--script-seconds raises or lowers that)"
    )
