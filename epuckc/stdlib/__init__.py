"""The one table of the language's standard names, and the units of its values.

- table.py: every standard action, event and choice (LED, sound, key) with its
  parameters, their kinds and ranges, a one-line doc and the runtime call it
  becomes; the checker, lowering, docs/language.md section 3 and the language
  server's hover and completion all read it, so a new action is one entry.
  `python3 -m epuckc.stdlib.table` prints section 3 of docs/language.md.
- units.py: kinds (distance, speed, angle, duration, count), units, the
  robot's geometry and the exact conversions to runtime integers.

May import: base.
"""
