import pytest


@pytest.fixture(autouse=True)
def _private_cache(tmp_path_factory, monkeypatch):
    """Host builds go to a cache of this test session, not the user's."""
    monkeypatch.setenv("EPUCKC_CACHE_DIR", str(tmp_path_factory.getbasetemp() / "epuckc-cache"))
