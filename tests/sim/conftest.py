"""What the simulation's tests share: `enki`, for the modules whose every
test runs a world (`pytestmark = pytest.mark.usefixtures("enki")`):
skipped without Enki's headers, library and a C++ compiler, failed in CI
(tests/conftest.py require_enki). Helpers to import are in
tests/support/world.py."""
import pytest

from tests.conftest import require_enki


@pytest.fixture
def enki():
    require_enki()
