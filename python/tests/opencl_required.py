"""What a test that needs an OpenCL device does on a machine without one: SKIP locally; under CI (the
CI environment variable set, as .ci/run sets it) it runs and FAILS, so that a broken OpenCL install
cannot pass as a green run of skipped tests (tests/opencl_required.h does the same for C++)."""
import os

import pytest

import phongcl


def running_in_ci():
    return os.environ.get("CI", "") not in ("", "0", "false")


needs_device = pytest.mark.skipif(not phongcl.devices() and not running_in_ci(),
                                  reason="no OpenCL device on this machine (a run with CI set fails here)")
