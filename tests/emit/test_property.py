"""Property: every program the checker accepts builds and runs.

Random programs with hostile names (C keywords, libc and runtime names,
look-alikes of the generated names, reserved identifiers, odd file names),
random geometry and values: each one the checker accepts must compile with
gcc and 16-bit avr-gcc under -Werror and run clean under ASan/UBSan.
CI runs EPUCKC_PROPERTY_EXAMPLES examples (default 25);
bench/fuzz_campaign.py runs a long campaign."""
import itertools
import os

from hypothesis import HealthCheck, given, settings

from tests.conftest import require_tool

from tests.support.hostile import Outcome, check_one, programs, runtime_objects

EXAMPLES = int(os.environ.get("EPUCKC_PROPERTY_EXAMPLES", "25"))


def test_accepted_programs_build_and_run_clean(tmp_path_factory):
    cc = require_tool("cc")
    avr = require_tool("avr-gcc")
    runtime = runtime_objects(tmp_path_factory.mktemp("runtime"), cc)
    counter = itertools.count()
    outcomes = []

    @settings(max_examples=EXAMPLES, deadline=None, database=None,
              suppress_health_check=list(HealthCheck))
    @given(programs())
    def prop(program):
        work = tmp_path_factory.getbasetemp() / "property" / str(next(counter))
        outcomes.append(check_one(program, work, cc, avr, runtime))

    prop()
    # the generator must not be so hostile that nothing is ever built
    assert outcomes.count(Outcome.BUILT) > 0, outcomes
