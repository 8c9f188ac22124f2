// Highlighting of rule files from the editor packages' own word lists: the
// patterns of editors/vscode's TextMate grammar (which tests/editors keeps
// equal to the lexer's keywords and the standard table), read at build
// time, not copied. Each `match` pattern is tried at the current position,
// in the grammar's order, as TextMate does; its captures become tokens.
import { HighlightStyle, StreamLanguage, StringStream, syntaxHighlighting } from "@codemirror/language";
import { tags } from "@lezer/highlight";
import grammar from "../../editors/vscode/syntaxes/epuck.tmLanguage.json";

type Rule = { match?: string; name?: string; captures?: Record<string, { name: string }>;
              begin?: string; end?: string; patterns?: Rule[]; include?: string };
type Compiled = { re: RegExp; name?: string; captures?: Record<string, { name: string }>;
                  string?: boolean };

// TextMate scopes to the token names CodeMirror's default highlight style knows
const STYLES: [string, string][] = [
  ["comment", "comment"], ["string", "string"], ["constant.character.escape", "string2"],
  ["entity.name.function", "def"], ["variable.other.constant.definition", "def"],
  ["storage.type", "keyword"], ["keyword.control", "keyword"],
  ["keyword.operator.logical", "keyword"], ["keyword.other.unit", "unit"],
  ["constant.numeric", "number"], ["variable.parameter", "propertyName"],
  ["support.function", "builtin"], ["variable.language", "sensor"],
  ["keyword.operator", "operator"], ["punctuation", "punctuation"],
  ["variable.other", "variableName"],
];

function style(scope: string | undefined): string | null {
  if (!scope) return null;
  for (const [prefix, name] of STYLES) if (scope.startsWith(prefix)) return name;
  return null;
}

function flatten(rules: Rule[], out: Compiled[]): Compiled[] {
  const repository = (grammar as { repository: Record<string, Rule> }).repository;
  for (const rule of rules) {
    if (rule.include) flatten([repository[rule.include.slice(1)]], out);
    else if (rule.match) {
      // every group numbered as in the grammar; `d` gives the groups' places
      out.push({ re: new RegExp(rule.match, "yd"), name: rule.name, captures: rule.captures });
    } else if (rule.begin) out.push({ re: new RegExp(rule.begin, "y"), name: rule.name, string: true });
    else if (rule.patterns) flatten(rule.patterns, out);
  }
  return out;
}

const RULES = flatten((grammar as { patterns: Rule[] }).patterns, []);

type State = { queue: [number, string | null][]; inString: boolean };

function stringBody(stream: StringStream, state: State): string {
  while (!stream.eol()) {
    const ch = stream.next();
    if (ch === "\\") stream.next();
    else if (ch === '"') { state.inString = false; return "string"; }
  }
  state.inString = false;       // "end": "\"|$"
  return "string";
}

export const epuckLanguage = StreamLanguage.define<State>({
  name: "epuck",
  startState: () => ({ queue: [], inString: false }),
  copyState: s => ({ queue: s.queue.slice(), inString: s.inString }),
  token(stream, state) {
    if (state.queue.length) {
      const [length, name] = state.queue.shift()!;
      for (let i = 0; i < length; i++) stream.next();
      return name;
    }
    if (state.inString) return stringBody(stream, state);
    if (stream.eatSpace()) return null;
    const line = stream.string, at = stream.pos;
    for (const rule of RULES) {
      rule.re.lastIndex = at;
      const m = rule.re.exec(line);
      if (!m || m[0].length === 0) continue;
      if (rule.string) {
        stream.pos = at + m[0].length;
        state.inString = true;
        return "string";
      }
      if (!rule.captures) {
        stream.pos = at + m[0].length;
        return style(rule.name);
      }
      // captured groups as tokens, the text between them with the rule's own scope
      const indices = (m as RegExpExecArray & { indices: [number, number][] }).indices;
      const parts: [number, string | null][] = [];
      let pos = at;
      for (let g = 1; g < indices.length; g++) {
        const span = indices[g];
        if (!span || span[0] < pos) continue;
        if (span[0] > pos) parts.push([span[0] - pos, style(rule.name)]);
        const capture = rule.captures[String(g)];
        parts.push([span[1] - span[0], style(capture ? capture.name : rule.name)]);
        pos = span[1];
      }
      if (at + m[0].length > pos) parts.push([at + m[0].length - pos, style(rule.name)]);
      const tokens = parts.filter(p => p[0] > 0);
      const first = tokens.shift()!;
      state.queue = tokens;
      stream.pos = at + first[0];
      return first[1];
    }
    stream.next();
    return null;
  },
  languageData: { commentTokens: { line: "#" } },
  tokenTable: { unit: tags.unit, builtin: tags.standard(tags.function(tags.variableName)),
                sensor: tags.special(tags.variableName), def: tags.definition(tags.name) },
});

export const epuckHighlighting = syntaxHighlighting(HighlightStyle.define([
  { tag: tags.keyword, color: "#7928a1", fontWeight: "bold" },
  { tag: tags.comment, color: "#8a6d3b", fontStyle: "italic" },
  { tag: tags.string, color: "#a11" },
  { tag: tags.number, color: "#164" },
  { tag: tags.unit, color: "#2a7a8c" },
  { tag: tags.standard(tags.function(tags.variableName)), color: "#05a" },
  { tag: tags.special(tags.variableName), color: "#b35900" },
  { tag: tags.definition(tags.name), color: "#00f" },
  { tag: tags.propertyName, color: "#555" },
  { tag: tags.operator, color: "#708" },
]));
