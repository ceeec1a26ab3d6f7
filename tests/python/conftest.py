"""Fixtures of the Python suite: one backend of each kind for the whole session, the command
line to compare with, the repository's paths. A backend listed in MASAV_REQUIRE_BACKENDS (CI:
cpu,vulkan) fails the tests that need it when absent; any other absent one skips them, with the
reason printed."""
import os
import pathlib

import pytest

import masav

SOURCE_DIR = pathlib.Path(__file__).resolve().parents[2]
REQUIRED = {b for b in os.environ.get("MASAV_REQUIRE_BACKENDS", "").split(",") if b}


def open_backend(name):
    status = {s.name: s for s in masav.backends()}[name]
    if not status.available:
        if name in REQUIRED:
            pytest.fail(f"{name} is required (MASAV_REQUIRE_BACKENDS) but absent: {status.reason}")
        pytest.skip(f"{name} absent: {status.reason}")
    return masav.Backend(name)


@pytest.fixture(scope="session")
def cpu():
    return masav.Backend("cpu")


@pytest.fixture(scope="session")
def vulkan():
    return open_backend("vulkan")


@pytest.fixture(scope="session")
def cuda():
    return open_backend("cuda")


@pytest.fixture(scope="session")
def masav_cli():
    path = os.environ.get("MASAV_CLI", "")
    if not path:
        pytest.skip("no masav command line given (run_pytest.sh's MASAV argument)")
    return path


@pytest.fixture(scope="session")
def source_dir():
    return SOURCE_DIR
