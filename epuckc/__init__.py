"""epuckc: a compiler from event rules to C for the e-puck's event-driven runtime."""

__version__ = "0.1.0"
