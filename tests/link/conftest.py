"""A real stream of the robot's tracer, made once for the tests of its
reader: examples/bump_counter.epk with its scenario, built for the 16-bit
AVR with the tracer and run on simavr."""
import pytest

from conftest import REPO


@pytest.fixture(scope="session")
def bump_stream(tmp_path_factory):
    """(table, the UART's bytes, the records they decode to)."""
    from tests.support.robot_trace import decode, program_of, require_simavr, robot_run
    from epuckc.build.trace_table import trace_table
    require_simavr()
    program = program_of(REPO / "examples" / "bump_counter.epk")
    run = robot_run(program, REPO / "examples" / "bumps.scn", 6000)
    table = trace_table(program)
    return table, run.uart, decode(table, run.uart)
