"""A farm job's plan, without Dask: borders cover every pixel once, frames and chunks and
Blender's #### names, and clear refusals of bad arguments."""

import numpy as np
import pytest

from core.farm.jobs import (
    Border,
    FarmError,
    borders,
    chunks,
    frame_path,
    parse_frames,
    parse_split,
    plan,
)


@pytest.mark.parametrize("size, split", [((48, 36), (4, 4)), ((37, 23), (5, 3)), ((7, 5), (7, 5))])
def test_borders_cover_every_pixel_exactly_once(size, split):
    width, height = size
    covered = np.zeros((height, width), int)
    parts = borders(width, height, *split)
    assert len(parts) == split[0] * split[1]
    for b in parts:
        covered[b.y : b.y + b.height, b.x : b.x + b.width] += 1
        assert b.width >= width // split[0] and b.height >= height // split[1]
    assert np.all(covered == 1)


def test_frames_chunks_and_names():
    assert parse_frames("1-4") == (1, 2, 3, 4)
    assert parse_frames("3,1-2,2") == (3, 1, 2)
    assert list(chunks((1, 2, 3, 4, 5), 2)) == [(1, 2), (3, 4), (5,)]
    assert parse_split("4x3") == (4, 3)
    assert frame_path("out/frame_####.png", 7).as_posix() == "out/frame_0007.png"
    assert frame_path("a##/b_##.png", 123).as_posix() == "a##/b_123.png"  # the last run
    assert frame_path("still.png", 5).as_posix() == "still.png"


def test_a_plan_is_a_task_per_border_or_per_chunk():
    split = plan("s.blend", (1, 2), (40, 30), (2, 2), chunk=1)
    assert len(split) == 8 and {t.frames for t in split} == {(1,), (2,)}
    assert split[0].border == Border(0, 0, 20, 15)
    assert split[0].describe() == "border x 0-19, y 0-14 of frame 1"
    whole = plan("s.blend", (1, 2, 3), None, (1, 1), chunk=2)
    assert [t.frames for t in whole] == [(1, 2), (3,)] and whole[1].describe() == "frame 3"
    assert len({t.key for t in split}) == len(split)


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: parse_split("4by4"), "give columns x rows"),
        (lambda: parse_frames("5-2"), "runs backwards"),
        (lambda: parse_frames("a-b"), "give frames as"),
        (lambda: borders(4, 4, 8, 1), "only 4 x 4 pixels"),
        (lambda: chunks((1,), 0), "at least 1"),
    ],
)
def test_bad_arguments_are_refused_clearly(call, message):
    with pytest.raises(FarmError, match=message):
        call()
