# The module under test is the one in the build tree (PYTHONPATH, set by
# ctest); the rendered dataset is shared by the tests of one session.
import os
import subprocess
import tempfile

import pytest


@pytest.fixture(scope="session")
def scratch():
    with tempfile.TemporaryDirectory(prefix="depot_pytest_") as folder:
        yield folder


@pytest.fixture(scope="session")
def walking(scratch):
    """30 frames of walking_xyz at 160x120, rendered from Python."""
    import depot

    out = os.path.join(scratch, "walking")
    summary = depot.render("depot_walking_xyz", out, frames=30, seed=1, width=160)
    assert summary["frames"] == 30
    return out


@pytest.fixture(scope="session")
def depot_program():
    return os.path.join(os.environ["DEPOT_BINARY_DIR"], "tools", "depot", "depot")
