import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
FIXTURE = ROOT / "tests" / "fixtures" / "two-planes"
ISN = ROOT.parent / "shared" / "data" / "isn"
for cand in (ROOT / "shared" / "data" / "isn", ROOT.parent / "shared" / "data" / "isn", Path("/work/shared/data/isn")):
    if cand.is_dir():
        ISN = cand
        break
sys.path.insert(0, str(ROOT / "scripts"))


@pytest.fixture
def fixture_net():
    import septa

    return septa.load(FIXTURE)
