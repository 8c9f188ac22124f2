"""Golden-output tests of rule programs (`epuckc test` and the pytest
plugin): the case model and its options (case.py: a rule file with its
inputs and expected outputs found by name beside it, `NAME.toml` and a
folder's `epuckc-test.toml`), property checks over a run's JSON trace
(props.py), comparison with tolerances, trimmed diffs and the point where
two traces diverge (compare.py), running cases in parallel and blessing
their expected files (runner.py), and the pytest plugin (plugin.py, which
only pytest loads, through the `pytest11` entry point).

A case's run is `epuckc run` in a child process: its standard output is
the readable trace a user sees, byte for byte, and children run in
parallel.

May import: base, diagnostics, check, emit, build, sim.
"""
