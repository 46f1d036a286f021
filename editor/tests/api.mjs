// A small client of the editor's JSON API for the tests (node's http, so the Host header
// can be set).
import http from "node:http";

export function request(port, method, path, { body, token, host, raw } = {}) {
  const data = raw !== undefined ? raw : body === undefined ? undefined : JSON.stringify(body);
  const headers = { Host: host || `127.0.0.1:${port}` };
  if (token) headers["X-Sfit-Token"] = token;
  if (data !== undefined) {
    headers["Content-Type"] = "application/json";
    headers["Content-Length"] = Buffer.byteLength(data);
  }
  return new Promise((resolve, reject) => {
    const req = http.request({ host: "127.0.0.1", port, method, path, headers }, (res) => {
      const chunks = [];
      res.on("data", (c) => chunks.push(c));
      res.on("end", () => {
        const text = Buffer.concat(chunks).toString("utf8");
        let json = null;
        try { json = JSON.parse(text); } catch { /* not JSON */ }
        resolve({ status: res.statusCode, json, text, headers: res.headers });
      });
    });
    req.on("error", reject);
    req.end(data);  // headers and body in one write (no delayed-ACK stall)
  });
}

/// Bound to one server: api.get("/api/state"), api.post("/api/edit", {...}).
export function client(ed) {
  return {
    get: (path, o = {}) => request(ed.port, "GET", path, { token: ed.token, ...o }),
    post: (path, body, o = {}) => request(ed.port, "POST", path, { token: ed.token, body, ...o }),
  };
}
