// Run the extension's client (extension.js) against stand-ins for the
// `vscode` API and vscode-languageclient, and print what it did as JSON:
// the language clients it created (server command, arguments, documents)
// and what happened on a restart and on a change of settings.
// Usage: node test/client.js '{"path": ..., "args": [...]}'
"use strict";

const Module = require("module");
const path = require("path");

const settings = JSON.parse(process.argv[2] || "{}");
const log = { clients: [], stopped: 0, errors: [], commands: [] };
const commands = {};
const configListeners = [];

const vscode = {
  workspace: {
    getConfiguration: (section) => ({ get: (key) => settings[`${section}.${key}`] }),
    onDidChangeConfiguration: (listener) => {
      configListeners.push(listener);
      return { dispose() {} };
    },
  },
  commands: {
    registerCommand: (name, fn) => {
      commands[name] = fn;
      log.commands.push(name);
      return { dispose() {} };
    },
  },
  window: { showErrorMessage: (message) => log.errors.push(message) },
};

class LanguageClient {
  constructor(id, name, serverOptions, clientOptions) {
    log.clients.push({ id, name, serverOptions, documentSelector: clientOptions.documentSelector });
  }
  start() {
    return settings.failStart ? Promise.reject(new Error("spawn ENOENT")) : Promise.resolve();
  }
  stop() {
    log.stopped += 1;
    return Promise.resolve();
  }
}

const load = Module._load;
Module._load = function (request, parent, isMain) {
  if (request === "vscode") return vscode;
  if (request === "vscode-languageclient/node") return { LanguageClient, TransportKind: { stdio: 0 } };
  return load.call(this, request, parent, isMain);
};

(async () => {
  const extension = require(path.join(__dirname, "..", "extension.js"));
  const context = { subscriptions: [] };
  await extension.activate(context);
  await commands["epuckc.restartServer"]();
  settings["epuckc.args"] = ["-m", "epuckc", "lsp"];
  for (const listener of configListeners) {
    await listener({ affectsConfiguration: (key) => key === "epuckc.args" });
  }
  await new Promise((resolve) => setTimeout(resolve, 10));
  await extension.deactivate();
  log.subscriptions = context.subscriptions.length;
  process.stdout.write(JSON.stringify(log));
})().catch((error) => {
  process.stderr.write(String((error && error.stack) || error) + "\n");
  process.exit(1);
});
