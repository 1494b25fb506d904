"""Every platform's zip, as `make addon` builds it (without the kernels, which only the
Linux zip ships and test_extension checks): its manifest names its one platform and exactly
the wheels it carries, and those wheels are for that platform and give every package to
each Python its Blenders run. Read from the wheels' own file names, as pip and Blender do."""

import re
import tomllib
import zipfile

import pytest
from packaging.utils import parse_wheel_filename

from blender_addon.packaging.build_extension import PLATFORMS, build
from tests.blender.conftest import ROOT

# A wheel's platform tag, by the Blender platform it is for
PLATFORM_TAG = {
    "linux-x64": r"manylinux(\d+|_\d+_\d+)_x86_64",
    "windows-x64": r"win_amd64",
    "macos-arm64": r"macosx_\d+_\d+_(arm64|universal2)",
    "macos-x64": r"macosx_\d+_\d+_(x86_64|universal2|intel)",
}


@pytest.fixture(scope="module")
def zips(tmp_path_factory):
    out = tmp_path_factory.mktemp("dist")
    return build(out, levels=(), wheel_cache=ROOT / ".cache" / "wheels")


def runs_on(tag, python: str) -> bool:
    """Whether a wheel tag serves CPython `python` ("3.13"): its own cpXY, or the stable
    ABI from an older one."""
    major, minor = map(int, python.split("."))
    found = re.fullmatch(r"cp(\d)(\d+)", tag.interpreter)
    if not found or int(found[1]) != major:
        return False
    if tag.abi == "abi3":
        return int(found[2]) <= minor
    return int(found[2]) == minor and tag.abi == tag.interpreter


def test_one_zip_per_platform(zips):
    assert sorted(zips) == sorted(p.name for p in PLATFORMS)


@pytest.mark.parametrize("platform", PLATFORMS, ids=lambda p: p.name)
def test_each_zip_carries_its_platforms_wheels_for_every_python(zips, platform):
    with zipfile.ZipFile(zips[platform.name]) as archive:
        names = archive.namelist()
        manifest = tomllib.loads(archive.read("blender_manifest.toml").decode())
    assert manifest["platforms"] == [platform.name]
    carried = sorted(n for n in names if n.startswith("wheels/"))
    assert sorted(w.removeprefix("./") for w in manifest["wheels"]) == carried
    assert not any(n.startswith("kernel_cache/") for n in names)
    packages = {re.sub(r"==.*", "", w).lower() for w in platform.wheels}
    for python in platform.pythons:
        served = set()
        for wheel in carried:
            package, _, _, tags = parse_wheel_filename(wheel.removeprefix("wheels/"))
            assert all(re.fullmatch(PLATFORM_TAG[platform.name], t.platform) for t in tags), wheel
            if any(runs_on(t, python) for t in tags):
                served.add(str(package))
        assert served == packages, f"Python {python} on {platform.name}: {served} of {packages}"
    for wheel in carried:
        _, _, _, tags = parse_wheel_filename(wheel.removeprefix("wheels/"))
        assert any(runs_on(t, p) for t in tags for p in platform.pythons), wheel  # none extra
    if platform.blender_version_max:
        assert manifest["blender_version_max"] == platform.blender_version_max
