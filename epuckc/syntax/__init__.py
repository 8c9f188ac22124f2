"""Text to a typed syntax tree, with positions: the first stage.

- lexer.py: tokens and statement boundaries (a statement starts at a keyword
  at the start of a line), lexical errors;
- lalr.py: the LALR(1) driver over tables Lark computes from
  grammar/epuck.lark; _parse_tables.py: those tables, shipped
  (`python3 -m epuckc.syntax.lalr` regenerates them);
- parser.py: statements to AST nodes, syntax errors with fixes, recovery at
  the next statement;
- ast.py: the nodes (slots classes with a Span each);
- _front.c + accel.py: the optional C front end, which lexes and parses a
  file with nothing to report and hands everything else to parser.py.

May import: base, diagnostics.
"""
