"""Property: every program the checker accepts builds and runs.

Random programs with hostile names (C keywords, libc and runtime names,
look-alikes of the generated names, reserved identifiers, odd file names),
random geometry and values: each one the checker accepts must compile with
gcc and 16-bit avr-gcc under -Werror and run clean under ASan/UBSan.
CI runs EPUCKC_PROPERTY_EXAMPLES examples (default 25);
bench/fuzz_campaign.py runs a long campaign."""
import os

from tests.support.hostile import Outcome, build_outcomes, programs

EXAMPLES = int(os.environ.get("EPUCKC_PROPERTY_EXAMPLES", "25"))


def test_accepted_programs_build_and_run_clean(tmp_path_factory):
    outcomes = build_outcomes(tmp_path_factory, programs(), EXAMPLES, "property")
    # the generator must not be so hostile that nothing is ever built
    assert outcomes.count(Outcome.BUILT) > 0, outcomes
