"""`epuckc studio`: write, check, run and replay rule programs in the
browser, and check a class's exercises, from one local server.

The server (server.py, on aiohttp) listens on 127.0.0.1 only and every
request and socket carries a random token (security.py, which also checks
Host and Origin against DNS rebinding). The page's editor talks LSP over a
WebSocket to the language server of epuckc/ide, in this process
(lspbridge.py: ide.lsp's handlers, not a copy of them); files are read and
saved inside the folder only (workspace.py: no `..`, no symbolic link out,
atomic saves that notice a change made outside); a run is `epuckc run`
itself, a child process whose JSON trace is streamed to the page as the
simulation writes it, and killed by Stop or when the page goes away
(runs.py); a class folder is a list of exercises whose Check runs their
`epuckc test` cases (exercises.py, over epuckc/testing); the generated C
of a rule comes from the compiler's own front end and emitter (ccode.py);
the robots' ports are epuckc/link's, and Flash and Monitor are `epuckc
flash` and `epuckc monitor` in child processes, Monitor's robot trace
streamed as a run's (robots.py).
The page itself is built from the TypeScript sources in studio/ at the top
of the repository into static/ (docs/studio.md); no node is needed to run
it.

May import: base, diagnostics, stdlib, syntax, check, emit, build, sim, ide,
testing, link.
"""
