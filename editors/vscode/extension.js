// The VS Code client of `epuckc lsp`: it starts the language server on
// standard input/output for .epk files and restarts it on demand or when
// its settings change. Everything else (diagnostics, hover, completion,
// definitions, rename, quick fixes, formatting) comes from the server.
"use strict";

const vscode = require("vscode");
const { LanguageClient } = require("vscode-languageclient/node");

let client;

function serverOptions() {
  const config = vscode.workspace.getConfiguration("epuckc");
  // No `transport`: the server talks on standard input/output, and
  // TransportKind.stdio would append `--stdio` to its arguments.
  return {
    command: config.get("path") || "epuckc",
    args: config.get("args") || ["lsp"],
  };
}

async function start(context) {
  client = new LanguageClient(
    "epuckc",
    "epuckc",
    serverOptions(),
    {
      documentSelector: [
        { scheme: "file", language: "epuck" },
        { scheme: "untitled", language: "epuck" },
      ],
      outputChannelName: "epuckc",
    },
  );
  try {
    await client.start();
  } catch (error) {
    client = undefined;
    const command = serverOptions().command;
    vscode.window.showErrorMessage(
      `epuckc: cannot start the language server with \`${command}\` (${error.message || error}). ` +
        "Install epuckc (pip install epuckc) or set epuckc.path and epuckc.args.",
    );
  }
}

async function restart(context) {
  if (client) {
    await client.stop().catch(() => undefined);
    client = undefined;
  }
  await start(context);
}

function activate(context) {
  context.subscriptions.push(
    vscode.commands.registerCommand("epuckc.restartServer", () => restart(context)),
    vscode.workspace.onDidChangeConfiguration((event) => {
      if (event.affectsConfiguration("epuckc.path") || event.affectsConfiguration("epuckc.args")) {
        restart(context);
      }
    }),
  );
  return start(context);
}

function deactivate() {
  return client ? client.stop() : undefined;
}

module.exports = { activate, deactivate };
