// The studio's HTTP API and sockets, every request with the page's token
// (epuckc/studio/security.py).
export const token = new URLSearchParams(location.search).get("token") || "";

export async function api<T>(method: string, path: string, body?: unknown): Promise<T> {
  const init: RequestInit = { method, headers: { "X-Studio-Token": token } };
  if (body !== undefined) {
    (init.headers as Record<string, string>)["Content-Type"] = "application/json";
    init.body = JSON.stringify(body);
  }
  const response = await fetch(path, init);
  const data = await response.json().catch(() => ({}));
  if (!response.ok) throw Object.assign(new Error(data.error || response.statusText),
                                        { status: response.status, data });
  return data as T;
}

export function socketURL(path: string): string {
  return `ws://${location.host}${path}?token=${encodeURIComponent(token)}`;
}

export function withToken(path: string): string {
  return `${path}${path.includes("?") ? "&" : "?"}token=${encodeURIComponent(token)}`;
}

export type Info = {
  version: string; name: string; root_uri: string; files: string[];
  exercises: { folder: string; title: string; files: string[] }[];
  flash: boolean; monitor: boolean;
};
