// The editor's language server: ide/lsp.py's server over a WebSocket
// (epuckc/studio/lspbridge.py), through @codemirror/lsp-client for hover,
// completion, signature help and formatting. Diagnostics are ours: the
// text is sent a few ms after each change (lsp-client waits 500 ms), and
// each diagnostic carries its quick fixes (the server's code actions),
// applied with a click in the lint tooltip or panel.
import { LSPClient, LSPPlugin, Transport, hoverTooltips, serverCompletion, signatureHelp,
         formatKeymap, renameKeymap, jumpToDefinitionKeymap,
         findReferencesKeymap } from "@codemirror/lsp-client";
import { Diagnostic, setDiagnostics } from "@codemirror/lint";
import { EditorView, ViewPlugin, ViewUpdate, keymap } from "@codemirror/view";
import { Text } from "@codemirror/state";
import { socketURL } from "./api";

const SYNC_MS = 0;      // the next task: changes of one task (a paste, a fix) go together

type LspPosition = { line: number; character: number };
type LspRange = { start: LspPosition; end: LspPosition };
type LspDiagnostic = { range: LspRange; message: string; severity?: number; code?: string };
type TextEdit = { range: LspRange; newText: string };
type CodeAction = { title: string; diagnostics?: LspDiagnostic[];
                    edit?: { changes?: Record<string, TextEdit[]> } };

export type Shown = { from: number; to: number; severity: string; message: string;
                      code?: string; fixes: string[] };

export const diagnosticsShown: Map<string, Shown[]> = new Map();
export const listeners: ((uri: string, withFixes: boolean) => void)[] = [];

function connectSocket(): Promise<Transport> {
  const handlers: ((value: string) => void)[] = [];
  const sock = new WebSocket(socketURL("/ws/lsp"));
  sock.onmessage = e => { for (const h of handlers) h(String(e.data)); };
  return new Promise((resolve, reject) => {
    sock.onerror = () => reject(new Error("the studio's language server socket failed"));
    sock.onopen = () => resolve({
      send(message: string) { sock.send(message); },
      subscribe(handler) { handlers.push(handler); },
      unsubscribe(handler) {
        const i = handlers.indexOf(handler);
        if (i >= 0) handlers.splice(i, 1);
      },
    });
  });
}

const severities: Record<number, "error" | "warning" | "info" | "hint"> =
  { 1: "error", 2: "warning", 3: "info", 4: "hint" };

function same(a: LspDiagnostic, b: LspDiagnostic): boolean {
  return a.message === b.message && a.code === b.code
    && a.range.start.line === b.range.start.line
    && a.range.start.character === b.range.start.character;
}

function publish(client: LSPClient, params: { uri: string; version?: number;
                                              diagnostics: LspDiagnostic[] }) {
  // the diagnostics are drawn at once; their quick fixes (the server's code
  // actions for them) are added when the server has answered for them
  const file = client.workspace.getFile(params.uri);
  if (!file || (params.version != null && params.version !== file.version)) return;
  const view = file.getView();
  const plugin = view && LSPPlugin.get(view);
  if (!view || !plugin) return;
  const synced = plugin.syncedDoc;
  show(view, synced, params, [], false);
  if (!params.diagnostics.length) return;
  client.request<unknown, CodeAction[]>("textDocument/codeAction", {
    textDocument: { uri: params.uri },
    range: { start: { line: 0, character: 0 }, end: plugin.toPosition(synced.length, synced) },
    context: { diagnostics: params.diagnostics },
  }).then(actions => {
    if (file.version === (params.version ?? file.version) && LSPPlugin.get(view)?.syncedDoc === synced)
      show(view, synced, params, actions || [], true);
  }, () => {});
}

function show(view: EditorView, synced: Text, params: { uri: string; diagnostics: LspDiagnostic[] },
              actions: CodeAction[], withFixes: boolean) {
  const now = LSPPlugin.get(view);
  if (!now) return;
  const map = (pos: LspPosition) => now.unsyncedChanges.mapPos(now.fromPosition(pos, synced));
  const shown: Shown[] = [];
  const diagnostics: Diagnostic[] = params.diagnostics.map(d => {
    const fixes = actions.filter(a => a.diagnostics && a.diagnostics.some(x => same(x, d)));
    const item: Diagnostic = {
      from: map(d.range.start), to: map(d.range.end),
      severity: severities[d.severity ?? 1], message: d.message,
      source: d.code ? `epuckc ${d.code}` : "epuckc",
      actions: fixes.map(fix => ({
        name: fix.title,
        apply(target: EditorView) { applyEdit(target, params.uri, fix); },
      })),
    };
    shown.push({ from: item.from, to: item.to, severity: item.severity, message: d.message,
                 code: d.code, fixes: fixes.map(f => f.title) });
    return item;
  });
  view.dispatch(setDiagnostics(view.state, diagnostics));
  diagnosticsShown.set(params.uri, shown);
  for (const listener of listeners) listener(params.uri, withFixes);
}

function applyEdit(view: EditorView, uri: string, action: CodeAction) {
  const plugin = LSPPlugin.get(view);
  const edits = action.edit?.changes?.[uri];
  if (!plugin || !edits) return;
  const synced = plugin.syncedDoc;
  view.dispatch({
    changes: edits.map(e => ({
      from: plugin.unsyncedChanges.mapPos(plugin.fromPosition(e.range.start, synced)),
      to: plugin.unsyncedChanges.mapPos(plugin.fromPosition(e.range.end, synced)),
      insert: e.newText,
    })),
    userEvent: "input.fix",
  });
}

// the text goes to the server SYNC_MS after the last change
const quickSync = ViewPlugin.fromClass(class {
  pending = -1;
  update(update: ViewUpdate) {
    if (!update.docChanged) return;
    if (this.pending > -1) clearTimeout(this.pending);
    this.pending = window.setTimeout(() => {
      this.pending = -1;
      const plugin = LSPPlugin.get(update.view);
      if (plugin) plugin.client.sync();
    }, SYNC_MS);
  }
  destroy() { if (this.pending > -1) clearTimeout(this.pending); }
});

export async function connect(rootUri: string): Promise<LSPClient> {
  const client = new LSPClient({
    rootUri,
    initializationOptions: { debounceMs: 0 },
    timeout: 10000,
    extensions: [
      serverCompletion(), hoverTooltips(), signatureHelp(),
      keymap.of([...formatKeymap, ...renameKeymap, ...jumpToDefinitionKeymap, ...findReferencesKeymap]),
      {
        clientCapabilities: { textDocument: { publishDiagnostics: { versionSupport: true },
                                              codeAction: {} } },
        notificationHandlers: {
          "textDocument/publishDiagnostics": (c: LSPClient, params: any) => {
            publish(c, params);
            return true;
          },
        },
        editorExtension: quickSync,
      },
    ],
  });
  client.connect(await connectSocket());
  await client.initializing;
  return client;
}
