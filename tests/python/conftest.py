import os
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
FIXTURE = ROOT / "tests" / "fixtures" / "two-planes"
SEPTA = ROOT / "target" / "release" / "septa"
# The shared test data (../shared/data beside the clone, as in CI; or
# SEPTA_SHARED; or the machine-wide copy).
SHARED = ROOT.parent / "shared" / "data"
for cand in ([Path(os.environ["SEPTA_SHARED"])] if os.environ.get("SEPTA_SHARED") else []) + [
        ROOT / "shared" / "data", ROOT.parent / "shared" / "data", Path("/work/shared/data")]:
    if (cand / "isn").is_dir():
        SHARED = cand
        break
ISN = SHARED / "isn"
sys.path.insert(0, str(ROOT / "scripts"))

# In CI (CI=true, set by .ci/run) nothing may be skipped: a skip there means
# a test silently did not run.
IN_CI = os.environ.get("CI", "").lower() in ("1", "true", "yes")


def need(path, what):
    """Skips the calling test when ``path`` is missing (outside CI), fails it
    in CI, where every input must be present."""
    path = Path(path)
    if path.exists():
        return path
    msg = f"{what} not found at {path}"
    if IN_CI:
        pytest.fail(msg + " (CI must provide it)", pytrace=False)
    pytest.skip(msg)


_skipped = []


def pytest_runtest_logreport(report):
    if report.skipped:
        _skipped.append(report.nodeid)


def pytest_collectreport(report):
    if report.skipped:
        _skipped.append(report.nodeid)


def pytest_sessionfinish(session, exitstatus):
    if IN_CI and _skipped:
        sys.stderr.write(f"\nCI: {len(_skipped)} skipped (skips fail in CI): {', '.join(_skipped)}\n")
        session.exitstatus = pytest.ExitCode.TESTS_FAILED


@pytest.fixture
def fixture_net():
    import septa

    return septa.load(FIXTURE)
