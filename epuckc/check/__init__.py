"""The checker: names, values and units, the robot block, externs, calls,
events and rules, modes and arbitration; the second stage.

checker.py is the orchestrator: `Checker` holds the state (as the records of
state.py: the declarations, the facts found, the memories of what is said
once) and the order of work, and takes its methods from one mixin per
concern (names.py,
externs.py, robot.py, values.py, exprs.py, variables.py, ranges.py,
calls.py, rules.py, overflow.py, branches.py; exprs.py calls the
functions of arrays.py, bits.py and functions.py with the checker); modes.py and
arbitration.py are
the whole-program analyses (modes entered, W009 races; races.py reports
them); conditions.py reads
conditions as comparisons of variables and readings (for W009 and guards).
reeval.py computes an assignment's value again, for the intervals ranges.py's
fixpoint asks, from the plan of its first evaluation.
program.py is its output, a `CheckedProgram` whose calls carry runtime
integers; messages.py the shared wording; cnames.py the C names a user's
extern may not take; splice.py how named actions splice into steps;
frontend.py runs read + parse + check as one call (`check_file`).

May import: base, diagnostics, stdlib, syntax.
"""
