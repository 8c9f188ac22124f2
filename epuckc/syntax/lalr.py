"""A small LALR(1) driver over tables that Lark computes from grammar/epuck.lark.

Lark builds the tables (which takes tens of milliseconds, and importing Lark
itself as long again), and they are kept in a cache file between runs; the
common run then loads plain tuples with `marshal` and never imports Lark.
The driver shapes its results the way Lark's tree builder does with
`maybe_placeholders=True` and `propagate_positions=True`: tokens whose names
start with `_` are dropped, rules whose names start with `_` are spliced into
their parent, a missing `[optional]` gives None, and every node's span runs
from its first to its last token, dropped tokens included. Instead of
building a tree and transforming it afterwards, each reduction calls the
transformer's method for the rule at once: callback(meta, children).

The cache file is keyed on the grammar text and the Lark, Python and format
versions, so an edited grammar is honoured on the next run. When no cache
folder is writable the tables are built in memory each time.
"""
from __future__ import annotations

import os
import sys
import zlib
from operator import itemgetter


FORMAT = 2          # bump when the table layout below changes
NO_ACTION = -(2 ** 31)  # an empty cell of the packed table


class ParseError(Exception):
    """The token `token` cannot come next; `expected` are the terminal
    names that could have (as Lark says: where the parser stopped), and
    `before` those that could have come after the last token, before the
    reductions `token` caused (LALR merges the lookaheads of states alike:
    a `do` may end a number's `value` that a unit or an operator could have
    continued), which the messages list."""

    def __init__(self, token, expected, before=None):
        super().__init__(f"unexpected {token.type}")
        self.token = token
        self.expected = expected
        self.before = expected if before is None else before | expected


class Meta:
    __slots__ = ("line", "column", "end_line", "end_column")

    def __init__(self, line, column, end_line, end_column):
        self.line = line
        self.column = column
        self.end_line = end_line
        self.end_column = end_column


class Tables:
    """names: every symbol's name, a symbol being its index;
    packed: the action table, one native int32 per state and symbol
            (state * len(names) + symbol): a code >= 0 shifts to (or, for
            a rule's symbol, goes to) that state, a code < 0 reduces by
            rule -code - 1, NO_ACTION is an error;
    states: the same as state -> {symbol name: code}, made when first used
            (the C front end reads `packed` as it is);
    rules: (origin, callback name or None to splice, size,
            ((index, splice, nones_before), ...), nones_after)."""

    def __init__(self, data):
        self.names, self.packed, self.start, self.end, self.rules = data
        self._states = None
        self.bound = {}     # id(callbacks) -> (callbacks, _plan(rules, callbacks))

    @property
    def states(self) -> dict:
        if self._states is None:
            from array import array
            cells = array("i")
            cells.frombytes(self.packed)
            names, width = self.names, len(self.names)
            self._states = {
                state: {names[sym]: code for sym, code in
                        enumerate(cells[state * width:(state + 1) * width]) if code != NO_ACTION}
                for state in range(len(cells) // width)}
        return self._states


def pack(states: dict, rules, extra=()) -> tuple:
    """(names, packed) of a table given as state -> {symbol name: code};
    `extra` names symbols to have a column though the table never uses
    them."""
    from array import array
    names = set(extra)
    for row in states.values():
        names.update(row)
    names.update(rule[0] for rule in rules)
    names = sorted(names)
    index = {name: i for i, name in enumerate(names)}
    if sorted(states) != list(range(len(states))):
        raise ValueError("the LALR states are not numbered 0..n-1")
    cells = array("i", [NO_ACTION]) * (len(states) * len(names))
    for state, row in states.items():
        for name, code in row.items():
            cells[state * len(names) + index[name]] = code
    return names, cells.tobytes()


# ---- building the tables with Lark ------------------------------------------------

def _child_filter(expansion, empty_indices):
    """Lark's maybe_create_child_filter (parse_tree_builder.py), as data."""
    if empty_indices:
        ones = "".join(str(int(b)) for b in empty_indices).split("0")
        empties = [len(x) for x in ones]
    else:
        empties = [0] * (len(expansion) + 1)
    include, nones = [], 0
    for i, sym in enumerate(expansion):
        nones += empties[i]
        if not (sym.is_term and sym.filter_out):
            include.append((i, bool((not sym.is_term) and sym.name.startswith("_")), nones))
            nones = 0
    return tuple(include), nones + empties[len(expansion)]


def build_tables(grammar: str, start: str):
    """Run Lark's LALR analysis and return the tables as plain data."""
    from lark import Lark
    from lark.lexer import Lexer
    from lark.parsers.lalr_analysis import Shift

    class _NoLexer(Lexer):
        def __init__(self, conf):
            pass

        def lex(self, data):
            return iter(data)

    lark = Lark(grammar, parser="lalr", lexer=_NoLexer, start=start,
                propagate_positions=True, maybe_placeholders=True)
    for rule in lark.rules:
        if rule.options.expand1 or rule.options.keep_all_tokens:
            raise ValueError(f"the LALR driver does not support `?` or `!` rules ({rule.origin.name})")
    table = lark.parser.parser.parser.parse_table
    rule_index, rules = {}, []

    def index_of(rule):
        if rule not in rule_index:
            rule_index[rule] = len(rules)
            include, after = _child_filter(rule.expansion, rule.options.empty_indices)
            name = str(rule.origin.name)
            callback = str(rule.alias or name)
            if name.startswith("_") and not rule.alias:
                callback = None
            rules.append((name, callback, len(rule.expansion), include, after))
        return rule_index[rule]

    states = {}
    for state, actions in table.states.items():
        row = {}
        for symbol, (action, arg) in actions.items():
            row[str(symbol)] = int(arg) if action is Shift else -index_of(arg) - 1
        states[state] = row
    return _canonical(states, int(table.start_states[start]), int(table.end_states[start]),
                      rules)


def _canonical(states: dict, start: int, end: int, rules: list) -> tuple:
    """The tables numbered independently of Lark's (which vary with the
    interpreter's hash seed), so that the same grammar always gives the
    same bytes: rules sorted (identical ones merged), states numbered in
    the order a breadth-first walk from the start state reaches them,
    symbols in name order."""
    order = sorted(set(rules), key=repr)
    new_rule = {i: order.index(rule) for i, rule in enumerate(rules)}
    number = {start: 0}
    queue = [start]
    for state in queue:
        for name in sorted(states[state]):
            code = states[state][name]
            if code >= 0 and code not in number:
                number[code] = len(number)
                queue.append(code)
    if end not in number:
        raise ValueError("the end state cannot be reached")
    renumbered = {number[state]: {name: number[code] if code >= 0 else -new_rule[-code - 1] - 1
                                  for name, code in states[state].items()}
                  for state in queue}
    rules = tuple(order)
    return pack(renumbered, rules) + (0, number[end], rules)


# ---- the cache ----------------------------------------------------------------------

def _lark_version() -> str:
    """Lark's version, read from its source rather than by importing it
    (importing Lark costs ~30 ms, importlib.metadata ~10 ms)."""
    import importlib.util
    import re
    try:
        spec = importlib.util.find_spec("lark")
        with open(spec.origin, encoding="utf-8") as f:
            found = re.search(r"__version__\s*(?::\s*str\s*)?=\s*['\"]([^'\"]+)", f.read())
        if found:
            return found.group(1)
    except Exception:
        pass
    import lark
    return lark.__version__


# ---- the tables shipped with the package ------------------------------------------

SHIPPED = "_parse_tables.py"


def tables_module(grammar: str, start: str) -> str:
    """The source of epuckc/syntax/_parse_tables.py: the tables Lark computes for
    `grammar`, with the grammar they were computed from. The packed table
    is kept little-endian, compressed, in base64."""
    import binascii
    names, packed, start_state, end_state, rules = build_tables(grammar, start)
    blob = binascii.b2a_base64(zlib.compress(_little_endian(packed), 9),
                               newline=False).decode("ascii")
    lines = "\n".join(blob[i:i + 76] for i in range(0, len(blob), 76))
    return (f'''"""The LALR tables of grammar/epuck.lark, as Lark computes them: made by
`python3 -m epuckc.syntax.lalr`, not by hand (see lalr.load_tables), so that
epuckc neither imports Lark nor builds them when it runs.
tests/syntax/test_lalr_vs_lark.py checks they are the grammar's."""
FORMAT = {FORMAT}
START_SYMBOL = {start!r}
GRAMMAR = {grammar!r}
NAMES = {tuple(names)!r}
START = {start_state}
END = {end_state}
RULES = {rules!r}
PACKED = """
{lines}
"""
''')


def _shipped(grammar: str, start: str):
    """The shipped tables, when they are the tables of `grammar`."""
    try:
        from . import _parse_tables as shipped
    except ImportError:
        return None
    if (shipped.FORMAT, shipped.START_SYMBOL, shipped.GRAMMAR) != (FORMAT, start, grammar):
        return None                 # the grammar was edited: the cache or Lark
    import binascii
    packed = _little_endian(zlib.decompress(binascii.a2b_base64(shipped.PACKED)))
    return Tables((shipped.NAMES, packed, shipped.START, shipped.END, shipped.RULES))


def _little_endian(packed: bytes) -> bytes:
    """A packed table, native <-> little-endian (the same swap both ways)."""
    if sys.byteorder == "little":
        return packed
    from array import array
    cells = array("i")
    cells.frombytes(packed)
    cells.byteswap()
    return cells.tobytes()


def load_tables(grammar: str, start: str) -> Tables:
    """The tables for `grammar`: shipped with the package, or else from the
    cache when it holds them, or else built with Lark (and cached)."""
    tables = _shipped(grammar, start)
    if tables is not None:
        return tables
    if os.environ.get("EPUCKC_NO_CACHE"):
        return Tables(build_tables(grammar, start))
    # The file is named by a checksum of everything the tables depend on and
    # holds that text itself, compared whole on loading: no hash collision
    # can hand back another grammar's tables (and hashlib, which takes ~3 ms
    # to import, is not needed).
    from ..base import cache
    key = "\0".join((grammar, start, str(FORMAT), _lark_version(), sys.version, sys.byteorder))
    path = cache.area("tables") / f"{cache.key_name(key.encode('utf-8'))}.marshal"
    data = cache.load(path)
    if isinstance(data, tuple) and len(data) == 6 and data[0] == key:
        return Tables(data[1:])
    data = build_tables(grammar, start)
    cache.store(path, (key,) + data)    # an unusable cache: built each time
    return Tables(data)


# ---- parsing --------------------------------------------------------------------------

class EndToken:
    """The `$END` token, placed where the last token ends."""
    type = "$END"
    value = ""

    def __init__(self, last):
        if last is None:
            self.line = self.column = self.end_line = self.end_column = 1
            self.start_pos = self.end_pos = 0
        else:
            self.line, self.column = last.end_line, last.end_column
            self.end_line, self.end_column = last.end_line, last.end_column
            self.start_pos = self.end_pos = last.end_pos


def _accepts(tables: Tables, stack: list, terminal: str) -> bool:
    """Whether `terminal` can be shifted from this stack, following the
    reductions it would cause (which a state's own row does not show)."""
    states, rules = tables.states, tables.rules
    stack = list(stack)
    for _ in range(10000):
        code = states[stack[-1]].get(terminal)
        if code is None:
            return False
        if code >= 0:
            return True
        origin, _, size, _, _ = rules[-code - 1]
        if size:
            del stack[-size:]
        stack.append(states[stack[-1]][origin])
        if terminal == "$END" and stack[-1] == tables.end:
            return True
    return False


def _stack_after(tables: Tables, tokens: list, n: int) -> list:
    """The parser's states right after shifting tokens[n - 1] (they parse)."""
    states, rules = tables.states, tables.rules
    stack = [tables.start]
    for token in tokens[:n]:
        while True:
            code = states[stack[-1]][token.type]
            if code >= 0:
                stack.append(code)
                break
            origin, _, size, _, _ = rules[-code - 1]
            if size:
                del stack[-size:]
            stack.append(states[stack[-1]][origin])
    return stack


def expected(tables: Tables, stack: list) -> set:
    """The terminals that can really come next. LALR merges states, so a
    state's row may list terminals that only fit in another context (a `}`
    after a number inside `sensor(...)`); those are left out."""
    row = tables.states[stack[-1]]
    return {t for t in row if t.isupper() and _accepts(tables, stack, t)}


PICK, ONE, NONE, GROW, GENERAL, PASS = range(6)


def passes_child(func) -> bool:
    """A callback marked `passes_child = True` gives its one child back as
    it is (`sum: term`, the levels of an expression without their
    operator): the drivers skip the call."""
    return getattr(func, "passes_child", False)


def _plan(rules, callbacks) -> list:
    """How to make each rule's value from the stack, decided once per table
    and set of callbacks: (origin, size, callback or None for a spliced
    `_rule`, how, arg, Nones after), where
    `how` says how the kept children are gathered:
      PICK    arg(values) with arg an itemgetter over offsets from the top
              of the stack, offset 0 being the None at its bottom (a
              missing `[optional]`); a tuple of two or more children
      ONE     the one child at offset arg, or None when arg is 0
      NONE    no child at all
      GROW    `_rule: _rule SEP item` (left recursion): the item at offset
              arg is appended to the list that is the first child, in place
      GENERAL anything else (a `_rule` spliced among other children)
      PASS    the one child at offset arg is the value itself (passes_child)."""
    plan = []
    for origin, callback, size, include, after in rules:
        func = callbacks[callback] if callback is not None else None
        splices = any(splice for _, splice, _ in include)
        if not splices:
            layout = []
            for i, _, nones in include:
                layout += [0] * nones + [i - size]
            layout += [0] * after
            if len(layout) >= 2:
                how, arg = PICK, itemgetter(*layout)
            elif len(layout) == 1:
                how, arg = ONE, layout[0]
            else:
                how, arg = NONE, None
        elif (callback is None and after == 0 and len(include) == 2 and include[0][:2] == (0, True)
              and not include[1][1] and include[0][2] == include[1][2] == 0):
            how, arg = GROW, include[1][0] - size
        else:
            how, arg = GENERAL, include
        if func is not None and passes_child(func) and size == 1 and after == 0 \
                and include == ((0, False, 0),):
            how, arg = PASS, -1
        plan.append((origin, size, func, how, arg, after))
    return plan


def parse(tables: Tables, tokens, callbacks, meta=Meta) -> object:
    """Parse a list of tokens (with .type, .line, .column, .end_line,
    .end_column); `callbacks` maps a rule's name or alias to f(meta, children),
    where meta = meta(line, column, end_line, end_column) is the rule's span
    and children a sequence shaped as Lark's tree builder shapes them."""
    states = tables.states
    plan = tables.bound.get(id(callbacks))
    if plan is None or plan[0] is not callbacks:
        plan = tables.bound[id(callbacks)] = (callbacks, _plan(tables.rules, callbacks))
    plan = plan[1]
    end_state = tables.end
    new_tuple = tuple.__new__
    tuple_meta = issubclass(meta, tuple)
    # Three stacks in step: the parser states, their values, and the index
    # of the first token each value covers. The bottom of `values` is the
    # None that stands for every missing `[optional]` (see _plan). A value's
    # span runs from its first token to the last token shifted so far.
    stack = [tables.start]
    values = [None]
    starts = [0]
    tokens = list(tokens)
    tokens.append(EndToken(tokens[-1] if tokens else None))
    index = -1
    for token in tokens:
        index += 1
        ttype = token.type
        while True:
            code = states[stack[-1]].get(ttype)
            if code is None:
                raise ParseError(token, expected(tables, stack),
                                 expected(tables, _stack_after(tables, tokens, index)))
            if code >= 0:
                stack.append(code)
                values.append(token)
                starts.append(index)
                break
            origin, size, func, how, arg, after = plan[-code - 1]
            if how == PASS:                 # `sum: term`: the term itself, where it is
                stack[-1] = states[stack[-2]][origin]
                if ttype == "$END" and stack[-1] == end_state:
                    return values[-1]
                continue
            first = starts[-size] if size else index
            if how == PICK:
                kept = arg(values)
            elif how == ONE:
                kept = (values[arg],)
            elif how == GROW:
                kept = values[-size]
                kept.append(values[arg])
            elif how == NONE:
                kept = ()
            else:
                kept = []
                for i, splice, nones in arg:
                    if nones:
                        kept.extend([None] * nones)
                    if splice:
                        kept.extend(values[i - size])
                    else:
                        kept.append(values[i - size])
                if after:
                    kept.extend([None] * after)
            if size:
                del stack[-size:]
                del values[-size:]
                del starts[-size:]
            if func is None:
                value = kept if type(kept) is list else list(kept)
            elif first == index:            # the rule matched no token
                value = func(meta(1, 1, 1, 1), kept)
            else:
                head, tail = tokens[first], tokens[index - 1]
                if tuple_meta:
                    value = func(new_tuple(meta, (head.line, head.column,
                                                  tail.end_line, tail.end_column)), kept)
                else:
                    value = func(meta(head.line, head.column, tail.end_line, tail.end_column),
                                 kept)
            stack.append(states[stack[-1]][origin])
            values.append(value)
            starts.append(first)
            if ttype == "$END" and stack[-1] == end_state:
                return value
    raise ParseError(token, set())      # not reached with a sound table


def main() -> int:
    """`python3 -m epuckc.syntax.lalr`: write epuckc/syntax/_parse_tables.py anew from
    the grammar (after editing grammar/epuck.lark)."""
    from ..base.output import write_file
    from ..base.resources import grammar_path
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), SHIPPED)
    write_file(path, tables_module(grammar_path().read_text(encoding="utf-8"), "statement"))
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
