"""Writing the output, hostile cases: every way the system can refuse the picture, run as a
user runs the command line. Each ends with `error: -o PATH: ...` (or the script's gr.render
file) giving the system's reason, exit 1, no traceback, and nothing written: no picture, no
pass file, no staging folder.

A read-only folder and a full disk are real file systems (tmpfs mounts), which needs root;
elsewhere those two cases are skipped."""

import contextlib
import os
import subprocess
from pathlib import Path

import pytest

from tests.support import hostile

SCRIPT = """r = gr.node('r')
r:add_child(gr.sphere('s'))
gr.render(r, '{file}', {size}, {size}, {{0, 0, 5}}, {{0, 0, -1}}, {{0, 1, 0}}, 50, {{0, 0, 0}},
          {{gr.light({{3, 3, 3}}, {{1, 1, 1}}, {{1, 0, 0}})}})
"""


def run(folder: Path, *args, file="o.png", size=8):
    """The command line, leaving no temporary file or process (checked by `hostile.run`)."""
    (folder / "scene.lua").write_text(SCRIPT.format(file=file, size=size))
    return hostile.run(folder, "scene.lua", *args)


def tree(folder: Path) -> list[str]:
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*"))


@contextlib.contextmanager
def mounted(folder: Path, options: str):
    """A tmpfs at `folder`, unmounted afterwards; skips the test where mounting is not ours."""
    folder.mkdir()
    if os.geteuid() != 0:
        pytest.skip("a read-only or full file system needs a tmpfs mount, which needs root")
    done = subprocess.run(["mount", "-t", "tmpfs", "-o", options, "tmpfs", str(folder)],
                          capture_output=True, text=True)  # fmt: skip
    if done.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs here: {done.stderr.strip()}")
    try:
        yield folder
    finally:
        subprocess.run(["umount", str(folder)], check=True)


def fill(folder: Path, leave: int) -> None:
    """Fill the file system at `folder` until `leave` bytes are free."""
    free = os.statvfs(folder).f_bavail * os.statvfs(folder).f_frsize
    (folder / "filler").write_bytes(b"\0" * max(0, free - leave))


def refused(result, label: str, reason: str) -> None:
    assert result.returncode == 1, result.stdout + result.stderr
    assert "Traceback" not in result.stderr, result.stderr
    last = result.stderr.strip().splitlines()[-1]
    assert last.startswith(f"error: {label}: "), last
    assert reason in last, last


# (case, what to set up in the folder, the -o path, the system's reason, the hint)
LONG_NAME = "n" * 300 + ".png"
CASES = [
    ("a name too long", {}, LONG_NAME, "File name too long", "use a shorter"),
    ("a path too long", {}, "d/" * 2100 + "o.png", "File name too long", "use a shorter"),
    ("the parent is a file", {"taken": "file"}, "taken/o.png", "taken is a file, not a folder", ""),
    ("a grandparent is a file", {"taken": "file"}, "taken/deeper/o.png",
     "taken is a file, not a folder", ""),
    ("the parent is a link loop", {"loop": "loop"}, "loop/o.png",
     "loop is a symbolic link to no folder", ""),
    ("the parent is a link to nothing", {"gone": "dangling"}, "gone/o.png",
     "gone is a symbolic link to no folder", ""),
    ("the picture's name is a folder", {"o.png": "folder"}, "o.png", "is a folder", ".png file"),
    ("a folder the system keeps", {}, "/proc/whitted/o.png", "No such file or directory", ""),
]  # fmt: skip


def make(folder: Path, things: dict) -> None:
    for name, kind in things.items():
        path = folder / name
        if kind == "file":
            path.write_text("not a folder")
        elif kind == "folder":
            path.mkdir()
        elif kind == "loop":
            path.symlink_to(f"{name}.2")
            (folder / f"{name}.2").symlink_to(name)
        elif kind == "dangling":
            path.symlink_to("nowhere")


@pytest.mark.parametrize("case, things, target, reason, hint", CASES, ids=[c[0] for c in CASES])
def test_a_path_that_cannot_take_the_picture_is_named_before_rendering(
    tmp_path, case, things, target, reason, hint
):
    make(tmp_path, things)
    (tmp_path / "scene.lua").touch()
    before = tree(tmp_path)
    result = run(tmp_path, "-o", target)
    refused(result, f"-o {target}", reason)
    assert hint in result.stderr
    assert "tiles" not in result.stderr  # named before rendering, not after
    assert tree(tmp_path) == before


def test_the_scripts_own_file_is_named_as_the_script_names_it(tmp_path):
    (tmp_path / "taken").write_text("not a folder")
    result = run(tmp_path, file="taken/o.png")
    refused(result, f"scene.lua: gr.render's file {tmp_path / 'taken' / 'o.png'}",
            "taken is a file, not a folder")  # fmt: skip


def test_a_read_only_folder(tmp_path):
    with mounted(tmp_path / "ro", "ro,size=64k"):
        result = run(tmp_path, "-o", "ro/o.png")
        refused(result, "-o ro/o.png", "Read-only file system; choose a folder on another disk")
        assert tree(tmp_path / "ro") == []


@pytest.mark.parametrize(
    "leave, passes",
    [(0, ()), (2048, ("--passes", "all"))],
    ids=["no room for the picture", "room for the PNG, not its passes"],
)
def test_a_full_disk_leaves_nothing_half_written(tmp_path, leave, passes):
    """The disk fills while writing: no picture, no pass file, no staging folder stays. With
    2 KiB free the 64 x 64 PNG fits and its EXR passes do not: the PNG goes too."""
    with mounted(tmp_path / "full", "size=256k") as full:
        fill(full, leave)
        result = run(tmp_path, "-o", "full/o.png", *passes, size=64)
        refused(result, "-o full/o.png", "No space left on device; free some space")
        assert "the image was not written" in result.stderr
        assert tree(full) == ["filler"]


def test_the_same_command_writes_the_picture_where_it_can(tmp_path):
    """The cases above fail for their paths, not for the command: here it writes."""
    result = run(tmp_path, "-o", "fine/o.png")
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "fine" / "o.png").stat().st_size > 0
    assert tree(tmp_path / "fine") == ["o.png"]
