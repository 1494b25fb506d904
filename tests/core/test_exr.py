"""core.exr's files read back by the tests' own reader (tests/support/exr.py, itself checked
against the files Blender writes, and core.exr's files against Blender's reader, in
tests/blender/test_exr_files.py): values bit for bit, names, metadata, and blocks that do not
compress stored raw."""

import numpy as np

from core.exr import write_exr
from tests.support.exr import read_exr


def test_channels_and_metadata_come_back_bit_for_bit(tmp_path):
    rng = np.random.default_rng(7)
    noise = rng.standard_normal((37, 23)).astype(np.float32)  # does not compress: raw blocks
    ramp = np.linspace(0.0, 1.0, 37 * 23, dtype=np.float32).reshape(37, 23)  # compresses
    special = np.array([[0.0, -0.0, 1e10, np.float32(3.4e38)]], np.float32)
    path = write_exr(tmp_path / "t.exr", {"R": noise, "Depth.Z": ramp},
                     {"cryptomatte/abcdef0/name": "ViewLayer.CryptoObject"})  # fmt: skip
    channels, metadata = read_exr(path)
    assert sorted(channels) == ["Depth.Z", "R"]
    assert np.array_equal(channels["R"], noise) and np.array_equal(channels["Depth.Z"], ramp)
    assert metadata == {"cryptomatte/abcdef0/name": "ViewLayer.CryptoObject"}
    assert path.stat().st_size < noise.nbytes + ramp.nbytes  # the ramp was compressed
    channels, _ = read_exr(write_exr(tmp_path / "s.exr", {"Y": special}))
    assert np.array_equal(channels["Y"], special)
