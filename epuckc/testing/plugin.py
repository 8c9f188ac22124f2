"""The pytest plugin: `pytest DIR` runs the cases of `epuckc test DIR` as
test items, one per rule file, with the same comparison and diffs;
`--bless` writes the expected files; pytest's own `--junitxml` gives the
report. Registered as the `pytest11` entry point `epuckc`, so pytest loads
it wherever epuckc is installed, and nothing else imports it (pytest stays
an optional dependency of epuckc).

Which rule files are cases: those in a folder that holds an
`epuckc-test.toml` (the folder's defaults; it may be empty), or below such
a folder, up to pytest's root folder. A rule file anywhere else is not
collected: the `.epk` files of a project's own test data (epuckc's
tests/) stay out of its pytest run.
"""
from __future__ import annotations

from pathlib import Path

import pytest

from .case import FOLDER_FILE, UsageError, load_case, _folder_file


def pytest_addoption(parser):
    group = parser.getgroup("epuckc", "golden-output tests of e-puck rule files")
    group.addoption("--bless", action="store_true", default=False,
                    help="epuckc cases: write or rewrite the expected files (NAME.trace, "
                         "NAME.diag, NAME.c) from what the cases produce now")


def _marked(path: Path, root: Path):
    """The `epuckc-test.toml` that makes `path` a case, or None."""
    stop = root if (root == path.parent or root in path.parents) else path.parent
    return _folder_file(path.parent, stop)


def pytest_collect_file(file_path: Path, parent):
    if file_path.suffix != ".epk":
        return None
    marker = _marked(file_path, Path(str(parent.config.rootpath)))
    if marker is None:
        return None
    return EpuckcFile.make(parent, path=file_path, marker=marker)


class EpuckcFile(pytest.File):
    @classmethod
    def make(cls, parent, path, marker):
        node = cls.from_parent(parent, path=path)
        node.marker = marker
        return node

    def collect(self):
        yield EpuckcCase.from_parent(self, name=self.path.name)


class CaseFailed(Exception):
    """A case's report, shown as it is."""


class EpuckcCase(pytest.Item):
    # pytest-lsp's pytest_runtest_call wrapper (an epuckc test dependency)
    # returns without yielding for an item with no `funcargs`, which breaks
    # every non-Python item; a case has no fixtures, so none are given.
    funcargs: dict = {}

    def runtest(self):
        from .runner import FAILED, SKIPPED, describe, run_case
        try:
            case = load_case(self.path, self.parent.marker.parent,
                             base=Path(str(self.config.rootpath)))
        except UsageError as exc:
            raise CaseFailed(str(exc)) from None
        outcome = run_case(case, bless=self.config.getoption("bless"),
                           bless_hint="`pytest --bless`")
        if outcome.status == SKIPPED:
            pytest.skip(outcome.reason)
        text = describe(outcome)
        if outcome.written:
            # blessing is news: show it with -rP / in the report's sections
            self.add_report_section("call", "blessed", text)
        if outcome.status == FAILED:
            raise CaseFailed(text)

    def repr_failure(self, excinfo, style=None):
        if isinstance(excinfo.value, CaseFailed):
            return str(excinfo.value)
        return super().repr_failure(excinfo, style=style)

    def reportinfo(self):
        return self.path, None, f"epuckc case {self.path.name}"


__all__ = ["FOLDER_FILE", "pytest_addoption", "pytest_collect_file"]
