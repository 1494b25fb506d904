"""Writing the command line's picture and pass files whole, or not at all.

Each file is written into a staging folder beside its target and renamed into place when all
are complete: readers never see half a file, and a failure (a full disk, Ctrl-C) leaves none
of them. Before anything renders, `check_writable` tries the target's folder, so a path that
cannot take the picture is named at once rather than after the render.
"""

from __future__ import annotations

import errno
import os
import shutil
import tempfile
from pathlib import Path

from .image_io import save_png
from .pass_files import write_pass_files

# What a user can do about each reason the system gives (its own words come first)
_HINTS = {
    errno.ENAMETOOLONG: "use a shorter file or folder name",
    errno.EACCES: "choose a folder you may write to",
    errno.EPERM: "choose a folder you may write to",
    errno.EROFS: "choose a folder on another disk",
    errno.ENOSPC: "free some space on that disk, or write elsewhere",
    errno.EDQUOT: "your disk quota is used up; free some space, or write elsewhere",
    errno.EFBIG: "the file is larger than this system lets a process write",
    errno.ELOOP: "the path is a loop of symbolic links",
    errno.EISDIR: "a folder of that name is in the way",
}


class OutputError(Exception):
    """The picture cannot be written where asked; the message names the path and why."""


def reason(error: OSError, target: Path | None = None) -> str:
    """The system's reason, in its words, and what to do about it where that is plain."""
    said = error.strerror or str(error)
    if error.errno in (errno.ENOTDIR, errno.EEXIST) and target is not None:
        return _not_a_folder(target) or said
    hint = _HINTS.get(error.errno)
    return f"{said}; {hint}" if hint else said


def _not_a_folder(target: Path) -> str | None:
    """What stands where a folder of target's path should be: a file, or a link to none."""
    for part in reversed(target.parents):
        if not os.path.lexists(part):
            return None
        try:
            if part.is_dir():
                continue
        except OSError:
            pass
        if part.is_symlink():
            return f"{part} is a symbolic link to no folder (a loop, or to nothing)"
        return f"{part} is a file, not a folder"
    return None


def check_writable(target: Path, label: str) -> None:
    """Raise OutputError unless a file of target's name can be made in its folder (made if
    missing). `label` is how the user named it: "-o out.png"."""
    try:
        if target.is_dir():
            raise OutputError(f"{label}: is a folder; name a .png file to write the image to")
        target.parent.mkdir(parents=True, exist_ok=True)
        staging = Path(tempfile.mkdtemp(prefix=".whitted-", dir=target.parent))
        try:
            (staging / target.name).touch()  # the name's length, the folder's permission
        finally:
            shutil.rmtree(staging, ignore_errors=True)
    except OSError as error:
        raise OutputError(
            f"{label}: cannot write the image there: {reason(error, target)}"
        ) from None


def write_whole(image, target: Path, label: str, passes=None, names=None) -> None:
    """Write the PNG and its pass files beside their targets, then rename them all into place.
    Raises OutputError, having left nothing behind."""
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        staging = Path(tempfile.mkdtemp(prefix=".whitted-", dir=target.parent))
    except OSError as error:
        raise OutputError(
            f"{label}: cannot write the image there: {reason(error, target)}"
        ) from None
    try:
        written = [save_png(image, staging / target.name)]
        written += write_pass_files(staging / target.name, passes or {}, names or {})
        # As files made by open() would be (0644 under the usual umask), not mkstemp's 0600
        umask = os.umask(0)
        os.umask(umask)
        for path in written:
            os.chmod(path, 0o666 & ~umask)
        for path in written:
            os.replace(path, target.parent / path.name)
    except OSError as error:
        raise OutputError(f"{label}: the image was not written: {reason(error, target)}") from None
    finally:
        shutil.rmtree(staging, ignore_errors=True)
